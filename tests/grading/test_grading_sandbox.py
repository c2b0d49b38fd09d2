"""What a submission cannot do (docs/grading.md, "What a submission can and cannot
do"): hostile submissions graded by ``rrt-grade`` beside a good one. They need the
full sandbox (root, namespaces), as in CI; elsewhere they are skipped and say why."""

from __future__ import annotations

import os
import shutil
import socket
import sqlite3
import subprocess
import sys
import tempfile
from pathlib import Path
from types import SimpleNamespace

import pytest

from grading.config import GradeConfig, Limits
from grading.grade import grade
from grading.rubric import Rubric
from grading.runs import sandbox_here
from grading.sandbox import FIRST_UID, FULL, SLOTS, Place, Sandbox
from grading_fixtures import (HOSTILE, ROOT, closed_folder, closed_message, make_hostile,
                              make_submission)

MODES = ("point", "grad")
MARKER = f"rrt-grade-marker-{os.getpid()}"
HOST_DIRS = ("/tmp", "/var/tmp", "/run", "/dev/shm")


def _need_the_full_sandbox() -> None:
    sandbox = sandbox_here(True)
    if sandbox.level != "full":
        pytest.skip(f"needs the full sandbox (root and namespaces); here: {sandbox.note}")


def _listener(path: Path) -> socket.socket:
    server = socket.socket(socket.AF_UNIX)
    server.bind(str(path))
    os.chmod(path, 0o777)
    server.listen(8)
    server.setblocking(False)
    return server


def _reader(path: Path) -> int:
    os.mkfifo(path)
    os.chmod(path, 0o666)
    return os.open(path, os.O_RDONLY | os.O_NONBLOCK)


def _drain(fd: int) -> bytes:
    try:
        return os.read(fd, 4096)
    except BlockingIOError:
        return b""


def _accepted(server: socket.socket) -> bool:
    try:
        server.accept()[0].close()
        return True
    except BlockingIOError:
        return False


def _sandboxed_processes(token: str) -> list[int]:
    """Processes with one of the sandbox's uids and ``token`` in their command line
    (other gradings may be running)."""
    found = []
    for name in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{name}/status") as status:
                uid = next(int(line.split()[1]) for line in status if line.startswith("Uid:"))
            with open(f"/proc/{name}/cmdline", "rb") as cmdline:
                mine = token.encode() in cmdline.read()
        except (OSError, StopIteration):
            continue
        if mine and FIRST_UID <= uid < FIRST_UID + SLOTS:
            found.append(int(name))
    return found


def _logs(out: Path, name: str) -> str:
    folder = out / "logs" / name
    return "".join(path.read_text(errors="replace") for path in sorted(folder.glob("*")))


@pytest.fixture(scope="module", params=[("point",), pytest.param(MODES, marks=pytest.mark.slow)],
                ids=["point", "two-modes"])
