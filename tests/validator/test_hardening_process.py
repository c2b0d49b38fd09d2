"""Issue 16, process containment: nothing a planner starts outlives the validator
(a ``setsid`` grandchild, a double-forked daemon, a planner whose validator is
SIGKILLed), and a planner flooding its stderr gets only so much of it through.

The planners here are small Python scripts; each process that should end writes
its pid to a file first, and every test kills what it finds there at the end, so
a failing run leaves nothing behind.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from validator.checks import INVALID_VERDICT, VALID_VERDICT
from validator.run_planner import DEFAULT_STDERR_CAP, run_planner
from validator_testlib import (PROBLEMS, ROOT, VALID_POINT_PLAN, gone_within, python_planner,
                              run_validator)

SPACE0 = (PROBLEMS / "space-0.sw").read_text()

# Leaves the planner's session and process group, says where it is, sleeps.
SETSID_SLEEPER = ("import os, sys, time\n"
                  "os.setsid()\n"
                  "open(sys.argv[1] + '.tmp', 'w').write(str(os.getpid()))\n"
                  "os.rename(sys.argv[1] + '.tmp', sys.argv[1])\n"
                  "time.sleep(60)\n")
WAIT_FOR_FILE = ("def wait_for(path):\n"
                 "    while not os.path.exists(path):\n"
                 "        time.sleep(0.01)\n")


def planner_with_setsid_child(pid_file: Path, then: str) -> list[str]:
    """A planner that starts SETSID_SLEEPER (no pipes of ours), waits until it has
    left the group, then runs ``then``."""
    code = ("import os, subprocess, sys, time\n" + WAIT_FOR_FILE +
            f"subprocess.Popen([sys.executable, '-c', {SETSID_SLEEPER!r}, {str(pid_file)!r}],\n"
            "                 stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,\n"
            "                 stderr=subprocess.DEVNULL)\n"
            f"wait_for({str(pid_file)!r})\n" + then)
    return python_planner(code)


def planner_with_daemon(pid_file: Path) -> list[str]:
    """A planner that double-forks a daemon (its parent exits at once, so it is
    orphaned while the planner still runs), then prints a valid plan and exits."""
    code = ("import os, subprocess, sys, time\n" + WAIT_FOR_FILE +
            "middle = subprocess.Popen([sys.executable, '-c', 'import subprocess, sys; '\n"
            f"    'subprocess.Popen([sys.executable, \"-c\", sys.argv[1], sys.argv[2]], '\n"
            "    'stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, '\n"
            "    'stderr=subprocess.DEVNULL)',\n"
            f"    {SETSID_SLEEPER!r}, {str(pid_file)!r}], stdin=subprocess.DEVNULL,\n"
            "    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)\n"
            "middle.wait()\n"
            f"wait_for({str(pid_file)!r})\n"
            f"sys.stdout.write({VALID_POINT_PLAN!r})\n")
    return python_planner(code)


@pytest.fixture
def pid_files(tmp_path):
    """Pid files the test's processes write; whatever they name is killed at the end."""
    files: list[Path] = []

    def make(name: str) -> Path:
        files.append(tmp_path / name)
        return files[-1]
    yield make
    for path in files:
        if path.exists():
            try:
                os.kill(int(path.read_text()), signal.SIGKILL)
            except (ProcessLookupError, ValueError):
                pass


needs_proc = pytest.mark.skipif(not Path("/proc/self/stat").exists(),
                                reason="containment walks /proc (Linux)")


