"""Named subsets of the suite: which problems, vehicles, seeds and time limits.

* ``smoke``: the course problems, one seed (for trying the tool).
* ``quick``: every family up to 50x50 for the point vehicle (but maze-50; plus the
  open and narrow 500x500 maps) and up to 20x20 for the spaceship (but maze-20) and
  up to 10x10 for the left-only ship (but maze-10), the course problems, 3 seeds.
* ``course``: the README's planner table: the course problems and the
  200x200 random field, all three vehicles, 5 seeds; 30 s (point) and 60 s
  (ships) limits. Run it with ``--planners rrt``.
* ``sweep``: every problem up to 100x100 and the course problems, all three
  vehicles, 20 seeds, 30 s limit (the planner's default); run it with
  ``--planners`` and ``--vehicles`` in parts.
* ``full``: every problem to 500x500 for the point vehicle (10 s limit), to
  200x200 for the spaceship (120 s) and to 50x50 for the left-only ship (30 s),
  10 seeds (5 for the ships).
* ``grid-sweep``: issue 30's acceptance on the grid: the new planners (``NEW_PLANNERS``:
  sst for both ships; rrtstar and informed for the point; rrt, rrtconnect, rrtstar and
  informed for the Dubins car, radius 0.5) on every suite and course problem, 20 seeds,
  30 s to a first solution, every answer validated (the Dubins car's with its turning
  check). Narrow it with ``--seeds``, ``--max-size``, ``--problems``, ``--planners``.
* ``grid-optimize``: the same problems with sst, rrtstar and informed run with
  ``-optimize -time 5``: the best answer after 5 s, validated.

How long each takes on 2 cores: docs/benchmarks.md.
"""

from __future__ import annotations

import fnmatch
from dataclasses import dataclass
from pathlib import Path

from benchmarks.generator import PROBLEMS_DIR, problem_id, suite_files
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle


@dataclass(frozen=True)
class VehiclePlan:
    """The problems one vehicle runs on in a preset, and its time limit."""

    vehicle: Vehicle
    time_limit: float
    max_size: int
    seeds: int
    patterns: tuple[str, ...] = ("*",)
    """Problem names (as in reports: file stem, or course-<stem>; shell patterns) to
    include, if within max_size."""
    extra: tuple[str, ...] = ()
    """Problem names included whatever their size."""
    exclude: tuple[str, ...] = ()
    """Problem names (shell patterns) left out."""
    planners: tuple[str, ...] = ()
    """Only these planners (harness ids) on this vehicle; empty: every one that plans for it."""


@dataclass(frozen=True)
class Preset:
    name: str
    plans: tuple[VehiclePlan, ...]
    optimize: bool = False
    """Run the optimizing planners with ``-optimize`` (to the time limit, then check the
    best answer); the others stop at their first solution."""


NEW_PLANNERS = {Vehicle.POINT: ("rrtstar", "informed"),
                Vehicle.DUBINS: ("rrt", "rrtconnect", "rrtstar", "informed"),
                Vehicle.SPACESHIP: ("sst",), Vehicle.LEFT_SPACESHIP: ("sst",)}
"""Issue 30's planners per grid vehicle: what ``grid-sweep`` runs."""
OPTIMIZING = ("sst", "rrtstar", "informed")


def _new_planners(time_limit: float, seeds: int, optimizing_only: bool = False
                  ) -> tuple[VehiclePlan, ...]:
    """Every problem of the suite and the course for each vehicle's new planners."""
    return tuple(VehiclePlan(vehicle, time_limit, 500, seeds, planners=tuple(
        p for p in planners if not optimizing_only or p in OPTIMIZING))
        for vehicle, planners in NEW_PLANNERS.items())


PRESETS = {
    "smoke": Preset("smoke", (
        VehiclePlan(Vehicle.POINT, 5.0, 10, 1, ("course-*",)),
        VehiclePlan(Vehicle.SPACESHIP, 10.0, 10, 1, ("course-simple-0", "course-space-0")),
    )),
    "quick": Preset("quick", (
        # maze-50 and maze-20 are left out: most runs there use their whole limit.
        VehiclePlan(Vehicle.POINT, 10.0, 50, 3, extra=("open-500", "narrow-500"),
                    exclude=("maze-50",)),
        VehiclePlan(Vehicle.SPACESHIP, 30.0, 20, 3, exclude=("maze-20",)),
        VehiclePlan(Vehicle.LEFT_SPACESHIP, 30.0, 10, 3, exclude=("maze-10",)),
    )),
    "course": Preset("course", (
        VehiclePlan(Vehicle.POINT, 30.0, 10, 5, ("course-*",), extra=("random-d20-200",)),
        VehiclePlan(Vehicle.SPACESHIP, 60.0, 10, 5, ("course-*",), extra=("random-d20-200",)),
        VehiclePlan(Vehicle.LEFT_SPACESHIP, 60.0, 10, 5, ("course-*",),
                    extra=("random-d20-200",)),
    )),
    "sweep": Preset("sweep", (
        VehiclePlan(Vehicle.POINT, 30.0, 100, 20),
        VehiclePlan(Vehicle.SPACESHIP, 30.0, 100, 20),
        VehiclePlan(Vehicle.LEFT_SPACESHIP, 30.0, 100, 20),
    )),
    "full": Preset("full", (
        VehiclePlan(Vehicle.POINT, 10.0, 500, 10),
        VehiclePlan(Vehicle.SPACESHIP, 120.0, 200, 5),
        VehiclePlan(Vehicle.LEFT_SPACESHIP, 30.0, 50, 5),
    )),
    "grid-sweep": Preset("grid-sweep", _new_planners(30.0, 20)),
    "grid-optimize": Preset("grid-optimize", _new_planners(5.0, 20, optimizing_only=True),
                            optimize=True),
}


ACCEPTANCE_PRESETS = ("grid-sweep", "grid-optimize")
"""Presets whose report leads with solved and validated counts per problem group."""


def problem_size(path: Path) -> int:
    """The larger side, read from the file's first two numbers."""
    with open(path) as handle:
        head = handle.read(64).split()
    try:
        return max(int(head[0]), int(head[1]))
    except (IndexError, ValueError):  # an unusual layout: let the real parser decide
        problem = parse_problem(path.read_text())
        return max(problem.width, problem.height)


def select_problems(plan: VehiclePlan, directory: Path = PROBLEMS_DIR) -> list[Path]:
    chosen = []
    for path in suite_files(directory):
        name = problem_id(path)
        wanted = any(fnmatch.fnmatchcase(name, pattern) for pattern in plan.patterns)
        if any(fnmatch.fnmatchcase(name, pattern) for pattern in plan.exclude):
            continue
        if (wanted and problem_size(path) <= plan.max_size) or name in plan.extra:
            chosen.append(path)
    return chosen