def attacked(request, tmp_path_factory):
    """Every HOSTILE submission graded by ``python -m grading --jobs 2`` (a process of
    its own: before the sandbox, some of them killed their grader): in one mode in the
    unit run; ./test.sh grades them in two modes too, each run beside its twin."""
    _need_the_full_sandbox()
    modes = request.param
    base = tmp_path_factory.mktemp("hostile")
    out, outside, subs = base / "out", base / "outside", base / "subs"
    out.mkdir()
    outside.mkdir()
    places = [outside, out, subs]  # beside the folder, in --out, among the submissions
    sentinel = subprocess.Popen(["sleep", "600"])
    submissions, problems = make_hostile(
        base, list(HOSTILE), ["simple-0.sw"], out=out, sentinel=sentinel.pid,
        fifos=" ".join(str(place / "fifo") for place in places),
        sockets=" ".join(str(place / "sock") for place in places))
    readers = [_reader(place / "fifo") for place in places]
    servers = [_listener(place / "sock") for place in places]
    markers = [Path(folder) / MARKER for folder in HOST_DIRS]
    for marker in markers:
        marker.write_text("the host's\n")
    try:
        done = subprocess.run(
            [sys.executable, "-m", "grading", "--submissions", str(submissions), "--problems",
             str(problems), "--out", str(out), "--modes", ",".join(modes), "--jobs", "2",
             "--timeout", "30"], cwd=ROOT, capture_output=True, timeout=900,
            env=dict(os.environ, PYTHONPATH=str(ROOT)))
        seen = SimpleNamespace(
            status=done.returncode, stderr=done.stderr.decode(errors="replace"), out=out,
            subs=submissions, modes=modes, sentinel_alive=sentinel.poll() is None,
            fifo_data=[_drain(fd) for fd in readers],
            connected=[_accepted(server) for server in servers],
            left=_sandboxed_processes(str(submissions)))
    finally:
        sentinel.kill()
        sentinel.wait()
        for fd in readers:
            os.close(fd)
        for server in servers:
            server.close()
        for marker in markers:
            marker.unlink(missing_ok=True)
    db = sqlite3.connect(out / "grades.sqlite") if (out / "grades.sqlite").exists() else None
    seen.rows = {} if db is None else {
        (row[0], row[1]): row[2:] for row in db.execute(
            "SELECT submission, mode, verdict, valid, sandbox FROM runs")}
    return seen


def _valid_in_every_mode(seen, name: str) -> None:
    for mode in seen.modes:
        verdict, valid, note = seen.rows[name, mode]
        assert (verdict, valid) == ("valid", 1), (name, mode, _logs(seen.out, name))
        assert note.startswith(FULL)


def test_rrt_grade_survives_them_all_and_stores_every_run(attacked):
    assert attacked.status == 0, attacked.stderr
    assert set(attacked.rows) == {(name, mode) for name in HOSTILE for mode in attacked.modes}
    _valid_in_every_mode(attacked, "good")


def test_a_run_that_kills_whatever_it_can_see_kills_nothing_else(attacked):
    log = _logs(attacked.out, "killall")
    assert "attacked" in log and "killed the sentinel" not in log
    assert attacked.sentinel_alive
    _valid_in_every_mode(attacked, "killall")


def test_a_run_cannot_kill_its_parent_its_worker_or_rrt_grade(attacked):
    assert "parent 1 grandparent 0" in _logs(attacked.out, "killparents")
    _valid_in_every_mode(attacked, "killparents")


def test_no_fifo_or_unix_socket_outside_the_folder_is_reachable(attacked):
    log = _logs(attacked.out, "ipc")
    assert attacked.fifo_data == [b""] * 3 and attacked.connected == [False] * 3
    assert "wrote" not in log and "connected" not in log
    assert log.count("refused") == 3 * len(attacked.modes)


def test_no_device_kernel_setting_or_sysfs_file_opens_for_writing(attacked):
    log = _logs(attacked.out, "devices")
    assert "opened" not in log
    assert log.count("refused") == 8 * len(attacked.modes)


def _seen(log: str) -> dict[str, list[str]]:
    """``seen FOLDER: ENTRY...`` lines of the 'looks' submission's log (its first run)."""
    seen = {}
    for line in log.splitlines():
        if line.startswith("seen "):
            folder, _, entries = line[5:].partition(":")
            seen.setdefault(folder, entries.split())
    return seen


def test_a_run_sees_empty_tmp_run_shm_a_minimal_dev_and_not_out(attacked):
    log = _logs(attacked.out, "looks")
    seen = _seen(log)
    subs = attacked.subs
    on_the_way = [subs.parts[2]] if subs.parts[1] == "tmp" else []  # the path to its folder
    assert seen["/tmp"] == on_the_way and MARKER not in log
    assert seen["/var/tmp"] == seen["/run"] == seen["/dev/shm"] == []
    assert sorted(seen["/dev"]) == ["fd", "null", "random", "shm", "stderr", "stdin",
                                    "stdout", "urandom", "zero"]
    assert seen[str(subs)] == ["looks"]  # not the other submissions
    assert "sees --out" not in log
    assert f"home {subs / 'looks'} tmp /tmp\n" in log


