"""The validator's checks: SPEC section 3, checks 1 to 7, in that order (for a
``kinoplan 1`` problem, SPEC 5.5's: 7 checks kinodynamic, 6 geometric).

:func:`validate_output` reads a planner's output text, re-simulates it and
returns a :class:`ValidationReport`. It prints nothing and imports only
planning_core.

The run stops at the first failed check, as the course tool did: later checks
would only report consequences of the same fault, and on a hostile output they
would spend time for nothing. Each failure carries the SPEC message exactly as
written (grading scripts grep for them), the 1-based line of the planner's
output at fault, a detail sentence with the values, and the world point where
it happens (for the PDF).
"""

from __future__ import annotations

import math

from planning_core.costs import path_cost
from planning_core.goal import GOAL_TOLERANCE
from planning_core.plan_reader import PlanArrays, PlanRowError, compile_row_patterns, read_plan
from planning_core.plan_rows import row_widths
from planning_core.plan_text import PlanParseError
from planning_core.problem import Problem
from planning_core.setups import Setup, grid_setup
from planning_core.vehicles import Vehicle
from planning_core.worlds.grid import SAMPLE_STEP

# The SPEC 3 messages, verbatim.
PARSE_ERROR = "Error parsing planner output!"
EMPTY_TRAJECTORY = "Empty trajectory!"
OUT_OF_BOUNDS = "State in trajectory that goes out of bounds!"
NOT_AT_START = "Trajectory doesn't start at start!"
LAST_EDGE_COLLISION = "Last edge in trajectory had collision!"
NOT_AT_GOAL = "Trajectory doesn't get close enough to goal!"
POINT_COLLISION = "Trajectory collides with an obstacle!"
SPACESHIP_COLLISION = "Trajectory collides with something!"
# Not in the course tool: a trajectory whose check would cost unbounded time.
TOO_LONG = "Trajectory too long to check!"
VALID_VERDICT = "Solution trajectory appears valid."
INVALID_VERDICT = "Putative solution trajectory has problems."

TURNING_TOO_TIGHT = "Trajectory turns tighter than the turning radius!"
START_TOLERANCE = 0.001  # in each of x and y (and dx, dy for the spaceship)
STATE_TOLERANCE = 0.01   # check 7, in each of x, y, dx, dy
TURNING_TOLERANCE = 1e-6  # check 8: the turn allowed at a point, relative
TURNING_SLACK = 1e-5      # check 8: and absolute, radians (a path node meets its curve's
                          # computed end within ~1e-8: a kink of ~3e-7 rad at a 0.05 chord)
CHORD_SLACK = 1e-9        # check 8: a chord may exceed SAMPLE_STEP by this (rounding)



class Check:
    """One check of SPEC 3 (5.5 for the family), registered by name. (The records
    here are plain classes, as on the planner's start-up path, so that the validator
    makes fewer dataclasses while the planner runs; Limits, a parameter set, stays
    a dataclass.)"""

    name: str
    """What grading scripts and the JSON call it."""
    title: str
    """What it asserts, in a few words."""
    kinodynamic_only: bool
    """It applies only to systems driven by controls."""
    directed_only: bool
    """It applies only to systems of one-way curved motions (``-dubins``)."""

    def __init__(self, name: str, title: str, kinodynamic_only: bool = False,
                 directed_only: bool = False) -> None:
        self.name, self.title = name, title
        self.kinodynamic_only, self.directed_only = kinodynamic_only, directed_only

    def __repr__(self) -> str:
        return (f"Check({self.name!r}, {self.title!r}, kinodynamic_only="
                f"{self.kinodynamic_only!r}, directed_only={self.directed_only!r})")

    def applies(self, kinodynamic: bool, directed: bool = False) -> bool:
        return ((kinodynamic or not self.kinodynamic_only)
                and (directed or not self.directed_only))


CHECKS = (
    Check("parse", "the output parses"),
    Check("nonempty", "the trajectory is not empty"),
    Check("bounds", "every trajectory state is inside the map, with legal controls"),
    Check("start", "the trajectory starts at the start"),
    Check("goal", "the trajectory ends within 0.1 of the goal"),
    Check("collision", "the trajectory is collision-free"),
    Check("dynamics", "each control leads to the next state", kinodynamic_only=True),
    Check("turning", "the sampled path turns no tighter than the turning radius",
          directed_only=True),
)
"""The checks in the order they run; a check's number is its place here (from 1)."""
CHECK_NUMBERS = {check.name: number for number, check in enumerate(CHECKS, 1)}


