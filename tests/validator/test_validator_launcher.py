"""rrt-validator's launcher (validator/launch.c, taken over by validator/launched.py):
with the problem in a file it starts the planner before the interpreter, and the run
is the one the validator would have started; anything it does not take over is killed
with what it started. (The hostile planners of the other validator tests run through
it too: run_validator gives the problem in a file.)"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from planning_core.problem_text import format_problem, parse_problem
from validator.checks import INVALID_VERDICT
from tests.conftest import script_code
from validator_testlib import (PROBLEMS, ROOT, VALID_POINT_PLAN, gone_within, python_planner,
                              run_validator)

LAUNCHER = ROOT / ".build" / "launcher" / "rrt-validator-launch"
SPACE0 = (PROBLEMS / "space-0.sw").read_text()

pytestmark = pytest.mark.skipif(not LAUNCHER.exists() or not Path("/proc/self").exists(),
                                reason="./make.sh builds the launcher where cc is (Linux)")


def recording_planner(log: Path) -> list[str]:
    """A planner that appends what it read to ``log``, then answers space-0."""
    return python_planner("import sys\n"
                          "data = sys.stdin.buffer.read()\n"
                          f"with open({str(log)!r}, 'a') as log:\n"
                          "    log.write(repr(data.decode()) + '\\n')\n"
                          f"sys.stdout.write({VALID_POINT_PLAN!r})\n")


def runs(log: Path) -> list[str]:
    from ast import literal_eval
    return [literal_eval(line) for line in log.read_text().splitlines()]


def judged(done: subprocess.CompletedProcess) -> dict:
    """The -json report's verdict and who started the planner it judged."""
    report = json.loads(done.stdout)
    return {"verdict": report["verdict"], "started_by": report["planner"]["started_by"]}


def test_the_launcher_starts_the_planner_and_the_validator_takes_it_over(tmp_path):
    log = tmp_path / "runs.log"
    done = run_validator(["-noviz", "-json", "--", *recording_planner(log)], SPACE0, tmp_path)
    assert done.returncode == 0, done.stderr
    assert judged(done) == {"verdict": "valid", "started_by": "launcher"}
    assert runs(log) == [SPACE0]


def test_a_problem_on_a_pipe_is_started_by_the_validator(tmp_path):
    log = tmp_path / "runs.log"
    done = run_validator(["-noviz", "-json", "--", *recording_planner(log)], SPACE0, tmp_path,
                         pipe=True)
    assert judged(done) == {"verdict": "valid", "started_by": "validator"}
    assert runs(log) == [SPACE0]


def test_a_problem_not_as_the_validator_writes_it_is_given_again(tmp_path):
    log = tmp_path / "runs.log"
    loose = SPACE0.replace("\n", "  \n")  # the same problem, spaces at the line ends
    assert format_problem(parse_problem(loose)) == SPACE0
    done = run_validator(["-noviz", "-json", "--", *recording_planner(log)], loose, tmp_path)
    assert judged(done) == {"verdict": "valid", "started_by": "validator"}
    # The launcher's run had the file's bytes and was stopped (perhaps before it
    # wrote); the one judged had the validator's.
    assert runs(log)[-1] == SPACE0 and runs(log)[:-1] in ([], [loose])


def test_the_planner_is_judged_on_the_problem_as_it_was_read(tmp_path):
    # It rewrites the problem's file without obstacles, then goes straight through one.
    problem = tmp_path / "space-0.sw"
    problem.write_text(SPACE0)
    cleared = SPACE0.replace("#", "_")
    straight = "2\n0.1 1.54\n3.8 1.1\n0\n"  # valid on the cleared map only
    assert run_validator(["-noviz", "--", *python_planner(
        f"import sys; sys.stdout.write({straight!r})")], cleared, tmp_path).returncode == 0
    planner = python_planner(f"import sys\nopen({str(problem)!r}, 'w').write({cleared!r})\n"
                             f"sys.stdin.read()\nsys.stdout.write({straight!r})\n")
    with open(problem, "rb") as stdin:
        done = subprocess.run([str(ROOT / "rrt-validator"), "-noviz", "--", *planner],
                              stdin=stdin, capture_output=True, timeout=60, cwd=tmp_path)
    assert problem.read_text() == cleared  # it did rewrite it
    assert done.returncode == 1 and done.stdout.decode().splitlines()[-1] == INVALID_VERDICT


def pid_writer(pid_file: Path) -> list[str]:
    """A planner (a shell: up in a millisecond, long before the validator's checks)
    whose child leaves its session (so only the sweep finds it) and says where it is."""
    return ["/bin/sh", "-c", f"setsid sleep 60 & echo $! > {pid_file}.tmp; "
            f"mv {pid_file}.tmp {pid_file}; sleep 60"]


def wait_for(path: Path, seconds: float = 20) -> int:
    deadline = time.monotonic() + seconds
    while not path.exists():
        assert time.monotonic() < deadline, f"{path} never came"
        time.sleep(0.01)
    return int(path.read_text())


@pytest.mark.parametrize("flags, text", [
    (["-noviz", "-ugrad", "-grad"], SPACE0), (["-o", "tree.unknown"], SPACE0),
    (["-noviz", "-timeout", "-1"], SPACE0), (["-noviz", "-h"], SPACE0),
    (["-noviz"], SPACE0.replace("_", "?", 1))])
