"""Planners, by the name ``-planner`` takes.

Each planner module has a frozen ``Params`` dataclass and
``solve(si, stop, rng, params) -> PlanResult`` over a
:class:`~planning_core.space_information.SpaceInformation`. A planner declares
the kinds of system it plans for (geometric, kinodynamic); modules are imported
on first use so that start-up only pays for the planner it runs.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass

GEOMETRIC = frozenset({"geometric"})
KINODYNAMIC = frozenset({"kinodynamic"})
ANY = GEOMETRIC | KINODYNAMIC


def system_kind(system) -> str:
    return "kinodynamic" if system.kinodynamic else "geometric"


@dataclass(frozen=True)
class PlannerEntry:
    """A planner's registry line: its module, what it plans for, one line about it."""

    module: str
    kinds: frozenset
    summary: str
    kinoplan: frozenset = frozenset()
    """The kinds of ``kinoplan 1`` system (SPEC 5) it plans for."""

    def load(self):
        return importlib.import_module(self.module)

    def plans_for(self, system) -> bool:
        return system_kind(system) in self.kinds

    def plans_for_kinoplan(self, system) -> bool:
        """A kinoplan system of a kind the planner says it plans for."""
        return system_kind(system) in self.kinoplan


PLANNERS: dict[str, PlannerEntry] = {
    "blossom": PlannerEntry("rrt_cli.planners.blossom", frozenset(),
                            "blossom RRT: b random controls held while valid (seed 004)",
                            kinoplan=KINODYNAMIC),
    "kpiece": PlannerEntry("rrt_cli.planners.kpiece", KINODYNAMIC,
                           "KPIECE1, interior-exterior cell exploration (Sucan & Kavraki 2012)",
                           kinoplan=KINODYNAMIC),
    "rgrrt": PlannerEntry("rrt_cli.planners.rgrrt", KINODYNAMIC,
                          "reachability-guided RRT (Shkolnik, Walter & Tedrake 2009)",
                          kinoplan=KINODYNAMIC),
    "rrt": PlannerEntry("rrt_cli.planners.rrt", ANY, "RRT, the course's reference planner",
                        kinoplan=ANY),
    "rrtconnect": PlannerEntry("rrt_cli.planners.rrtconnect", GEOMETRIC,
                               "bidirectional RRT-Connect (Kuffner & LaValle 2000)",
                               kinoplan=GEOMETRIC),
    "prm": PlannerEntry("rrt_cli.planners.prm", GEOMETRIC,
                        "probabilistic roadmap, k nearest, A* query (Kavraki et al. 1996)",
                        kinoplan=GEOMETRIC),
    "prmstar": PlannerEntry("rrt_cli.planners.prmstar", GEOMETRIC,
                            "PRM*, k = e(1 + 1/d) log n (Karaman & Frazzoli 2011)",
                            kinoplan=GEOMETRIC),
}