def test_a_run_has_an_unprivileged_uid_of_its_own_and_no_capabilities(attacked):
    log = _logs(attacked.out, "looks")
    uid = int(log.split("uid ")[1].split()[0])
    assert FIRST_UID <= uid < FIRST_UID + SLOTS
    for line in ("CapEff:\t0000000000000000", "CapBnd:\t0000000000000000", "NoNewPrivs:\t1"):
        assert line in log


def test_a_fork_bomb_is_capped_and_nothing_is_left_running(attacked):
    counts = [int(line.split()[1]) for line in _logs(attacked.out, "forkbomb").splitlines()
              if line.startswith("forked ")]
    assert len(counts) == len(attacked.modes)
    assert all(0 < count < Limits().processes for count in counts), counts
    assert attacked.left == []
    _valid_in_every_mode(attacked, "forkbomb")


def _grade_one(tmp_path: Path, make: str, run: str, **limits) -> tuple[Path, Path, dict]:
    """One submission graded in-process with small disk caps; (out, its folder, rows)."""
    folder = make_submission(tmp_path / "subs", "one", make, run, tmp_path / "unused")
    problems = tmp_path / "problems"
    problems.mkdir()
    (problems / "simple-0.sw").write_text((ROOT / "benchmarks/problems/course/simple-0.sw")
                                          .read_text())
    config = GradeConfig(tmp_path / "subs", problems, tmp_path / "out",
                         rubric=Rubric(modes=MODES), jobs=1, calibrate=False,
                         limits=Limits(**limits), build_limits=Limits(**limits))
    outcome = grade(config)
    return config.out, folder, {row["mode"]: row for row in outcome.runs}


def test_the_folder_and_tmp_share_one_size_cap_in_builds_and_runs(tmp_path):
    _need_the_full_sandbox()
    fill = ('dd if=/dev/zero of=big bs=1M count=64 2>/dev/null; echo "folder $(stat -c %s big)"'
            ' >&2; dd if=/dev/zero of=/tmp/more bs=1M count=1 2>/dev/null; echo "tmp $(stat -c '
            '%s /tmp/more)" >&2; rm -f big /tmp/more\n')
    out, folder, rows = _grade_one(tmp_path, fill, fill + 'exec "{run}" "$@"',
                                   disk_bytes=8 << 20)
    for log in ["make.log", "simple-0-point.stderr", "simple-0-grad.stderr"]:
        text = (out / "logs" / "one" / log).read_text()
        written = int(text.split("folder ")[1].split()[0])
        more = int(text.split("tmp ")[1].split()[0])
        assert 0 < written <= 8 << 20 and written + more <= 8 << 20, text
    assert all(row["valid"] for row in rows.values())
    assert sorted(os.listdir(folder)) == ["make.sh", "run.sh"]


def test_runs_see_the_build_not_each_other_and_the_submission_is_untouched(tmp_path):
    _need_the_full_sandbox()
    run = ('[ -e product ] && echo "product seen" >&2; [ -e marker ] && echo "marker seen" >&2\n'
           'touch marker /tmp/marker\nexec "{run}" "$@"')
    out, folder, rows = _grade_one(tmp_path, "echo built > product", run)
    for mode in MODES:
        log = (out / "logs" / "one" / f"simple-0-{mode}.stderr").read_text()
        assert log == "product seen\n" and rows[mode]["valid"]
    assert sorted(os.listdir(folder)) == ["make.sh", "run.sh"]
    assert (out / "built" / "one" / "product").read_text() == "built\n"
    assert not (out / "built" / "one" / "marker").exists()