class Limits:
    """Bounds that keep validation time and memory finite on hostile output.

    Far beyond any honest answer: the course maps need tens of lines, a 500 x 500
    map a few thousand. Keyword arguments override the defaults; an instance does
    not change. A plain class, not a frozen dataclass: the validator imports it while
    the planner runs, where defining a dataclass is start-up time that shows
    (docs/setup-and-startup.md).
    """

    max_trajectory_lines: int = 1_000_000
    """A larger trajectory count fails check 1."""
    max_point_path_length: float = 1_000_000.0
    """A longer point path fails check 6 with TOO_LONG."""
    max_tree_rows_kept: int = 250_000
    """Tree rows past this many are parsed and counted but not kept (nor drawn)."""
    max_motion_samples: int = 1_000_000
    """Geometric family: more samples fail check 6 with TOO_LONG."""
    max_slices: int = 1_200_000
    """Kinodynamic family: the slices re-simulated and tested, each line's K plus
    ``line_cost`` (its printed state's test, its checks); more fail check 6 (the
    last line alone: check 5) with TOO_LONG before any is simulated."""
    line_cost: int = 4
    """What one line of a kinodynamic answer costs besides its K slices, in slices."""
    world_vertices: int = 64
    """The family's caps (samples, slices) hold in worlds of up to this many
    vertices, the obstacles' and the body's; a larger world lowers them in
    proportion, as a validity test there looks at more."""
    max_warnings_listed: int = 20
    """Corner-cut warnings listed one by one; the rest are summed up in one line."""

    def __init__(self, **overrides: float) -> None:
        for name, value in overrides.items():
            if name not in _LIMIT_NAMES:
                raise TypeError(f"Limits has no {name!r}")
            object.__setattr__(self, name, value)

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"a Limits does not change (setting {name!r})")

    def __repr__(self) -> str:
        return f"Limits({', '.join(f'{k}={v!r}' for k, v in vars(self).items())})"


_LIMIT_NAMES = frozenset(Limits.__annotations__)


class CheckResult:
    """What one check found."""

    number: int                # its place in CHECKS (from 1), as in SPEC 3
    name: str                  # its name in CHECKS
    passed: bool
    message: str               # on failure: the SPEC message, verbatim
    detail: str                # values, expected vs found; on success a short summary
    line: int | None           # 1-based line of the planner's output at fault
    where: tuple[float, float] | None  # world point of the fault

    def __init__(self, number: int, name: str, passed: bool, message: str = "",
                 detail: str = "", line: int | None = None,
                 where: tuple[float, float] | None = None) -> None:
        self.number, self.name, self.passed = number, name, passed
        self.message, self.detail, self.line, self.where = message, detail, line, where

    def __repr__(self) -> str:
        return (f"CheckResult({self.number!r}, {self.name!r}, {self.passed!r}, "
                f"{self.message!r}, {self.detail!r}, line={self.line!r}, "
                f"where={self.where!r})")

    @property
    def title(self) -> str:
        return CHECKS[self.number - 1].title


class CornerCut:
    """A point segment that enters a blocked cell between two 0.05 samples."""

    line: int                  # line of the segment's first point (the next line ends it)
    column: int
    row: int
    where: tuple[float, float]  # where the segment enters the cell

    def __init__(self, line: int, column: int, row: int, where: tuple[float, float]) -> None:
        self.line, self.column, self.row, self.where = line, column, row, where

    def __repr__(self) -> str:
        return f"CornerCut({self.line!r}, {self.column!r}, {self.row!r}, {self.where!r})"


class ValidationReport:
    """The checks run on one answer, in order (the run stops at the first failure),
    and what they measured."""

    system: object             # what was checked (planning_core.systems)
    strict: bool
    checks: list[CheckResult]
    warnings: list[str]
    corner_cuts: list[CornerCut]
    plan: PlanArrays | None
    path_length: float | None
    # Spaceship: the state the last line's control leads to (not printed by planners).
    final_state: tuple[float, float, float, float] | None
    cost: float | None
    """A valid answer's cost (:func:`answer_cost`), else None."""
    cost_kind: str
    """What the cost measures: "length", or "duration" (the family's kinodynamic systems)."""

    def __init__(self, system: object, strict: bool, checks: list[CheckResult],
                 warnings: list[str] | None = None, corner_cuts: list[CornerCut] | None = None,
                 plan: PlanArrays | None = None, path_length: float | None = None,
                 final_state: tuple[float, float, float, float] | None = None,
                 cost: float | None = None, cost_kind: str = "length") -> None:
        self.system, self.strict, self.checks = system, strict, checks
        self.warnings = [] if warnings is None else warnings
        self.corner_cuts = [] if corner_cuts is None else corner_cuts
        self.plan, self.path_length, self.final_state = plan, path_length, final_state
        self.cost, self.cost_kind = cost, cost_kind

    def __repr__(self) -> str:
        return (f"ValidationReport({self.system!r}, {self.strict!r}, {self.checks!r}, "
                f"warnings={self.warnings!r}, path_length={self.path_length!r}, "
                f"cost={self.cost!r})")

    @property
    def vehicle(self) -> Vehicle:
        """The course's name for the system checked."""
        return Vehicle(self.system.name)

    @property
    def checks_expected(self) -> int:
        system = self.system
        return sum(check.applies(system.kinodynamic, getattr(system, "directed", False))
                   for check in CHECKS)

    @property
    def valid(self) -> bool:
        return (len(self.checks) == self.checks_expected
                and all(check.passed for check in self.checks))

    @property
    def first_failure(self) -> CheckResult | None:
        return next((check for check in self.checks if not check.passed), None)

    @property
    def first_failing_line(self) -> int | None:
        failure = self.first_failure
        return failure.line if failure else None

    @property
    def verdict(self) -> str:
        return VALID_VERDICT if self.valid else INVALID_VERDICT

    @property
    def trajectory_count(self) -> int | None:
        return self.plan.trajectory_count if self.plan else None

    @property
    def tree_count(self) -> int | None:
        return self.plan.tree_count if self.plan else None


