"""Planners, by the name ``-planner`` takes.

Each planner module has a frozen ``Params`` dataclass and
``solve(si, pdef, stop, rng, params) -> PlanResult``, asking only what the
protocols of :mod:`planning_core.space_information` declare. A planner declares
the kinds of system it plans for (geometric: straight motions; kinodynamic:
controls), on the grid and in the family alike; modules are imported on first use
so that start-up only pays for the planner it runs.
"""

from __future__ import annotations

import sys

GEOMETRIC = frozenset({"geometric"})
KINODYNAMIC = frozenset({"kinodynamic"})
ANY = GEOMETRIC | KINODYNAMIC


def system_kind(system) -> str:
    return "kinodynamic" if system.kinodynamic else "geometric"


class PlannerEntry:
    """A planner's registry line: its module, what it plans for, one line about it (a
    plain class, not a dataclass, as every record on the planner's start-up path)."""

    module: str
    kinds: frozenset
    """The kinds of system it plans for (GEOMETRIC, KINODYNAMIC, ANY)."""
    summary: str
    family_only: bool
    """It asks what only the family's space information answers (blossom: ``advance``)."""
    optimizing: bool
    """It keeps improving its answer when the problem has an objective (``-optimize``)."""
    directed: bool
    """It plans for systems whose motions are one-way (the Dubins car: the motion
    a -> b travelled back is not the motion b -> a); a roadmap that joins its
    vertices both ways does not."""

    def __init__(self, module: str, kinds: frozenset, summary: str, family_only: bool = False,
                 optimizing: bool = False, directed: bool = False) -> None:
        self.module, self.kinds, self.summary = module, kinds, summary
        self.family_only, self.optimizing, self.directed = family_only, optimizing, directed

    def __repr__(self) -> str:
        return f"PlannerEntry({self.module!r}, {sorted(self.kinds)!r}, {self.summary!r})"

    def load(self):
        __import__(self.module)  # (importlib.import_module: importlib imports warnings)
        return sys.modules[self.module]

    def plans_for(self, system) -> bool:
        """A grid vehicle (the course's point, ships, Dubins car) of a kind it plans for."""
        return (not self.family_only and system_kind(system) in self.kinds
                and (self.directed or not getattr(system, "directed", False)))

    def plans_for_kinoplan(self, system) -> bool:
        """A ``kinoplan 1`` system (SPEC 5) of a kind it plans for."""
        return system_kind(system) in self.kinds


PLANNERS: dict[str, PlannerEntry] = {
    "blossom": PlannerEntry("rrt_cli.planners.blossom", KINODYNAMIC,
                            "blossom RRT: b random controls held while valid (seed 004)",
                            family_only=True),
    "kpiece": PlannerEntry("rrt_cli.planners.kpiece", KINODYNAMIC,
                           "KPIECE1, interior-exterior cell exploration (Sucan & Kavraki 2012)"),
    "rgrrt": PlannerEntry("rrt_cli.planners.rgrrt", KINODYNAMIC,
                          "reachability-guided RRT (Shkolnik, Walter & Tedrake 2009)"),
    "rrt": PlannerEntry("rrt_cli.planners.rrt", ANY, "RRT, the course's reference planner",
                        directed=True),
    "rrtconnect": PlannerEntry("rrt_cli.planners.rrtconnect", GEOMETRIC,
                               "bidirectional RRT-Connect (Kuffner & LaValle 2000)",
                               directed=True),
    "prm": PlannerEntry("rrt_cli.planners.prm", GEOMETRIC,
                        "probabilistic roadmap, k nearest, A* query (Kavraki et al. 1996)"),
    "prmstar": PlannerEntry("rrt_cli.planners.prmstar", GEOMETRIC,
                            "PRM*, k = e(1 + 1/d) log n (Karaman & Frazzoli 2011)"),
    "rrtstar": PlannerEntry("rrt_cli.planners.rrtstar", GEOMETRIC,
                            "RRT*, k-nearest rewiring (Karaman & Frazzoli 2011)",
                            optimizing=True, directed=True),
    "informed": PlannerEntry("rrt_cli.planners.informed", GEOMETRIC,
                             "Informed RRT*, ellipsoidal informed sampling and pruning "
                             "(Gammell et al. 2014)", optimizing=True, directed=True),
    "sst": PlannerEntry("rrt_cli.planners.sst", KINODYNAMIC,
                        "Stable Sparse RRT, anytime (Li, Littlefield & Bekris 2016)",
                        optimizing=True),
}
