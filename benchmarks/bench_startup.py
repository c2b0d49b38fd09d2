"""Whole-process time of two planner commands on the same problems, taking turns.

    python -m benchmarks.bench_startup [--pairs 15] [--problems FILE ...] [--flags=-grad]
                                       [--ours "./run.sh -seed 1"]
                                       [--theirs "python benchmarks/ompl_planner.py -seed 1"]

What a grader's script pays per run is the whole process: interpreter start-up,
imports, reading, planning and printing. Each pair runs both commands once with
the problem on stdin (stdout and stderr discarded), in alternating order (ours
first in even pairs, theirs first in odd ones) so that a drift in the machine's
load hits both alike; one unmeasured run of each comes first. Prints, per problem
and over all of them, the median seconds of each command, the ratio of the
medians (ours over theirs) and the median of the per-pair ratios. The default
``theirs`` is OMPL's peer planner, run by this interpreter (it needs the ``ompl``
package). Tables on stdout; a command that fails is one line on stderr, exit 1.
"""

from __future__ import annotations

import argparse
import shlex
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
COURSE = sorted((ROOT / "benchmarks" / "problems" / "course").glob("*.sw"))


@dataclass(frozen=True)
class Pairs:
    """The seconds of each command, pair by pair, on one problem."""

    ours: tuple[float, ...]
    theirs: tuple[float, ...]

    @property
    def ratio_of_medians(self) -> float:
        return statistics.median(self.ours) / statistics.median(self.theirs)

    @property
    def median_pair_ratio(self) -> float:
        return statistics.median(a / b for a, b in zip(self.ours, self.theirs))


class CommandFailed(Exception):
    """A measured command exited non-zero."""


def time_once(command: list[str], problem: Path) -> float:
    """Seconds from start to exit of ``command < problem``."""
    with open(problem, "rb") as stdin:
        began = time.perf_counter()
        done = subprocess.run(command, stdin=stdin, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, cwd=ROOT)
        seconds = time.perf_counter() - began
    if done.returncode != 0:
        last = (done.stderr.decode(errors="replace").strip().splitlines() or [""])[-1]
        raise CommandFailed(f"{shlex.join(command)} < {problem.name}: exit status "
                            f"{done.returncode}: {last}")
    return seconds


def alternate(ours: list[str], theirs: list[str], problem: Path, pairs: int) -> Pairs:
    """``pairs`` runs of each, taking turns, after one unmeasured run of each."""
    time_once(ours, problem)
    time_once(theirs, problem)
    mine, others = [], []
    for pair in range(pairs):
        if pair % 2 == 0:
            mine.append(time_once(ours, problem))
            others.append(time_once(theirs, problem))
        else:
            others.append(time_once(theirs, problem))
            mine.append(time_once(ours, problem))
    return Pairs(tuple(mine), tuple(others))


def table(results: dict[str, Pairs]) -> str:
    lines = [f"{'problem':<14} {'ours (ms)':>10} {'theirs (ms)':>12} {'ratio':>7} "
             f"{'pair ratio':>11}"]
    pooled = Pairs(tuple(t for p in results.values() for t in p.ours),
                   tuple(t for p in results.values() for t in p.theirs))
    for name, pairs in [*results.items(), ("all", pooled)]:
        lines.append(f"{name:<14} {1000 * statistics.median(pairs.ours):>10.1f} "
                     f"{1000 * statistics.median(pairs.theirs):>12.1f} "
                     f"{pairs.ratio_of_medians:>7.2f} {pairs.median_pair_ratio:>11.2f}")
    return "\n".join(lines)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="bench_startup", description="Whole-process time of two planner commands, "
        "alternating, medians and their ratio.")
    parser.add_argument("--pairs", type=int, default=15, help="measured pairs per problem")
    parser.add_argument("--problems", nargs="+", type=Path, default=COURSE,
                        help="problem files (default: the course problems)")
    parser.add_argument("--flags", default="",
                        help="added to both commands, e.g. --flags=-grad")
    parser.add_argument("--ours", default="./run.sh -seed 1", help="our command")
    parser.add_argument("--theirs", default=f"{shlex.quote(sys.executable)} "
                        "benchmarks/ompl_planner.py -seed 1", help="the peer's command")
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.pairs < 1:
        parser.error("--pairs must be at least 1")
    ours = shlex.split(args.ours) + shlex.split(args.flags)
    theirs = shlex.split(args.theirs) + shlex.split(args.flags)
    print(f"ours:   {shlex.join(ours)}\ntheirs: {shlex.join(theirs)}\n"
          f"{args.pairs} alternating pairs per problem, whole process, medians")
    try:
        results = {path.stem: alternate(ours, theirs, path.resolve(), args.pairs)
                   for path in args.problems}
    except CommandFailed as error:
        sys.stderr.write(f"bench_startup: {error}\n")
        return 1
    print(table(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