@needs_proc
def test_setsid_grandchild_of_a_planner_that_exits_is_killed(tmp_path, pid_files):
    pid_file = pid_files("grandchild.pid")
    planner = planner_with_setsid_child(pid_file, f"sys.stdout.write({VALID_POINT_PLAN!r})\n")
    done = run_validator(["-noviz", "-timeout", "30", "--", *planner], SPACE0, tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stdout.decode().splitlines() == [VALID_VERDICT]
    assert gone_within(int(pid_file.read_text()), 0.5), "the setsid grandchild outlived us"


@needs_proc
def test_setsid_grandchild_of_a_planner_that_times_out_is_killed(tmp_path, pid_files):
    pid_file = pid_files("grandchild.pid")
    planner = planner_with_setsid_child(pid_file, "time.sleep(60)\n")
    began = time.monotonic()
    # 1 s: ten times what the planner and its grandchild need to start on a loaded machine
    done = run_validator(["-noviz", "-timeout", "1", "--", *planner], SPACE0, tmp_path)
    assert done.returncode == 3 and time.monotonic() - began < 15
    assert done.stdout.decode().splitlines()[-1] == INVALID_VERDICT
    assert gone_within(int(pid_file.read_text()), 0.5), "the setsid grandchild outlived us"


@needs_proc
def test_double_forked_daemon_is_killed(tmp_path, pid_files):
    pid_file = pid_files("daemon.pid")
    done = run_validator(["-noviz", "-timeout", "30", "--", *planner_with_daemon(pid_file)],
                         SPACE0, tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert gone_within(int(pid_file.read_text()), 0.5), "the daemon outlived us"


@needs_proc
def test_run_planner_in_process_kills_and_reaps_the_setsid_grandchild(tmp_path, pid_files):
    pid_file = pid_files("grandchild.pid")
    planner = planner_with_setsid_child(pid_file, f"sys.stdout.write({VALID_POINT_PLAN!r})\n")
    run = run_planner(planner, SPACE0.encode(), timeout=30)
    assert run.exit_code == 0 and run.output == VALID_POINT_PLAN.encode()
    pid = int(pid_file.read_text())
    # Killed, and reaped here (it was re-parented to us): no zombie of ours is left.
    assert not Path(f"/proc/{pid}").exists(), Path(f"/proc/{pid}/status").read_text()


@needs_proc
def test_sigkill_of_the_validator_kills_the_planner(tmp_path, pid_files):
    pid_file = pid_files("planner.pid")
    planner = python_planner("import os, sys, time\n"
                             f"open({str(pid_file)!r} + '.tmp', 'w').write(str(os.getpid()))\n"
                             f"os.rename({str(pid_file)!r} + '.tmp', {str(pid_file)!r})\n"
                             "time.sleep(60)\n")
    validator = subprocess.Popen([sys.executable, "-m", "validator", "-noviz", "--", *planner],
                                 stdin=subprocess.PIPE, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL, cwd=tmp_path,
                                 env=dict(os.environ, PYTHONPATH=str(ROOT)))
    validator.stdin.write(SPACE0.encode())
    validator.stdin.close()
    deadline = time.monotonic() + 20
    while not pid_file.exists():
        assert time.monotonic() < deadline and validator.poll() is None
        time.sleep(0.02)
    validator.kill()
    assert validator.wait(timeout=10) == -signal.SIGKILL
    assert gone_within(int(pid_file.read_text()), 2.0), "the planner outlived its validator"


FLOOD = 50_000_000
FLOOD_THEN_PLAN = ("import sys\n"
                   f"for _ in range({FLOOD // 1_000_000}):\n"
                   "    sys.stderr.buffer.write(b'e' * 999_999 + b'\\n')\n"
                   "sys.stderr.flush()\n"
                   f"sys.stdout.write({VALID_POINT_PLAN!r})\n")
NOTICE = (f"rrt-validator: the planner wrote {FLOOD} bytes on stderr; only the first "
          f"{DEFAULT_STDERR_CAP} were passed on")


def check_flooded_stderr(err: bytes) -> None:
    """The first DEFAULT_STDERR_CAP bytes as written, a newline (the cut fell mid-line),
    the notice, and the validator's own summary line last."""
    assert len(err) < DEFAULT_STDERR_CAP + 1000, f"{len(err)} bytes on our stderr"
    written = (b"e" * 999_999 + b"\n") * (DEFAULT_STDERR_CAP // 1_000_000 + 1)
    assert err[:DEFAULT_STDERR_CAP] == written[:DEFAULT_STDERR_CAP]
    rest = err[DEFAULT_STDERR_CAP:].decode().splitlines()
    assert rest[:2] == ["", NOTICE], rest[:2]
    assert len(rest) == 3 and rest[2].startswith("rrt-validator: planner ")


def test_stderr_flood_is_capped_on_a_pipe(tmp_path):
    done = run_validator(["-noviz", "--", *python_planner(FLOOD_THEN_PLAN)], SPACE0, tmp_path)
    assert done.returncode == 0 and done.stdout.decode().splitlines() == [VALID_VERDICT]
    check_flooded_stderr(done.stderr)


def test_stderr_flood_is_capped_on_a_file(tmp_path):
    # A regular file as our stderr (which epoll refuses to watch).
    err_path = tmp_path / "err.txt"
    with open(err_path, "wb") as err:
        done = subprocess.run([sys.executable, "-m", "validator", "-noviz", "--",
                               *python_planner(FLOOD_THEN_PLAN)], input=SPACE0.encode(),
                              stdout=subprocess.PIPE, stderr=err, cwd=tmp_path, timeout=60,
                              env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert done.returncode == 0 and done.stdout.decode().splitlines() == [VALID_VERDICT]
    check_flooded_stderr(err_path.read_bytes())


def test_run_planner_counts_the_stderr_it_cut(capfd):
    planner = python_planner("import sys; sys.stderr.write('x' * 300_000 + 'END'); "
                             "print('out')")
    run = run_planner(planner, b"", timeout=30, stderr_cap=1000)
    err = capfd.readouterr().err
    assert run.output == b"out\n" and run.exit_code == 0
    assert (run.stderr_bytes, run.stderr_cut) == (300_003, True)
    assert err == "x" * 1000 + "\n" + ("rrt-validator: the planner wrote 300003 bytes on "
                                       "stderr; only the first 1000 were passed on\n")
    run = run_planner(python_planner("import sys; sys.stderr.write('short\\n')"), b"",
                      timeout=30, stderr_cap=1000)
    assert capfd.readouterr().err == "short\n" and not run.stderr_cut


# ----- issue 28: without prctl and /proc, and Ctrl-C ---------------------------------


def planner_with_child_in_its_group(pid_file: Path) -> list[str]:
    """A planner that starts a sleeper in its own process group (no pipes of ours),
    waits until it says where it is, prints a valid plan and exits."""
    sleeper = ("import os, sys, time\n"
               "open(sys.argv[1] + '.tmp', 'w').write(str(os.getpid()))\n"
               "os.rename(sys.argv[1] + '.tmp', sys.argv[1])\n"
               "time.sleep(60)\n")
    code = ("import os, subprocess, sys, time\n" + WAIT_FOR_FILE +
            f"subprocess.Popen([sys.executable, '-c', {sleeper!r}, {str(pid_file)!r}],\n"
            "                 stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,\n"
            "                 stderr=subprocess.DEVNULL)\n"
            f"wait_for({str(pid_file)!r})\n"
            f"sys.stdout.write({VALID_POINT_PLAN!r})\n")
    return python_planner(code)


def test_without_prctl_and_proc_the_planners_group_is_still_killed(monkeypatch, pid_files):
    # The module's fallback where prctl or /proc is missing: only the process group.
    # With the subreaper and the /proc sweep gone, killing the planner alone (not its
    # group) would leave its child running.
    import validator.run_planner as module
    monkeypatch.setattr(module, "_load_prctl", lambda: None)
    monkeypatch.setattr(module, "_proc_table", lambda: None)
    pid_file = pid_files("child.pid")
    run = run_planner(planner_with_child_in_its_group(pid_file), SPACE0.encode(), timeout=30)
    assert run.exit_code == 0 and run.output == VALID_POINT_PLAN.encode()
    assert gone_within(int(pid_file.read_text()), 2.0), "the planner's child outlived it"


def run_validator_until(marker: Path, planner: list[str]) -> subprocess.Popen:
    """``python -m validator -noviz -- PLANNER`` on space-0 with SIGINT as a shell
    leaves it (not ignored), once the planner has written ``marker``."""
    validator = subprocess.Popen([sys.executable, "-m", "validator", "-noviz", "--", *planner],
                                 stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, cwd=marker.parent,
                                 env=dict(os.environ, PYTHONPATH=str(ROOT)),
                                 preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    validator.stdin.write(SPACE0.encode())
    validator.stdin.close()
    validator.stdin = None  # (for communicate)
    deadline = time.monotonic() + 20
    while not marker.exists():
        assert time.monotonic() < deadline and validator.poll() is None
        time.sleep(0.02)
    return validator


@needs_proc
def test_ctrl_c_says_interrupted_exits_130_and_kills_the_planners_group(tmp_path, pid_files):
    pid_file = pid_files("child.pid")
    planner = planner_with_child_in_its_group(pid_file)
    planner[2] = planner[2].replace(f"sys.stdout.write({VALID_POINT_PLAN!r})\n",
                                    "time.sleep(60)\n")
    validator = run_validator_until(pid_file, planner)
    validator.send_signal(signal.SIGINT)
    out, err = validator.communicate(timeout=20)
    assert validator.returncode == 130 and out == b""
    assert err.decode() == "rrt-validator: interrupted\n"
    assert gone_within(int(pid_file.read_text()), 2.0), "the planner's child outlived us"
