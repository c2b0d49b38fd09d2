"""Measure the Dubins car against the point vehicle on the course maps: for each map,
vehicle and planner, SEEDS seeds of ``./run.sh ... -stats``; success, median planning
time and median path length (the -stats cost), each answer checked by the validator's
own checks (the turning check included). Prints a Markdown table.

    python tools/dubins_measure.py [SEEDS] [TIME] [GLOB]   # docs/dubins.md: 20 seeds
"""

from __future__ import annotations

import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from planning_core.problem_text import parse_problem  # noqa: E402
from planning_core.setups import grid_setup  # noqa: E402
from planning_core.systems.dubins import DubinsOptions  # noqa: E402
from validator.checks import validate_plan  # noqa: E402

VEHICLES = (("point", [], None), ("dubins R=0.5", ["-dubins", "-radius", "0.5"], 0.5),
            ("dubins R=2", ["-dubins", "-radius", "2"], 2.0))


def _run(flags: list[str], text: str, seed: int, limit: str):
    done = subprocess.run([str(ROOT / "run.sh"), *flags, "-seed", str(seed), "-time", limit,
                           "-stats"], input=text.encode(), capture_output=True, timeout=600)
    stats = dict(word.split("=", 1) for line in done.stderr.decode().splitlines()
                 if line.startswith("rrt_cli stats:") for word in line.split()[2:])
    return done, stats


def measure(path: Path, planner: str, seeds: int, limit: str) -> list[str]:
    text = path.read_text()
    problem = parse_problem(text)
    rows = []
    for name, flags, radius in VEHICLES:
        if planner != "rrt" and radius is None:
            continue
        setup = grid_setup(problem, "dubins" if radius else "point",
                           DubinsOptions(radius) if radius else None)
        solved, times, lengths = 0, [], []
        for seed in range(1, seeds + 1):
            done, stats = _run(flags + ["-planner", planner], text, seed, limit)
            times.append(float(stats.get("planning_seconds", "nan")))
            if done.returncode == 0:
                assert validate_plan(setup, done.stdout.decode()).valid, (path, name, seed)
                solved += 1
                lengths.append(float(stats["cost"]))
        length = f"{statistics.median(lengths):.2f}" if lengths else "-"
        rows.append(f"| {path.stem} | {name} | {planner} | {solved}/{seeds} | "
                    f"{statistics.median(times):.3f} | {length} |")
    return rows


def main() -> None:
    seeds = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    limit = sys.argv[2] if len(sys.argv) > 2 else "10"
    pattern = sys.argv[3] if len(sys.argv) > 3 else "*.sw"
    print("| map | vehicle | planner | solved | median s | median length |")
    print("|---|---|---|---|---|---|")
    for path in sorted((ROOT / "benchmarks" / "problems" / "course").glob(pattern)):
        for planner in ("rrt", "rrtconnect"):
            for row in measure(path, planner, seeds, limit):
                print(row, flush=True)


if __name__ == "__main__":
    main()