def test_a_launched_planner_the_validator_does_not_run_is_killed(tmp_path, flags, text):
    # A usage error, a bad problem (or -h) is found after the launcher started the
    # planner: it is killed with what it started; the status and the line as before.
    pid_file = tmp_path / "child.pid"
    problem = tmp_path / "space-0.sw"
    problem.write_text(text)
    with open(problem, "rb") as stdin:
        validator = subprocess.Popen([str(ROOT / "rrt-validator"), *flags, "--",
                                      *pid_writer(pid_file)], stdin=stdin,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     cwd=tmp_path)
    out, err = validator.communicate(timeout=60)
    assert validator.returncode == (0 if "-h" in flags else 2), err
    if "-h" not in flags:
        assert err.splitlines()[-1].startswith(b"rrt-validator: ")  # the one error line
    if pid_file.exists():  # it got that far before the validator stopped it (it does)
        assert gone_within(int(pid_file.read_text()), 2.0), "the planner's child outlived us"


def test_sigkill_of_the_validator_kills_the_launched_planner(tmp_path):
    pid_file = tmp_path / "planner.pid"
    planner = python_planner("import os, time\n"
                             f"open({str(pid_file)!r} + '.tmp', 'w').write(str(os.getpid()))\n"
                             f"os.rename({str(pid_file)!r} + '.tmp', {str(pid_file)!r})\n"
                             "time.sleep(60)\n")
    problem = tmp_path / "space-0.sw"
    problem.write_text(SPACE0)
    with open(problem, "rb") as stdin:
        validator = subprocess.Popen([str(ROOT / "rrt-validator"), "-noviz", "--", *planner],
                                     stdin=stdin, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL, cwd=tmp_path)
    pid = wait_for(pid_file)
    validator.kill()
    assert validator.wait(timeout=10) == -signal.SIGKILL
    assert gone_within(pid, 2.0), "the planner outlived its validator"


def test_a_launcher_of_another_source_is_not_taken_over(tmp_path):
    # Built from other bytes (a checkout updated without ./make.sh): its run is
    # stopped and the validator starts the planner itself.
    stale = tmp_path / "stale-launch"
    subprocess.run(["cc", "-O2", '-DRRT_LAUNCH_KEY="0000000000000000"', "-o", str(stale),
                    str(ROOT / "validator" / "launch.c")], check=True)
    code = script_code("rrt-validator")
    log = tmp_path / "runs.log"
    problem = tmp_path / "space-0.sw"
    problem.write_text(SPACE0)
    with open(problem, "rb") as stdin:
        done = subprocess.run([str(stale), sys.executable, code, str(ROOT), "-noviz", "-json",
                               "--", *recording_planner(log)], stdin=stdin,
                              capture_output=True, timeout=60, cwd=tmp_path)
    assert judged(done) == {"verdict": "valid", "started_by": "validator"}
    assert runs(log)[-1] == SPACE0 and len(runs(log)) <= 2


def test_a_planner_that_cannot_start_is_reported_as_before(tmp_path):
    missing = str(tmp_path / "no-such-planner")
    by_file = run_validator(["-noviz", "--", missing], SPACE0, tmp_path)
    by_pipe = run_validator(["-noviz", "--", missing], SPACE0, tmp_path, pipe=True)
    assert by_file.returncode == by_pipe.returncode == 3
    assert by_file.stdout == by_pipe.stdout and by_file.stderr == by_pipe.stderr


def test_the_problem_is_read_from_where_stdin_stands(tmp_path):
    # As the interpreter reads it: from the file's offset (here after a first line a
    # shell has read), not from its start.
    log = tmp_path / "runs.log"
    problem = tmp_path / "space-0.sw"
    problem.write_text("a line read before\n" + SPACE0)
    with open(problem, "rb") as stdin:
        stdin.readline()
        os.lseek(stdin.fileno(), stdin.tell(), os.SEEK_SET)
        done = subprocess.run([str(ROOT / "rrt-validator"), "-noviz", "-json", "--",
                               *recording_planner(log)], stdin=stdin, capture_output=True,
                              timeout=60, cwd=tmp_path)
    assert judged(done) == {"verdict": "valid", "started_by": "launcher"}
    assert runs(log) == [SPACE0]


def test_a_problem_larger_than_the_pipe_reaches_the_planner_whole(tmp_path):
    # The launcher writes what the pipe takes (64 KiB); the validator writes the rest.
    log = tmp_path / "runs.log"
    big = (ROOT / "benchmarks" / "problems" / "maze-500.sw").read_text()
    assert len(big) > 3 * 65536 and format_problem(parse_problem(big)) == big
    done = run_validator(["-noviz", "-json", "--", *recording_planner(log)], big, tmp_path)
    assert json.loads(done.stdout)["planner"]["started_by"] == "launcher"
    assert runs(log) == [big]


def test_the_launcher_reads_no_more_than_the_validator():
    from cli_common import MAX_PROBLEM_BYTES
    source = (ROOT / "validator" / "launch.c").read_text()
    assert "#define MAX_PROBLEM_BYTES (64L * 1024 * 1024)" in source
    assert MAX_PROBLEM_BYTES == 64 * 1024 * 1024
