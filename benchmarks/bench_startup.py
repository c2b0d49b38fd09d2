"""Whole-process time of two planner commands on the same problems, taking turns.

    python -m benchmarks.bench_startup [--pairs 15] [--problems FILE ...] [--flags=-grad]
                                       [--ours "./run.sh -seed 1" [--ours "OTHER" ...]]
                                       [--theirs "python -m benchmarks.ompl_planner -seed 1"]
                                       [--seeds] [--page docs/results/startup.md]

What a grader's script pays per run is the whole process: interpreter start-up,
imports, reading, planning and printing. Each pair runs both commands once with
the problem on stdin (stdout and stderr discarded), in alternating order (ours
first in even pairs, theirs first in odd ones) so that a drift in the machine's
load hits both alike; one unmeasured run of each comes first. Several ``--ours``
(e.g. a checkout before and after a change) are measured in the same rounds, the
first command of each round rotating, each paired with that round's run of
theirs. With ``--seeds`` round r adds ``-seed r`` to every command (the commands name
no seed then): where the run's length depends on the seed, as a ship's search does,
the per-round ratios compare like with like and their median spans the seeds. Prints,
per problem and over all of them, the median seconds of each command, the ratio of the
medians (ours over theirs) and the median of the per-pair ratios: one table per
``--ours``. The default
``theirs`` is OMPL's peer planner, run by this interpreter as the benchmark harness
runs it (it needs the ``ompl`` package). Tables on stdout, and with ``--page`` also
in a Markdown results page with the command that made it; a command that fails is
one line on stderr, exit 1.
"""

from __future__ import annotations

import argparse
import os
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


def take_turns(commands: list[list[str]], problem: Path, rounds: int,
               seeds: bool = False) -> list[tuple[float, ...]]:
    """``rounds`` runs of each command, one of each per round, round r starting with
    command r (modulo their number: two commands alternate), after one unmeasured
    run of each; with ``seeds``, round r (from 1) adds ``-seed r`` to each command."""
    for command in commands:
        time_once(command + (["-seed", "1"] if seeds else []), problem)
    seconds: list[list[float]] = [[] for _ in commands]
    for round_ in range(rounds):
        seed = ["-seed", str(round_ + 1)] if seeds else []
        for turn in range(len(commands)):
            which = (round_ + turn) % len(commands)
            seconds[which].append(time_once(commands[which] + seed, problem))
    return [tuple(times) for times in seconds]


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


def _interpreter() -> str:
    """This interpreter, relative to the checkout when it is the checkout's (.venv): the
    commands run there, and a results page names no one's folder."""
    inside = os.path.relpath(sys.executable, ROOT)
    return sys.executable if inside.startswith("..") else inside


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="bench_startup", description="Whole-process time of two planner commands, "
        "alternating, medians and their ratio.")
    parser.add_argument("--pairs", type=int, default=15, help="measured pairs per problem")
    parser.add_argument("--problems", nargs="+", type=Path, default=COURSE,
                        help="problem files (default: the course problems)")
    parser.add_argument("--flags", default="",
                        help="added to both commands, e.g. --flags=-grad")
    parser.add_argument("--ours", action="append",
                        help="our command (default: ./run.sh -seed 1); repeat it to "
                             "measure several in the same rounds")
    parser.add_argument("--theirs", default=None, help="the peer's command (default: "
                        "OMPL's peer planner, python -m benchmarks.ompl_planner -seed 1)")
    parser.add_argument("--seeds", action="store_true",
                        help="round r adds -seed r to every command (the default commands "
                             "then name no seed)")
    parser.add_argument("--page", type=Path, default=None, metavar="FILE",
                        help="also write the tables into this Markdown results page")
    return parser


def page(argv: list[str], tables: str, load_before: float, load_after: float) -> str:
    """The results page: the command that regenerates it, how to read it, the tables."""
    return (f"# Whole-process start-up\n\nRegenerated by `python -m benchmarks.bench_startup "
            f"{shlex.join(argv)}` on {os.cpu_count()} processors, load average "
            f"{load_before:.1f} before and {load_after:.1f} after (other work on the machine "
            "slows both commands; compare the ratios, taken in the same rounds, rather than "
            "the milliseconds). Wall time of each command as a whole process with the "
            "problem on stdin, the commands taking turns; medians, the ratio of the medians "
            "and the median of the per-round ratios (ours over theirs).\n\n"
            f"```text\n{tables}\n```\n")


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.pairs < 1:
        parser.error("--pairs must be at least 1")
    seed = "" if args.seeds else " -seed 1"
    ours = [shlex.split(command) + shlex.split(args.flags)
            for command in args.ours or [f"./run.sh{seed}"]]
    theirs = shlex.split(args.theirs or f"{shlex.quote(_interpreter())} "
                         f"-m benchmarks.ompl_planner{seed}") + shlex.split(args.flags)
    load_before = os.getloadavg()[0]
    try:
        times = {path.stem: take_turns([*ours, theirs], path.resolve(), args.pairs, args.seeds)
                 for path in args.problems}
    except CommandFailed as error:
        sys.stderr.write(f"bench_startup: {error}\n")
        return 1
    seeded = ", round r with -seed r" if args.seeds else ""
    lines = [f"theirs: {shlex.join(theirs)}", f"{args.pairs} rounds per problem{seeded}, the "
             "commands taking turns, whole process, medians"]
    for which, command in enumerate(ours):
        lines.append(f"ours:   {shlex.join(command)}")
        lines.append(table({name: Pairs(runs[which], runs[-1])
                            for name, runs in times.items()}))
    print("\n".join(lines))
    if args.page is not None:
        given = sys.argv[1:] if argv is None else argv
        args.page.write_text(page(given, "\n".join(lines), load_before, os.getloadavg()[0]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
