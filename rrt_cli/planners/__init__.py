"""Planners, by the name ``-planner`` takes.

Each planner module has a frozen params dataclass and
``solve(problem, vehicle, stop, rng, params) -> PlanResult``. Modules are
imported on first use so that start-up only pays for the planner it runs.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass

from planning_core.vehicles import Vehicle

_POINT = frozenset({Vehicle.POINT})
_SPACESHIPS = frozenset({Vehicle.SPACESHIP, Vehicle.LEFT_SPACESHIP})
_ALL = _POINT | _SPACESHIPS


@dataclass(frozen=True)
class PlannerEntry:
    module: str
    vehicles: frozenset
    summary: str

    def load(self):
        return importlib.import_module(self.module)


PLANNERS: dict[str, PlannerEntry] = {
    "kpiece": PlannerEntry("rrt_cli.planners.kpiece", _SPACESHIPS,
                           "KPIECE1, interior-exterior cell exploration (Sucan & Kavraki 2012)"),
    "rgrrt": PlannerEntry("rrt_cli.planners.rgrrt", _SPACESHIPS,
                          "reachability-guided RRT (Shkolnik, Walter & Tedrake 2009)"),
    "rrt": PlannerEntry("rrt_cli.planners.rrt", _ALL, "RRT, the course's reference planner"),
    "rrtconnect": PlannerEntry("rrt_cli.planners.rrtconnect", _POINT,
                               "bidirectional RRT-Connect (Kuffner & LaValle 2000)"),
    "prm": PlannerEntry("rrt_cli.planners.prm", _POINT,
                        "probabilistic roadmap, k nearest, A* query (Kavraki et al. 1996)"),
    "prmstar": PlannerEntry("rrt_cli.planners.prmstar", _POINT,
                            "PRM*, k = e(1 + 1/d) log n (Karaman & Frazzoli 2011)"),
}
