"""The cases whose planner output is pinned byte for byte (issue 13's acceptance).

Every planner x vehicle it plans for x (course problems + four benchmark
problems) x seeds 1-2; and every family planner x family problem x seeds 1-2
(vehicle ``family``), with ``-smooth`` for the geometric ones' RRT-Connect
(vehicle ``family-smooth``). ``make_golden.py`` records the SHA-256 of each run's
stdout and its exit status in ``golden.json``; ``test_golden.py`` replays them.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PROBLEM_DIR = ROOT / "benchmarks" / "problems"
PROBLEMS = [f"course/{name}.sw" for name in ("simple-0", "space-0", "space-1", "space-2",
                                              "space-3")]
PROBLEMS += ["maze-20.sw", "narrow-20.sw", "random-d20-20.sw", "random-d35-10.sw"]
SEEDS = (1, 2)
VEHICLE_FLAGS = {"point": [], "grad": ["-grad"], "left": ["-grad", "-left"], "family": [],
                 "family-smooth": ["-smooth"]}
PLANNERS_BY_VEHICLE = {
    "point": ("rrt", "rrtconnect", "prm", "prmstar"),
    "grad": ("rrt", "kpiece", "rgrrt"),
    "left": ("rrt", "kpiece", "rgrrt"),
}


FAMILY_PROBLEMS = sorted(f"family/{path.name}"
                         for path in (PROBLEM_DIR / "family").glob("*.kp"))
GEOMETRIC_FAMILY = ("arm2", "rigid2")
"""The family's geometric systems (by the problem's name); the others are kinodynamic."""
FAMILY_PLANNERS = {"kinodynamic": ("rrt", "kpiece", "rgrrt", "blossom"),
                   "geometric": ("rrt", "rrtconnect", "prm", "prmstar")}


def family_kind(problem: str) -> str:
    name = problem.removeprefix("family/")
    return "geometric" if name.startswith(GEOMETRIC_FAMILY) else "kinodynamic"


def cases() -> list[tuple[str, str, str, int]]:
    """(vehicle, planner, problem, seed) for every pinned run."""
    grid = [(vehicle, planner, problem, seed)
            for vehicle, planners in PLANNERS_BY_VEHICLE.items()
            for planner in planners
            for problem in PROBLEMS
            for seed in SEEDS]
    family = [("family", planner, problem, seed)
              for problem in FAMILY_PROBLEMS
              for planner in FAMILY_PLANNERS[family_kind(problem)]
              for seed in SEEDS]
    smooth = [("family-smooth", "rrtconnect", problem, seed)
              for problem in FAMILY_PROBLEMS if family_kind(problem) == "geometric"
              for seed in SEEDS]
    return grid + family + smooth


def case_id(vehicle: str, planner: str, problem: str, seed: int) -> str:
    name = problem.removeprefix("course/").removeprefix("family/")
    return f"{vehicle}/{planner}/{name}/{seed}"


def argv(vehicle: str, planner: str, seed: int) -> list[str]:
    """The planner's arguments: no time limit in practice, so only the seed decides."""
    return [*VEHICLE_FLAGS[vehicle], "-planner", planner, "-seed", str(seed),
            "-time", "100000"]


# The unit run (-m "not slow") replays a sample with the first seed (test_golden.py); CI
# replays every case both ways. Interpreted: each grid vehicle x planner on one benchmark
# map, and a family problem per system with every family planner among them; compiled:
# compiled_quick's.
UNIT_GRID_PROBLEM = "random-d35-10.sw"
UNIT_FAMILY = {  # problem -> its planners in the unit run (cheap ones, measured)
    "family/pendulum-t10.kp": ("rrt", "blossom"), "family/car1-scene3.kp": ("kpiece",),
    "family/car2-corridors.kp": ("rgrrt",), "family/unicycle-circles.kp": ("kpiece",),
    "family/arm2-pair3.kp": ("prm", "prmstar", "rrtconnect"), "family/rigid2-scene2.kp": ("rrt",),
}
UNIT_SMOOTH = "family/arm2-pair3.kp"
"""The family problem the unit run replays with -smooth (interpreted)."""


def unit_interpreted(case: tuple[str, str, str, int]) -> bool:
    """A case the unit run replays interpreted (any seed: the caller picks the first)."""
    vehicle, planner, problem, _ = case
    if vehicle == "family":
        return planner in UNIT_FAMILY.get(problem, ())
    if vehicle == "family-smooth":
        return problem == UNIT_SMOOTH
    return problem == UNIT_GRID_PROBLEM


def compiled_quick(case: tuple[str, str, str, int]) -> bool:
    """The cases the unit run also replays compiled (one problem per planner and
    vehicle); CI replays every case both ways."""
    return case[2] in ("course/space-1.sw", "family/pendulum-t3.kp", "family/arm2-pair1.kp")