class _Failed(Exception):
    """Raised inside a check; carries its result."""

    def __init__(self, result: CheckResult):
        self.result = result


def _num(value: float) -> str:
    return f"{value:.6g}"


def _point(*values: float) -> str:
    return "(" + ", ".join(_num(v) for v in values) + ")"


def _angle(*values: float) -> str:
    return "<" + ", ".join(_num(v) for v in values) + ">"


def _place(problem: Problem, x: float, y: float) -> str:
    if not (0.0 <= x < problem.width and 0.0 <= y < problem.height):
        return f"{_point(x, y)} is outside the map [0, {problem.width}) x [0, {problem.height})"
    return f"{_point(x, y)} is in blocked cell ({int(x)}, {int(y)})"


def dynamics_message(control: tuple[float, float], state: tuple[float, ...],
                     claimed: tuple[float, ...], computed: tuple[float, ...]) -> str:
    """Check 7's message, SPEC 3's form with the values filled in."""
    return (f"Trajectory claims that control {_angle(*control)} at state {_angle(*state)} "
            f"gives state {_angle(*claimed)} but I get state {_angle(*computed)}!")


def _same_signs(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    # 0.0 == -0.0, yet atan2 tells them apart: a velocity of (-0.0, 0.0) points at pi.
    return all(math.copysign(1.0, u) == math.copysign(1.0, v) for u, v in zip(a, b))


def _other_answer_hint(error: PlanParseError, system) -> str:
    """Name the likely cause when the numbers per line fit the other kind of system."""
    found = getattr(error, "found", None)
    if system.kinodynamic and found in (2, 4):
        return (" (a point-vehicle answer? the output is being checked for the "
                f"{system.name} vehicle, 6 numbers a line)")
    if not system.kinodynamic and found == 6:
        return " (a spaceship answer? check it with -grad)"
    return ""


class _Validation:
    """One run of the checks; each ``check_*`` method returns a result or raises _Failed."""

    def __init__(self, setup: Setup, strict: bool, limits: Limits):
        self.si = si = setup.si
        self.pdef = setup.pdef
        self.system = si.system
        self.problem = setup.problem
        self.strict = strict
        self.limits = limits
        self.world = si.world
        self.plan: PlanArrays | None = None
        self.warnings: list[str] = []
        self.corner_cuts: list[CornerCut] = []
        self.path_length: float | None = None
        self.final_state: tuple[float, float, float, float] | None = None
        self.last_slices: list[tuple[float, float, float, float]] = []

    def fail(self, check: str, message: str, detail: str, line: int | None,
             where: tuple[float, float] | None = None) -> _Failed:
        """The failure of the check named ``check``."""
        return _Failed(CheckResult(CHECK_NUMBERS[check], check, False, message, detail,
                                   line, where))

    def passed(self, check: str, detail: str = "") -> CheckResult:
        return CheckResult(CHECK_NUMBERS[check], check, True, "", detail)

    def line_of(self, index: int) -> int:
        return self.plan.trajectory_line(index)

    def other_answer_hint(self, error: PlanParseError) -> str:
        return _other_answer_hint(error, self.system)

    def check_parse(self, text: str, output_cap: int | None) -> CheckResult:
        fields, tree_fields = row_widths(self.system)
        if output_cap is not None:
            line = text.count("\n") + 1
            raise self.fail("parse", PARSE_ERROR, f"line {line}: the planner wrote more than "
                            f"{output_cap} bytes on stdout (the validator's cap); the output "
                            "was cut off there", line)
        try:
            self.plan = read_plan(text, fields, tree_fields,
                                  max_trajectory_rows=self.limits.max_trajectory_lines,
                                  max_tree_rows_kept=self.limits.max_tree_rows_kept)
        except PlanParseError as error:
            detail = f"line {error.line}: {error.message}"
            if isinstance(error, PlanRowError):
                detail += self.other_answer_hint(error)
            raise self.fail("parse", PARSE_ERROR, detail, error.line) from None
        if self.plan.trailing_line is not None:
            self.warnings.append(f"line {self.plan.trailing_line}: text after the tree "
                                 "is ignored")
        return self.passed("parse", f"{self.plan.trajectory_count} trajectory lines, "
                              f"{self.plan.tree_count} tree lines")

    def check_nonempty(self) -> CheckResult:
        if self.plan.trajectory_count == 0:
            line = self.plan.trajectory_first_line - 1
            raise self.fail("nonempty",
                            EMPTY_TRAJECTORY, f"line {line}: the trajectory count is 0; "
                            "a trajectory has at least one line, the start", line)
        return self.passed("nonempty")

    def check_bounds(self) -> CheckResult:
        width, height = self.problem.width, self.problem.height
        system, printable = self.system, self.si.printable
        n = len(system.state_names)
        for index, row in enumerate(self.plan.trajectory_rows()):
            x, y = row[0], row[1]
            if not printable(x, y):
                raise self.fail("bounds", OUT_OF_BOUNDS, f"line {self.line_of(index)}: point "
                                f"{_point(x, y)} is not strictly inside the map (0, {width}) "
                                f"x (0, {height})", self.line_of(index), (x, y))
            if system.kinodynamic:
                violation = system.control_violation(row[n:])
                if violation is not None:
                    raise self.fail("bounds",
                                    OUT_OF_BOUNDS, f"line {self.line_of(index)}: {violation}",
                                    self.line_of(index), (x, y))
        return self.passed("bounds")

    def check_start(self) -> CheckResult:
        row = self.plan.trajectory_row(0)
        start, names = self.pdef.start, self.system.state_names
        line = self.line_of(0)
        sx, sy = start[0], start[1]
        if abs(row[0] - sx) > START_TOLERANCE or abs(row[1] - sy) > START_TOLERANCE:
            raise self.fail("start",
                            NOT_AT_START, f"line {line}: first point {_point(row[0], row[1])}"
                            f", start {_point(sx, sy)} (tolerance {START_TOLERANCE} in x and y)",
                            line, (row[0], row[1]))
        rest = range(2, len(start))
        if any(abs(row[k] - start[k]) > START_TOLERANCE for k in rest):
            raise self.fail("start", NOT_AT_START, f"line {line}: first velocity "
                            f"{_point(*(row[k] for k in rest))} is not at rest (tolerance "
                            f"{START_TOLERANCE} in {' and '.join(names[2:])})", line,
                            (row[0], row[1]))
        return self.passed("start")

    def _slices_or_fail(self, check: str, message: str, row, line: int) -> list:
        """The slice states of a kinodynamic row's control; a failure of check
        ``check`` at the first slice that is not valid."""
        system = self.system
        n = len(system.state_names)
        state, control = row[:n], row[n:]
        slices = system.slice_states(state, control)
        for k, sliced in enumerate(slices):
            if not self.si.is_valid(sliced):
                x, y = sliced[0], sliced[1]
                raise self.fail(check, message, f"line {line}: control {_angle(*control)} from "
                                f"state {_angle(*state)}: slice {k + 1} of {len(slices)} "
                                f"{self.invalid_place(sliced)}", line, (x, y))
        return slices

    def invalid_place(self, state) -> str:
        """Where an invalid state is, for a message."""
        return f"at {_place(self.problem, state[0], state[1])}"

    def check_goal(self) -> CheckResult:
        plan, goal = self.plan, self.pdef.goal
        last = plan.trajectory_count - 1
        row = plan.trajectory_row(last)
        line = self.line_of(last)
        gx, gy = goal.point
        if self.system.kinodynamic:
            slices = self._slices_or_fail("goal", LAST_EDGE_COLLISION, row, line)
            self.last_slices = slices
            self.final_state = slices[-1]
            x, y = slices[-1][0], slices[-1][1]
            control = row[len(self.system.state_names):]
            what = f"the last line's control {_angle(*control)} ends at {_point(x, y)}"
        else:
            x, y = row
            what = f"the last point {_point(x, y)}"
        distance = goal.distance((x, y))
        if not goal.accepts((x, y)):
            raise self.fail("goal", NOT_AT_GOAL, f"line {line}: {what}, {_num(distance)} from the "
                            f"goal {_point(gx, gy)} (at most {goal.tolerance})", line, (x, y))
        return self.passed("goal", f"ends {_num(distance)} from the goal")

    # collision, point vehicle
    def check_point_collisions(self) -> CheckResult:
        plan, world, problem = self.plan, self.world, self.problem
        values = plan.trajectory  # x0, y0, x1, y1, ... (streamed: up to a million points)
        n = plan.trajectory_count
        length = math.fsum(math.hypot(values[2 * k + 2] - values[2 * k],
                                      values[2 * k + 3] - values[2 * k + 1])
                           for k in range(n - 1))
        self.path_length = length
        if length > self.limits.max_point_path_length:
            raise self.fail("collision",
                            TOO_LONG, f"the path is {_num(length)} map units long; the "
                            f"validator samples at most {_num(self.limits.max_point_path_length)}"
                            " units", plan.trajectory_first_line)
        if n == 1:  # no segment: the sampling below covers every point but a lone one
            x, y = values[0], values[1]
            if not world.point_free(x, y):
                raise self.fail("collision", POINT_COLLISION, f"line {self.line_of(0)}: point "
                                f"{_place(problem, x, y)}", self.line_of(0), (x, y))
        cut_count = 0
        for index in range(n - 1):
            x0, y0, x1, y1 = values[2 * index:2 * index + 4]
            hit = world.first_sampled_collision(x0, y0, x1, y1, SAMPLE_STEP)
            exact = None if hit is not None else world.first_blocked_cell_on_segment(
                x0, y0, x1, y1)
            if hit is None and exact is None:
                continue  # (most segments: nothing to say, so no message is formatted)
            line = self.line_of(index)
            segment = (f"segment from line {line} {_point(x0, y0)} to line {line + 1} "
                       f"{_point(x1, y1)}")
            if hit is not None:
                raise self.fail("collision", POINT_COLLISION, f"{segment}: the sample at "
                                f"{_place(problem, *hit)}", line, hit)
            where = (x0 + (x1 - x0) * exact.fraction, y0 + (y1 - y0) * exact.fraction)
            cut = (f"{segment} cuts the corner of blocked cell ({exact.column}, {exact.row}) "
                   f"between the {SAMPLE_STEP}-unit samples")
            if self.strict:
                raise self.fail("collision", POINT_COLLISION, f"{cut} (-strict)", line, where)
            self.corner_cuts.append(CornerCut(line, exact.column, exact.row, where))
            cut_count += 1
            if cut_count <= self.limits.max_warnings_listed:
                self.warnings.append(f"{cut} (a failure with -strict)")
        if cut_count > self.limits.max_warnings_listed:
            self.warnings.append(f"... and {cut_count - self.limits.max_warnings_listed} more "
                                 "segments that cut a blocked cell's corner")
        return self.passed("collision", f"{n - 1} segments"
                              + (f", {cut_count} cutting a corner" if cut_count else ""))

    def _motion(self, index: int, row, line: int) -> tuple[tuple, float]:
        """A kinodynamic line's end state and the length of its flown curve; fails
        check 6 at its state or first slice that is not valid."""
        x, y = row[0], row[1]
        if not self.si.is_valid(row[:len(self.system.state_names)]):
            raise self.fail("collision", SPACESHIP_COLLISION, f"line {line}: state "
                            f"{self.invalid_place(row)}", line, (x, y))
        last = index == self.plan.trajectory_count - 1
        slices = (self.last_slices if last and self.last_slices
                  else self._slices_or_fail("collision", SPACESHIP_COLLISION, row, line))
        length = 0.0
        for sliced in slices:
            sx, sy = sliced[0], sliced[1]
            length += math.hypot(sx - x, sy - y)
            x, y = sx, sy
        return slices[-1], length

    state_tolerance = STATE_TOLERANCE

    def motion_summary(self, n: int) -> str:
        return f"{n} steps of {self.system.slices} slices"

    def same_state(self, claimed, computed) -> bool:
        """Check 7's test: each variable within ``state_tolerance``."""
        tolerance = self.state_tolerance
        return all(abs(a - b) <= tolerance for a, b in zip(claimed, computed))

    # collision and dynamics, kinodynamic systems: one integration per line serves both.
    def check_kinodynamic_motion(self) -> tuple[CheckResult, CheckResult]:
        plan, names = self.plan, self.system.state_names
        n, dims = plan.trajectory_count, len(names)
        length = 0.0
        mismatch: _Failed | None = None
        previous_row: tuple[float, ...] | None = None
        previous = ((), 0.0)
        for index, row in enumerate(plan.trajectory_rows()):
            line = self.line_of(index)
            if not (row == previous_row and _same_signs(row, previous_row)):
                # (Same state and control as the line before: same valid motion.)
                previous_row, previous = row, self._motion(index, row, line)
            end, step_length = previous
            length += step_length
            if mismatch is None and index + 1 < n:
                claimed = plan.trajectory_row(index + 1)[:dims]
                if not self.same_state(claimed, end):
                    mismatch = self.fail(
                        "dynamics", dynamics_message(row[dims:], row[:dims], claimed, end),
                        f"line {line}: its control applied to its state does not give line "
                        f"{line + 1}'s state (tolerance {self.state_tolerance:g} in each of "
                        f"{', '.join(names)})", line + 1, (claimed[0], claimed[1]))
        self.path_length = length
        collision_free = self.passed("collision", self.motion_summary(n))
        if mismatch is not None:
            return collision_free, mismatch.result
        return collision_free, self.passed("dynamics")

    def run(self, text: str, output_cap: int | None) -> list[CheckResult]:
        results: list[CheckResult] = []
        try:
            results.append(self.check_parse(text, output_cap))
            results.append(self.check_nonempty())
            results.append(self.check_bounds())
            results.append(self.check_start())
            results.append(self.check_goal())
            results.extend(self.motion_checks())
        except _Failed as failure:
            results.append(failure.result)
        return results

    def motion_checks(self) -> tuple[CheckResult, ...]:
        """The checks after the goal: collisions (and dynamics, kinodynamic systems;
        turning, the Dubins car)."""
        if self.system.kinodynamic:
            return self.check_kinodynamic_motion()
        collision_free = self.check_point_collisions()
        if getattr(self.system, "directed", False):
            return (collision_free, self.check_turning())
        return (collision_free,)

    def check_turning(self) -> CheckResult:
        """The Dubins car's: every chord at most ``SAMPLE_STEP`` long (so that its turns
        can be seen), and at each point the turn between the chords before and after it
        (zero-length chords skipped) no sharper than an arc of the turning radius R
        through both allows, ``asin(l1 / 2R) + asin(l2 / 2R)``, within
        ``TURNING_TOLERANCE`` relative plus ``TURNING_SLACK`` radians."""
        plan, radius = self.plan, self.system.radius
        values, n = plan.trajectory, plan.trajectory_count
        previous: tuple[float, float, float] | None = None
        for index in range(n - 1):
            dx, dy = values[2 * index + 2] - values[2 * index], values[2 * index + 3] - values[2 * index + 1]
            length = math.hypot(dx, dy)
            if length > SAMPLE_STEP + CHORD_SLACK:
                line = self.line_of(index)
                raise self.fail("turning", TURNING_TOO_TIGHT, f"line {line}: the chord to line "
                                f"{line + 1} is {_num(length)} long; a Dubins answer is sampled "
                                f"at most {SAMPLE_STEP} apart, so that its turns can be checked",
                                line, (values[2 * index], values[2 * index + 1]))
            if length == 0.0:
                continue
            if previous is not None:
                self._turn_or_fail(previous, (dx, dy, length), radius, index)
            previous = (dx, dy, length)
        return self.passed("turning", f"turning radius at least {_num(radius)} "
                                      f"(tolerance {TURNING_TOLERANCE:g} relative)")

    def _turn_or_fail(self, before: tuple[float, float, float],
                      after: tuple[float, float, float], radius: float, index: int) -> None:
        """Fails check 8 when the turn at point ``index`` is too sharp for ``radius``."""
        (ux, uy, l1), (vx, vy, l2) = before, after
        turn = math.atan2(abs(ux * vy - uy * vx), ux * vx + uy * vy)
        allowed = (math.asin(min(1.0, l1 / (2.0 * radius)))
                   + math.asin(min(1.0, l2 / (2.0 * radius))))
        if turn <= allowed * (1.0 + TURNING_TOLERANCE) + TURNING_SLACK:
            return
        line = self.line_of(index)
        where = (self.plan.trajectory[2 * index], self.plan.trajectory[2 * index + 1])
        seen = (l1 + l2) / (2.0 * turn)
        raise self.fail("turning", TURNING_TOO_TIGHT, f"line {line}: the path turns "
                        f"{_num(math.degrees(turn))} degrees at {_point(*where)} between chords "
                        f"of {_num(l1)} and {_num(l2)}: a turning radius of about {_num(seen)}, "
                        f"below {_num(radius)}", line, where)


def world_vertices(problem) -> int:
    """What a family validity test's cost grows with: the obstacles' vertices (a
    rect 4, a disc 1, as the problem reader counts them) and the body's."""
    from planning_core.worlds.shapes import Disc, Rect  # (loaded with a kinoplan problem)
    shapes = (*(problem.world.obstacles if problem.world is not None else ()),
              *((problem.system.body,) if problem.system.body is not None else ()))
    return sum(1 if isinstance(shape, Disc) else 4 if isinstance(shape, Rect)
               else len(shape.points) for shape in shapes)


KINOPLAN_TOLERANCE = 1e-6
"""SPEC 5.5, checks 4 and 7: each variable within this, angles modulo 2 pi."""


def _gaps(space, a, b) -> list[float]:
    """Per variable |a - b|, angles by their wrapped difference."""
    return [abs(math.remainder(y - x, 2 * math.pi)) if v.angle else abs(y - x)
            for v, x, y in zip(space.variables, a, b)]


class _KinoplanValidation(_Validation):
    """SPEC 5.5's checks for a kinodynamic ``kinoplan 1`` answer: the same order,
    messages and verdicts as SPEC 3, over full states. ``-strict`` changes
    nothing here: every slice of every line is checked already."""

    state_tolerance = KINOPLAN_TOLERANCE

    def __init__(self, setup: Setup, strict: bool, limits: Limits):
        si = setup.si
        self.si, self.pdef, self.system, self.strict, self.limits = (
            si, setup.pdef, si.system, strict, limits)
        self.problem, self.world = setup.problem, si.world
        self.plan = None
        self.warnings, self.corner_cuts = [], []
        self.path_length = self.final_state = None
        self.last_slices = []
        self.n = len(self.system.state_names)
        self.vertices = world_vertices(setup.problem)
        self.angles = [(i, v.name) for i, v in enumerate(si.space.variables) if v.angle]

    def invalid_place(self, state) -> str:
        return f"{_angle(*state[:self.n])}: {self.si.invalid_reason(state[:self.n])}"

    def where(self, state) -> tuple[float, float]:
        i, j = self.system.position_indices
        return (state[i], state[j])

    def same_state(self, claimed, computed) -> bool:
        return all(gap <= KINOPLAN_TOLERANCE for gap in _gaps(self.si.space, claimed, computed))

    def motion_summary(self, n: int) -> str:
        return f"{n} held controls, every slice valid"

    def capped(self, cap: int) -> tuple[int, str]:
        """``cap`` in this world, and where a world of more than
        ``Limits.world_vertices`` vertices lowered it, a note saying so."""
        share = self.limits.world_vertices
        if self.vertices <= share:
            return cap, ""
        return cap * share // self.vertices, (f" in a world of {self.vertices} vertices "
                                              f"(obstacles and body; {cap} in one of up to "
                                              f"{share})")

    def _slice_budget_or_fail(self, check: str, slices: int, lines: int, what: str,
                              line: int) -> None:
        """TOO_LONG, as a failure of ``check``, when ``slices`` and ``lines``
        pass ``Limits.max_slices`` in this world (before any slice is simulated)."""
        per_line = self.limits.line_cost
        work = slices + per_line * lines
        cap, where = self.capped(self.limits.max_slices)
        if work > cap:
            raise self.fail(check, TOO_LONG, f"line {line}: {what} {slices} slices: {work} "
                            f"slices to check (K + {per_line} a line) > {cap}, the most the "
                            f"validator checks{where}", line)

    def other_answer_hint(self, error: PlanParseError) -> str:
        names = (*self.system.state_names, *self.system.control_names)
        return f" ({self.system.name}: {len(names)} numbers a line, {' '.join(names)})"

    # parse: the numbers per line, then K a positive integer
    def check_parse(self, text: str, output_cap: int | None) -> CheckResult:
        result = super().check_parse(text, output_cap)
        for index, row in enumerate(self.plan.trajectory_rows()):
            k = row[-1]
            if not (k >= 1 and k == int(k)):
                line = self.line_of(index)
                raise self.fail("parse",
                                PARSE_ERROR, f"line {line}: K = {k!r} (the last number) is "
                                "not a positive integer", line)
        return result

    def angle_violation(self, state) -> str | None:
        """An angle printed larger than the problem's numbers may be (angle
        differences past it could overflow), or None."""
        from planning_core.kinoplan import MAX_MAGNITUDE  # (loaded with a kinoplan problem)
        for i, name in self.angles:
            if abs(state[i]) > MAX_MAGNITUDE:
                return (f"{name} = {state[i]!r} is larger than {MAX_MAGNITUDE:g} in magnitude "
                        "(an angle may be printed in any turn within it)")
        return None

    def row_violation(self, row) -> str | None:
        """Why a trajectory line is out of bounds (state, angle turns, control), or None."""
        system, n = self.system, self.n
        return (system.bounds_violation(row[:n]) or self.angle_violation(row)
                or system.control_violation(row[n:]))

    def check_bounds(self) -> CheckResult:
        for index, row in enumerate(self.plan.trajectory_rows()):
            why = self.row_violation(row)
            if why is not None:
                line = self.line_of(index)
                raise self.fail("bounds",
                                OUT_OF_BOUNDS, f"line {line}: {why}", line, self.where(row))
        return self.passed("bounds")

    def check_start(self) -> CheckResult:
        row = self.plan.trajectory_row(0)[:self.n]
        start, line = self.pdef.start, self.line_of(0)
        gaps = _gaps(self.si.space, row, start)
        if not all(gap <= KINOPLAN_TOLERANCE for gap in gaps):
            name = self.system.state_names[max(range(self.n), key=gaps.__getitem__)]
            raise self.fail("start",
                            NOT_AT_START, f"line {line}: first state {_angle(*row)}, start "
                            f"{_angle(*start)} ({name} is {_num(max(gaps))} off; tolerance "
                            f"{KINOPLAN_TOLERANCE:g} per variable, angles modulo 2 pi)", line,
                            self.where(row))
        return self.passed("start")

    def check_goal(self) -> CheckResult:
        plan, goal = self.plan, self.pdef.goal
        last = plan.trajectory_count - 1
        row, line = plan.trajectory_row(last), self.line_of(last)
        self._slice_budget_or_fail("goal",
                                   int(row[-1]), 1, "the last line holds its control", line)
        slices = self._slices_or_fail("goal", LAST_EDGE_COLLISION, row, line)
        self.last_slices = slices
        end = self.final_state = slices[-1]
        distance = goal.distance(end)
        if not goal.accepts(end):
            raise self.fail("goal", NOT_AT_GOAL, f"line {line}: the last line's control "
                            f"{_angle(*row[self.n:])} ends at {_angle(*end)}, {_num(distance)} "
                            f"from the goal ({', '.join(goal.names)} within {goal.tolerance:g})",
                            line, self.where(end))
        return self.passed("goal", f"ends {_num(distance)} from the goal")

    # collision and dynamics: within the slice budget, then as the spaceship's
    def check_kinodynamic_motion(self) -> tuple[CheckResult, CheckResult]:
        plan = self.plan
        fields, lines = plan.trajectory_fields, plan.trajectory_count
        slices = int(sum(plan.trajectory[fields - 1::fields]))
        self._slice_budget_or_fail("collision",
                                   slices, lines, f"the trajectory's {lines} lines hold "
                                   "their controls", plan.trajectory_first_line)
        return super().check_kinodynamic_motion()

    def _motion(self, index: int, row, line: int) -> tuple[tuple, float]:
        """A line's end state and its metric length over its slices."""
        if not self.si.is_valid(row[:self.n]):
            raise self.fail("collision", SPACESHIP_COLLISION, f"line {line}: state "
                            f"{self.invalid_place(row)}", line, self.where(row))
        last = index == self.plan.trajectory_count - 1
        slices = (self.last_slices if last and self.last_slices
                  else self._slices_or_fail("collision", SPACESHIP_COLLISION, row, line))
        distance, state, length = self.si.space.distance, row[:self.n], 0.0
        for sliced in slices:
            length += distance(state, sliced)
            state = sliced
        return slices[-1], length


