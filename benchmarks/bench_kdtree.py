"""Nearest-neighbour queries: the wrap-aware kd-tree against a linear scan.

For each space (R^2; SE(2) with ``metric x,y 0.7 theta 0.3``; a 5-D state
x, y, theta, psi, v with ``metric x,y 1 theta,psi 0.5 v 0.3``, two angles) and
each size N, grows N points the way RRT does (from the centre, each new point
a step of at most 1 from its nearest neighbour toward a uniform sample, on a
100 x 100 world), then times ``nearest`` for uniform queries on the final
structure: the median over repeats of microseconds per query, and the
scan/kd-tree ratio, measured in the same run. The scan is O(N) per query in
Python, so it answers fewer queries at large N (the table says how many); its
answers are checked against the kd-tree's.

    python -m benchmarks.bench_kdtree [--sizes 1000 10000 100000] [--repeats 3] [--queries 1000]

With ``--k-nearest``, seed 004's table instead: ``k_nearest`` for
k = 3..20 on roadmaps of N = 100..2000 uniform points (as PRM grows them) in
the arm's torus (theta1, theta2, metric 1) and SE(2) (``x,y 0.7 theta 0.3``,
a 2 x 2 world as in the rigid2 scenes), kd-tree against the scan, answers
compared on every query:

    python -m benchmarks.bench_kdtree --k-nearest [--sizes 100 200 500 1000 2000] [--ks 3 5 10 20]

Table on stdout; progress on stderr.
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys
import time

from planning_core.nearest.kdtree import KDTree, LinearScan
from planning_core.spaces import StateSpace, Variable

SIDE = 100.0
STEP = 1.0
SCAN_BUDGET = 2_000_000  # distance evaluations per repeat for the linear scan


def spaces() -> dict[str, StateSpace]:
    """The three spaces of the table, by label."""
    x, y = Variable("x", 0.0, SIDE), Variable("y", 0.0, SIDE)
    theta = Variable("theta", angle=True)
    return {
        "R^2": StateSpace.from_metric((x, y), {"x,y": 1.0}),
        "SE(2)": StateSpace.from_metric((x, y, theta), {"x,y": 0.7, "theta": 0.3}),
        "5-D, 2 angles": StateSpace.from_metric(
            (x, y, theta, Variable("psi", angle=True), Variable("v", -2.0, 2.0)),
            {"x,y": 1.0, "theta,psi": 0.5, "v": 0.3}),
    }


def roadmap_spaces() -> dict[str, StateSpace]:
    """The geometric family's two spaces: the arm's torus and the rigid body's SE(2)."""
    x, y = Variable("x", 0.0, 2.0), Variable("y", 0.0, 2.0)
    theta1, theta2 = Variable("theta1", angle=True), Variable("theta2", angle=True)
    return {
        "torus (arm2)": StateSpace.from_metric((theta1, theta2), {"theta1,theta2": 1.0}),
        "SE(2) (rigid2)": StateSpace.from_metric((x, y, Variable("theta", angle=True)),
                                                 {"x,y": 0.7, "theta": 0.3}),
    }


def measure_k_nearest(space: StateSpace, size: int, k: int, repeats: int,
                      n_queries: int) -> dict:
    """One row of seed 004's table: microseconds per ``k_nearest`` query on N
    uniform points, kd-tree and scan (medians over ``repeats``), answers compared."""
    rng = random.Random(size * 100 + k)
    tree, scan = KDTree(space), LinearScan(space)
    for _ in range(size):
        point = space.sample_uniform(rng)
        tree.add(point)
        scan.add(point)
    kd_times, scan_times = [], []
    for repeat in range(repeats):
        queries = [space.sample_uniform(rng) for _ in range(n_queries)]
        timed = []
        for structure in (tree, scan):
            k_nearest = structure.k_nearest
            began = time.perf_counter()
            timed.append([k_nearest(q, k) for q in queries])
            (kd_times if structure is tree else scan_times).append(
                (time.perf_counter() - began) / n_queries)
        if timed[0] != timed[1]:
            raise AssertionError(f"kd-tree and scan disagree at N = {size}, k = {k}")
    return {"kd": statistics.median(kd_times) * 1e6, "scan": statistics.median(scan_times) * 1e6}


