"""Planning time with the compiled hot modules against the same source interpreted,
and both against OMPL with Python callbacks, measured in one run.

    python -m benchmarks.bench_compiled [--seeds 3] [--repeats 1] [--time 30]
                                        [--vehicles point spaceship left arm2 rigid2]
                                        [--problems PATTERN ...] [--no-ompl]
    python -m benchmarks.bench_compiled --kernels 5

Problems: the quick preset's course problems and maps of 50x50 and up for the
point vehicle, and its problems for the two ships; the family's arm2 and rigid2
problems (``benchmarks/problems/family``) for those two "vehicles" (the geometric
family, the point targets of benchmarks/targets.py). Each case runs as whole processes in turn
(./run.sh compiled, ./run.sh with RRT_INTERPRETED=1, OMPL's planner), the order
alternating, and reads each run's own planning time from its -stats line. The
OMPL reference is geometric RRT for the point vehicle, the arm and the rigid body,
control RRT for the ships (the targets' ratios); with g++ and Debian's
libompl-dev, the same set-up in C++ too (``benchmarks/ompl_cpp/``, built on first
use into ``.build/``: benchmarks/ompl_cpp_programs.py). Prints a Markdown table of
medians over seeds and repeats; an unsolved run counts its whole time limit (noted).
``--kernels`` times the two hot loops alone, in-process, per mode."""

from __future__ import annotations

import argparse
import fnmatch
import os
import re
import statistics
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from benchmarks.family import FAMILY_DIR
from benchmarks.generator import problem_id
from benchmarks.ompl_cpp_programs import binary, family_input, grid_input
from benchmarks.presets import PRESETS, select_problems
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle

ROOT = Path(__file__).resolve().parent.parent
OUR_PLANNERS = {"point": ("rrt", "rrtconnect"), "spaceship": ("rrt", "kpiece", "rgrrt"),
                "left": ("rrt", "kpiece", "rgrrt"), "arm2": ("rrt", "rrtconnect"),
                "rigid2": ("rrt", "rrtconnect")}
VEHICLE_FLAGS = {vehicle.value: list(vehicle.flags) for vehicle in Vehicle}
FAMILY = ("arm2", "rigid2")
"""The geometric family's systems, benchmarked as vehicles of their own."""
STATS = re.compile(r"stats: status=(\w+) .*planning_seconds=([0-9.]+)")
MODES = ("compiled", "interpreted")
POINT_TARGET_SIZE = 50
"""Issue 19's point targets apply to maps of this width and height and up."""
OMPL_CPP_MODE = {"point": "point", "spaceship": "ship", "left": "left"}
"""grid_ompl's mode per vehicle; family_ompl runs geometric RRT on arm2 and rigid2."""


@dataclass(frozen=True)
class Run:
    seconds: float
    """The planner's own planning time (its time limit when it did not solve)."""
    solved: bool


def problems_for(vehicle: str, patterns: list[str]) -> list[Path]:
    """The quick preset's problems for ``vehicle`` (point: its course problems and
    its maps of 50x50 and up, where benchmarks/targets.py sets the point targets; arm2 and rigid2:
    the family's problems of that system)."""
    if vehicle in FAMILY:
        chosen = sorted(FAMILY_DIR.glob(f"{vehicle}-*.kp"))
        return [path for path in chosen if not patterns
                or any(fnmatch.fnmatchcase(problem_id(path), p) for p in patterns)]
    plan = next(plan for plan in PRESETS["quick"].plans if plan.vehicle.value == vehicle)
    chosen = select_problems(plan)
    if vehicle == "point":
        chosen = [path for path in chosen if problem_id(path).startswith("course-")
                  or min(_map_size(path)) >= POINT_TARGET_SIZE]
    return [path for path in chosen
            if not patterns or any(fnmatch.fnmatchcase(problem_id(path), p) for p in patterns)]


def _map_size(problem: Path) -> tuple[int, int]:
    parsed = parse_problem(problem.read_text())
    return parsed.width, parsed.height


def cpp_program(vehicle: str) -> Path | None:
    """The C++ OMPL program for ``vehicle``'s problems, or None when it cannot be built."""
    return binary("family_ompl" if vehicle in FAMILY else "grid_ompl")


