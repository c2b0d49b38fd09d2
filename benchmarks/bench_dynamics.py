"""One spaceship extension: 10 controls x 20 slices, pure Python vs one numpy batch.

The planner integrates with plain Python floats (planning_core.systems.spaceship);
this measures whether a numpy batch over the 10 controls would be cheaper at this
size. Medians over repeats, ratio measured in the same run.

    python -m benchmarks.bench_dynamics [--repeats 7]
"""

from __future__ import annotations

import argparse
import math
import random
import statistics
import timeit

from planning_core.problem import Problem
from planning_core.systems import spaceship
from planning_core.worlds.grid import GridWorld


def numpy_batch(np, state, thetas, thrusts, blocked, width, height):
    """The same slices for all controls at once; returns the collision-free mask."""
    x = np.full(len(thetas), state[0])
    y = np.full(len(thetas), state[1])
    dx = np.full(len(thetas), state[2])
    dy = np.full(len(thetas), state[3])
    alive = np.ones(len(thetas), dtype=bool)
    step = spaceship.DT * thrusts
    for _ in range(spaceship.SLICES):
        a = np.arctan2(dy, dx) + thetas
        dx = dx + step * np.cos(a)
        dy = dy + step * np.sin(a)
        x = x + spaceship.DT * dx
        y = y + spaceship.DT * dy
        alive &= (x >= 0) & (x < width) & (y >= 0) & (y < height)
        cols = np.clip(x.astype(int), 0, width - 1)
        rows = np.clip(y.astype(int), 0, height - 1)
        alive &= ~blocked[rows, cols]
    return alive


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--number", type=int, default=500)
    args = parser.parse_args(argv)
    import numpy as np  # only the comparison needs it

    width = height = 50
    # Open map: no early exits, the worst case.
    problem = Problem(width, height, bytes(width * height), (1.0, 1.0), (2.0, 2.0))
    grid = GridWorld(problem)
    propagate_while = spaceship.SYSTEM.propagate_while
    blocked_array = np.zeros((height, width), dtype=bool)
    rng = random.Random(0)
    controls = [(rng.random() * 2 * math.pi, rng.random() * 0.5) for _ in range(10)]
    thetas = np.array([c[0] for c in controls])
    thrusts = np.array([c[1] for c in controls])
    state = (25.0, 25.0, 0.2, -0.1)

    def pure_python():
        for control in controls:
            propagate_while(state, control, grid)

    def batched():
        numpy_batch(np, state, thetas, thrusts, blocked_array, width, height)

    results = {}
    for name, fn in (("pure Python (math)", pure_python), ("numpy batch", batched)):
        times = timeit.repeat(fn, number=args.number, repeat=args.repeats)
        results[name] = statistics.median(times) / args.number * 1e6
    base = results["pure Python (math)"]
    print(f"# one extension = 10 controls x {spaceship.SLICES} slices, open 50x50 map; "
          f"median of {args.repeats} x {args.number}")
    print("| integration | us per extension | vs pure Python |")
    print("|---|---:|---:|")
    for name, value in results.items():
        print(f"| {name} | {value:.1f} | {value / base:.2f}x |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
