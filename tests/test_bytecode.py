"""The launchers' bytecode (rrt_startup/bytecode.py): read only from the checkout's
.build/pycache, and only when whole and of the very source. So no bytecode a planner
writes anywhere else is ever loaded, a run on a full disk leaves no lasting damage,
and an edit that keeps a source's size and time is seen."""

from __future__ import annotations

import marshal
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from tests.conftest import script_code
from tests.test_launch_scripts import SPACE1, checkout_copy, launch, python_on_path
from validator.checks import INVALID_VERDICT

ROOT = Path(__file__).resolve().parent.parent
FORGER = Path(__file__).resolve().parent / "bytecode_forger.py"
OTHER_USER = 65534  # nobody: root ignores the permissions a read-only checkout relies on
PYTHONS = (sys.executable, "/usr/bin/python3", "/usr/local/bin/python3")


def as_other_user() -> list[str]:
    """The command prefix that runs as a user without root's powers ([] when this
    process has none already)."""
    if os.geteuid() != 0:
        return []
    if shutil.which("setpriv") is None:
        pytest.skip("running as root without setpriv: a read-only checkout cannot be tried")
    return ["setpriv", f"--reuid={OTHER_USER}", f"--regid={OTHER_USER}", "--clear-groups"]


def python_for(user: list[str]) -> str:
    """A python3 (3.10 or newer) that ``user`` may run and whose standard library it
    may not write: the forger writes bytecode for every module it can, and what it left
    there would outlast the test in every program that Python runs."""
    for python in PYTHONS:
        real = os.path.realpath(python)
        done = subprocess.run([*user, "sh", "-c", '[ -x "$0" ] && "$0" -c "import sys; '
                               'sys.exit(sys.version_info < (3, 10))"', real],
                              capture_output=True, timeout=60)
        if done.returncode == 0 and not _stdlib_writable_by(user, real):
            return real
    pytest.skip(f"no python3 that {f'user {OTHER_USER}' if user else 'you'} may run but "
                "not write into (the forger would leave its bytecode in its standard "
                "library): as root the forger runs as nobody")


def _stdlib_writable_by(user: list[str], python: str) -> bool:
    """Whether ``user`` may write ``python``'s standard library or its bytecode folder
    (True when that cannot be told)."""
    stdlib = subprocess.run([python, "-c", "import sysconfig; print(sysconfig.get_paths()"
                             "['stdlib'])"], capture_output=True, text=True,
                            timeout=60).stdout.strip()
    return not stdlib or any(
        subprocess.run([*user, "test", "-w", folder], timeout=60).returncode == 0
        for folder in (stdlib, os.path.join(stdlib, "__pycache__")))


MEMORY = "/dev/shm"


def _free_bytes(folder: str) -> int:
    status = os.statvfs(folder)
    return status.f_bavail * status.f_frsize


@pytest.fixture
def scratch():
    """A fresh folder other users may enter (pytest's tmp_path is root's alone), in
    memory when the system has a memory file system for all to write: these runs
    write hundreds of small files, the forger thousands (seconds on a disk)."""
    memory = (os.path.isdir(MEMORY) and os.access(MEMORY, os.W_OK | os.X_OK)
              and _free_bytes(MEMORY) > 512 << 20)  # not a container's small /dev/shm
    folder = Path(tempfile.mkdtemp(prefix="rrt-bytecode-", dir=MEMORY if memory else None))
    folder.chmod(0o755)
    yield folder
    subprocess.run(["chmod", "-R", "u+w", str(folder)], check=True)
    shutil.rmtree(folder)


def writable_by(user: list[str], folder: Path) -> Path:
    folder.mkdir()
    if user:
        os.chown(folder, OTHER_USER, OTHER_USER)
    return folder


