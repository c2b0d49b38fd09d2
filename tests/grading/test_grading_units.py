"""The score rule, the command line's usage errors, the sandbox's command."""

from __future__ import annotations

import subprocess
import sys

import pytest

from grading.cli import main
from grading.config import Limits
from grading.rubric import Rubric, score
from grading.sandbox import Place, Sandbox
from grading_fixtures import ROOT


def _score(rubric: Rubric, valid: dict[str, int]) -> float:
    """Five problems in point and grad; the first ``valid[mode]`` of them valid in mode."""
    items = rubric.items([f"p{n}.sw" for n in range(5)])
    shares = {(item.problem, item.mode): float(int(item.problem[1]) < valid.get(item.mode, 0))
              for item in items}
    return score(rubric.points(items), shares, rubric.digits)


def test_the_score_weighs_modes_and_scales():
    modes = ("point", "grad")
    assert _score(Rubric(modes=modes), {"point": 5}) == 50.0
    assert _score(Rubric(modes=modes, mode_weights=(("grad", 3.0),)), {"point": 5}) == 25.0
    assert _score(Rubric(modes=modes, scale=20, digits=2), {"point": 1, "grad": 1}) == 4.0
    assert _score(Rubric(modes=modes, scale=None), {"point": 5, "grad": 2}) == 7.0
    assert score({}, {}, 1) == 0.0


@pytest.mark.parametrize("argv", [
    ["--problems", ".", "--out", "o"],
    ["--submissions", ".", "--problems", ".", "--out", "o", "--modes", "point,fly"],
    ["--submissions", "/nonexistent", "--problems", ".", "--out", "o"],
    ["--submissions", ".", "--problems", ".", "--out", "o", "--jobs", "0"],
])
def test_usage_errors_exit_2_with_the_usage_and_one_error_line(argv, capsys):
    with pytest.raises(SystemExit) as done:
        main(argv)
    assert done.value.code == 2
    usage, error = capsys.readouterr().err.splitlines()
    assert usage.startswith("usage: rrt-grade ") and error.startswith("rrt-grade: error: ")


def test_the_contained_command_sets_the_limits_before_the_program(tmp_path):
    place = Place(tmp_path, tmp_path, tmp=tmp_path / "tmp")
    command = Sandbox("none", "").command(place, ["./run.sh", "-grad"], Limits(), 2.5)
    assert command[-2:] == ["./run.sh", "-grad"]
    done = subprocess.run([*command[:-2], "sh", "-c", "ulimit -t; ulimit -v; ulimit -p; pwd; "
                           "echo $TMPDIR; trap"], capture_output=True, text=True, timeout=10)
    assert done.stdout.split() == ["4", str(Limits().memory_bytes // 1024), "64",
                                   str(tmp_path), str(tmp_path / "tmp")]  # no signal ignored


def test_rrt_grade_runs_as_a_module_and_says_what_it_needs():
    done = subprocess.run([sys.executable, "-m", "grading", "--help"], cwd=ROOT,
                          capture_output=True, text=True, timeout=30)
    assert done.returncode == 0 and "--scheduler" in done.stdout


def test_a_bad_problem_is_one_line_and_exit_2_before_anything_runs(tmp_path, capsys):
    (tmp_path / "subs").mkdir()
    (tmp_path / "problems").mkdir()
    (tmp_path / "problems" / "bad.sw").write_text("3 x\n")
    status = main(["--submissions", str(tmp_path / "subs"), "--problems",
                   str(tmp_path / "problems"), "--out", str(tmp_path / "out")])
    assert status == 2 and not (tmp_path / "out").exists()
    assert capsys.readouterr().err.count("bad problem") == 1


def test_rerun_redoes_everything(tmp_path, capsys):
    from grading_fixtures import make_class
    submissions, problems, _ = make_class(tmp_path, ["garbage", "nobuild"], ["simple-0.sw"])
    argv = ["--submissions", str(submissions), "--problems", str(problems),
            "--out", str(tmp_path / "out"), "--modes", "point"]
    assert main(argv) == 0
    assert main(argv) == 0
    assert main([*argv, "--rerun"]) == 0
    lines = [line for line in capsys.readouterr().err.splitlines() if "runs now" in line]
    assert [line.split(";")[0] for line in lines] == [
        "rrt-grade: 2 runs now, 0 kept", "rrt-grade: 0 runs now, 2 kept",
        "rrt-grade: 2 runs now, 0 kept"]
    assert (tmp_path / "out" / "pdf" / "garbage" / "simple-0-point.pdf").exists()
