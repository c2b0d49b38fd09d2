"""The validator's start-up savings: before the planner starts it imports neither
subprocess (with threading and locale), selectors, ctypes (the containment's prctl is
made from its C module), the checks nor dataclasses; inspect and copy are never
imported (stand-ins, as for the planner), nor typing, nor argparse for the usual
command line."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.conftest import script_code
from validator_testlib import PROBLEMS, ROOT

# Prepended to ./rrt-validator's own start: which of these modules are imported when
# the planner is forked, and at the end (atexit: exit_now runs it too).
PROBE = """
import atexit, os, sys
NAMES = ("subprocess", "threading", "locale", "selectors", "ctypes", "dataclasses", "typing", "ast",
         "weakref", "argparse", "validator.checks", "planning_core.setups")
def loaded():
    return ",".join(name for name in NAMES if name in sys.modules) or "-"
real_fork = os.fork
def fork():
    pid = real_fork()
    if pid:
        sys.stderr.write("at fork: %s\\n" % loaded())
    return pid
os.fork = fork
atexit.register(lambda: sys.stderr.write("at exit: %s\\n" % loaded()))
"""


def validator_loads(*args: str) -> tuple[int, list[str], list[str]]:
    """``./rrt-validator ARGS < space-1``'s status and the probe's two lists."""
    code = script_code("rrt-validator")
    with open(PROBLEMS / "space-1.sw", "rb") as problem:
        done = subprocess.run([sys.executable, "-S", "-I", "-B", "-c", PROBE + code, str(ROOT),
                               *args], stdin=problem, capture_output=True, text=True,
                              timeout=120)
    lines = done.stderr.splitlines()
    at_fork = next(line for line in lines if line.startswith("at fork: "))[len("at fork: "):]
    at_exit = lines[-1][len("at exit: "):]
    return done.returncode, at_fork.split(","), at_exit.split(",")


def test_the_planner_starts_before_the_heavy_imports():
    status, at_fork, _ = validator_loads("-noviz", "--", sys.executable, "-c",
                                         "print(0); print(0)")
    assert status == 1  # an empty trajectory: the checks ran
    assert at_fork == ["-"]


@pytest.mark.parametrize("flags", [[], ["-grad"]])
def test_the_validator_imports_neither_inspect_copy_typing_nor_argparse(flags):
    status, _, at_exit = validator_loads("-noviz", *flags, "--", str(ROOT / "run.sh"), *flags,
                                         "-seed", "1")
    assert status == 0
    assert {"validator.checks", "planning_core.setups", "dataclasses"} <= set(at_exit)
    assert not {"ast", "weakref", "typing", "argparse", "subprocess", "threading", "locale",
                "selectors", "ctypes"} & set(at_exit)
