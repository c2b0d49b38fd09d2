"""What the harness can run: our planners (from rrt_cli's registry) and OMPL's.

Our planners are read from ``rrt_cli.planners.PLANNERS``, so a planner added
there appears here without a change. OMPL's appear when the ``ompl`` package
can be imported.
"""

from __future__ import annotations

import importlib.util
import sys
from dataclasses import dataclass
from pathlib import Path

from planning_core.vehicles import Vehicle

ROOT = Path(__file__).resolve().parent.parent
VEHICLE_FLAGS = {vehicle: vehicle.flags for vehicle in Vehicle}
OMPL_PREFIX = "ompl-"
OMPL_CPP_PREFIX = "ompl-cpp-"
"""OMPL in C++ (benchmarks/ompl_cpp_planner.py): ``ompl-cpp-rrtstar``, ..."""


@dataclass(frozen=True)
class PlannerChoice:
    """One planner as the harness runs it."""

    id: str                   # "rrt" (ours), "ompl-rrt", "blossom-b1", ...
    implementation: str       # "ours" | "ompl" (Python bindings) | "ompl-cpp" (C++)
    cli_name: str             # the value of -planner
    vehicles: frozenset
    systems: frozenset = frozenset()
    """The kinoplan family systems (SPEC 5) it plans for, by name."""
    params: tuple[str, ...] = ()
    """``NAME=VALUE`` overrides of our planner's ``Params`` (run through
    ``benchmarks.planner_params``), e.g. ``("b=1",)`` for blossom."""
    optimize: bool = False
    """Run with ``-optimize``: keep improving until the time limit (the ``optimal*``
    presets; the other presets time every planner to its first solution)."""

    def command(self, vehicle: Vehicle | None, seed: int, time_limit: float) -> list[str]:
        """The planner's command line; ``vehicle`` None for a kinoplan problem."""
        if self.implementation == "ompl":
            head = ["benchmarks.ompl_planner"]
        elif self.implementation == "ompl-cpp":
            head = ["benchmarks.ompl_cpp_planner"]
        else:
            head = ["benchmarks.planner_params", *self.params] if self.params else ["rrt_cli"]
        flags = VEHICLE_FLAGS[vehicle] if vehicle is not None else ()
        return [sys.executable, "-m", *head, *flags, "-planner", self.cli_name, "-seed",
                str(seed), "-time", repr(float(time_limit)), "-stats",
                *(("-optimize",) if self.optimize else ())]


GEOMETRIC_SYSTEMS = ("arm2", "rigid2")
KINODYNAMIC_SYSTEMS = ("pendulum", "car2", "unicycle", "car1")
FAMILY_SYSTEMS = KINODYNAMIC_SYSTEMS + GEOMETRIC_SYSTEMS
BLOSSOM_VARIANTS = (1, 3)
"""Blossom's b besides its default (5), as planners ``blossom-b1`` and ``blossom-b3``."""


def label(planner_id: str, vehicle: str) -> str:
    """A planner's name in tables, plots and OMPL logs."""
    if not planner_id.startswith(OMPL_PREFIX):
        return f"{planner_id} (ours)"
    cpp = planner_id.startswith(OMPL_CPP_PREFIX)
    name = planner_id[len(OMPL_CPP_PREFIX if cpp else OMPL_PREFIX):]
    kind = ("geometric" if vehicle in (Vehicle.POINT.value, *GEOMETRIC_SYSTEMS)
            else "control")
    named = {"rrt": f"OMPL {kind} RRT", "rrtconnect": "OMPL RRTConnect",
             "kpiece1": "OMPL control KPIECE1", "prm": "OMPL PRM", "rrtstar": "OMPL RRT*",
             "informed": "OMPL Informed RRT*", "sst": "OMPL SST"}.get(name)
    if named is None:
        return planner_id
    return named.replace("OMPL", "OMPL C++", 1) if cpp else named


def ompl_installed() -> bool:
    try:
        return importlib.util.find_spec("ompl") is not None
    except (ImportError, ValueError):
        return False


def our_planners() -> list[PlannerChoice]:
    from rrt_cli.planners import PLANNERS
    return [PlannerChoice(name, "ours", name,
                          frozenset(v for v in Vehicle if entry.plans_for(v.system)))
            for name, entry in sorted(PLANNERS.items())]


def ompl_planners() -> list[PlannerChoice]:
    from benchmarks.ompl_adapters import POINT_PLANNERS, SPACESHIP_PLANNERS
    point = frozenset({Vehicle.POINT})
    ships = frozenset({Vehicle.SPACESHIP, Vehicle.LEFT_SPACESHIP})
    names = sorted(set(POINT_PLANNERS) | set(SPACESHIP_PLANNERS))
    return [PlannerChoice(OMPL_PREFIX + name, "ompl", name,
                          (point if name in POINT_PLANNERS else frozenset())
                          | (ships if name in SPACESHIP_PLANNERS else frozenset()))
            for name in names]


def all_planners(include_ompl: bool = True) -> list[PlannerChoice]:
    planners = our_planners()
    if include_ompl and ompl_installed():
        planners += ompl_planners()
    return planners


def reference_planner(vehicle: Vehicle) -> str:
    """The OMPL planner our times are compared with: RRT (geometric or control)."""
    del vehicle  # ompl-rrt is geometric RRT for the point, control RRT for ships
    return OMPL_PREFIX + "rrt"


def family_planners(include_ompl: bool = True) -> list[PlannerChoice]:
    """Every planner that plans for some kinoplan family system: ours as the registry
    says (``plans_for_kinoplan``), blossom also at each of ``BLOSSOM_VARIANTS``, and
    OMPL's (``benchmarks.ompl_family``)."""
    from planning_core.systems import load
    from rrt_cli.planners import PLANNERS
    systems = {name: load(name) for name in FAMILY_SYSTEMS}
    planners = []
    for name, entry in sorted(PLANNERS.items()):
        mine = frozenset(s for s, system in systems.items() if entry.plans_for_kinoplan(system))
        if mine:
            planners.append(PlannerChoice(name, "ours", name, frozenset(), mine))
            if name == "blossom":
                planners += [PlannerChoice(f"blossom-b{b}", "ours", name, frozenset(), mine,
                                           (f"b={b}",)) for b in BLOSSOM_VARIANTS]
    if include_ompl and ompl_installed():
        from benchmarks.ompl_family import GEOMETRIC_PLANNERS, KINODYNAMIC_PLANNERS
        for name in sorted(set(GEOMETRIC_PLANNERS) | set(KINODYNAMIC_PLANNERS)):
            mine = frozenset((KINODYNAMIC_SYSTEMS if name in KINODYNAMIC_PLANNERS else ())
                             + (GEOMETRIC_SYSTEMS if name in GEOMETRIC_PLANNERS else ()))
            planners.append(PlannerChoice(OMPL_PREFIX + name, "ompl", name, frozenset(), mine))
    return planners