@pytest.mark.parametrize("warm", [True, False], ids=["after-a-run", "bare"])
def test_no_bytecode_a_planner_writes_is_ever_loaded(scratch, warm):
    """A planner run by the validator forges bytecode for every module, in every
    place it can write (its user's caches, /tmp, __pycache__, .build/pycache, the
    user site); the checkout is read-only to it. The next validator run still
    judges garbage invalid, with or without the PDF, and the planner answers as
    before."""
    user = as_other_user()
    python = python_for(user)
    copy = checkout_copy(scratch)
    forger = shutil.copy(FORGER, scratch / FORGER.name)
    env = {"PATH": python_on_path(scratch, python)}
    answer = launch(["./run.sh", "-seed", "1"], copy, env)  # writes .build/pycache
    assert answer.returncode == 0, answer.stderr
    if not warm:
        shutil.rmtree(copy / ".build", ignore_errors=True)
    subprocess.run(["chmod", "-R", "a-w", str(copy)], check=True)
    home = writable_by(user, scratch / "home")
    env.update(HOME=str(home), XDG_CACHE_HOME=str(writable_by(user, scratch / "xdg")),
               TMPDIR=str(writable_by(user, scratch / "tmp")))

    def run(*command: str) -> subprocess.CompletedProcess:
        return launch([*user, *command], copy, env)

    forged = run("./rrt-validator", "-noviz", "--", python, str(forger), str(copy))
    assert forged.returncode == 1 and forged.stdout.endswith(INVALID_VERDICT + "\n")
    assert int(forged.stderr.split("forged ")[1].split()[0]) > 1000  # it could write them
    again = run("./rrt-validator", "-noviz", "--", "sh", "-c", "echo garbage")
    assert (again.returncode, again.stdout.splitlines()[-1]) == (1, INVALID_VERDICT)
    pdf = run("./rrt-validator", "-o", str(home / "tree.pdf"), "--", "sh", "-c", "echo garbage")
    assert pdf.returncode in (1, 2) and "appears valid" not in pdf.stdout  # 2: no reportlab
    planner = run("./run.sh", "-seed", "1")
    assert (planner.returncode, planner.stdout) == (0, answer.stdout)


def full_disk() -> None:
    """In the child: files may grow to 1500 bytes, and a write past that fails
    (EFBIG) after writing what fits, as on a full disk."""
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (1500, 1500))


def whole_pycs(folder: Path) -> list[Path]:
    """The pycs under ``folder``, each checked to unmarshal whole."""
    pycs = list(folder.rglob("*.pyc"))
    for pyc in pycs:
        marshal.loads(pyc.read_bytes()[16:])
    return pycs


def test_a_run_on_a_full_disk_leaves_no_lasting_damage(scratch):
    """The first runs write bytecode on a full disk: they work, leave no short file,
    and the next runs work and write it whole."""
    copy = checkout_copy(scratch)
    env = {"PATH": python_on_path(scratch), "XDG_CACHE_HOME": str(scratch / "cache")}
    planner, validator = ["./run.sh", "-seed", "1"], ["./rrt-validator", "-noviz", "--",
                                                       "./run.sh", "-seed", "1"]
    for command in (planner, validator):
        with open(SPACE1, "rb") as problem:
            done = subprocess.run(command, stdin=problem, capture_output=True, text=True,
                                  cwd=copy, env=dict(os.environ, **env), timeout=120,
                                  preexec_fn=full_disk)
        assert done.returncode == 0, done.stderr
    whole_pycs(scratch)  # none cut short (the first write that failed was the last)
    answer = launch(planner, copy, env)
    assert answer.returncode == 0 and answer.stdout.startswith("3\n"), answer.stderr
    verdict = launch(validator, copy, env)
    assert (verdict.returncode, verdict.stdout) == (0, "Solution trajectory appears valid.\n")
    assert len(whole_pycs(scratch)) > 20  # the checkout's modules the two import
    assert not list(scratch.rglob("*.tmp"))


FAKE_CLI = 'def entry_point():\n    print("AAA")\n'


def fake_planner(scratch: Path) -> tuple[Path, dict]:
    """A checkout whose planner prints what its rrt_cli/cli.py says, and the env."""
    copy = checkout_copy(scratch, packages=())
    (copy / "rrt_cli").mkdir()
    (copy / "rrt_cli" / "__init__.py").write_text("")
    (copy / "rrt_cli" / "cli.py").write_text(FAKE_CLI)
    return copy, {"PATH": python_on_path(scratch), "XDG_CACHE_HOME": str(scratch / "cache")}


def test_an_edit_that_keeps_size_and_time_is_run(scratch):
    """As ``cp -p`` or ``tar x`` of an edited copy leaves it: the bytecode is keyed by
    the source's content, so the edit runs."""
    copy, env = fake_planner(scratch)
    assert launch(["./run.sh"], copy, env).stdout == "AAA\n"
    cli = copy / "rrt_cli" / "cli.py"
    status = cli.stat()
    cli.write_text(FAKE_CLI.replace("AAA", "BBB"))
    os.utime(cli, ns=(status.st_atime_ns, status.st_mtime_ns))
    assert launch(["./run.sh"], copy, env).stdout == "BBB\n"


