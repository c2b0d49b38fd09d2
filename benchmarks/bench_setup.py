"""What a planner pays before its first iteration on a big map, and whether the
time limit bounds the whole run.

Part 1, in this process, on random maps (``--density`` of the cells blocked,
start in the bottom-left cell, goal in the top-right one): the median over
``--repeats`` of

* the start-goal proof: one full flood fill from the start (``connected_free_cells``,
  what the planners ran before) against the two-sided fill that stops when the
  fills meet (``cells_joined``);
* the free-cell index: a list of every free cell (before) against
  :class:`~planning_core.worlds.grid_cells.FreeCells` (counts per block), and
  the microseconds of one lookup in each;
* Dijkstra over the free cells (``CellDistanceToGoal``), up to ``--dijkstra-max``
  cells a side (the one set-up left that walks every cell of the map).

Part 2: ``python -m rrt_cli -time T`` for every planner x vehicle on each
``--run-sizes`` map, each run a fresh process: wall time, peak RSS (the child's
own, through ``benchmarks/launch.py``), status and planning seconds from ``-stats``.

    python -m benchmarks.bench_setup [--sizes 100 1000 3000]
                                     [--run-sizes 3000 7000] [--time 2]

Tables on stdout; progress on stderr.
"""

from __future__ import annotations

import argparse
import os
import random
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from planning_core.problem_text import parse_problem
from planning_core.worlds.grid import cells_joined, connected_free_cells
from planning_core.worlds.grid_cells import FreeCells
from planning_core.worlds.grid_distance import CellDistanceToGoal

ROOT = Path(__file__).resolve().parent.parent
RUNS = [([], "rrt"), ([], "rrtconnect"), ([], "prm"), ([], "prmstar"),
        (["-grad"], "rrt"), (["-grad"], "kpiece"), (["-grad"], "rgrrt"),
        (["-grad", "-left"], "rrt"), (["-grad", "-left"], "kpiece"),
        (["-grad", "-left"], "rgrrt")]


def random_map_text(size: int, density: float = 0.2, seed: int = 1) -> str:
    """A size x size `.sw` text, each cell blocked with probability ~density,
    the start (bottom-left) and goal (top-right) cells free."""
    rng = random.Random(seed)
    cut = round(256 * density)
    table = bytes(ord("#") if byte < cut else ord("_") for byte in range(256))
    cells = bytearray(rng.randbytes(size * size).translate(table))
    cells[(size - 1) * size] = cells[size - 1] = ord("_")  # text rows are top first
    rows = [cells[r * size:(r + 1) * size].decode() for r in range(size)]
    return (f"{size}\n{size}\n" + "\n".join(rows)
            + f"\n0.5 0.5\n{size - 0.5} {size - 0.5}\n")


