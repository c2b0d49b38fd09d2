"""Shared test helpers: the repository root, the course problems, a planner runner."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
# Copies of the course problems (../shared/problems/course) kept in the repo, so a clone is self-contained.
COURSE_DIR = ROOT / "benchmarks" / "problems" / "course"
COURSE_PROBLEMS = sorted(COURSE_DIR.glob("*.sw"))


def run_planner(args: list[str], stdin: str, timeout: float = 120) -> subprocess.CompletedProcess:
    """Run ``python -m rrt_cli`` as a user would, with the problem on stdin."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "rrt_cli", *args], input=stdin.encode(),
                          capture_output=True, timeout=timeout, cwd=ROOT, env=env)


@pytest.fixture(scope="session")
def course_problems() -> list[Path]:
    if not COURSE_PROBLEMS:
        pytest.fail(f"course problems not found in {COURSE_DIR}")
    return COURSE_PROBLEMS