def k_nearest_table(sizes: list[int], ks: list[int], repeats: int, n_queries: int) -> None:
    print(f"# k_nearest(): N uniform points, {n_queries} uniform queries a repeat; median of "
          f"{repeats} repeats, microseconds per query; answers identical on every query")
    print("| space | N | k | kd-tree (us) | linear scan (us) | scan / kd-tree |")
    print("|---|---:|---:|---:|---:|---:|")
    for label, space in roadmap_spaces().items():
        for size in sizes:
            for k in ks:
                print(f"bench_kdtree: {label}, N = {size}, k = {k} ...", file=sys.stderr,
                      flush=True)
                row = measure_k_nearest(space, size, k, repeats, n_queries)
                print(f"| {label} | {size} | {k} | {row['kd']:.1f} | {row['scan']:.0f} | "
                      f"{row['scan'] / row['kd']:.1f}x |", flush=True)


def grow(space: StateSpace, size: int, seed: int) -> tuple[KDTree, float]:
    """An RRT-like tree of ``size`` points; also the mean seconds per ``add``."""
    rng = random.Random(seed)
    tree = KDTree(space)
    centre = tuple(0.0 if v.angle else (v.low + v.high) / 2 for v in space.variables)
    tree.add(centre)
    adding = 0.0
    for _ in range(size - 1):
        target = space.sample_uniform(rng)
        near = tree[tree.nearest(target)]
        d = space.distance(near, target)
        new = space.interpolate(near, target, min(1.0, STEP / d) if d > 0 else 0.0)
        began = time.perf_counter()
        tree.add(new)
        adding += time.perf_counter() - began
    return tree, adding / size


def time_queries(structure, queries: list) -> tuple[float, list[int]]:
    """Seconds per ``nearest`` query, and the answers."""
    nearest = structure.nearest
    began = time.perf_counter()
    answers = [nearest(q) for q in queries]
    return (time.perf_counter() - began) / len(queries), answers


def measure(space: StateSpace, size: int, repeats: int, n_queries: int) -> dict:
    """One table row: medians over ``repeats`` query batches on one grown tree."""
    tree, add_seconds = grow(space, size, seed=size)
    scan = LinearScan(space)
    for i in range(len(tree)):
        scan.add(tree[i])
    n_scan = min(n_queries, max(10, SCAN_BUDGET // size))
    kd_times, scan_times = [], []
    for repeat in range(repeats):
        rng = random.Random(1000 + repeat)
        queries = [space.sample_uniform(rng) for _ in range(n_queries)]
        seconds, kd_answers = time_queries(tree, queries)
        kd_times.append(seconds)
        seconds, scan_answers = time_queries(scan, queries[:n_scan])
        scan_times.append(seconds)
        if scan_answers != kd_answers[:n_scan]:
            raise AssertionError(f"kd-tree and scan disagree at N = {size}")
    return {"kd": statistics.median(kd_times) * 1e6, "scan": statistics.median(scan_times) * 1e6,
            "add": add_seconds * 1e6, "n_scan": n_scan}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=None,
                        help="N (default: 1000 10000 100000; --k-nearest: 100 200 500 1000 2000)")
    parser.add_argument("--k-nearest", action="store_true",
                        help="seed 004's table: k_nearest on the torus and SE(2)")
    parser.add_argument("--ks", type=int, nargs="+", default=[3, 5, 10, 20],
                        help="k for --k-nearest (default: 3 5 10 20)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--queries", type=int, default=1000,
                        help="kd-tree queries per repeat (the scan: fewer at large N)")
    args = parser.parse_args(argv)
    if args.sizes is None:
        args.sizes = [100, 200, 500, 1000, 2000] if args.k_nearest else [1000, 10000, 100000]
    if min(args.sizes + args.ks) < 1 or args.repeats < 1 or args.queries < 1:
        parser.error("sizes, ks, repeats and queries must be positive")
    if args.k_nearest:
        k_nearest_table(args.sizes, args.ks, args.repeats, args.queries)
        return 0
    print(f"# nearest(): RRT-like trees (step {STEP:g}, {SIDE:g} x {SIDE:g} world), uniform queries;")
    print(f"# median of {args.repeats} repeats, microseconds per query; the scan answers "
          f"{SCAN_BUDGET:,} / N queries per repeat (at least 10, at most {args.queries})")
    print("| space | N | kd-tree (us) | linear scan (us) | scan / kd-tree | kd add (us) | scan queries |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    began = time.perf_counter()
    for label, space in spaces().items():
        for size in args.sizes:
            print(f"bench_kdtree: {label}, N = {size} ...", file=sys.stderr, flush=True)
            row = measure(space, size, args.repeats, args.queries)
            print(f"| {label} | {size} | {row['kd']:.1f} | {row['scan']:.0f} | "
                  f"{row['scan'] / row['kd']:.0f}x | {row['add']:.1f} | {row['n_scan']} |", flush=True)
    print(f"# answers identical on every scan query; total {time.perf_counter() - began:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
