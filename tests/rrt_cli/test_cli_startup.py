"""The planner's start-up savings change nothing a user sees: the common command
lines parsed without argparse give argparse's values, its errors and the same
bytes; ``./run.sh`` leaves argparse and smoothing (and, once every dataclass it builds
has a docstring, inspect and copy) unimported."""

from __future__ import annotations

import ast
import subprocess
import sys

import pytest

from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from rrt_cli import cli
from tests.conftest import COURSE_DIR, ROOT, plan_in_process, script_code
from validator.checks import validate_output

SPACE1 = COURSE_DIR / "space-1.sw"


@pytest.mark.parametrize("argv", [
    [], ["-seed", "1"], ["-grad", "-seed", "0"], ["-left", "-stats", "-seed", "18446744073709551615"],
    ["-ugrad", "-smooth", "-time", "2.5", "-iterations", "+7"], ["-planner", "rrtconnect"],
    ["-seed", "1", "-seed", "2"], ["-time", "1e-3", "-grad", "-grad"], ["-ugrad", "-grad"],
])
def test_quick_parse_gives_what_argparse_gives(argv):
    quick = cli.quick_parse(argv)
    assert quick is not None
    assert vars(quick) == vars(cli.build_parser().parse_args(argv))


@pytest.mark.parametrize("argv", [
    ["-h"], ["-see", "1"], ["-seed=1"], ["-seed"], ["-seed", "-1"], ["-seed", "x"],
    ["-time", "0"], ["-iterations", "0"], ["-planner", "nope"], ["-planner", ""],
    ["map.sw"], ["--"], ["-gard"], ["-seed", "1", "extra"],
])
def test_quick_parse_leaves_everything_else_to_argparse(argv):
    assert cli.quick_parse(argv) is None


def test_a_usage_error_after_quick_parse_reads_as_argparse_writes_it(monkeypatch, capsys):
    # "-gra" is an abbreviation, so argparse parses that line; "-grad" is parsed quickly.
    errors = []
    for argv in (["-ugrad", "-grad"], ["-ugrad", "-gra"]):
        with pytest.raises(SystemExit) as done:
            cli.main(argv)
        assert done.value.code == 2
        errors.append(capsys.readouterr().err)
    assert errors[0] == errors[1]
    assert errors[0].splitlines()[-1] == ("rrt_cli: error: -ugrad cannot be combined with "
                                          "-grad or -left")


@pytest.mark.parametrize("flags", [[], ["-grad"]])
def test_both_parsers_give_the_same_answer_and_it_validates(monkeypatch, flags):
    text = SPACE1.read_text()
    quick = plan_in_process(monkeypatch, [*flags, "-seed", "4"], text)
    full = plan_in_process(monkeypatch, [*flags, "-seed=4"], text)  # argparse's path
    assert quick == full
    assert quick[0] == 0
    vehicle = Vehicle.SPACESHIP if flags else Vehicle.POINT
    report = validate_output(parse_problem(text), vehicle, quick[1])
    assert report.valid, report.first_failure


PROBE = """
import atexit, sys
def report():
    names = ("argparse", "rrt_cli.smoothing", "ast", "weakref", "planning_core.kinoplan",
             "planning_core.family_geometric_space_information", "planning_core.nearest.kdtree",
             "typing")
    sys.stderr.write("loaded: %s\\n" % ",".join(n for n in names if n in sys.modules))
atexit.register(report)
"""


def run_sh_start_loads(*flags: str) -> set[str]:
    """Which of the probe's modules ``./run.sh -seed 1 [flags] < space-1`` imported."""
    code = script_code("run.sh")
    with open(SPACE1, "rb") as problem:
        done = subprocess.run([sys.executable, "-S", "-I", "-B", "-c", PROBE + code, str(ROOT),
                               "-seed", "1", *flags], stdin=problem, capture_output=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return set(done.stderr.decode().splitlines()[-1][len("loaded: "):].split(","))


def test_run_sh_imports_neither_argparse_nor_smoothing():
    assert not {"argparse", "rrt_cli.smoothing"} & run_sh_start_loads()


def test_run_sh_imports_nothing_of_the_family_for_a_grid_problem():
    assert not {"planning_core.kinoplan", "planning_core.family_geometric_space_information",
                "planning_core.nearest.kdtree"} & run_sh_start_loads()


@pytest.mark.parametrize("flags", [(), ("-grad",), ("-grad", "-left")])
def test_run_sh_imports_no_typing(flags):
    """The start-up path's annotations are for type checking only (docs/setup-and-startup.md)."""
    assert "typing" not in run_sh_start_loads(*flags)


def test_run_sh_imports_neither_inspect_nor_copy():
    assert not {"ast", "weakref"} & run_sh_start_loads()  # what inspect and copy import


STUB_PROBE = """
from dataclasses import dataclass
before = sorted({"ast", "weakref"} & set(sys.modules))

@dataclass
class NoDoc:
    x: int

import inspect
real = sys.modules["inspect"]
missing = getattr(inspect, "no_such_name", None)
print(before, NoDoc.__doc__, sys.modules["inspect"] is real, inspect.signature is real.signature,
      missing, __import__("copy").deepcopy([[1]]))
"""


def test_run_sh_imports_inspect_and_copy_when_used_and_once():
    stub = (f"import sys\nsys.path.insert(0, {str(ROOT)!r})\n"
            "from rrt_startup.launch import defer_dataclasses_imports\n"
            "defer_dataclasses_imports()\n")
    done = subprocess.run([sys.executable, "-S", "-I", "-B", "-c", stub + STUB_PROBE],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split("\n")[0] == "[] NoDoc(x: int) True True None [[1]]"


def test_a_dataclass_with_class_variables_imports_typing_when_it_runs():
    """``dataclasses`` tells a string annotation ``ClassVar[...]`` from a field's only
    when ``typing`` is imported: a dataclass declaring class variables in its own body
    is in a module that imports ``typing`` at its top level (not under
    ``TYPE_CHECKING``, as the start-up path's modules do; their class variables go on
    a plain base, as the grid systems' ``*Variables`` classes)."""
    found = []
    for package in ("planning_core", "rrt_cli", "cli_common", "validator"):
        for path in (ROOT / package).rglob("*.py"):
            module = ast.parse(path.read_text())
            imports_typing = any(isinstance(node, ast.ImportFrom) and node.module == "typing"
                                 or isinstance(node, ast.Import)
                                 and "typing" in [alias.name for alias in node.names]
                                 for node in module.body)
            for node in ast.walk(module):
                if isinstance(node, ast.ClassDef) and any(
                        "dataclass" in ast.unparse(decorator) for decorator in node.decorator_list):
                    found += [f"{path.name}:{item.lineno}" for item in node.body
                              if isinstance(item, ast.AnnAssign) and not imports_typing
                              and "ClassVar" in ast.unparse(item.annotation)]
    assert found == []
