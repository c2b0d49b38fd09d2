"""The compiled planners (issue 19): no interpreted class derives from a compiled
one (mypyc refuses it at run time), and a compiled family run prints the bytes the
interpreted one does, an answer the validator accepts. (Grid outputs: tests/golden.)"""

from __future__ import annotations

import ast

import pytest

from rrt_startup import compiled
from planning_core.kinoplan_text import parse_kinoplan
from planning_core.setups import kinoplan_setup
from tests.conftest import ROOT, run_planner
from tests.test_compiled import run_planner_compiled
from validator.checks import validate_plan

PACKAGES = ("planning_core", "cli_common", "rrt_cli", "validator", "benchmarks")
SMALL_CAR2 = ("kinoplan 1\nsystem car2\nworld 0 0 20 20\nrect 8 0 9 12\n"
              "start x 3 y 5 theta 0 v 0\ngoal x 14 y 5 within 2\n")


def _classes(path) -> list[ast.ClassDef]:
    tree = ast.parse(path.read_text())
    return [node for node in ast.walk(tree) if isinstance(node, ast.ClassDef)]


def test_no_interpreted_class_derives_from_a_compiled_class():
    compiled_classes = {(module, node.name) for module in compiled.MODULES
                        for node in _classes(ROOT / compiled.source_path(module))}
    compiled_paths = {compiled.source_path(module) for module in compiled.MODULES}
    offenders = []
    for package in PACKAGES:
        for path in (ROOT / package).rglob("*.py"):
            text = path.read_text()
            if str(path.relative_to(ROOT)) in compiled_paths or not any(
                    f"from {module} import" in text for module in compiled.MODULES):
                continue  # (a base class named here comes from a compiled module's import)
            tree = ast.parse(text)
            imported = {alias.asname or alias.name: (node.module, alias.name)
                        for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)
                        for alias in node.names}
            offenders += [f"{path.relative_to(ROOT)}: {node.name}({base.id})"
                          for node in ast.walk(tree) if isinstance(node, ast.ClassDef)
                          for base in node.bases
                          if isinstance(base, ast.Name) and imported.get(base.id) in compiled_classes]
    assert offenders == []


PENDULUM = (ROOT / "benchmarks" / "problems" / "family" / "pendulum-t3.kp").read_text()


@pytest.mark.parametrize("planner, problem", [
    ("rrt", SMALL_CAR2), ("rgrrt", PENDULUM), ("sst", PENDULUM),
    pytest.param("kpiece", SMALL_CAR2, marks=pytest.mark.slow),
    pytest.param("rgrrt", SMALL_CAR2, marks=pytest.mark.slow),
    pytest.param("blossom", SMALL_CAR2, marks=pytest.mark.slow),
    pytest.param("sst", SMALL_CAR2, marks=pytest.mark.slow),
    pytest.param("rrt", PENDULUM, marks=pytest.mark.slow)])
def test_a_compiled_family_run_prints_the_interpreted_bytes(planner, problem):
    args = ["-planner", planner, "-seed", "2"]
    fast = run_planner_compiled(args, problem)
    assert fast.returncode == 0, fast.stderr
    slow = run_planner(args, problem, interpreted=True)
    assert fast.stdout == slow.stdout
    report = validate_plan(kinoplan_setup(parse_kinoplan(problem)), fast.stdout.decode())
    assert report.valid, report.first_failure


@pytest.mark.parametrize("flags", [["-grad"], ["-grad", "-left"]], ids=["grad", "left"])
def test_a_compiled_ship_sst_run_prints_the_interpreted_bytes(flags):
    """The golden tests pin no SST run: a ship's, compiled and interpreted."""
    problem = (ROOT / "benchmarks" / "problems" / "course" / "space-3.sw").read_text()
    args = [*flags, "-planner", "sst", "-seed", "3"]
    fast = run_planner_compiled(args, problem)
    assert fast.returncode == 0, fast.stderr
    assert fast.stdout == run_planner(args, problem, interpreted=True).stdout
