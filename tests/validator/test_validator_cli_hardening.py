"""Issues 16 and 17 on the validator's command line: bad problems and options are one
line and exit 2 before any planner runs, an unwritable PDF is exit 2, stderr never
changes the exit status, a stdout that takes no verdict is exit 4 with one line, the
usual slips get a hint, and reportlab and json load only when they are used."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from tests.conftest import unit_sample
from validator.checks import INVALID_VERDICT, VALID_VERDICT
from validator_testlib import CORPUS, ROOT, python_planner, run_validator

SPACE0 = (CORPUS / "problems/space-0.sw").read_text()
GOOD_POINT = CORPUS / "outputs/point/valid-handmade.out"
VALID = ["--", "cat", str(GOOD_POINT)]
BORDER_GOAL = "4 3\n____\n____\n____\n2.5 1.5\n0 1.5\n"


def shell(command: str, cwd, stdin: bytes = SPACE0.encode()) -> subprocess.CompletedProcess:
    """``command`` in bash (for redirections such as 2>&-); $V runs the validator."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), V=f"{sys.executable} -m validator",
               GOOD=str(GOOD_POINT))
    return subprocess.run(["bash", "-c", command], input=stdin, capture_output=True,
                          timeout=60, cwd=cwd, env=env)


def last_error(done: subprocess.CompletedProcess) -> str:
    err = done.stderr.decode()
    assert "Traceback" not in err
    return err.splitlines()[-1]


# ----- items 4 and 5: bad problems, planner output -----------------------------------


@pytest.mark.parametrize("problem, where", [
    ("4 3\n____\n____\n____\n0 1.5\n2.5 1.5\n", "line 5, column 1"),
    ("4 3\n____\n____\n____\n1.5 0.0\n2.5 1.5\n", "line 5, column 1"),
    ("1" * 5000 + "\n3\n", "line 1, column 1"),
])
def test_bad_problems_exit_2_before_the_planner_runs(problem, where, tmp_path):
    marker = tmp_path / "ran"
    # On a pipe (the validator starts the planner; in a file the launcher has started it
    # already, and it is stopped: test_validator_launcher.py).
    done = run_validator(["--", "touch", str(marker)], problem, tmp_path, pipe=True)
    assert done.returncode == 2 and done.stdout == b"" and not marker.exists()
    lines = done.stderr.decode().splitlines()
    assert len(lines) == 1 and lines[0].startswith("rrt-validator: bad problem: ")
    assert where in lines[0] and len(lines[0]) < 300


@pytest.mark.parametrize("last_point, valid", [("1e-06 1.5", True), ("0.0 1.5", False)])
def test_a_goal_on_the_border_is_allowed_and_the_answer_must_stay_inside(last_point, valid,
                                                                         tmp_path):
    # The goal (0, 1.5) is free; an answer may end within 0.1 of it, but every printed
    # point must lie strictly inside the map (check 3), so not on the goal itself.
    (tmp_path / "out").write_text(f"2\n2.5 1.5\n{last_point}\n0\n")
    done = run_validator(["-noviz", "--", "cat", "out"], BORDER_GOAL, tmp_path)
    assert done.returncode == (0 if valid else 1)
    assert done.stdout.decode().splitlines()[-1] == (VALID_VERDICT if valid else INVALID_VERDICT)
    if not valid:
        assert "State in trajectory that goes out of bounds!" in done.stdout.decode()


def test_planner_counts_with_5000_leading_zeros_are_read(tmp_path):
    (tmp_path / "out").write_text("0" * 5000 + GOOD_POINT.read_text())
    done = run_validator(["-noviz", "--", "cat", "out"], SPACE0, tmp_path)
    assert done.returncode == 0 and done.stdout.decode().endswith(VALID_VERDICT + "\n")


@pytest.mark.parametrize("output", ["1" * 5000 + "\n", "1\n0.1 " + "1" * 5000 + "\n0\n",
                                    "\u0661\n0.1 1.54\n0\n"])
def test_hostile_numbers_in_planner_output_fail_check_1(output, tmp_path):
    # Guard (held before): the plan reader never calls int() on a long count.
    (tmp_path / "out").write_text(output)
    done = run_validator(["-noviz", "--", "cat", "out"], SPACE0, tmp_path)
    assert done.returncode == 1
    assert done.stdout.decode().splitlines()[0] == "Error parsing planner output!"


# ----- item 7: exit statuses ---------------------------------------------------------


