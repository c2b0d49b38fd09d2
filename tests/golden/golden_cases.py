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


# Runs over a second each (measured when golden.json was made): marked slow, as is
# every run with the second seed (test_golden.py), so the unit run (-m "not slow")
# replays ~85 (the first seed) and CI replays all.
SLOW = {
    "left/rrt/maze-20.sw/1", "left/rrt/maze-20.sw/2", "left/rrt/space-3.sw/1",
    "left/rrt/space-3.sw/2", "left/rrt/random-d20-20.sw/1", "left/rrt/random-d20-20.sw/2",
    "left/rrt/space-2.sw/1", "left/rrt/narrow-20.sw/1", "left/rrt/narrow-20.sw/2",
    "grad/rrt/maze-20.sw/1", "grad/rrt/maze-20.sw/2", "grad/rrt/space-3.sw/1",
    "family/prmstar/rigid2-scene1.kp/1", "family/prmstar/rigid2-scene1.kp/2",
    "family/prmstar/rigid2-scene2.kp/1", "family/prmstar/rigid2-scene2.kp/2",
}


FAMILY_QUICK = ("family/pendulum-t3.kp", "family/arm2-pair1.kp", "family/car1-scene2.kp",
                "family/rigid2-scene3.kp")
"""The family problems the unit run replays (first seed); CI replays every one."""


def compiled_quick(case: tuple[str, str, str, int]) -> bool:
    """The cases the unit run also replays compiled (one problem per planner and
    vehicle); CI replays every case both ways."""
    return case[2] in ("course/space-1.sw", "family/pendulum-t3.kp", "family/arm2-pair1.kp")
