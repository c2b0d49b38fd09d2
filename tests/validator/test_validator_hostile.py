"""Hostile and broken planners: the validator ends promptly, in bounded memory, with
the right exit status and message, and cleans up the planner's process group."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from planning_core.problem_text import format_problem, parse_problem
from validator.checks import INVALID_VERDICT, VALID_VERDICT
from validator.run_planner import run_planner
from validator_testlib import (PROBLEMS, ROOT, VALID_POINT_PLAN, gone, python_planner,
                              run_validator)

SPACE0 = (PROBLEMS / "space-0.sw").read_text()


# run_planner, in-process -----------------------------------------------------

def test_run_planner_reports_exit_code_and_output():
    run = run_planner(python_planner("import sys; sys.stdout.write(sys.stdin.read()); "
                                     "sys.exit(5)"), b"hello\n", timeout=20)
    assert run.started and run.output == b"hello\n" and run.exit_code == 5
    assert run.signal is None and not run.timed_out and run.wall_time < 20


def test_run_planner_reports_a_signal():
    run = run_planner(python_planner("import os; print('1'); os.kill(os.getpid(), 9)"), b"",
                      timeout=20)
    assert run.signal == 9 and run.exit_code is None and run.output == b"1\n"


def test_run_planner_cap_cuts_the_output_and_stops_the_planner():
    began = time.monotonic()
    run = run_planner(python_planner("import sys\nwhile True: sys.stdout.write('x' * 4096)"),
                      b"", timeout=30, output_cap=100_000)
    assert run.output_cap_exceeded and len(run.output) == 100_000
    assert not run.timed_out and time.monotonic() - began < 10


def test_run_planner_cannot_start():
    run = run_planner(["/nonexistent/planner"], b"", timeout=5)
    assert not run.started and "No such file" in run.start_error


def test_run_planner_words_a_failed_start_as_popen_does(tmp_path):
    # run_planner forks and execs itself (subprocess costs the validator's start
    # milliseconds): its reasons must read as Popen's, PATH searched the same way.
    not_executable = tmp_path / "first" / "planner"
    not_executable.parent.mkdir()
    not_executable.write_text("#!/bin/sh\n")
    bad_interpreter = tmp_path / "second" / "planner"
    bad_interpreter.parent.mkdir()
    bad_interpreter.write_text("#!/nonexistent/sh\n")
    bad_interpreter.chmod(0o755)
    garbage = tmp_path / "garbage"
    garbage.write_bytes(b"\x00\x01not a program")
    garbage.chmod(0o755)
    path = f"{not_executable.parent}{os.pathsep}{bad_interpreter.parent}"
    for command, env_path in [(["/nonexistent/planner"], None), ([str(not_executable)], None),
                              ([str(tmp_path)], None), ([str(bad_interpreter)], None),
                              ([str(garbage)], None), (["planner"], path),
                              (["planner"], str(bad_interpreter.parent)), (["planner"], ""),
                              (["bad\0name"], None)]:
        old_path = os.environ.get("PATH")
        if env_path is not None:
            os.environ["PATH"] = env_path
        try:
            run = run_planner(command, b"", timeout=5)
            try:
                subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, start_new_session=True).wait()
                expected = None
            except (OSError, ValueError) as error:
                expected = str(error)
        finally:
            if env_path is not None:
                os.environ["PATH"] = old_path
        assert expected is not None and (run.started, run.start_error) == (False, expected)


def test_run_planner_gives_the_planner_its_own_session_and_only_the_three_pipes():
    # As Popen(start_new_session=True, close_fds=True, restore_signals=True) did: its
    # own session and group, none of our files (an inheritable one included), and
    # SIGPIPE and SIGXFSZ, which Python ignores, not ignored (grep, started by sh,
    # shows the mask it inherited; a Python planner would ignore both again).
    probe = ("import os, sys\n"
             "print(os.getsid(0) == os.getpid() == os.getpgid(0))\n"
             "print(sorted(int(fd) for fd in os.listdir('/proc/self/fd')))\n"
             "print(sys.stdin.read())")
    read_end, write_end = os.pipe()
    os.set_inheritable(write_end, True)
    try:
        run = run_planner(python_planner(probe), b"problem", timeout=20)
        ignored = run_planner(["sh", "-c", "grep SigIgn /proc/self/status"], b"", timeout=20)
    finally:
        os.close(read_end)
        os.close(write_end)
    # listdir's own fd is the fourth.
    assert run.output.decode().splitlines() == ["True", "[0, 1, 2, 3]", "problem"]
    mask = int(ignored.output.split()[1], 16)
    assert mask & (1 << (signal.SIGPIPE - 1)) == mask & (1 << (signal.SIGXFSZ - 1)) == 0


def test_run_planner_feeds_a_big_problem_to_a_planner_that_never_reads_it():
    began = time.monotonic()
    run = run_planner(python_planner("print('done')"), b"_" * 5_000_000, timeout=20)
    assert run.output == b"done\n" and run.exit_code == 0 and time.monotonic() - began < 10


# the command ------------------------------------------------------------------

def test_planner_sleeping_past_the_timeout_exits_3_promptly(tmp_path):
    pid_file = tmp_path / "child.pid"
    planner = ["sh", "-c", f"sleep 60 & echo $! > {pid_file}; sleep 60"]
    began = time.monotonic()
    # 0.5 s: sh has started its child and written the pid in milliseconds
    done = run_validator(["-timeout", "0.5", "--", *planner], SPACE0, tmp_path)
    elapsed = time.monotonic() - began
    assert done.returncode == 3
    out = done.stdout.decode().splitlines()
    assert out == ["Solver timed out after 0.5 s; its process group was killed.",
                   INVALID_VERDICT]
    assert elapsed < 6
    assert gone(int(pid_file.read_text()))  # the whole group, not just the leader
    assert (tmp_path / "tree-viz.pdf").stat().st_size > 0  # no stale PDF left behind


def test_planner_flooding_stdout_is_cut_at_the_cap_in_bounded_memory(tmp_path):
    # A wrapper measures the validator's peak memory (ru_maxrss of its children).
    flood = "import sys\nwhile True: sys.stdout.write('0 0\\n' * 65536)"
    wrapper = ("import resource, subprocess, sys\n"
               "done = subprocess.run(sys.argv[1:], stdin=sys.stdin, capture_output=True)\n"
               "sys.stdout.write(done.stdout.decode())\n"
               "print(done.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    began = time.monotonic()
    done = subprocess.run([sys.executable, "-c", wrapper, sys.executable, "-m", "validator",
                           "-noviz", "-timeout", "30", "--", sys.executable, "-c", flood],
                          input=SPACE0.encode(), capture_output=True, timeout=60, cwd=tmp_path,
                          env=dict(os.environ, PYTHONPATH=str(ROOT)))
    elapsed = time.monotonic() - began
    lines = done.stdout.decode().splitlines()
    status, max_rss_kib = map(int, lines[-1].split())
    assert status == 1
    assert lines[0].startswith("Solver output passed the cap of 67108864 bytes")
    assert "Error parsing planner output!" in lines and lines[-2] == INVALID_VERDICT
    assert elapsed < 25  # ended by the cap, long before the 30 s timeout
    assert max_rss_kib < 400 * 1024, f"peak memory {max_rss_kib} KiB"


def test_planner_trickling_output_forever_ends_by_the_timeout(tmp_path):
    trickle = "import sys, time\nwhile True:\n sys.stdout.write('0 0\\n' * 256)\n " \
              "sys.stdout.flush()\n time.sleep(0.01)"
    began = time.monotonic()
    done = run_validator(["-noviz", "-timeout", "0.5", "--", *python_planner(trickle)], SPACE0,
                         tmp_path)
    assert done.returncode == 3 and time.monotonic() - began < 6
    assert done.stdout.decode().splitlines()[-1] == INVALID_VERDICT


def test_planner_exiting_7_with_empty_output(tmp_path):
    done = run_validator(["-noviz", "--", "sh", "-c", "exit 7"], SPACE0, tmp_path)
    assert done.returncode == 1
    assert done.stdout.decode().splitlines() == [
        "Solver returned non-zero exit code 7.", "Error parsing planner output!",
        "  line 1: output is empty: expected the trajectory count", INVALID_VERDICT]


def test_non_zero_exit_is_reported_and_validation_goes_on(tmp_path):
    planner = python_planner(f"import sys; print({VALID_POINT_PLAN!r}, end=''); sys.exit(7)")
    done = run_validator(["-noviz", "--", *planner], SPACE0, tmp_path)
    assert done.returncode == 0
    assert done.stdout.decode().splitlines() == ["Solver returned non-zero exit code 7.",
                                                  VALID_VERDICT]


def test_death_by_signal_is_reported_and_validation_goes_on(tmp_path):
    planner = python_planner(f"import os, sys; sys.stdout.write({VALID_POINT_PLAN!r}); "
                             "sys.stdout.flush(); os.kill(os.getpid(), 9)")
    done = run_validator(["-noviz", "-json", "--", *planner], SPACE0, tmp_path)
    report = json.loads(done.stdout)
    assert done.returncode == 0 and report["verdict"] == "valid"
    assert report["solver_messages"] == ["Solver killed by signal 9."]
    assert report["planner"]["signal"] == 9 and report["planner"]["exit_code"] is None


def test_planner_that_cannot_start_exits_3(tmp_path):
    done = run_validator(["-noviz", "--", str(tmp_path / "no-such-planner")], SPACE0, tmp_path)
    assert done.returncode == 3
    lines = done.stdout.decode().splitlines()
    assert lines[0].startswith("Could not start solver:") and lines[-1] == INVALID_VERDICT


def test_planner_leaving_a_child_holding_stdout_does_not_stall_it(tmp_path):
    plan = tmp_path / "plan.out"
    plan.write_text(VALID_POINT_PLAN)
    pid_file = tmp_path / "child.pid"
    planner = ["sh", "-c", f"cat {plan}; sleep 60 & echo $! > {pid_file}"]
    began = time.monotonic()
    done = run_validator(["-noviz", "-timeout", "30", "--", *planner], SPACE0, tmp_path)
    assert done.returncode == 0 and time.monotonic() - began < 6
    assert gone(int(pid_file.read_text()))


def test_planner_closing_stdout_and_running_on_times_out(tmp_path):
    planner = python_planner("import os, time; os.close(1); time.sleep(60)")
    began = time.monotonic()
    done = run_validator(["-noviz", "-timeout", "0.5", "--", *planner], SPACE0, tmp_path)
    assert done.returncode == 3 and time.monotonic() - began < 6


def test_binary_output_is_invalid_not_a_crash(tmp_path):
    planner = python_planner("import sys; sys.stdout.buffer.write(bytes(range(256)) * 4000)")
    done = run_validator(["-grad", "--", *planner], SPACE0, tmp_path)
    assert done.returncode == 1 and b"Traceback" not in done.stderr
    assert done.stdout.decode().splitlines()[-1] == INVALID_VERDICT
    assert (tmp_path / "tree-viz.pdf").exists()


def test_planner_gets_the_problem_in_canonical_layout(tmp_path):
    received = tmp_path / "received.sw"
    loose = "4 3\r\n____  \r\n_*@_\r\n\r\n___#\r\n0.1   1.54\r\n3.8 1.1\r\n"
    planner = python_planner(f"import sys; open({str(received)!r}, 'w').write(sys.stdin.read())"
                             f"; sys.stdout.write({VALID_POINT_PLAN.replace('1.5 2.5', '1.5 1.5')!r})")
    done = run_validator(["-noviz", "--", *planner], loose, tmp_path)
    assert received.read_text() == format_problem(parse_problem(loose))
    assert done.returncode in (0, 1)


def test_planner_stderr_passes_through(tmp_path):
    planner = python_planner("import sys; sys.stderr.write('planner says hi\\n')")
    done = run_validator(["-noviz", "--", *planner], SPACE0, tmp_path)
    assert b"planner says hi" in done.stderr and done.returncode == 1


def test_terminating_the_validator_kills_the_planner_group(tmp_path):
    pid_file = tmp_path / "planner.pid"
    planner = ["sh", "-c", f"echo $$ > {pid_file}; sleep 60"]
    validator = subprocess.Popen([sys.executable, "-m", "validator", "-noviz", "--", *planner],
                                 stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, cwd=tmp_path,
                                 env=dict(os.environ, PYTHONPATH=str(ROOT)))
    validator.stdin.write(SPACE0.encode())
    validator.stdin.close()
    deadline = time.monotonic() + 20
    while not (pid_file.exists() and pid_file.read_text().strip()):
        assert time.monotonic() < deadline
        time.sleep(0.05)
    validator.terminate()
    assert validator.wait(timeout=10) == 128 + 15
    validator.stdout.close()
    validator.stderr.close()
    assert gone(int(pid_file.read_text()))


def test_prctl_made_through_ctypes_itself_reads_the_same_subreaper_flag():
    """The fallback when ctypes' private C module no longer makes prctl."""
    from validator import run_planner
    fast, public = run_planner._load_prctl(), run_planner._load_prctl_by_ctypes()
    if public is None:
        pytest.skip("no libc prctl here")
    assert fast is not None
    assert run_planner._get_subreaper(fast) == run_planner._get_subreaper(public)
