"""Shared test helpers: the repository root, the course problems, a planner runner."""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
# Copies of the course problems (../shared/problems/course) kept in the repo, so a clone is self-contained.
COURSE_DIR = ROOT / "benchmarks" / "problems" / "course"
COURSE_PROBLEMS = sorted(COURSE_DIR.glob("*.sw"))


def script_code(name: str) -> str:
    """The Python code ``./run.sh`` or ``./rrt-validator`` (``name``) starts the
    interpreter with: its ``-c '...'`` argument, or the validator's ``code='...'``."""
    script = (ROOT / name).read_text()
    if "code='" in script:
        return script.split("code='", 1)[1].split("\n'\n", 1)[0]
    return script.split("-c '", 1)[1].split("\n' ", 1)[0]


def run_planner(args: list[str], stdin: str, timeout: float = 120,
                interpreted: bool = False) -> subprocess.CompletedProcess:
    """Run ``./run.sh ARGS`` as a user would, with the problem on stdin (with the
    compiled modules when their build is fresh, unless ``interpreted``)."""
    env = dict(os.environ)
    if interpreted:
        env["RRT_INTERPRETED"] = "1"
    return subprocess.run([str(ROOT / "run.sh"), *args], input=stdin.encode(),
                          capture_output=True, timeout=timeout, cwd=ROOT, env=env)


def solve_on(planner, setup, *args):
    """``planner.solve`` (a planner module) on a :class:`~planning_core.setups.Setup`:
    its space information and problem definition, then ``stop, rng[, params]``."""
    return planner.solve(setup.si, setup.pdef, *args)


@pytest.fixture(scope="session")
def course_problems() -> list[Path]:
    if not COURSE_PROBLEMS:
        pytest.fail(f"course problems not found in {COURSE_DIR}")
    return COURSE_PROBLEMS


def seed_sweep(seeds, fast=(0,)) -> list:
    """``seeds`` as parameters: the ``fast`` ones run in the unit run, the others
    are marked slow (``-m "not slow"`` skips them; ``./test.sh`` runs them all).
    Test ids stay the bare seeds."""
    return [pytest.param(seed, marks=() if seed in fast else pytest.mark.slow)
            for seed in seeds]


def unit_sample(params, keep: int = 1) -> list:
    """``params`` for ``parametrize`` with the first ``keep`` in the unit run and the
    rest marked slow: one case per path stays in ``-m "not slow"``, every case runs in
    ``./test.sh``. An item is a ``pytest.param`` (its id and marks are kept), a tuple
    (one case's values, as for several argnames) or one value."""
    sample = []
    for index, item in enumerate(params):
        if isinstance(item, type(pytest.param(None))):
            values, marks, ident = item.values, item.marks, item.id
        else:
            values, marks, ident = item if isinstance(item, tuple) else (item,), (), None
        if index >= keep:
            marks = (*marks, pytest.mark.slow)
        sample.append(pytest.param(*values, marks=marks, id=ident))
    return sample


def property_pair(check, *strategies, unit: int, full: int, **named) -> tuple:
    """``check`` as two Hypothesis properties over the same strategies: ``unit`` examples
    in the unit run and a twin with ``full`` examples, marked slow, in ``./test.sh``.
    Bind both: ``test_x, test_x_full = property_pair(check_x, st.integers(), unit=50,
    full=150)``."""
    from hypothesis import given, settings

    def made(examples: int):
        return settings(max_examples=examples, deadline=None)(
            given(*strategies, **named)(check))
    return made(unit), pytest.mark.slow(made(full))


def plan_in_process(monkeypatch, argv: list[str], problem_text: str) -> tuple[int, str, str]:
    """``python -m rrt_cli ARGV < problem`` without a new interpreter: the exit
    status, stdout and stderr."""
    from rrt_cli import cli
    stdin = io.TextIOWrapper(io.BytesIO(problem_text.encode()), encoding="utf-8")
    stdout = io.TextIOWrapper(io.BytesIO(), encoding="utf-8")
    stderr = io.TextIOWrapper(io.BytesIO(), encoding="utf-8")
    with monkeypatch.context() as patch:
        patch.setattr(sys, "stdin", stdin)
        patch.setattr(sys, "stdout", stdout)
        patch.setattr(sys, "stderr", stderr)
        status = cli.main(argv)
        stdout.flush()
        stderr.flush()
    return status, stdout.buffer.getvalue().decode(), stderr.buffer.getvalue().decode()


def built_kernel(name: str):
    """The C kernel module ``name`` of the compiled build, loaded by its path (the test
    process runs interpreted), or None when the build is not fresh. Loading registers
    it in ``sys.modules``; it is taken out again, so it is in use only when asked."""
    import importlib.util
    from rrt_startup import compiled
    if compiled.why_not_fresh(compiled.BUILD_DIR) is not None:
        return None
    path = os.path.join(compiled.BUILD_DIR, *name.split(".")) + compiled.extension_suffix()
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    sys.modules.pop(name, None)
    return module
