"""The ``optimal*`` presets: cost against time for the optimizing planners, ours and
OMPL's side by side on the same problems, seeds and budget.

Every run is one ``-optimize`` run of the preset's time limit; its progress line gives
the best cost at any time, so the costs at 1 s and at 10 s come from the same 10 s run
(``checkpoints``). Our planners come from the registry: an id it does not have (a
planner not merged yet), or one of OMPL's the bindings do not offer, is skipped with one
line on stderr, so the preset runs today and picks the planners up when they exist.

* ``optimal``: sst, rrtstar, informed (ours) and OMPL's SST, RRT*, Informed RRT* (its
  Python bindings, and C++ through benchmarks/ompl_cpp_planner.py) on the course maps and
  two small suite maps (point vehicle, both ships), arm2's five pairs, the rigid2 scenes
  and one problem of each kinodynamic family system; 20 seeds, 10 s.
* ``optimal-smoke``: one small point problem and one arm2 pair, 2 seeds, 2 s (tests).
"""

from __future__ import annotations

import fnmatch
import sys
from dataclasses import dataclass
from typing import Callable

from benchmarks.catalog import OMPL_CPP_PREFIX, OMPL_PREFIX, PlannerChoice, ompl_installed
from benchmarks.family import family_problems, system_of
from benchmarks.generator import problem_id
from benchmarks.harness import RunSpec
from benchmarks.presets import VehiclePlan, select_problems
from planning_core.vehicles import Vehicle

OURS = ("sst", "rrtstar", "informed")
OMPLS = tuple(OMPL_PREFIX + name for name in OURS)
OMPL_CPPS = tuple(OMPL_CPP_PREFIX + name for name in OURS)
OMPL_GAPS = {"ompl-sst": "OMPL's Python bindings (ompl 2.0) bind SST without a "
                         "constructor (OMPL's SST runs in C++: ompl-cpp-sst)"}
"""OMPL planners the preset names but cannot run, and why (said when skipped)."""


@dataclass(frozen=True)
class OptimalPreset:
    name: str
    planners: tuple[str, ...]
    """Harness ids, ours and OMPL's."""
    grid: tuple[VehiclePlan, ...]
    """Grid problems per vehicle (their time limits and seeds are the preset's)."""
    family: tuple[str, ...]
    """Family problem names (shell patterns) of ``benchmarks/problems/family``."""
    seeds: int
    time_limit: float
    checkpoints: tuple[float, ...]
    """Times (s) at which the report gives each planner's median cost."""


def _grid(vehicle: Vehicle, *names: str) -> VehiclePlan:
    return VehiclePlan(vehicle, 0.0, 10 ** 6, 0, names)


OPTIMAL_PRESETS = {
    "optimal": OptimalPreset(
        "optimal", OURS + OMPLS + OMPL_CPPS,
        (_grid(Vehicle.POINT, "course-*", "random-d20-20", "maze-10"),
         _grid(Vehicle.SPACESHIP, "course-*"), _grid(Vehicle.LEFT_SPACESHIP, "course-*")),
        ("arm2-pair*", "rigid2-scene*", "pendulum-t3", "car2-corridors", "unicycle-circles",
         "car1-scene1"),
        20, 10.0, (1.0, 10.0)),
    "optimal-smoke": OptimalPreset(
        "optimal-smoke", OURS + OMPLS + OMPL_CPPS, (_grid(Vehicle.POINT, "course-simple-0"),),
        ("arm2-pair1",), 2, 2.0, (1.0, 2.0)),
}


