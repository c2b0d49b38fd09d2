"""A problem file of the problems folder as a run needs it: parsed, the text its
planner reads on stdin, and the validator's Setup for a mode. The suffix says the
format: ``.sw`` a grid map (any mode), ``.kp`` a ``kinoplan`` problem (its one mode)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from grading.rubric import KINOPLAN, MODE_FLAGS, MODE_VEHICLES
from planning_core.problem_text import ProblemFormatError, format_problem, parse_problem
from planning_core.setups import Setup, grid_setup, kinoplan_setup
from planning_core.vehicles import Vehicle

MAX_PROBLEM_BYTES = 64 << 20  # as rrt-validator reads from stdin


@dataclass(frozen=True)
class GradedProblem:
    """One problem file, read."""

    problem: Any      # planning_core Problem (.sw) or KinoplanProblem (.kp)
    stdin: bytes      # what run.sh reads: the canonical .sw layout, a .kp text as it is
    kinoplan: bool

    def setup(self, mode: str) -> Setup:
        """The validator's Setup of this problem in ``mode``."""
        if self.kinoplan:
            return kinoplan_setup(self.problem)
        return grid_setup(self.problem, MODE_VEHICLES[mode])

    @staticmethod
    def flags(mode: str) -> tuple[str, ...]:
        """The flags run.sh gets in ``mode`` (none for a .kp problem)."""
        return () if mode == KINOPLAN else MODE_FLAGS[mode]

    @staticmethod
    def vehicle(mode: str) -> Vehicle:
        """The vehicle the drawing is told of (a .kp problem draws its own system)."""
        return MODE_VEHICLES.get(mode, Vehicle.POINT)


def read_problem(path: Path) -> GradedProblem:
    """The problem in ``path``; ProblemFormatError (line and column) or OSError."""
    with open(path, "rb") as file:
        data = file.read(MAX_PROBLEM_BYTES + 1)
    if len(data) > MAX_PROBLEM_BYTES:
        raise ProblemFormatError(1, 1, f"more than {MAX_PROBLEM_BYTES} bytes")
    text = data.decode("utf-8", errors="replace")
    if path.suffix == ".kp":
        from planning_core.kinoplan_text import parse_kinoplan  # only for .kp problems
        problem = parse_kinoplan(text)  # ASCII only: the text goes to run.sh as it is
        return GradedProblem(problem, text.encode("ascii"), True)
    problem = parse_problem(text)
    return GradedProblem(problem, format_problem(problem).encode("ascii"), False)