def test_a_submission_that_is_a_link_to_a_folder_of_roots_is_not_copied_for_it(tmp_path):
    _need_the_full_sandbox()
    secret = tmp_path / "roots"
    secret.mkdir(mode=0o700)
    (secret / "make.sh").write_text("#!/bin/sh\ncat secret\n")
    (secret / "make.sh").chmod(0o700)
    (secret / "secret").write_text("root's own\n")
    (tmp_path / "subs").mkdir()
    (tmp_path / "subs" / "linked").symlink_to(secret)
    (tmp_path / "problems").mkdir()
    (tmp_path / "problems" / "simple-0.sw").write_bytes(
        (ROOT / "benchmarks/problems/course/simple-0.sw").read_bytes())
    outcome = grade(GradeConfig(tmp_path / "subs", tmp_path / "problems", tmp_path / "out",
                                rubric=Rubric(modes=("point",)), jobs=1, calibrate=False))
    build = outcome.builds["linked"]
    assert not build["ok"] and "Not a directory" in build["reason"]
    assert "root's own" not in (tmp_path / "out" / "logs" / "linked" / "make.log").read_text()


_NOBODY = 65534
_SYSTEM_PYTHON = Path("/usr/bin/python3")


@pytest.fixture
def nobodys(tmp_path_factory):
    """A scratch folder directly in /tmp (pytest's is root's alone)."""
    folder = Path(tempfile.mkdtemp(prefix="rrt-grade-userns-", dir="/tmp"))
    yield folder
    shutil.rmtree(folder)


def test_without_root_a_user_namespace_gives_the_same_view_as_the_graders_uid(nobodys):
    """The ``userns`` level, run by an ordinary user (nobody, through setpriv, with the
    system's python: ours may be out of its reach)."""
    if os.geteuid() != 0 or not _SYSTEM_PYTHON.exists() or not Path("/usr/bin/setpriv").exists():
        pytest.skip("needs root (to become nobody), setpriv and /usr/bin/python3")
    if closed_folder() is not None:  # nobody runs the checkout's grading/jail.py
        pytest.skip(closed_message(closed_folder()))
    tmp_path = nobodys
    for name in ("subs/one", "built/one", "outside"):
        (tmp_path / name).mkdir(parents=True)
    (tmp_path / "built/one/given").write_text("layer\n")
    (tmp_path / "outside/secret").write_text("host\n")
    for path in [tmp_path, *tmp_path.rglob("*")]:
        os.chown(path, _NOBODY, _NOBODY)
    os.chmod(tmp_path, 0o755)
    place = Place(tmp_path / "subs/one", tmp_path / "built/one", hide=(tmp_path / "subs",))
    command = Sandbox("userns", "").command(place, ["sh", "-c", _LOOK_AROUND],
                                            Limits(), 10)
    done = subprocess.run(["setpriv", f"--reuid={_NOBODY}", f"--regid={_NOBODY}",
                           "--clear-groups", str(_SYSTEM_PYTHON), *command[1:]],
                          capture_output=True, text=True, timeout=30, cwd="/")
    if "unshare" in done.stderr:
        pytest.skip(f"this machine refuses unprivileged user namespaces: {done.stderr}")
    assert done.stdout.split("\n") == [
        "layer", "pid 2", "tmp " + tmp_path.parts[2], "dev fd null random shm stderr stdin "
        "stdout urandom zero", "run", "CapEff:\t0000000000000000", "NoNewPrivs:\t1", "wrote",
        "etc refused", "alive", ""], done.stderr
    assert sorted(os.listdir(tmp_path / "built/one")) == ["given"]  # its write thrown away


_LOOK_AROUND = ('cat given; echo "pid $$"; echo tmp $(ls -A /tmp); echo dev $(ls /dev); '
                'echo run $(ls -A /run); grep -E "^(CapEff|NoNewPrivs):" /proc/self/status; '
                'echo x > given && echo wrote; (echo x > /etc/rrt-grade-test) 2>/dev/null || '
                'echo etc refused; kill -9 -1 2>/dev/null; echo alive')  # nothing else to kill