class _GeometricValidation(_KinoplanValidation):
    """SPEC 5.5's checks for a geometric ``kinoplan 1`` answer (arm2, rigid2): a
    path of configurations, each straight segment checked at the system's
    ``motion_samples`` (``-strict``: ten times denser). Six checks, no dynamics."""

    def other_answer_hint(self, error: PlanParseError) -> str:
        names = " ".join(self.system.state_names)
        return (f" ({self.system.name}: {self.n} numbers a trajectory line, {names}; "
                f"{2 * self.n} a tree line)")

    # parse: only the widths (no K)
    check_parse = _Validation.check_parse

    def row_violation(self, row) -> str | None:
        """A configuration line: its bounds and angle turns (it holds no control)."""
        return self.system.bounds_violation(row) or self.angle_violation(row)

    # goal: the last configuration itself
    def check_goal(self) -> CheckResult:
        goal, last = self.pdef.goal, self.plan.trajectory_count - 1
        end, line = self.plan.trajectory_row(last), self.line_of(last)
        distance = goal.distance(end)
        if not goal.accepts(end):
            raise self.fail("goal", NOT_AT_GOAL, f"line {line}: the last configuration "
                            f"{_angle(*end)} is {_num(distance)} from the goal "
                            f"({', '.join(goal.names)} within {goal.tolerance:g})", line,
                            self.where(end))
        self.final_state = end
        return self.passed("goal", f"ends {_num(distance)} from the goal")

    def _segments(self):
        """``(index of the segment's first line, from, to)`` for each segment."""
        rows = self.plan.trajectory_rows()
        previous = next(rows)
        for index, row in enumerate(rows):
            yield index, previous, row
            previous = row

    def _sample_count(self) -> int:
        """Samples check 6 will test (each segment's ``n``, plus the first state);
        fails with TOO_LONG past the limit before any is tested."""
        system, distance = self.system, self.system.distance
        scale = (10.0 if self.strict else 1.0) / system.check
        count, length = 1, 0.0
        for _, a, b in self._segments():
            d = distance(a, b)
            length += d
            count += max(1, math.ceil(d * scale))
        self.path_length = length
        cap, where = self.capped(self.limits.max_motion_samples)
        if count > cap:
            raise self.fail("collision",
                            TOO_LONG, f"the path's segments make {count} samples at the "
                            f"check step {system.check:g}{' (-strict)' if self.strict else ''};"
                            f" the validator tests at most {cap}{where}",
                            self.plan.trajectory_first_line)
        return count

    # collision: every sample of every segment
    def check_geometric_motion(self) -> CheckResult:
        is_valid, samples = self.si.is_valid, self.system.motion_samples
        count = self._sample_count()
        first = self.plan.trajectory_row(0)
        if not is_valid(first):
            line = self.line_of(0)
            raise self.fail("collision", POINT_COLLISION, f"line {line}: configuration "
                            f"{self.invalid_place(first)}", line, self.where(first))
        for index, a, b in self._segments():
            states = samples(a, b, strict=self.strict)
            for k in range(1, len(states)):
                if not is_valid(states[k]):
                    line = self.line_of(index)
                    raise self.fail("collision", POINT_COLLISION, f"segment from line {line} "
                                    f"{_angle(*a)} to line {line + 1} {_angle(*b)}: sample "
                                    f"{k} of {len(states) - 1} {self.invalid_place(states[k])}",
                                    line, self.where(states[k]))
        density = " (-strict: ten times denser)" if self.strict else ""
        return self.passed("collision",
                           f"{self.plan.trajectory_count - 1} segments, {count} samples at "
                              f"most {self.system.check:g} apart{density}")

    def motion_checks(self) -> tuple[CheckResult, ...]:
        return (self.check_geometric_motion(),)