def optimal_planners(preset: OptimalPreset, include_ompl: bool,
                     say: Callable[[str], None] = lambda line: sys.stderr.write(line + "\n")
                     ) -> list[PlannerChoice]:
    """The preset's planners that can run here, each set to ``-optimize``; one line
    through ``say`` per planner skipped."""
    from rrt_cli.planners import PLANNERS
    from planning_core.systems import load
    from benchmarks.catalog import FAMILY_SYSTEMS
    systems = {name: load(name) for name in FAMILY_SYSTEMS}
    chosen = []
    for planner_id in preset.planners:
        if planner_id.startswith(OMPL_PREFIX):
            found = _ompl_choice(planner_id, include_ompl, say)
        else:
            entry = PLANNERS.get(planner_id)
            found = None
            if entry is None or not entry.optimizing:
                say(f"benchmarks: note: {planner_id}: no optimizing planner of that name in "
                    "rrt_cli's registry: skipped")
            else:
                found = PlannerChoice(
                    planner_id, "ours", planner_id,
                    frozenset(v for v in Vehicle if entry.plans_for(v.system)),
                    frozenset(s for s, system in systems.items()
                              if entry.plans_for_kinoplan(system)), optimize=True)
        if found is not None:
            chosen.append(found)
    return chosen


def _ompl_choice(planner_id: str, include_ompl: bool, say) -> PlannerChoice | None:
    if not include_ompl:
        return None
    if planner_id.startswith(OMPL_CPP_PREFIX):
        return _ompl_cpp_choice(planner_id, say)
    if planner_id in OMPL_GAPS:
        say(f"benchmarks: note: {planner_id}: {OMPL_GAPS[planner_id]}: skipped")
        return None
    if not ompl_installed():
        return None  # the command says so once for every OMPL planner
    from benchmarks.catalog import GEOMETRIC_SYSTEMS
    return PlannerChoice(planner_id, "ompl", planner_id[len(OMPL_PREFIX):],
                         frozenset({Vehicle.POINT}), frozenset(GEOMETRIC_SYSTEMS),
                         optimize=True)


def _ompl_cpp_choice(planner_id: str, say) -> PlannerChoice | None:
    """OMPL's planner in C++ (its programs built here, now, not in every worker): SST for
    the ships and the kinodynamic family, RRT* and Informed RRT* for the point vehicle,
    arm2 and rigid2."""
    from benchmarks.catalog import GEOMETRIC_SYSTEMS, KINODYNAMIC_SYSTEMS
    from benchmarks.ompl_cpp_programs import binary
    if binary("grid_ompl") is None or binary("family_ompl") is None:
        say(f"benchmarks: note: {planner_id}: the C++ programs could not be built (g++ and "
            "libompl-dev: apt-get install libompl-dev): skipped")
        return None
    name = planner_id[len(OMPL_CPP_PREFIX):]
    if name == "sst":
        vehicles, systems = {Vehicle.SPACESHIP, Vehicle.LEFT_SPACESHIP}, KINODYNAMIC_SYSTEMS
    else:
        vehicles, systems = {Vehicle.POINT}, GEOMETRIC_SYSTEMS
    return PlannerChoice(planner_id, "ompl-cpp", name, frozenset(vehicles), frozenset(systems),
                         optimize=True)


def optimal_specs(preset: OptimalPreset, planners: list[PlannerChoice], seeds: int,
                  time_limit: float, problems: tuple[str, ...] = (),
                  vehicles: tuple[str, ...] = ()) -> list[RunSpec]:
    """Every planner x problem it plans for x seed; ``problems`` (shell patterns) and
    ``vehicles`` (grid vehicles' names) narrow the preset's."""
    def wanted(name: str) -> bool:
        return not problems or any(fnmatch.fnmatchcase(name, p) for p in problems)

    specs = []
    for plan in preset.grid:
        if vehicles and plan.vehicle.value not in vehicles:
            continue
        for path in select_problems(plan):
            specs += [RunSpec(planner, plan.vehicle, path, seed, time_limit)
                      for planner in planners if plan.vehicle in planner.vehicles
                      and wanted(problem_id(path)) for seed in range(1, seeds + 1)]
    if vehicles:
        return specs
    for path in family_problems():
        if any(fnmatch.fnmatchcase(path.stem, p) for p in preset.family) and wanted(path.stem):
            system = system_of(path)
            specs += [RunSpec(planner, None, path, seed, time_limit) for planner in planners
                      if system in planner.systems for seed in range(1, seeds + 1)]
    return specs