@pytest.mark.parametrize("path", ["", "/proc/no-such.pdf", "missing-folder/x.pdf", "."])
def test_an_unwritable_pdf_is_a_usage_error_before_the_planner_runs(path, tmp_path):
    marker = tmp_path / "ran"
    done = run_validator(["-o", path, "--", "touch", str(marker)], SPACE0, tmp_path,
                         pipe=True)  # (in a file: test_validator_launcher.py)
    assert done.returncode == 2 and done.stdout == b"" and not marker.exists()
    assert last_error(done).startswith(f"rrt-validator: error: -o {path!r}: cannot write")
    assert os.listdir(tmp_path) == []   # the probe left nothing behind


PROBE_WATCH = """
import json, os, sys
target, existing = sys.argv[1], sys.argv[2]
touched = []
def watch(event, args):
    if event in ("open", "os.remove", "os.rename", "os.replace") and args and str(args[0]) in (
            target, existing):
        touched.append((event, str(args[0]), args[2] if event == "open" else 0))
sys.addaudithook(watch)
from validator.cli import _output_path_problem
assert _output_path_problem(target) is None and _output_path_problem(existing) is None
print(json.dumps(touched))
"""


def test_the_pdf_probe_never_creates_nor_removes_the_target(tmp_path):
    # It made and unlinked a missing target by name, which raced with a second
    # validator checking the same -o (5 in 40 000 paired checks failed). Now: a file
    # of its own name in the folder; an existing target is opened, never created.
    target, existing = tmp_path / "viz.pdf", tmp_path / "old.pdf"
    existing.write_bytes(b"%PDF old")
    done = subprocess.run([sys.executable, "-c", PROBE_WATCH, str(target), str(existing)],
                          capture_output=True, timeout=60, cwd=tmp_path,
                          env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert done.returncode == 0, done.stderr.decode()
    touched = json.loads(done.stdout)
    assert [event for event, path, _ in touched] == ["open"]
    assert touched[0][1] == str(existing) and not touched[0][2] & os.O_CREAT
    assert sorted(os.listdir(tmp_path)) == ["old.pdf"] and existing.read_bytes() == b"%PDF old"


def test_a_pdf_write_that_fails_at_the_end_is_exit_2_with_one_line(tmp_path):
    done = run_validator(["-o", "/dev/full", *VALID], SPACE0, tmp_path)
    assert done.returncode == 2
    assert done.stdout.decode() == VALID_VERDICT + "\n"   # the verdict is still given
    lines = done.stderr.decode().splitlines()
    assert "rrt-validator: cannot write the PDF /dev/full: No space left on device" in lines
    assert "Traceback" not in done.stderr.decode()


def test_json_exit_status_is_the_exit_status(tmp_path):
    done = run_validator(["-json", "-o", "/dev/full", *VALID], SPACE0, tmp_path)
    report = json.loads(done.stdout)
    assert done.returncode == 2 and report["exit_status"] == 2 and report["pdf"] is None
    assert report["verdict"] == "valid"


@pytest.mark.parametrize("redirect", ["2>&-", "2>/dev/full"])
def test_a_closed_or_full_stderr_does_not_change_the_exit_status(redirect, tmp_path):
    done = shell(f'$V -noviz -- cat "$GOOD" {redirect}', tmp_path)
    assert done.returncode == 0 and done.stdout.decode() == VALID_VERDICT + "\n"
    assert shell(f'$V -noviz -bogus -- cat "$GOOD" {redirect}', tmp_path).returncode == 2


@pytest.mark.parametrize("redirect, words", [(">&-", "stdout is closed"),
                                             (">/dev/full", "No space left on device")])
def test_a_stdout_that_takes_no_verdict_is_exit_4_with_one_line(redirect, words, tmp_path):
    done = shell(f'$V -noviz -- cat "$GOOD" {redirect}', tmp_path)
    assert done.returncode == 4
    assert done.stderr.decode() == f"rrt-validator: cannot write the verdict to stdout: {words}\n"


# The unit run ends the launcher once per exit status and way of failing a write;
# CI also with the other of a full and a closed stream.
@pytest.mark.parametrize("command, status", unit_sample([
    ('-noviz -- cat "$GOOD" >&-', 4), ('-noviz -- cat "$GOOD" 2>/dev/full', 0),
    ("-noviz -- cat /dev/null 2>&-", 1), ("-h >/dev/full", 4),
    ("-noviz -bogus -- cat 2>/dev/full", 2),
    ('-noviz -- cat "$GOOD" >/dev/full', 4), ('-noviz -- cat "$GOOD" 2>&-', 0),
    ("-h >&-", 4)], keep=5))
def test_the_launcher_ends_as_the_module_does(command, status, tmp_path):
    # ./rrt-validator ends the process without the interpreter's tear-down
    # (rrt_startup.launch.exit_now): same status, same output as python -m validator.
    launcher = shell(f"{ROOT / 'rrt-validator'} {command}", tmp_path)
    module = shell(f"$V {command}", tmp_path)
    assert (launcher.returncode, launcher.stdout, launcher.stderr.splitlines()[:1]) == \
        (module.returncode, module.stdout, module.stderr.splitlines()[:1])
    assert launcher.returncode == status


# ----- item 9: ASCII option values ---------------------------------------------------


@pytest.mark.parametrize("value", ["\uff14", "\u0664", "1_0", "9" * 5000, "-1"])
def test_timeout_takes_ascii_positive_numbers_only(value, tmp_path):
    marker = tmp_path / "ran"
    done = run_validator(["-timeout", value, "--", "touch", str(marker)], SPACE0, tmp_path,
                         pipe=True)  # (in a file: test_validator_launcher.py)
    assert done.returncode == 2 and not marker.exists()
    line = last_error(done)
    assert line.startswith("rrt-validator: error: argument -timeout: ") and len(line) < 200


# ----- issue 17: hints ----------------------------------------------------------------


def test_a_problem_given_as_an_argument_gets_the_redirection_hint(tmp_path):
    done = run_validator(["map.sw"], "", tmp_path)
    assert done.returncode == 2
    assert last_error(done) == ("rrt-validator: error: unrecognized arguments: map.sw "
                                "(the problem is read from stdin: use < map.sw)")


@pytest.mark.parametrize("args, suggestion", [
    (["./run.sh", "-grad"], "rrt-validator -- ./run.sh -grad < problem.sw"),
    (["-noviz", "python3", "planner.py", "-seed", "3"],
     "rrt-validator -noviz -- python3 planner.py -seed 3 < problem.sw"),
])
def test_a_planner_without_the_double_dash_gets_the_separator_hint(args, suggestion, tmp_path):
    done = run_validator(args, SPACE0, tmp_path)
    assert done.returncode == 2
    line = last_error(done)
    assert line.startswith("rrt-validator: error: unrecognized arguments: ")
    assert line.endswith(f"(the planner's command goes after --: {suggestion})")


def test_an_executable_planner_file_is_no_problem_file(tmp_path):
    done = run_validator([str(ROOT / "run.sh")], SPACE0, tmp_path)
    assert "use <" not in last_error(done) and "goes after --" in last_error(done)


def test_a_near_miss_flag_gets_did_you_mean(tmp_path):
    done = run_validator(["-gard", "--", "cat"], SPACE0, tmp_path)
    assert done.returncode == 2
    assert last_error(done) == ("rrt-validator: error: unrecognized arguments: -gard "
                                "(did you mean -grad?)")


def test_arguments_after_the_double_dash_get_no_hint(tmp_path):
    # `rrt-validator -- ./run.sh map.sw` is the planner's business: it runs as given.
    code = "import sys; print(sys.argv[1:], file=sys.stderr); print(0)"
    done = run_validator(["-noviz", "--", *python_planner(code), "map.sw", "-gard"], SPACE0,
                         tmp_path)
    assert done.returncode == 1 and b"['map.sw', '-gard']" in done.stderr


# ----- lazy imports --------------------------------------------------------------------


def imported_modules(args: list[str], cwd) -> set[str]:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "validator", *args],
                          input=SPACE0.encode(), capture_output=True, timeout=60, cwd=cwd,
                          env=env)
    return {line.split("|")[-1].strip() for line in done.stderr.decode().splitlines()
            if line.startswith("import time:")}


def test_noviz_imports_no_reportlab_and_text_output_no_json(tmp_path):
    modules = imported_modules(["-noviz", *VALID], tmp_path)
    assert "validator.checks" in modules
    assert not any(m == "reportlab" or m.startswith("reportlab.") for m in modules)
    assert "validator.render_pdf" not in modules
    assert "json" not in modules
    # A grid problem loads nothing of the family's (its reader, shapes, limits).
    assert not {"planning_core.kinoplan", "planning_core.worlds.shapes"} & set(modules)
    with_pdf = imported_modules(["-json", *VALID], tmp_path)
    assert "reportlab" in with_pdf and "json" in with_pdf
