"""The cases whose planner output is pinned byte for byte (issue 13's acceptance).

Every planner x vehicle it plans for x (course problems + four benchmark
problems) x seeds 1-2. ``make_golden.py`` records the SHA-256 of each run's
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
VEHICLE_FLAGS = {"point": [], "grad": ["-grad"], "left": ["-grad", "-left"]}
PLANNERS_BY_VEHICLE = {
    "point": ("rrt", "rrtconnect", "prm", "prmstar"),
    "grad": ("rrt", "kpiece", "rgrrt"),
    "left": ("rrt", "kpiece", "rgrrt"),
}


def cases() -> list[tuple[str, str, str, int]]:
    """(vehicle, planner, problem, seed) for every pinned run."""
    return [(vehicle, planner, problem, seed)
            for vehicle, planners in PLANNERS_BY_VEHICLE.items()
            for planner in planners
            for problem in PROBLEMS
            for seed in SEEDS]


def case_id(vehicle: str, planner: str, problem: str, seed: int) -> str:
    return f"{vehicle}/{planner}/{problem.removeprefix('course/')}/{seed}"


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
}


def compiled_quick(case: tuple[str, str, str, int]) -> bool:
    """The cases the unit run also replays compiled (one problem per planner and
    vehicle); CI replays every case both ways."""
    return case[2] == "course/space-1.sw"