def command(mode: str, vehicle: str, planner: str, seed: int, limit: float) -> tuple[list, dict]:
    """argv and environment of one run: ours in ``mode``, or OMPL (mode "ompl" with
    Python callbacks, "ompl-cpp" in C++)."""
    args = [*VEHICLE_FLAGS.get(vehicle, []), "-planner", planner, "-seed", str(seed),
            "-time", str(limit), "-stats"]
    env = dict(os.environ)
    env.pop("RRT_INTERPRETED", None)
    if mode == "ompl-cpp":
        program = cpp_program(vehicle)
        return [str(program), OMPL_CPP_MODE.get(vehicle, "rrt"), str(limit), str(seed)], env
    if mode == "ompl":
        return [sys.executable, str(ROOT / "benchmarks" / "ompl_planner.py"), *args], env
    if mode == "interpreted":
        env["RRT_INTERPRETED"] = "1"
    return [str(ROOT / "run.sh"), *args], env


def run_once(argv: list, env: dict, problem: Path, limit: float, mode: str) -> Run:
    if mode == "ompl-cpp":
        flat = family_input if problem.suffix == ".kp" else grid_input
        stdin = flat(problem.read_text())
    else:
        stdin = problem.read_bytes()
    done = subprocess.run(argv, input=stdin, capture_output=True, env=env,
                          timeout=limit * 3 + 30)
    done.stderr = done.stderr.decode(errors="replace")
    if mode == "compiled" and "rrt_cli build: compiled" not in done.stderr:
        raise SystemExit(f"bench_compiled: the compiled modules are not in use: "
                         f"{done.stderr.splitlines()[:1]} (run ./make.sh)")
    found = STATS.search(done.stderr)
    if found is None:
        raise SystemExit(f"bench_compiled: no stats from {' '.join(map(str, argv))}: "
                         f"{done.stderr.strip()[-300:]}")
    solved = found.group(1) == "solved"
    return Run(float(found.group(2)) if solved else limit, solved)


def measure_case(vehicle: str, problem: Path, args) -> dict[tuple[str, str], list[Run]]:
    """Runs per (planner, mode) for one problem; OMPL's under ("ompl", "ompl")."""
    runs: dict[tuple[str, str], list[Run]] = {}
    turn = 0
    for seed in range(1, args.seeds + 1):
        for _ in range(args.repeats):
            jobs = [(planner, mode) for planner in args.planners.get(vehicle, ())
                    for mode in (MODES if turn % 2 == 0 else MODES[::-1])]
            if not args.no_ompl:
                jobs.insert(turn % (len(jobs) + 1), ("ompl", "ompl"))
                if args.ompl_cpp[vehicle]:
                    jobs.insert((turn + 1) % (len(jobs) + 1), ("ompl-cpp", "ompl-cpp"))
            turn += 1
            for planner, mode in jobs:
                ompl_planner = "rrt" if mode == "ompl" else planner
                argv, env = command(mode, vehicle, ompl_planner, seed, args.time)
                runs.setdefault((planner, mode), []).append(
                    run_once(argv, env, problem, args.time, mode))
    return runs


def _ms(runs: list[Run]) -> str:
    text = f"{statistics.median(run.seconds for run in runs) * 1000:.1f}"
    unsolved = sum(not run.solved for run in runs)
    return text + (f" ({unsolved} unsolved)" if unsolved else "")


def _ratio(a: list[Run], b: list[Run]) -> str:
    return f"{statistics.median(r.seconds for r in a) / statistics.median(r.seconds for r in b):.2f}"


def table_rows(vehicle: str, problem: Path, runs) -> list[str]:
    ompl, cpp = runs.get(("ompl", "ompl")), runs.get(("ompl-cpp", "ompl-cpp"))
    rows = []
    for planner in sorted({planner for planner, mode in runs if mode in MODES}):
        compiled, interpreted = runs[(planner, "compiled")], runs[(planner, "interpreted")]
        cells = [vehicle, problem_id(problem), planner, _ms(compiled), _ms(interpreted),
                 _ratio(interpreted, compiled)]
        cells += [_ms(ompl), _ratio(compiled, ompl), _ratio(interpreted, ompl)] if ompl else \
            ["-", "-", "-"]
        cells += [_ms(cpp), _ratio(compiled, cpp)] if cpp else ["-", "-"]
        rows.append("| " + " | ".join(cells) + " |")
    return rows


