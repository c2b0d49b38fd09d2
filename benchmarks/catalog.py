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
VEHICLE_FLAGS = {Vehicle.POINT: (), Vehicle.SPACESHIP: ("-grad",),
                 Vehicle.LEFT_SPACESHIP: ("-grad", "-left")}
OMPL_PREFIX = "ompl-"


@dataclass(frozen=True)
class PlannerChoice:
    """One planner as the harness runs it."""

    id: str                   # "rrt" (ours), "ompl-rrt", ...
    implementation: str       # "ours" | "ompl"
    cli_name: str             # the value of -planner
    vehicles: frozenset

    def command(self, vehicle: Vehicle, seed: int, time_limit: float) -> list[str]:
        module = "rrt_cli" if self.implementation == "ours" else "benchmarks.ompl_planner"
        return [sys.executable, "-m", module, *VEHICLE_FLAGS[vehicle], "-planner",
                self.cli_name, "-seed", str(seed), "-time", repr(float(time_limit)), "-stats"]


def label(planner_id: str, vehicle: str) -> str:
    """A planner's name in tables, plots and OMPL logs."""
    if not planner_id.startswith(OMPL_PREFIX):
        return f"{planner_id} (ours)"
    name = planner_id[len(OMPL_PREFIX):]
    kind = "geometric" if vehicle == Vehicle.POINT.value else "control"
    return {"rrt": f"OMPL {kind} RRT", "rrtconnect": "OMPL RRTConnect",
            "kpiece1": "OMPL control KPIECE1"}.get(name, planner_id)


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
