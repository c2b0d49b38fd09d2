"""The benchmark report's targets, as data.

Each target is a frozen dataclass of one kind; ``benchmarks/report.py`` has one
evaluator per kind and judges the targets of ``TARGETS`` in this order, a row per
planner of ours where the kind says "each of our planners". A target the run has
no runs to judge (no runs of the planners it names on its vehicle, maps and
family; for ``SuccessWithin``, no map as large as its ``max_size``; against
another planner, no problem and seed both ran) is left out of the report.

Vehicles and planners are named as in the run rows: vehicles ``point``,
``spaceship``, ``left``; planners by their harness id (``rrt``, ``kpiece``, ...).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class SuccessWithin:
    """Each of our planners solves every run on ``vehicle`` within ``seconds`` of
    planning time, on every map up to ``max_size`` x ``max_size``."""

    vehicle: str
    max_size: int
    """Largest map side judged; judged only when the run has maps this large."""
    seconds: float
    """Planning time a run must be solved within."""


@dataclass(frozen=True)
class SpeedVsReference:
    """Each of our planners' median time at most ``factor`` x that of OMPL's RRT
    for the vehicle (geometric or control), on the same problems and seeds."""

    vehicle: str
    min_size: int
    """Smallest map side judged (1: every map)."""
    factor: float
    """Largest allowed ratio of the medians, ours over OMPL RRT's."""
    process: bool = False
    """Whole-process wall time instead of planning time."""
    family: str | None = None
    """Only problems of this family (None: every family)."""


@dataclass(frozen=True)
class PlannerVsPlanner:
    """The fastest of ``planners`` (median planning time) within ``factor`` x our
    ``baseline``'s on the ``family`` problems, on the same problems and seeds."""

    vehicle: str
    family: str
    planners: tuple[str, ...]
    """Our planners compared; one of them meeting the bound meets the target."""
    factor: float
    """Largest allowed ratio of the medians, planner over baseline."""
    strict: bool = False
    """The ratio must be below ``factor``, not just at most it."""
    baseline: str = "rrt"
    """Our planner compared against."""


@dataclass(frozen=True)
class PathLengthVsPlanner:
    """``planner``'s paths shorter than our ``baseline``'s: the mean over problems
    (solved by both) of the ratio of median path lengths at most ``factor``. On
    the point vehicle the report adds what the shortest paths would score."""

    vehicle: str
    planner: str
    factor: float
    """Largest allowed mean ratio (0.8: paths at least 20% shorter)."""
    baseline: str = "rrt"
    """Our planner compared against."""


@dataclass(frozen=True)
class FirstSolutionVsPlanner:
    """``planner``'s median time to its first solution at most ``factor`` x our
    ``baseline``'s, judged per problem of the ``systems``, on the seeds both ran."""

    systems: tuple[str, ...]
    """The rows' vehicles judged (a family problem's system: ``arm2``, ``rigid2``)."""
    planner: str
    factor: float
    """Largest allowed ratio of the medians, planner over baseline."""
    baseline: str = "prm"
    """Our planner compared against."""


Target = (SuccessWithin | SpeedVsReference | PlannerVsPlanner | PathLengthVsPlanner
          | FirstSolutionVsPlanner)

ISSUE_4_TARGETS: tuple[Target, ...] = (
    # Against OMPL's RRT, and success within a time on maps up to a size.
    SuccessWithin("point", max_size=500, seconds=10.0),
    SpeedVsReference("point", min_size=1, factor=1.0),
    SpeedVsReference("point", min_size=100, factor=0.5),
    SuccessWithin("spaceship", max_size=100, seconds=30.0),
    SuccessWithin("spaceship", max_size=200, seconds=120.0),
    SpeedVsReference("spaceship", min_size=1, factor=0.5),
    SpeedVsReference("point", min_size=1, factor=1.0, process=True, family="course"),
    SpeedVsReference("spaceship", min_size=1, factor=1.0, process=True, family="course"),
)

ISSUE_5_TARGETS: tuple[Target, ...] = (
    # Against our own RRT in the same run.
    PlannerVsPlanner("spaceship", "maze", ("kpiece", "rgrrt"), factor=0.5),
    PlannerVsPlanner("spaceship", "narrow", ("kpiece", "rgrrt"), factor=0.5),
    PlannerVsPlanner("left", "maze", ("kpiece", "rgrrt"), factor=0.5),
    PlannerVsPlanner("left", "narrow", ("kpiece", "rgrrt"), factor=0.5),
    PathLengthVsPlanner("point", "prmstar", factor=0.8),
    PlannerVsPlanner("point", "maze", ("rrtconnect",), factor=1.0, strict=True),
)

TARGETS: tuple[Target, ...] = ISSUE_4_TARGETS + ISSUE_5_TARGETS

FAMILY_TARGETS: tuple[Target, ...] = (
    # Issue 33: PRM* as quick as PRM to its first answer (its refinement after it apart).
    FirstSolutionVsPlanner(("arm2", "rigid2"), "prmstar", factor=2.0),
)
"""The family presets' targets of this table (benchmarks/family_report.py judges the
others itself)."""