def validate_output(problem: Problem, vehicle: Vehicle | str, output_text: str,
                    strict: bool = False, limits: Limits = Limits(),
                    output_cap_exceeded: int | None = None) -> ValidationReport:
    """Run checks 1 to 7 of SPEC 3 on a planner's output for a ``.sw`` problem
    and the named vehicle (:func:`validate_plan` over its SpaceInformation)."""
    return validate_plan(grid_setup(problem, vehicle), output_text, strict,
                         limits, output_cap_exceeded)


def prepare(setup: Setup) -> None:
    """Do now what :func:`validate_plan` on ``setup`` would do first whatever the
    answer: the validator calls it while the planner runs."""
    compile_row_patterns(*row_widths(setup.system))


def validate_plan(setup: Setup, output_text: str, strict: bool = False,
                  limits: Limits = Limits(),
                  output_cap_exceeded: int | None = None) -> ValidationReport:
    """Run checks 1 to 7 of SPEC 3 on a planner's output.

    ``strict``: a point segment that cuts a blocked cell's corner between samples
    fails check 6 instead of giving a warning. ``output_cap_exceeded``: the cap in
    bytes, when the planner's output was cut off at it (check 1 then fails).
    Never raises on any text.
    """
    if not setup.family:
        validation = _Validation
    else:
        validation = _KinoplanValidation if setup.system.kinodynamic else _GeometricValidation
    run = validation(setup, strict, limits)
    checks = run.run(output_text, output_cap_exceeded)
    report = ValidationReport(setup.system, strict, checks, run.warnings, run.corner_cuts,
                              run.plan, run.path_length, run.final_state,
                              cost_kind="duration" if setup.rows_end_in_count else "length")
    if not report.valid:
        return report
    if hasattr(setup.system, "row_names"):  # rows sample curves (the Dubins car): their polyline
        report.cost = run.path_length
    else:
        report.cost = answer_cost(setup.si, run.plan, run.final_state)
    return report


def answer_cost(si, plan: PlanArrays, final_state) -> float:
    """A valid answer's cost as the optimizing planners count it
    (:func:`planning_core.costs.path_cost`: a geometric system's length, a ship's
    polyline through its printed positions, a family system's duration)."""
    rows = list(plan.trajectory_rows())
    if not si.system.kinodynamic:
        return path_cost(si, rows)
    dims = len(si.system.state_names)
    states = [row[:dims] for row in rows] + [tuple(final_state)]
    return path_cost(si, states, [row[dims:] for row in rows])
