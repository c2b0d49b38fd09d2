"""Helpers for the validator's tests: the corpus, and running the command as a user would."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle

ROOT = Path(__file__).resolve().parents[2]
CORPUS = Path(__file__).resolve().parent / "corpus"
PROBLEMS = CORPUS / "problems"


@dataclass(frozen=True)
class Case:
    name: str
    problem: str
    output: str
    flags: tuple[str, ...]
    valid: bool
    check: int | None
    message: str | None
    line: int | None
    warning: str | None
    note: str

    @property
    def vehicle(self) -> Vehicle:
        return vehicle_from_flags(self.flags)

    @property
    def output_path(self) -> Path:
        return CORPUS / "outputs" / self.output

    @property
    def problem_path(self) -> Path:
        return PROBLEMS / self.problem

    @property
    def id(self) -> str:
        return f"{self.output.split('/')[0]}-{self.name}" + (
            "-strict" if "-strict" in self.flags else "")


def load_cases() -> list[Case]:
    raw = json.loads((CORPUS / "cases.json").read_text())
    return [Case(**{**c, "flags": tuple(c["flags"])}) for c in raw]


def vehicle_from_flags(flags) -> Vehicle:
    if "-left" in flags:
        return Vehicle.LEFT_SPACESHIP
    return Vehicle.SPACESHIP if "-grad" in flags else Vehicle.POINT


def load_problem(name: str):
    return parse_problem((PROBLEMS / name).read_text())


def run_validator(args: list[str], problem_text: str | bytes, cwd: Path,
                  timeout: float = 60, pipe: bool = False) -> subprocess.CompletedProcess:
    """``./rrt-validator ARGS < problem.sw`` as a user runs it, in ``cwd`` (for
    tree-viz.pdf): the problem in a file of its own (so the launcher starts the
    planner, where built: validator/launch.c), or on a pipe (``pipe``: the validator
    starts it)."""
    data = problem_text.encode() if isinstance(problem_text, str) else problem_text
    command = [str(ROOT / "rrt-validator"), *args]
    if pipe:
        return subprocess.run(command, input=data, capture_output=True, timeout=timeout,
                              cwd=cwd)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "problem.sw"
        path.write_bytes(data)
        with open(path, "rb") as problem:
            return subprocess.run(command, stdin=problem, capture_output=True,
                                  timeout=timeout, cwd=cwd)


def python_planner(code: str) -> list[str]:
    """A planner command that runs ``code`` with this interpreter."""
    return [sys.executable, "-c", code]


def colour_near(image, page_point, rgb, scale: float, radius: int = 2,
                tolerance: int = 60) -> bool:
    """Whether a pixel within ``radius`` of a PDF point (rasterised at ``scale``
    pixels per point) has colour ``rgb`` (0-1 floats) within ``tolerance`` per channel."""
    px, py = page_point
    width, height = image.size
    cx, cy = round(px * scale), round(height - py * scale)
    target = [round(c * 255) for c in rgb]
    for x in range(cx - radius, cx + radius + 1):
        for y in range(cy - radius, cy + radius + 1):
            if 0 <= x < width and 0 <= y < height and all(
                    abs(a - b) <= tolerance for a, b in zip(image.getpixel((x, y)), target)):
                return True
    return False


# A point answer to the course's space-0 that the validator accepts.
VALID_POINT_PLAN = "4\n0.1 1.54\n1.5 2.5\n3.5 2.5\n3.8 1.1\n0\n"


def gone(pid: int) -> bool:
    """Dead: no such process, or a zombie (its parent has not reaped it yet)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except FileNotFoundError:
        return True
    return "\nState:\tZ" in status


def gone_within(pid: int, seconds: float) -> bool:
    """``pid`` is :func:`gone` within ``seconds``; if not, it is killed (nothing a failing
    test started is left running) and the answer is False."""
    deadline = time.monotonic() + seconds
    while not gone(pid):
        if time.monotonic() > deadline:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            return False
        time.sleep(0.02)
    return True
