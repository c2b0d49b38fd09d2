"""The kinoplan family's presets (SPEC 5): which problems of
``benchmarks/problems/family/`` (SPEC's examples) and ``family/variants/`` (ours),
which planners, how many runs, what time limit.

* ``family``: SPEC 5.6's seed tables: the second-order car and the pendulum at
  torque 3, 5 and 10 with our rrt, kpiece, rgrrt and OMPL's control RRT and
  KPIECE1; seed 004's blossom table (b = 1, 3, 5 x the three car1 scenes).
  100 runs each, as the seed.
* ``family-geometric``: arm2's five start/goal pairs and the rigid2 scenes with our
  rrt, rrtconnect, prm, prmstar and OMPL's RRT, RRTConnect, PRM; 20 runs.
* ``family-quick``: both, 3 runs, 10 s (tests, CI, a first look).
* ``family-sweep``: every one of our family planners
  on every family problem (variants included), 20 seeds, 30 s: solved and validated %.
* ``family-optimize``: sst, rrtstar and informed on every family problem they plan for,
  with ``-optimize -time 5``, 20 seeds: the best answer at 5 s, validated.

A planner a table names but the registry does not offer for the problem's system
(not written yet, or refused) gets no runs and a "not available" line.
"""

from __future__ import annotations

import fnmatch
from dataclasses import dataclass
from pathlib import Path

from benchmarks.catalog import PlannerChoice
from planning_core.kinoplan_text import parse_kinoplan

FAMILY_DIR = Path(__file__).resolve().parent / "problems" / "family"
SOLUTIONS_DIR = FAMILY_DIR / "solutions"
KINODYNAMIC_OURS = ("rrt", "kpiece", "rgrrt")
KINODYNAMIC_OMPL = ("ompl-rrt", "ompl-kpiece1")
BLOSSOM = ("blossom-b1", "blossom-b3", "blossom")
GEOMETRIC = ("rrt", "rrtconnect", "prm", "prmstar", "ompl-rrt", "ompl-rrtconnect", "ompl-prm")
OPTIMIZING = ("sst", "rrtstar", "informed")
EVERY_PLANNER = ("*",)
OUR_PLANNERS = ("(ours)",)


@dataclass(frozen=True)
class FamilyTable:
    """One table of the report: some problems, some planners."""

    title: str
    problems: tuple[str, ...]
    """Problem names (file stems; shell patterns) of ``benchmarks/problems/family``."""
    planners: tuple[str, ...]
    """Harness planner ids, in the table's order (``EVERY_PLANNER``: every family planner;
    ``OUR_PLANNERS``: every one of ours)."""
    published: tuple[tuple[str, str, str, str, str], ...] = ()
    """SPEC 5.6's rows (planner, success, time, path length, tree nodes), for comparison."""


@dataclass(frozen=True)
class FamilyPreset:
    name: str
    tables: tuple[FamilyTable, ...]
    runs: int
    """Seeds 1..runs of every planner on every problem."""
    time_limit: float
    """Seconds per run."""
    optimize: bool = False
    """Run every planner with ``-optimize`` (to the time limit; its best answer checked)."""


CAR_PUBLISHED = (("OMPL RRT (seed 000, C++)", "100", "0.3467 ± 0.2157", "60.06 ± 16.00",
                  "2217 ± 1401"),
                 ("OMPL RG-RRT (seed 000, C++)", "100", "0.3045 ± 0.2065", "53.83 ± 17.63",
                  "1913 ± 1364"),
                 ("OMPL KPIECE1 (seed 000, C++)", "100", "0.2647 ± 0.1862", "82.74 ± 33.56",
                  "8161 ± 5779"))
PENDULUM_PUBLISHED = (("OMPL RRT (seed 000, C++)", "100", "0.0123 ± 0.0072", "10.04 ± 1.49",
                       "1640 ± 923"),
                      ("OMPL RG-RRT (seed 000, C++)", "100", "0.0156 ± 0.0100",
                       "10.61 ± 1.66", "1809 ± 1123"),
                      ("OMPL KPIECE1 (seed 000, C++)", "100", "0.0101 ± 0.0067",
                       "12.23 ± 1.86", "2259 ± 1166"))