def kernel_times(seed: int = 1, calls: int = 2000,
                 repeats: int = 7) -> tuple[float, float, float]:
    """In this process: median microseconds per slice of ``propagate_while`` over an
    open map, per quadtree ``nearest`` query among 5000 uniform points, and per
    control tried by the ship RRT's steering (sample, propagate, closeness)."""
    import random
    import time
    from planning_core.nearest.quadtree import QuadtreeNearest
    from planning_core.problem import Problem
    from planning_core.setups import grid_setup
    from planning_core.systems.spaceship import SLICES, SYSTEM
    from rrt_cli.planners.steering import ControlSamplingSteering
    side = 100
    si = grid_setup(
        Problem(side, side, bytes(side * side), (1.0, 1.0), (99.0, 99.0)), "spaceship").si
    world = si.world
    rng = random.Random(seed)
    starts = [(rng.uniform(40, 60), rng.uniform(40, 60), rng.uniform(-1, 1), rng.uniform(-1, 1))
              for _ in range(calls)]
    controls = [SYSTEM.sample_control(rng) for _ in range(calls)]
    index = QuadtreeNearest(side, side)
    for _ in range(5000):
        index.add(rng.random() * side, rng.random() * side)
    queries = [(rng.random() * side, rng.random() * side) for _ in range(calls)]

    def per_call(work, count: int) -> float:
        times = []
        for _ in range(repeats):
            began = time.perf_counter()
            work()
            times.append((time.perf_counter() - began) / count * 1e6)
        return statistics.median(times)

    propagate, nearest = SYSTEM.propagate_while, index.nearest
    slice_us = per_call(lambda: [propagate(s, c, world) for s, c in zip(starts, controls)],
                        calls * SLICES)
    query_us = per_call(lambda: [nearest(x, y) for x, y in queries], calls)
    extend = ControlSamplingSteering(si, 10).extend
    steer_us = per_call(lambda: [extend(s, q, rng) for s, q in zip(starts, queries)], calls * 10)
    return slice_us, query_us, steer_us


def kernels(rounds: int) -> None:
    """Kernel times compiled and interpreted, each in its own process, alternating."""
    times: dict[str, list[tuple[float, ...]]] = {mode: [] for mode in MODES}
    for turn in range(rounds):
        for mode in MODES if turn % 2 == 0 else MODES[::-1]:
            env = dict(os.environ, PYTHONPATH=str(ROOT), RRT_INTERPRETED=(
                "1" if mode == "interpreted" else ""))
            child = ("import sys; from rrt_startup.compiled import activate; "
                     "state = activate(); from benchmarks.bench_compiled import kernel_times; "
                     "print(state.split()[0].rstrip(':'), *kernel_times())")
            out = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True,
                                 env=env, cwd=ROOT, check=True).stdout.split()
            if out[0] != mode:
                raise SystemExit(f"bench_compiled: asked for {mode}, ran {out[0]}")
            times[mode].append(tuple(float(value) for value in out[1:4]))
    print(f"# kernels: medians of {rounds} processes per mode (microseconds)")
    print("| mode | propagate_while, per slice | quadtree nearest, 5000 points "
          "| steering, per control |")
    print("|---|---:|---:|---:|")
    for mode, values in times.items():
        print(f"| {mode} | " + " | ".join(f"{statistics.median(v[k] for v in values):.3f}"
                                         for k in range(3)) + " |")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--time", type=float, default=30.0, help="time limit of every run")
    parser.add_argument("--vehicles", nargs="+", choices=sorted(OUR_PLANNERS),
                        default=["point", "spaceship", "left"])
    parser.add_argument("--problems", nargs="*", default=[], metavar="PATTERN")
    parser.add_argument("--no-ompl", action="store_true", help="leave OMPL out")
    parser.add_argument("--kernels", type=int, metavar="ROUNDS", default=0,
                        help="only time the slice and the nearest query, ROUNDS processes "
                             "per mode")
    args = parser.parse_args(argv)
    if args.kernels:
        kernels(args.kernels)
        return 0
    args.planners = OUR_PLANNERS
    args.ompl_cpp = {vehicle: not args.no_ompl and cpp_program(vehicle) is not None
                     for vehicle in args.vehicles}
    print(f"# planning time (ms, medians of {args.seeds} seeds x {args.repeats}), "
          f"compiled vs interpreted vs OMPL RRT (Python callbacks; C++ callbacks: "
          f"{'yes' if all(args.ompl_cpp.values()) else 'not built'}), limit {args.time:g} s")
    print("| vehicle | problem | planner | compiled | interpreted | interp / comp "
          "| OMPL RRT | comp / OMPL | interp / OMPL | OMPL C++ | comp / C++ |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for vehicle in args.vehicles:
        for problem in problems_for(vehicle, args.problems):
            for row in table_rows(vehicle, problem, measure_case(vehicle, problem, args)):
                print(row, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
