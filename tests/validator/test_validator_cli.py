"""The command's interface: flags, usage errors, bad problems, the JSON object."""

from __future__ import annotations

import json
import math
import sys

import pytest

from validator.checks import INVALID_VERDICT, VALID_VERDICT
from validator_testlib import CORPUS, run_validator

SPACE0 = (CORPUS / "problems/space-0.sw").read_text()
GOOD_POINT = CORPUS / "outputs/point/valid-handmade.out"


@pytest.mark.parametrize("args", [
    [],                                           # no planner
    ["-grad"],                                    # no --
    ["-grad", "cat", str(GOOD_POINT)],            # planner without --
    ["-ugrad", "-grad", "--", "cat"],
    ["-ugrad", "-left", "--", "cat"],
    ["-timeout", "0", "--", "cat"],
    ["-timeout", "nan", "--", "cat"],
    ["-timeout", "soon", "--", "cat"],
    ["-bogus", "--", "cat"],
    ["-o", ".", "--", "cat"],
])
def test_usage_errors_exit_2_without_running_anything(args, tmp_path):
    marker = tmp_path / "ran"
    done = run_validator([*args, "touch", str(marker)] if "--" in args else args, SPACE0,
                         tmp_path)
    assert done.returncode == 2
    assert done.stdout == b"" and b"Traceback" not in done.stderr
    assert done.stderr.decode().splitlines()[-1].startswith("rrt-validator: error: ")
    assert not marker.exists()


def test_help_exits_0_and_lists_every_flag(tmp_path):
    done = run_validator(["-h"], "", tmp_path)
    assert done.returncode == 0
    for flag in ("-ugrad", "-grad", "-left", "-strict", "-noviz", "-o FILE", "-timeout S",
                 "-json", "Exit status"):
        assert flag in done.stdout.decode()


@pytest.mark.parametrize("problem, where", [
    ("", "line 1, column 1"),
    ("4\n3\n____\n__#_\n___#\n0.1\n1.54\n3.8\n", "line 8"),
    ("4\n3\n____\n__#_\n___#\n2.5\n1.5\n3.8\n1.1\n", "line 6, column 1"),  # start blocked
    ("4\n3\n____\n__?_\n___#\n0.1\n1.54\n3.8\n1.1\n", "line 4, column 3"),
    ("\x00\xff garbage", "line 1"),
])
def test_bad_problem_exits_2_with_one_line(problem, where, tmp_path):
    marker = tmp_path / "ran"
    done = run_validator(["--", "touch", str(marker)], problem.encode("latin-1"), tmp_path,
                         pipe=True)  # (in a file: test_validator_launcher.py)
    assert done.returncode == 2 and done.stdout == b""
    lines = done.stderr.decode().splitlines()
    assert len(lines) == 1 and lines[0].startswith("rrt-validator: bad problem: ")
    assert where in lines[0]
    assert not marker.exists() and not (tmp_path / "tree-viz.pdf").exists()


def test_json_object_for_a_valid_answer(tmp_path):
    done = run_validator(["-json", "-noviz", "--", "cat", str(GOOD_POINT)], SPACE0, tmp_path)
    assert done.returncode == 0
    report = json.loads(done.stdout)  # stdout is only the JSON object
    assert report["verdict"] == "valid" and report["verdict_line"] == VALID_VERDICT
    assert report["exit_status"] == 0 and report["vehicle"] == "point"
    assert [c["status"] for c in report["checks"]] == ["passed"] * 6 + ["not applicable"] * 2
    assert report["first_failure"] is None and report["first_failing_line"] is None
    assert report["counts"] == {"trajectory": 4, "tree": 3, "corner_cuts": 0}
    assert report["path_length"] == pytest.approx(math.hypot(1.4, 0.96) + 2.0
                                                  + math.hypot(0.3, 1.4))
    assert report["planner"]["exit_code"] == 0 and report["planner"]["wall_time"] >= 0
    assert report["planner"]["command"] == ["cat", str(GOOD_POINT)]
    assert report["pdf"] is None


def test_json_object_for_an_invalid_spaceship_answer(tmp_path):
    output = CORPUS / "outputs/spaceship/dynamics-wrong-state.out"
    done = run_validator(["-grad", "-json", "--", "cat", str(output)],
                         (CORPUS / "problems/open.sw").read_text(), tmp_path)
    assert done.returncode == 1
    report = json.loads(done.stdout)
    assert report["verdict"] == "invalid" and report["verdict_line"] == INVALID_VERDICT
    assert [c["status"] for c in report["checks"]] == ["passed"] * 6 + ["failed", "not applicable"]
    assert report["first_failure"]["message"].startswith("Trajectory claims that control <0, 0>")
    assert report["first_failing_line"] == 5 and report["checks"][6]["line"] == 5
    assert report["pdf"] == "tree-viz.pdf" and (tmp_path / "tree-viz.pdf").exists()


def test_left_alone_means_the_left_spaceship(tmp_path):
    output = CORPUS / "outputs/spaceship/valid-right-thrust-grad.out"
    problem = (CORPUS / "problems/open-right.sw").read_text()
    assert run_validator(["-grad", "-noviz", "--", "cat", str(output)], problem,
                         tmp_path).returncode == 0
    done = run_validator(["-left", "-noviz", "--", "cat", str(output)], problem, tmp_path)
    assert done.returncode == 1
    assert "State in trajectory that goes out of bounds!" in done.stdout.decode()


def test_arguments_after_the_double_dash_reach_the_planner_unchanged(tmp_path):
    args = ["-grad", "--", "-x y", "", "--", "*"]
    code = "import sys, json; open('argv.json', 'w').write(json.dumps(sys.argv[1:]))"
    done = run_validator(["-noviz", "--", sys.executable, "-c", code, *args], SPACE0, tmp_path)
    assert done.returncode == 1
    assert json.loads((tmp_path / "argv.json").read_text()) == args
