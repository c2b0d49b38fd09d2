"""Our grid problems solved with OMPL's Python bindings (``pip install ompl``, 2.x),
written as an OMPL user in Python would write them: Python callbacks for state
validity and (spaceship) state propagation, OMPL's own planners and motion checks.

* Point vehicle: ``R^2`` bounded by the map; the validity callback is the grid
  point test; OMPL's DiscreteMotionValidator checks motions every 0.05 map units
  (resolution = 0.05 / the space's maximum extent), both ends included, as the
  course checker does. Planners: geometric RRT (goal bias 0.05) and RRT-Connect,
  with OMPL's default range (a fifth of the map's diagonal). Goal: the goal
  point, radius 0.1.
* Spaceships: ``R^4`` ``(x, y, dx, dy)``, velocities bounded by
  ``velocity_bound`` for sampling only; controls ``(theta, s)`` in
  ``[0, 2 pi) x [0, 0.5]`` (``[0, pi)`` for the left-only ship). The
  propagator runs planning_core's 20-slice integration for exactly one step
  (``setMinMaxControlDuration(1, 1)``, step size 1); a slice that collides
  makes the step's end state invalid (OMPL checks only end states, so the
  propagator says so by moving the state off the map). Planners: control RRT
  (goal bias 0.05) and KPIECE1 (its default goal bias is 0.05; states
  projected on their position, as OMPL's car demos do). Goal: within 0.1 of the goal point, any velocity.

OMPL's random generator is process-global: :func:`solve` seeds it, and the seed
only takes effect in a process that has not drawn from it yet (OMPL's rule), so
run one solve per process for reproducible runs (``ompl_planner.py`` does).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

from planning_core.problem import Problem
from planning_core.systems import spaceship
from planning_core.vehicles import Vehicle
from planning_core.worlds.grid import GridWorld

POINT_PLANNERS = ("rrt", "rrtconnect")
SPACESHIP_PLANNERS = ("rrt", "kpiece1")
OPTIMIZING_PLANNERS = ("rrtstar", "informed")
"""OMPL's RRT* and Informed RRT* (point vehicle, arm2, rigid2): run by the ``optimal*``
presets only, with ``-optimize`` (the other presets time first solutions)."""


@dataclass(frozen=True)
class OmplParams:
    goal_bias: float = 0.05
    """Probability of sampling the goal (RRT; KPIECE1's default is the same)."""
    goal_radius: float = 0.1
    """A state whose position is this close to the goal point solves the problem."""
    motion_check_step: float = 0.05
    """Point vehicle: largest gap between two checked states on a motion (map units)."""
    velocity_bound: float = 1.0
    """Spaceship: |dx|, |dy| bound of the sampled states (not a constraint on the ship)."""
    kpiece_cell_size: float = 0.5
    """KPIECE1 projects states on their position, in square cells this wide (map units;
    docs/benchmarks.md says why 0.5)."""


@dataclass(frozen=True)
class OmplResult:
    """Rows as in our output format (SPEC 2), and the run's statistics."""

    solved: bool
    status: str                 # OMPL's status text, e.g. "Exact solution", "Timeout"
    trajectory: tuple[tuple[float, ...], ...]
    tree: tuple[tuple[float, ...], ...]
    iterations: int             # planner loop iterations (termination-condition polls)
    tree_nodes: int
    planning_seconds: float
    improvements: tuple[tuple[float, float], ...] = ()
    """An optimizing planner's (planning seconds, best cost) at each improvement."""


def planners_for(vehicle: Vehicle) -> tuple[str, ...]:
    return SPACESHIP_PLANNERS if vehicle.is_spaceship else POINT_PLANNERS + OPTIMIZING_PLANNERS


def ompl_seed(seed: int) -> int:
    """OMPL seeds are 32-bit and must not be 0."""
    return seed % 0xFFFFFFFF + 1


def ompl_modules(planner: str, planners: tuple[str, ...], what: str, seed: int):
    """OMPL's base, control and geometric modules, its generator seeded and its log
    silenced, once ``planner`` is known to be one of ``planners`` (set up for ``what``)."""
    if planner not in planners:
        raise ValueError(f"OMPL planner {planner!r} is not set up for the "
                         f"{what} (choose from {planners})")
    from ompl import base as ob, control as oc, geometric as og, util as ou
    ou.RNG.setSeed(ompl_seed(seed))
    ou.setLogLevel(ou.LOG_NONE)
    return ob, oc, og


_OMPL_CLASSES = {"rrt": "RRT", "rrtconnect": "RRTConnect", "kpiece1": "KPIECE1", "prm": "PRM"}


def ompl_planner(module, planner: str, info, goal_bias: float):
    """OMPL's ``planner`` from ``module`` (geometric or control) on ``info``; RRT with
    ``goal_bias`` (the others keep OMPL's defaults)."""
    chosen = getattr(module, _OMPL_CLASSES[planner])(info)
    if planner == "rrt":
        chosen.setGoalBias(goal_bias)
    return chosen


def geometric_tree(ob, info, setup, get) -> tuple[int, tuple[tuple[float, ...], ...]]:
    """The planner data's vertex count and its edges as lines (parent, child), each
    state read by ``get``."""
    data = ob.PlannerData(info)
    setup.getPlannerData(data)
    tree = []
    for v in range(data.numVertices()):
        parent = get(data.getVertex(v).getState())
        tree.extend(parent + get(data.getVertex(child).getState()) for child in data.getEdges(v))
    return data.numVertices(), tuple(tree)


def solve(problem: Problem, vehicle: Vehicle, planner: str, time_limit: float, seed: int,
          params: OmplParams = OmplParams(), optimize: bool = False) -> OmplResult:
    """Plan with OMPL; ``planner`` is one of :func:`planners_for` ``(vehicle)``."""
    ob, oc, og = ompl_modules(planner, planners_for(vehicle), f"{vehicle.value} vehicle", seed)
    if vehicle.is_spaceship:
        return _solve_spaceship(ob, oc, problem, vehicle, planner, time_limit, params)
    return _solve_point(ob, og, problem, planner, time_limit, params, optimize)


class Termination:
    """A termination condition that counts planner iterations and keeps the clock; with
    ``best_cost`` (a function giving the planner's best cost so far), it also notes
    each improvement's time since ``began`` as OMPL's Benchmark samples the ``best
    cost`` progress property (which the bindings do not expose), at every poll."""

    def __init__(self, time_limit: float, best_cost=None, began: float | None = None):
        self.began = time.perf_counter() if began is None else began
        self.deadline = time.perf_counter() + time_limit
        self.polls = 0
        self.best_cost = best_cost
        self.improvements: list[tuple[float, float]] = []

    def __call__(self) -> bool:
        self.polls += 1
        now = time.perf_counter()
        if self.best_cost is not None:
            cost = self.best_cost()
            if math.isfinite(cost) and (not self.improvements or cost < self.improvements[-1][1]):
                self.improvements.append((now - self.began, cost))
        return now >= self.deadline


def optimizing_planner(ob, og, info, setup, name: str, objective, optimize: bool):
    """OMPL's RRT* or Informed RRT* (its defaults: k-nearest rewiring, goal bias 0.05)
    minimizing ``objective``: until the time limit with ``optimize``, else until its
    first solution (a cost threshold of infinity is met by any solution)."""
    objective.setCostThreshold(ob.Cost(0.0 if optimize else math.inf))
    setup.setOptimizationObjective(objective)
    return (og.RRTstar if name == "rrtstar" else og.InformedRRTstar)(info)


def solve_with(ob, setup, planner, time_limit: float, timed: bool = False,
               began: float | None = None):
    """``planner`` on ``setup`` until ``time_limit``: (status, termination, solved).
    ``timed``: OMPL's own timer instead of our counting condition (0 polls). An
    optimizing planner's improvements are noted (:class:`Termination`)."""
    setup.setPlanner(planner)
    best = getattr(planner, "bestCost", None)  # RRT* and Informed RRT*
    termination = Termination(time_limit, best and (lambda: best().value()), began)
    condition = (ob.timedPlannerTerminationCondition(time_limit) if timed
                 else ob.PlannerTerminationCondition(termination))
    status = setup.solve(condition)
    return status, termination, setup.haveExactSolutionPath()


def make_bounds(ob, lows, highs):
    bounds = ob.RealVectorBounds(len(lows))
    for index, (low, high) in enumerate(zip(lows, highs)):
        bounds.setLow(index, low)
        bounds.setHigh(index, high)
    return bounds


def _solve_point(ob, og, problem: Problem, planner: str, time_limit: float,
                 params: OmplParams, optimize: bool) -> OmplResult:
    began = time.perf_counter()
    world = GridWorld(problem)
    space = ob.RealVectorStateSpace(2)
    space.setBounds(make_bounds(ob, (0.0, 0.0), (float(problem.width), float(problem.height))))
    info = ob.SpaceInformation(space)
    point_free = world.point_free

    def is_valid(state) -> bool:
        x, y = state[0], state[1]
        # Printed points must lie strictly inside the map (SPEC 2).
        return x > 0.0 and y > 0.0 and point_free(x, y)

    info.setStateValidityChecker(is_valid)
    info.setStateValidityCheckingResolution(params.motion_check_step / space.getMaximumExtent())
    info.setup()
    setup = og.SimpleSetup(info)
    start, goal = space.allocState(), space.allocState()
    start[0], start[1] = problem.start
    goal[0], goal[1] = problem.goal
    setup.setStartAndGoalStates(start, goal, inside(params.goal_radius))
    if planner in OPTIMIZING_PLANNERS:  # OMPL's path length is our cost here
        chosen = optimizing_planner(ob, og, info, setup, planner,
                                    ob.PathLengthOptimizationObjective(info), optimize)
    else:
        chosen = ompl_planner(og, planner, info, params.goal_bias)
    status, termination, solved = solve_with(ob, setup, chosen, time_limit, began=began)
    trajectory = ()
    if solved:
        trajectory = tuple((s[0], s[1]) for s in setup.getSolutionPath().getStates())
    vertices, tree = geometric_tree(ob, info, setup, lambda s: (s[0], s[1]))
    return OmplResult(solved, status.asString(), trajectory, tree, termination.polls,
                      vertices, time.perf_counter() - began, tuple(termination.improvements))


def inside(radius: float) -> float:
    # A hair inside the radius, so that a checker recomputing the distance with
    # other rounding still finds the end within it.
    return radius * (1.0 - 1e-9)


def _solve_spaceship(ob, oc, problem: Problem, vehicle: Vehicle, planner: str,
                     time_limit: float, params: OmplParams) -> OmplResult:
    began = time.perf_counter()
    width, height = problem.width, problem.height
    blocked = list(problem.blocked)
    v = params.velocity_bound
    space = ob.RealVectorStateSpace(4)
    space.setBounds(make_bounds(ob, (0.0, 0.0, -v, -v), (float(width), float(height), v, v)))
    theta_range = vehicle.system.theta_range  # 2 pi, or pi for the left-only ship
    controls = oc.RealVectorControlSpace(space, 2)
    # OMPL samples [low, high]; theta_range itself (2 pi or pi) is drawn with
    # probability zero and is a legal angle anyway.
    controls.setBounds(make_bounds(ob, (0.0, 0.0), (theta_range, spaceship.MAX_THRUST)))
    info = oc.SpaceInformation(space, controls)
    propagate_while = spaceship.SYSTEM.propagate_while
    grid = GridWorld(problem)
    tree: list[tuple[float, ...]] = []

    def is_valid(state) -> bool:
        x, y = state[0], state[1]
        return 0.0 < x < width and 0.0 < y < height and not blocked[int(y) * width + int(x)]

    def propagate(start, control, duration, result) -> None:
        # duration is always one step of 1.0 (setMinMaxControlDuration(1, 1)).
        state = (start[0], start[1], start[2], start[3])
        applied = (control[0], control[1])
        end = propagate_while(state, applied, grid)
        if end is None or not (end[0] > 0.0 and end[1] > 0.0):
            result[0], result[1], result[2], result[3] = -1.0, -1.0, 0.0, 0.0  # invalid
            return
        result[0], result[1], result[2], result[3] = end
        # Valid one-step motions are exactly the edges RRT and KPIECE1 add.
        tree.append(state + applied)

    if planner == "kpiece1":
        cell = params.kpiece_cell_size
        space.registerDefaultProjection(
            ob.RealVectorOrthogonalProjectionEvaluator(space, [cell, cell], [0, 1]))
    info.setStateValidityChecker(is_valid)
    info.setStatePropagator(propagate)
    info.setPropagationStepSize(1.0)
    info.setMinMaxControlDuration(1, 1)
    info.setup()
    setup = oc.SimpleSetup(info)
    start = space.allocState()
    start[0], start[1], start[2], start[3] = problem.start[0], problem.start[1], 0.0, 0.0
    setup.setStartState(start)
    setup.setGoal(_position_goal(ob, info, problem.goal, inside(params.goal_radius)))
    chosen = ompl_planner(oc, planner, info, params.goal_bias)
    status, termination, solved = solve_with(ob, setup, chosen, time_limit)
    trajectory = ()
    if solved:
        path = setup.getSolutionPath()
        trajectory = _replay(problem, [(c[0], c[1]) for c in path.getControls()],
                             path.getControlDurations())
    return OmplResult(solved, status.asString(), trajectory, tuple(tree), termination.polls,
                      len(tree) + 1, time.perf_counter() - began)


def _replay(problem: Problem, controls, durations) -> tuple[tuple[float, ...], ...]:
    """Trajectory lines re-propagated from the start with OMPL's controls."""
    state = (problem.start[0], problem.start[1], 0.0, 0.0)
    lines = []
    for control, duration in zip(controls, durations):
        for _ in range(max(1, round(duration))):  # one line per step held
            lines.append(state + tuple(control))
            state = spaceship.SYSTEM.propagate(state, control)
    if not lines:
        lines.append(state + (0.0, 0.0))  # started in the goal: zero thrust stays there
    return tuple(lines)


def _position_goal(ob, info, goal: tuple[float, float], radius: float):
    """Within ``radius`` of the goal point at any velocity; samples the goal at rest."""
    gx, gy = goal

    class PositionGoal(ob.GoalSampleableRegion):
        def distanceGoal(self, state) -> float:
            return math.hypot(state[0] - gx, state[1] - gy)

        def sampleGoal(self, state) -> None:
            state[0], state[1], state[2], state[3] = gx, gy, 0.0, 0.0

        def maxSampleCount(self) -> int:
            return 1

    region = PositionGoal(info)
    region.setThreshold(radius)
    return region
