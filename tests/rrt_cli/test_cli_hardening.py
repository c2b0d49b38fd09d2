"""Issues 16 and 17 on the planner's command line: bad problems and options are one
line and exit 2, stdin is capped, stderr never changes the exit status, a closed or
full stdout is exit 1 without a traceback, and the usual slips get a hint."""

from __future__ import annotations

import io
import os
import subprocess
import sys

import pytest

import cli_common
from tests.conftest import COURSE_DIR, ROOT, run_planner

SPACE0 = (COURSE_DIR / "space-0.sw").read_text()
SPACE0_PATH = COURSE_DIR / "space-0.sw"
CAP = 64 * 1024 * 1024   # the documented stdin cap


def shell(command: str, stdin: bytes = SPACE0.encode(), timeout: float = 60
          ) -> subprocess.CompletedProcess:
    """``command`` in bash at the repository root (for redirections such as 2>&-)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), PY=sys.executable)
    return subprocess.run(["bash", "-c", command], input=stdin, capture_output=True,
                          timeout=timeout, cwd=ROOT, env=env)


def one_error_line(done: subprocess.CompletedProcess) -> str:
    err = done.stderr.decode()
    assert "Traceback" not in err and done.stdout == b""
    assert err.count("\n") == 1, err
    return err


# ----- items 4 and 5: bad problems --------------------------------------------------


@pytest.mark.parametrize("flags", [[], ["-grad"], ["-planner", "prm"]])
def test_start_on_the_border_is_a_bad_problem(flags):
    done = run_planner([*flags, "-seed", "1"], "4 3\n____\n____\n____\n0 1.5\n2.5 1.5\n")
    assert done.returncode == 2
    assert "line 5, column 1" in one_error_line(done)


def test_a_5000_digit_width_is_a_bad_problem_not_a_traceback():
    done = run_planner(["-seed", "1"], "1" * 5000 + "\n3\n")
    assert done.returncode == 2
    err = one_error_line(done)
    assert "line 1, column 1" in err and len(err) < 300


# ----- item 6: the stdin cap --------------------------------------------------------


class EndlessBytes(io.RawIOBase):
    """A stdin that never ends, counting what was read from it."""

    def __init__(self):
        self.taken = 0

    def readable(self):
        return True

    def readinto(self, buffer):
        buffer[:] = b" " * len(buffer)
        self.taken += len(buffer)
        return len(buffer)


def test_reader_takes_at_most_cap_plus_one_bytes(monkeypatch, capsys):
    raw = EndlessBytes()
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BufferedReader(raw, 4096)))
    assert cli_common.read_problem_text_from_stdin("prog", cap=100_000) is None
    assert raw.taken <= 100_000 + 1 + 4096   # the cap, one byte past it, one buffer
    err = capsys.readouterr().err
    assert err.startswith("prog: bad problem: more than 100000 bytes on stdin") and \
        err.count("\n") == 1


def test_reader_takes_a_stdin_of_exactly_the_cap_whole(monkeypatch):
    text = "1\n1\n_\n0.5\n0.5\n0.5\n0.5\n"
    padded = text + " " * (100_000 - len(text))
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(padded.encode())))
    assert cli_common.read_problem_text_from_stdin("prog", cap=100_000) == padded


# The command reading and parsing exactly 64 MiB runs in CI; in the unit run the reader
# tests above take exactly the cap and refuse a byte more, and the command is run one
# byte past 64 MiB.
@pytest.mark.parametrize("size, code", [pytest.param(CAP, 0, marks=pytest.mark.slow),
                                        (CAP + 1, 2)])
def test_the_cap_is_64_mib(size, code):
    # A valid problem padded with blanks to exactly the cap is read; one byte more is not.
    text = SPACE0.encode()
    done = run_planner(["-seed", "1"], (text + b" " * (size - len(text))).decode(), timeout=120)
    assert done.returncode == code
    if code:
        assert "more than 67108864 bytes on stdin (the cap is 64 MiB)" in one_error_line(done)
    assert getattr(cli_common, "MAX_PROBLEM_BYTES", None) == CAP


# ----- item 7: exit statuses ---------------------------------------------------------


@pytest.mark.parametrize("redirect", ["2>&-", "2>/dev/full"])
def test_a_closed_or_full_stderr_does_not_change_the_exit_status(redirect):
    done = shell(f'"$PY" -m rrt_cli -seed 1 -stats {redirect}')
    assert done.returncode == 0
    assert done.stdout == run_planner(["-seed", "1"], SPACE0).stdout
    assert shell(f'"$PY" -m rrt_cli -bogus {redirect}').returncode == 2


@pytest.mark.parametrize("redirect, words", [(">&-", "stdout is closed"),
                                             (">/dev/full", "No space left on device")])
def test_a_closed_or_full_stdout_is_exit_1_and_one_line(redirect, words):
    done = shell(f'"$PY" -m rrt_cli -seed 1 {redirect}')
    assert done.returncode == 1
    assert one_error_line(done) == f"rrt_cli: cannot write the answer to stdout: {words}\n"


def test_a_reader_that_goes_away_gets_no_traceback_and_no_note():
    # Guard (held before): `| head` ends the planner quietly, with status 1.
    done = shell('"$PY" -m rrt_cli -seed 1 < benchmarks/problems/random-d20-50.sw '
                 '| head -c 10 >/dev/null; echo "${PIPESTATUS[0]}" >&2', stdin=b"")
    assert done.stderr.decode() in ("1\n", "0\n")   # 0: it all fit in the pipe in time


# ----- item 9: options are ASCII, seeds in [0, 2^64) ---------------------------------


@pytest.mark.parametrize("option, value, words", [
    ("-seed", "\uff14", "not an integer"),
    ("-seed", "\u0664", "not an integer"),
    ("-seed", "1_000", "not an integer"),
    ("-seed", " 5", "not an integer"),
    ("-seed", "-5", "out of range"),
    ("-seed", "9" * 5000, "out of range"),
    ("-seed", str(2 ** 64), "out of range"),
    ("-time", "\uff14", "not a number"),
    ("-time", "1_0", "not a number"),
    ("-iterations", "\uff14", "not an integer"),
    ("-iterations", "9" * 5000, "out of range"),
    ("-iterations", "0", "out of range"),
])
def test_bad_option_values_are_usage_errors(option, value, words):
    done = run_planner([option, value], SPACE0)
    assert done.returncode == 2 and done.stdout == b""
    last = done.stderr.decode().splitlines()[-1]
    assert last.startswith(f"rrt_cli: error: argument {option}: ") and words in last
    assert len(last) < 200


def test_seeds_span_0_to_2_to_the_64():
    top = run_planner(["-seed", str(2 ** 64 - 1)], SPACE0)
    zero = run_planner(["-seed", "-0"], SPACE0)
    assert top.returncode == zero.returncode == 0
    assert zero.stdout == run_planner(["-seed", "0"], SPACE0).stdout


# ----- issue 17: hints ----------------------------------------------------------------


@pytest.mark.parametrize("argument", [str(SPACE0_PATH), "missing-map.sw"])
def test_a_problem_given_as_an_argument_gets_the_redirection_hint(argument):
    done = run_planner([argument], SPACE0)
    assert done.returncode == 2
    assert done.stderr.decode().splitlines()[-1] == (
        f"rrt_cli: error: unrecognized arguments: {argument} "
        f"(the problem is read from stdin: use < {argument})")


@pytest.mark.parametrize("typo, meant", [("-gard", "-grad"), ("--grad", "-grad"),
                                         ("-sed", "-seed"), ("-smoth", "-smooth")])
def test_a_near_miss_flag_gets_did_you_mean(typo, meant):
    done = run_planner([typo], SPACE0)
    assert done.returncode == 2
    lines = done.stderr.decode().splitlines()
    assert lines[0].startswith("usage: ./run.sh")
    assert lines[-1] == f"rrt_cli: error: unrecognized arguments: {typo} (did you mean {meant}?)"


def test_an_unrelated_argument_gets_no_hint():
    done = run_planner(["-zzzzzz", "banana"], SPACE0)
    assert done.stderr.decode().splitlines()[-1] == (
        "rrt_cli: error: unrecognized arguments: -zzzzzz banana")


# ----- issue 28, item 7: Ctrl-C, a folder on stdin ----------------------------------


def test_ctrl_c_says_interrupted_and_exits_130():
    # The planner reads its problem from a terminal (a pty) until Ctrl-C; SIGINT as a
    # shell leaves it, not ignored.
    import pty
    import select
    import signal
    terminal, stdin = pty.openpty()
    planner = subprocess.Popen([str(ROOT / "run.sh"), "-seed", "1"], stdin=stdin,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    os.close(stdin)
    try:
        assert select.select([planner.stderr], [], [], 30)[0], "no notice within 30 s"
        notice = planner.stderr.readline().decode()
        assert notice == "rrt_cli: reading the problem from stdin (end it with Ctrl-D)\n"
        planner.send_signal(signal.SIGINT)
        out, err = planner.communicate(timeout=20)
    finally:
        planner.kill()
        os.close(terminal)
    assert planner.returncode == 130 and out == b""
    assert err.decode() == "rrt_cli: interrupted\n"


@pytest.mark.parametrize("tool", ["run.sh", "rrt-validator"])
def test_a_folder_on_stdin_is_one_line_and_exit_2(tool, tmp_path):
    args = ["-seed", "1"] if tool == "run.sh" else ["-noviz", "--", "true"]
    folder = os.open(tmp_path, os.O_RDONLY)   # as the shell opens it for < folder
    try:
        done = subprocess.run([str(ROOT / tool), *args], stdin=folder, capture_output=True,
                              timeout=60, cwd=tmp_path)
    finally:
        os.close(folder)
    err = done.stderr.decode()
    assert done.returncode == 2 and done.stdout == b"", err
    assert err.count("\n") == 1 and "folder" in err and "Fatal Python error" not in err