def _median_seconds(work, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        began = time.perf_counter()
        work()
        times.append(time.perf_counter() - began)
    return statistics.median(times)


def _lookup_us(cells, rng: random.Random, count: int = 20000) -> float:
    picks = [rng.randrange(len(cells)) for _ in range(count)]
    began = time.perf_counter()
    for k in picks:
        cells[k]
    return (time.perf_counter() - began) / count * 1e6


def setup_rows(size: int, density: float, repeats: int, dijkstra_max: int) -> list[str]:
    problem = parse_problem(random_map_text(size, density))
    start, goal = (0, 0), (size - 1, size - 1)
    goal_index = goal[1] * size + goal[0]
    assert connected_free_cells(problem, start, True)[goal_index] == cells_joined(
        problem, start, goal, True)
    full = _median_seconds(lambda: connected_free_cells(problem, start, True), repeats)
    joined = _median_seconds(lambda: cells_joined(problem, start, goal, True), repeats)
    listed = _median_seconds(lambda: [i for i, b in enumerate(problem.blocked) if not b],
                             repeats)
    counted = _median_seconds(lambda: FreeCells(problem.blocked), repeats)
    free_list = [i for i, b in enumerate(problem.blocked) if not b]
    free_cells = FreeCells(problem.blocked)
    rng = random.Random(1)
    rows = [f"| {size} | full fill {full * 1e3:.1f} ms, two-sided {joined * 1e3:.2f} ms "
            f"({full / joined:.0f}x) | list {listed * 1e3:.1f} ms, counts "
            f"{counted * 1e3:.1f} ms ({listed / counted:.1f}x); lookup "
            f"{_lookup_us(free_list, rng):.2f} / {_lookup_us(free_cells, rng):.2f} us |"]
    if size <= dijkstra_max:
        dijkstra = _median_seconds(lambda: CellDistanceToGoal(problem, problem.goal), max(1, repeats // 2))
        rows[0] += f" {dijkstra * 1e3:.0f} ms ({dijkstra / size ** 2 * 1e6:.1f} us/cell) |"
    else:
        rows[0] += " (skipped) |"
    return rows


LAUNCHER = ROOT / "benchmarks" / "launch.py"


def measured_run(argv: list[str], problem_path: str,
                 limit_bytes: int | None = None) -> tuple[int, float, float, str]:
    """Exit status, wall seconds, peak RSS in MB (the planner's own, through
    launch.py: a child's peak counts the process it was forked from) and stderr of
    ``python -m rrt_cli argv < problem_path``; ``limit_bytes`` caps the address space."""
    def cap_memory():
        resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))

    env = dict(os.environ, PYTHONPATH=str(ROOT))
    with open(problem_path, "rb") as stdin, tempfile.TemporaryFile() as err, \
            tempfile.NamedTemporaryFile("r", suffix=".txt") as report:
        subprocess.run([sys.executable, "-S", "-I", str(LAUNCHER), report.name,
                        sys.executable, "-m", "rrt_cli", *argv],
                       stdin=stdin, stdout=subprocess.DEVNULL, stderr=err, cwd=ROOT, env=env,
                       preexec_fn=cap_memory if limit_bytes else None, check=True)
        status, wall, peak_kb = report.read().split()
        err.seek(0)
        return int(status), float(wall), int(peak_kb) / 1024, err.read().decode()


def run_rows(size: int, density: float, time_limit: float) -> list[str]:
    rows = []
    with tempfile.NamedTemporaryFile("w", suffix=".sw", delete=False) as handle:
        handle.write(random_map_text(size, density))
    try:
        for flags, planner in RUNS:
            argv = [*flags, "-planner", planner, "-seed", "1", "-time", str(time_limit),
                    "-stats"]
            status, wall, rss, err = measured_run(argv, handle.name)
            stats = dict(re.findall(r"(\w+)=(\S+)", err))
            label = " ".join([*flags, planner])
            print(f"  {size} {label}: {wall:.2f} s", file=sys.stderr)
            rows.append(f"| {size} | {label} | {status} | {stats.get('status', '?')} | "
                        f"{stats.get('iterations', '?')} | {stats.get('planning_seconds', '?')}"
                        f" | {wall:.2f} | {rss:.0f} |")
    finally:
        os.unlink(handle.name)
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_setup", description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", type=int, nargs="*", default=[100, 1000, 3000])
    parser.add_argument("--run-sizes", type=int, nargs="*", default=[3000])
    parser.add_argument("--density", type=float, default=0.2)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--dijkstra-max", type=int, default=1000)
    parser.add_argument("--time", type=float, default=2.0)
    args = parser.parse_args(argv)
    print("| cells a side | start-goal proof | free-cell index | Dijkstra |")
    print("|---:|---|---|---|")
    for size in args.sizes:
        print(f"  set-up {size}", file=sys.stderr)
        for row in setup_rows(size, args.density, args.repeats, args.dijkstra_max):
            print(row, flush=True)
    if args.run_sizes:
        print(f"\n`-time {args.time:g}`, seed 1, one run each:\n")
        print("| cells a side | run | exit | status | iterations | planning s | wall s | "
              "peak RSS MB |")
        print("|---:|---|---:|---|---:|---:|---:|---:|")
        for size in args.run_sizes:
            for row in run_rows(size, args.density, args.time):
                print(row, flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
