"""A parsed problem made ready to plan or to check (OMPL's SimpleSetup): the space
information of its substrate and kind, and the problem definition, built the same
way for the planner and the validator so that their numbers agree bit for bit.
"""

from __future__ import annotations

from planning_core.problem_definition import ProblemDefinition

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Any, Union

    from planning_core.space_information import ControlSpaceInformation, GeometricSpaceInformation

    SpaceInformation = Union[GeometricSpaceInformation, ControlSpaceInformation]


class Setup:
    """What a planner and the validator take from one problem (a plain class, not a
    dataclass, as every record on the planner's start-up path)."""

    si: SpaceInformation
    """How the system moves and where it may be."""
    pdef: ProblemDefinition
    """The start and the goal region."""
    problem: Any
    """The parsed problem it was made from (``Problem`` or ``KinoplanProblem``), for
    messages and drawings."""
    family: bool
    """A ``kinoplan`` problem (SPEC 5), not a grid map."""

    def __init__(self, si: SpaceInformation, pdef: ProblemDefinition, problem: Any,
                 family: bool = False) -> None:
        self.si = si
        self.pdef = pdef
        self.problem = problem
        self.family = family

    def __repr__(self) -> str:
        return f"Setup({self.si!r}, {self.pdef!r}, {self.problem!r}, family={self.family!r})"

    @property
    def system(self) -> Any:
        return self.si.system

    @property
    def rows_end_in_count(self) -> bool:
        """The output's rows end in K, an integer (a kinodynamic family system, SPEC 5.4)."""
        return self.family and self.si.system.kinodynamic


def grid_setup(problem: Any, system_name: Any, options: Any = None) -> Setup:
    """A ``.sw`` problem for the named system (``point``, ``spaceship``, ``left``,
    ``dubins``; a :class:`~planning_core.vehicles.Vehicle` names one too). ``options``:
    a ship's :class:`~planning_core.grid_space_information.GridControlOptions`; the
    Dubins car's :class:`~planning_core.systems.dubins.DubinsOptions` (its radius)."""
    from planning_core.goal import GoalRegion
    from planning_core.grid_space_information import (GridControlOptions,
                                                      GridControlSpaceInformation,
                                                      GridGeometricSpaceInformation)
    from planning_core.systems import load as load_system
    from planning_core.worlds.grid import GridWorld
    system = load_system(getattr(system_name, "value", system_name))
    world = GridWorld(problem)
    if system.kinodynamic:
        si: SpaceInformation = GridControlSpaceInformation(system, world,
                                                           options or GridControlOptions())
    elif getattr(system, "directed", False):
        from planning_core.dubins_space_information import DubinsSpaceInformation
        if options is not None:
            import dataclasses  # the Dubins car, a dataclass, has imported it
            system = dataclasses.replace(system, radius=options.radius)
        si = DubinsSpaceInformation(system, world)
    else:
        si = GridGeometricSpaceInformation(system, world)
    pdef = ProblemDefinition(system.start_state(*problem.start), GoalRegion(problem.goal))
    return Setup(si, pdef, problem)


def kinoplan_setup(problem: Any, options: Any = None) -> Setup:
    """A :class:`~planning_core.kinoplan.KinoplanProblem`. ``options``: a kinodynamic
    system's :class:`~planning_core.family_space_information.FamilyControlOptions`."""
    if problem.system.kinodynamic:
        from planning_core.family_space_information import (FamilyControlOptions,
                                                            FamilyControlSpaceInformation)
        si: SpaceInformation = FamilyControlSpaceInformation(
            problem, options or FamilyControlOptions())
    else:
        from planning_core.family_geometric_space_information import (
            FamilyGeometricSpaceInformation)
        si = FamilyGeometricSpaceInformation(problem)
    return Setup(si, ProblemDefinition(problem.start, problem.goal), problem, family=True)