SEED_TABLES = (
    FamilyTable("Second-order car (car2-corridors)", ("car2-corridors",),
                KINODYNAMIC_OURS + KINODYNAMIC_OMPL, CAR_PUBLISHED),
    FamilyTable("Pendulum, torque 3", ("pendulum-t3",), KINODYNAMIC_OURS + KINODYNAMIC_OMPL,
                PENDULUM_PUBLISHED),
    FamilyTable("Pendulum, torque 5", ("pendulum-t5",), KINODYNAMIC_OURS + KINODYNAMIC_OMPL),
    FamilyTable("Pendulum, torque 10", ("pendulum-t10",), KINODYNAMIC_OURS + KINODYNAMIC_OMPL),
    FamilyTable("Blossom RRT, first-order car (seed 004: b = 1, 3, 5 x three scenes)",
                ("car1-scene1", "car1-scene2", "car1-scene3"), BLOSSOM),
)
GEOMETRIC_TABLES = (
    FamilyTable("Two-link arm (seed 004's five start/goal pairs)", ("arm2-pair*",), GEOMETRIC),
    FamilyTable("Rigid body in SE(2)", ("rigid2-scene*",), GEOMETRIC),
)
FAMILY_PRESETS = {
    "family": FamilyPreset("family", SEED_TABLES, 100, 30.0),
    "family-geometric": FamilyPreset("family-geometric", GEOMETRIC_TABLES, 20, 30.0),
    "family-quick": FamilyPreset("family-quick", SEED_TABLES + GEOMETRIC_TABLES, 3, 10.0),
    "family-sweep": FamilyPreset("family-sweep", (
        FamilyTable("Every planner of ours on every family problem", ("*",), OUR_PLANNERS),),
        20, 30.0),
    "family-optimize": FamilyPreset("family-optimize", (
        FamilyTable("The optimizing planners with -optimize -time 5 on every family problem",
                    ("*",), OPTIMIZING),), 20, 5.0, optimize=True),
}


def family_problems(directory: Path = FAMILY_DIR) -> list[Path]:
    """SPEC's examples (``*.kp``, copies of the shared folder's) and our variants
    (``variants/*.kp``), by name."""
    return sorted([*directory.glob("*.kp"), *directory.glob("variants/*.kp")],
                  key=lambda path: path.stem)


def system_of(path: Path) -> str:
    return parse_kinoplan(path.read_text()).system_name


def table_problems(table: FamilyTable, directory: Path = FAMILY_DIR) -> list[Path]:
    return [p for p in family_problems(directory)
            if any(fnmatch.fnmatchcase(p.stem, pattern) for pattern in table.problems)]


def table_planners(table: FamilyTable, available: list[PlannerChoice]) -> list[str]:
    """The table's planner ids in order (every available one for ``*``)."""
    if table.planners == EVERY_PLANNER:
        return [p.id for p in available]
    if table.planners == OUR_PLANNERS:
        return [p.id for p in available if p.implementation == "ours"]
    return list(table.planners)


@dataclass(frozen=True)
class FamilyRun:
    """One planner on one problem: what the harness's RunSpecs are made of."""

    planner: PlannerChoice
    problem: Path


def family_runs(preset: FamilyPreset, available: list[PlannerChoice],
                problem_patterns: tuple[str, ...] = ()) -> list[FamilyRun]:
    """Every (planner, problem) of the preset's tables that the planner plans for,
    once each, in table order; ``problem_patterns`` narrows the problems."""
    by_id = {p.id: p for p in available}
    systems: dict[Path, str] = {}
    runs, seen = [], set()
    for table in preset.tables:
        for problem in table_problems(table):
            if problem_patterns and not any(fnmatch.fnmatchcase(problem.stem, pattern)
                                            for pattern in problem_patterns):
                continue
            system = systems.setdefault(problem, system_of(problem))
            for planner_id in table_planners(table, available):
                planner = by_id.get(planner_id)
                if planner and system in planner.systems and (planner_id, problem) not in seen:
                    seen.add((planner_id, problem))
                    runs.append(FamilyRun(planner, problem))
    return runs
