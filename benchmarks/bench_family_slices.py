"""Microseconds per slice of the family systems (SPEC 5.2): the generated integrator,
the readable reference it must equal, and propagate_while with the state test of an
example problem's world (body placement and obstacle tests included).

Each figure is the median over ``--repeats`` timings of ``--number`` controls held
for 20 slices; the ratio reference / compiled is taken in the same run.

    python -m benchmarks.bench_family_slices [--repeats 7] [--number 300]
"""

from __future__ import annotations

import argparse
import statistics
import timeit
from dataclasses import replace
from pathlib import Path

from planning_core.integrators import ReferenceIntegrator
from planning_core.kinoplan import state_validator
from planning_core.kinoplan_text import parse_kinoplan

PROBLEMS = Path(__file__).resolve().parent / "problems" / "family"
EXAMPLES = {"pendulum": "pendulum-t3.kp", "car2": "car2-corridors.kp",
            "unicycle": "unicycle-circles.kp", "car1": "car1-scene1.kp"}
SLICES = 20


def _median_us(fn, number: int, repeats: int) -> float:
    times = timeit.repeat(fn, number=number, repeat=repeats)
    return statistics.median(times) / (number * SLICES) * 1e6


def _reference(system):
    loop = ReferenceIntegrator(system.dynamics, system.scheme, system.dt,
                               system.space.satisfies_bounds)

    def run(state, held):
        return loop.slices(state, held, SLICES)
    return run


def measure(name: str, scheme: str, number: int, repeats: int) -> dict:
    problem = parse_kinoplan((PROBLEMS / EXAMPLES[name]).read_text())
    system = replace(problem.system, scheme=scheme, kmax=max(SLICES, problem.system.kmax))
    valid = state_validator(system, problem.world)
    start, held = problem.start, tuple(lo + 0.75 * (hi - lo) for lo, hi in system.controls)
    control = (*held, SLICES)
    reference = _reference(system)
    assert reference(start, held) == system.propagate(start, control)
    return {
        "generated": _median_us(lambda: system.propagate(start, control), number, repeats),
        "reference": _median_us(lambda: reference(start, held), number, repeats),
        "with_state_test": _median_us(lambda: system.propagate_while(start, control, valid),
                                      number, repeats),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--number", type=int, default=300)
    args = parser.parse_args(argv)
    print("| system | scheme | generated (us/slice) | reference (us/slice) | ratio | "
          "with state test (us/slice) |")
    print("|---|---|---|---|---|---|")
    for name in EXAMPLES:
        for scheme in ("euler", "rk4"):
            m = measure(name, scheme, args.number, args.repeats)
            print(f"| {name} | {scheme} | {m['generated']:.2f} | {m['reference']:.2f} | "
                  f"{m['reference'] / m['generated']:.1f}x | {m['with_state_test']:.2f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
