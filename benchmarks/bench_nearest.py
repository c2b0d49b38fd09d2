"""Nearest-neighbour structures: the planner's quadtree against a linear scan.

Grows trees the way RRT does (each new point is a step from its nearest
neighbour toward a uniform target) and times the nearest queries that growth
makes. Prints medians over several repeats and the scan/quadtree ratio,
measured in the same run.

    python -m benchmarks.bench_nearest [--sizes 1000 10000 50000] [--repeats 5]
"""

from __future__ import annotations

import argparse
import random
import statistics
import time

from planning_core.nearest.quadtree import LinearNearest, QuadtreeNearest


def grow(structure, size: int, width: float, height: float, seed: int,
         step: float) -> float:
    """Seconds spent in nearest() while growing an RRT-like tree of ``size`` points."""
    rng = random.Random(seed)
    structure.add(width / 2, height / 2)
    spent = 0.0
    for _ in range(size - 1):
        tx, ty = rng.random() * width, rng.random() * height
        began = time.perf_counter()
        near = structure.nearest(tx, ty)
        spent += time.perf_counter() - began
        nx, ny = structure.xs[near], structure.ys[near]
        dx, dy = tx - nx, ty - ny
        length = max((dx * dx + dy * dy) ** 0.5, 1e-12)
        scale = min(1.0, step / length)
        structure.add(nx + dx * scale, ny + dy * scale)
    return spent


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1000, 5000, 20000])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--map", type=float, default=200.0, help="square map side")
    parser.add_argument("--linear-max", type=int, default=20000,
                        help="skip the linear scan above this size (it is quadratic)")
    args = parser.parse_args(argv)
    side = args.map
    print(f"# nearest-neighbour queries while growing an RRT-like tree on a {side:g} x {side:g} map")
    print(f"# medians over {args.repeats} runs, microseconds per query")
    print("| tree size | quadtree (us) | linear scan (us) | scan / quadtree |")
    print("|---:|---:|---:|---:|")
    for size in args.sizes:
        quad, linear = [], []
        for repeat in range(args.repeats):
            quad.append(grow(QuadtreeNearest(side, side), size, side, side, repeat, 1.0) / size)
            if size <= args.linear_max:
                linear.append(grow(LinearNearest(), size, side, side, repeat, 1.0) / size)
        q = statistics.median(quad) * 1e6
        if linear:
            s = statistics.median(linear) * 1e6
            print(f"| {size} | {q:.1f} | {s:.1f} | {s / q:.1f}x |", flush=True)
        else:
            print(f"| {size} | {q:.1f} | (skipped) | |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