@pytest.mark.parametrize("damage", [lambda data: data[:len(data) // 2],
                                    lambda data: data[:16] + bytes(len(data) - 16)],
                         ids=["cut-short", "zeroed"])
@pytest.mark.parametrize("module", ["cli", "bytecode"])  # bytecode: read by CPython's loader
def test_a_damaged_pyc_in_the_checkout_is_ignored_and_written_again(scratch, damage, module):
    copy, env = fake_planner(scratch)
    assert launch(["./run.sh"], copy, env).stdout == "AAA\n"
    [pyc] = (copy / ".build" / "pycache").rglob(f"{module}.cpython-*.pyc")
    whole = pyc.read_bytes()
    pyc.write_bytes(damage(whole))
    done = launch(["./run.sh"], copy, env)
    assert (done.returncode, done.stdout, done.stderr) == (0, "AAA\n", "")
    assert pyc.read_bytes() == whole


LOADER_PROBE = """import sys
sys.path.insert(0, sys.argv[1])
from rrt_startup.bytecode import install
install(sys.argv[2])
sys.path.insert(0, sys.argv[3])
import plain
print(plain.VALUE)
try:
    import sourceless
except ImportError:
    print("no sourceless")
"""


def test_outside_the_checkout_a_damaged_pyc_and_a_bare_pyc_are_never_loaded(scratch):
    """A folder outside the checkout (as the interpreter's own): its ``__pycache__`` is
    read when whole and of the source, a cut one ignored; a ``.pyc`` without its
    source is never imported."""
    library = scratch / "library"
    library.mkdir()
    (library / "plain.py").write_text("VALUE = 'source'\n")
    beside = {k: v for k, v in os.environ.items() if k != "PYTHONPYCACHEPREFIX"}  # ./test.sh's
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(library)], check=True,
                   env=beside)
    [own] = (library / "__pycache__").glob("plain.*.pyc")
    own.write_bytes(own.read_bytes()[:-10])
    (library / "sourceless.pyc").write_bytes(own.read_bytes())
    done = subprocess.run([sys.executable, "-S", "-I", "-B", "-c", LOADER_PROBE, str(ROOT),
                           str(scratch / "pycache"), str(library)],
                          capture_output=True, text=True, timeout=60)
    assert (done.returncode, done.stdout, done.stderr) == (0, "source\nno sourceless\n", "")
    assert [marshal.loads(pyc.read_bytes()[16:]) for pyc in (scratch / "pycache").rglob(
        "plain.*.pyc")]  # compiled, and written whole under the prefix


COUNT_COMPILES = """import atexit, builtins, sys
compiled, real = [], builtins.compile
def counting(source, filename, *args, **kwargs):
    compiled.append(filename)
    return real(source, filename, *args, **kwargs)
builtins.compile = counting
atexit.register(lambda: sys.stderr.write("compiled: %s\\n" % ",".join(compiled)))
"""


@pytest.mark.parametrize("launcher, args, status", [
    ("run.sh", ["-seed", "1"], 0), ("rrt-validator", ["-noviz", "--", "sh", "-c", "echo 0"], 1)])
@pytest.mark.parametrize("interpreted", ["", "1"])
def test_a_second_run_compiles_nothing(scratch, launcher, args, status, interpreted):
    """Every module a launcher imports, those CPython loads before the checked loader
    included, has its bytecode after one run: the next compiles no source."""
    copy = checkout_copy(scratch)
    code = script_code(launcher)
    env = dict(os.environ, RRT_INTERPRETED=interpreted)
    for run in ("first", "second"):
        with open(SPACE1, "rb") as problem:
            done = subprocess.run([sys.executable, "-S", "-I", "-B", "-c", COUNT_COMPILES + code,
                                   str(copy), *args], stdin=problem, capture_output=True,
                                  text=True, env=env, timeout=120)
        assert done.returncode == status, done.stderr
    assert done.stderr.splitlines()[-1] == "compiled: "


def test_make_sh_builds_the_bytecode_afresh_and_whole(scratch):
    """./make.sh's step reads nothing already in .build/pycache and replaces the
    folder whole, stray files gone."""
    copy, env = fake_planner(scratch)
    assert launch(["./run.sh"], copy, env).stdout == "AAA\n"
    pycache = copy / ".build" / "pycache"
    [pyc] = pycache.rglob("bytecode.cpython-*.pyc")
    pyc.write_bytes(pyc.read_bytes()[:200])
    (pycache / "stray.pyc").write_bytes(b"stray")
    make_sh = (ROOT / "make.sh").read_text()
    step = make_sh[make_sh.index("compile_bytecode() {"):]
    code = step.split("-c '", 1)[1].split("' ", 1)[0]
    folder = copy / ".build" / ".pycache-test"
    folder.mkdir()
    done = subprocess.run([sys.executable, "-S", "-I", "-B", "-X", f"pycache_prefix={folder}",
                           "-c", code, str(copy), str(folder)], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert not folder.exists() and not (pycache / "stray.pyc").exists()
    assert len(whole_pycs(pycache)) > 5
    assert launch(["./run.sh"], copy, env).stdout == "AAA\n"
