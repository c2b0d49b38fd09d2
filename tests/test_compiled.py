"""The compiled hot modules: used only while their manifest matches the sources by
content and every built file is whole, and then really used; otherwise the same
source runs interpreted and says why (a damaged build in one line on stderr).
(Byte identity of the outputs both ways: tests/golden.)"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from functools import lru_cache
from pathlib import Path

import pytest

from rrt_startup import compiled
from tests.conftest import unit_sample
from tests.test_launch_scripts import checkout_copy, launch

ROOT = Path(__file__).resolve().parent.parent
SIMPLE0 = ROOT / "benchmarks" / "problems" / "course" / "simple-0.sw"
SPACE1 = ROOT / "benchmarks" / "problems" / "course" / "space-1.sw"
COMPILED_MAIN = """import sys
from rrt_startup.compiled import activate
build = activate()
if not build.startswith("compiled"):
    sys.exit("expected the compiled modules, got: " + build)
from rrt_cli.cli import entry_point
entry_point()
"""
LIBRARY = f"{compiled.GROUP}__mypyc{compiled.extension_suffix()}"


def fresh_or_skip() -> None:
    why = compiled.why_not_fresh(compiled.BUILD_DIR)
    if why is not None:
        pytest.skip(f"compiled modules not in use: {why}")


def _env() -> dict:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.pop(compiled.DISABLE_VARIABLE, None)
    return env


def run_probe(probe: str, timeout: float = 60, stdin=None) -> subprocess.CompletedProcess:
    """Python source ``probe`` run in a fresh interpreter at the project's root (text out)."""
    return subprocess.run([sys.executable, "-c", probe], stdin=stdin, capture_output=True,
                          text=True, cwd=ROOT, env=_env(), timeout=timeout)


def run_planner_compiled(args: list[str], stdin: str,
                         timeout: float = 120) -> subprocess.CompletedProcess:
    """tests.conftest.run_planner with the compiled modules (skips when none are fresh)."""
    fresh_or_skip()
    return subprocess.run([sys.executable, "-c", COMPILED_MAIN, *args], input=stdin.encode(),
                          capture_output=True, timeout=timeout, cwd=ROOT, env=_env())


def fake_build(folder: Path, change: dict[str, str] | None = None,
               files: dict[str, bytes] | None = None) -> Path:
    """A build folder whose manifest matches the sources and lists ``files`` (written
    there; no real compiled module: only the manifest and the files' sizes are read
    before use), with the lines of ``change`` (a source's path, or a kind of line)
    replaced."""
    files = {"a.so": b"\x7fELF" + bytes(100)} if files is None else files
    for name, data in files.items():
        (folder / name).write_bytes(data)
    lines = {"format": compiled.FORMAT, "suffix": f"suffix {compiled.extension_suffix()}",
             **{path: compiled.source_line(path) for path in compiled.sources()},
             **{name: compiled.file_line(str(folder), name) for name in files},
             **(change or {})}
    (folder / compiled.MANIFEST).write_text("\n".join([*lines.values(), compiled.END]) + "\n")
    return folder


@pytest.fixture(autouse=True)
def _enabled(monkeypatch):
    monkeypatch.delenv(compiled.DISABLE_VARIABLE, raising=False)


def test_a_matching_manifest_is_fresh(tmp_path):
    assert compiled.why_not_fresh(str(fake_build(tmp_path))) is None
    assert compiled.why_not_fresh(str(tmp_path), full=True) is None


@pytest.mark.parametrize("path", [compiled.source_path(compiled.MODULES[0]),
                                  compiled.source_path(compiled.MODULES[-1]),
                                  *compiled.KERNELS.values()])
def test_an_edited_source_is_never_used_compiled(tmp_path, path):
    key, digest = compiled.source_line(path).split()[2:]
    build = fake_build(tmp_path, {path: f"source {path} {'0' * 16} {digest}"})
    assert compiled.activate(str(build)) == (
        f"interpreted: {path} changed since the compiled modules were built (./make.sh rebuilds)")
    assert compiled.state.startswith("interpreted")
    build = fake_build(tmp_path, {path: f"source {path} {key} {'0' * 64}"})
    assert compiled.why_not_fresh(str(build)) is None  # the run-time check reads the key
    assert "changed since" in compiled.why_not_fresh(str(build), full=True)  # ./make.sh's


def test_a_build_of_another_compile_list_is_not_used(tmp_path):
    """A module dropped from the list keeps its old binary in the build: never used."""
    build = fake_build(tmp_path, {"gone": f"source planning_core/worlds/gone.py {'0' * 16} "
                                          f"{'0' * 64}"})
    assert "the compile list changed" in compiled.why_not_fresh(str(build))


def test_other_interpreter_older_build_missing_build_and_opt_out_run_interpreted(
        tmp_path, monkeypatch):
    (tmp_path / "other").mkdir()
    other = fake_build(tmp_path / "other", {"suffix": "suffix .cpython-39-x86_64-linux-gnu.so"})
    assert "another interpreter" in compiled.why_not_fresh(str(other))
    (tmp_path / "old").mkdir()
    older = fake_build(tmp_path / "old", {"format": "suffix .cpython-39-x86_64-linux-gnu.so"})
    assert "older tools/build_compiled.py" in compiled.why_not_fresh(str(older))
    assert "no compiled modules built" in compiled.why_not_fresh(str(tmp_path / "none"))
    monkeypatch.setenv(compiled.DISABLE_VARIABLE, "1")
    assert compiled.why_not_fresh(str(fake_build(tmp_path))) == "RRT_INTERPRETED is set"


def test_a_built_file_missing_cut_short_or_changed_is_damaged(tmp_path, capsys):
    """Cut short or missing: seen at run time (by size; a short library can kill
    the process with SIGBUS when loaded), and one line says so; changed in place
    at the same size: seen by ./make.sh's full check."""
    build = fake_build(tmp_path)
    library = build / "a.so"
    library.write_bytes(library.read_bytes()[:50])
    expected = "the compiled build is damaged: a.so has 50 bytes, built 104"
    assert compiled.why_not_fresh(str(build)) == expected
    assert compiled.activate(str(build)) == f"interpreted: {expected}"
    assert capsys.readouterr().err == (f"rrt_cli: {expected}; running interpreted "
                                       "(./make.sh rebuilds it)\n")
    library.unlink()
    assert compiled.why_not_fresh(str(build)) == "the compiled build is damaged: a.so is missing"
    library.write_bytes(b"\x7fELF" + bytes(99) + b"!")
    assert compiled.why_not_fresh(str(build)) is None
    assert compiled.why_not_fresh(str(build), full=True) == (
        "the compiled build is damaged: a.so is not as built")


def test_a_manifest_cut_short_is_damaged(tmp_path):
    build = fake_build(tmp_path)
    manifest = build / compiled.MANIFEST
    lines = manifest.read_text().splitlines()
    manifest.write_text("\n".join(lines[:-2]) + "\n")  # its last file line and the end gone
    assert compiled.why_not_fresh(str(build)) == (
        "the compiled build is damaged: its manifest is cut short")
    manifest.write_text("\n".join([*lines[:-2], "file a.so", compiled.END]) + "\n")
    assert compiled.why_not_fresh(str(build)) == (
        "the compiled build is damaged: its manifest does not read")


def test_activate_refuses_after_the_interpreted_module_is_imported(tmp_path):
    import planning_core.systems.spaceship  # noqa: F401  (interpreted, in this process)
    path_before = list(sys.path)
    assert "was imported before activate()" in compiled.activate(str(fake_build(tmp_path)))
    assert sys.path == path_before


def test_a_fresh_build_is_what_runs():
    fresh_or_skip()
    probe = ("from rrt_startup.compiled import activate, MODULES\nimport importlib\n"
             "activate()\nprint(*(importlib.import_module(m).__file__ for m in MODULES))")
    done = run_probe(probe)
    files = done.stdout.split()
    assert len(files) == len(compiled.MODULES), done.stderr
    assert all(file.startswith(compiled.BUILD_DIR) and file.endswith(compiled.extension_suffix())
               for file in files), files


def test_the_family_runs_its_generated_kernels_compiled_and_stats_says_so():
    """A planner's metric, goal metric and slice loop are the generated classes from the
    build, and its body test the C kernel; the compiled metric measures as the space does;
    -stats names them (interpreted: the same classes and the shapes' body test)."""
    fresh_or_skip()
    probe = ("from rrt_startup.compiled import activate\nactivate()\n"
             "from cli_common import parse_any_problem\n"
             "from planning_core.setups import kinoplan_setup\nimport random, sys\n"
             "p = parse_any_problem(open('benchmarks/problems/family/car2-corridors.kp').read())\n"
             "setup = kinoplan_setup(p)\nsi = setup.si\n"
             "for found in (si.advance.__self__, si.kernels['metric'], setup.pdef.goal.metric):\n"
             "    print(sys.modules[type(found).__module__].__file__)\n"
             "metric, rng = si.kernels['metric'], random.Random(1)\n"
             "pairs = [(si.sample_target(rng), si.sample_target(rng)) for _ in range(3000)]\n"
             "assert all(metric.distance(a, b).hex() == si.space.distance(a, b).hex()"
             " for a, b in pairs)\n")
    done = run_probe(probe)
    files = done.stdout.split()
    assert files == [os.path.join(compiled.BUILD_DIR, "planning_core", "generated_kernels"
                                  + compiled.extension_suffix())] * 3, done.stderr
    problem = (ROOT / "benchmarks" / "problems" / "family" / "car2-corridors.kp").read_text()
    for disable, mode, body in (("", "compiled", "C kernel"), ("1", "interpreted", (
            "reference (shapes), interpreted (the C kernel runs only with the compiled build)"))):
        ran = subprocess.run([str(ROOT / "run.sh"), "-seed", "1", "-stats"], input=problem,
                             capture_output=True, text=True, timeout=120,
                             env=dict(os.environ, RRT_INTERPRETED=disable))
        assert ran.stderr.splitlines()[-1] == (
            f"rrt_cli kernels: metric=generated, {mode}; integrator=generated, {mode}; "
            f"body test={body}; goal metric=generated, {mode}")


def test_python_m_rrt_cli_runs_the_compiled_build_as_run_sh_does():
    """The benchmark harness starts ``python -m rrt_cli``: it must measure what users run."""
    fresh_or_skip()
    probe = ("import runpy, sys\nsys.argv = ['rrt_cli', '-seed', '1']\n"
             "try:\n    runpy.run_module('rrt_cli', run_name='__main__')\n"
             "except SystemExit:\n    pass\n"
             "from rrt_startup import compiled\nsys.stderr.write(compiled.state)\n")
    with open(SIMPLE0, "rb") as problem:
        done = run_probe(probe, stdin=problem)
    assert done.stdout.strip() and done.stderr.startswith("compiled ("), done.stderr


def test_a_world_with_compiled_tests_pickles():
    """A world binds compiled segment and body tests; it pickles by its fields (a
    native object's __init__ takes arguments pickle does not give)."""
    fresh_or_skip()
    probe = ("import pickle\nfrom rrt_startup.compiled import activate\nactivate()\n"
             "from cli_common import parse_any_problem\n"
             "p = parse_any_problem(open('benchmarks/problems/family/arm2-pair1.kp').read())\n"
             "q = pickle.loads(pickle.dumps(p))\n"
             "assert q == p and q.world.segment_free(0, 0, 0.5, 0.5)\n"
             "import planning_core.worlds.segment_tests as t\nprint(t.__file__)\n")
    done = run_probe(probe)
    assert done.returncode == 0 and done.stdout.startswith(compiled.BUILD_DIR), done.stderr


@pytest.mark.parametrize("disable", ["", "1"])
def test_run_sh_stats_says_which_ran(disable):
    fresh_or_skip()
    env = dict(os.environ, RRT_INTERPRETED=disable)
    with open(SIMPLE0, "rb") as problem:
        done = subprocess.run([str(ROOT / "run.sh"), "-seed", "1", "-stats"],
                              stdin=problem, capture_output=True, text=True, env=env,
                              timeout=120)
    assert done.returncode == 0, done.stderr
    expected = "rrt_cli build: interpreted: RRT_INTERPRETED is set" if disable else (
        f"rrt_cli build: compiled ({len(compiled.MODULES)} modules, "
        f"{len(compiled.KERNELS)} C kernels, from {compiled.BUILD_DIR})")
    assert expected in done.stderr.splitlines()


def test_no_compiled_module_inside_the_source_tree():
    """Python prefers an extension module to the .py beside it: none may be there."""
    suffixes = (".so", ".pyd")
    strays = [path for package in ("planning_core", "cli_common", "rrt_cli", "validator")
              for path in (ROOT / package).rglob("*") if path.suffix in suffixes]
    assert strays == []


def test_the_build_used_the_pinned_flags():
    """Every C compile of the build in use had -ffp-contract=off and no flag that
    lets the compiler change float results."""
    fresh_or_skip()
    log = (Path(compiled.BUILD_DIR) / "build.log").read_text()
    compiles = [line.split() for line in log.splitlines() if " -c " in line]
    assert compiles
    for flags in compiles:
        assert "-ffp-contract=off" in flags
        assert not {"-march=native", "-ffast-math", "-Ofast"} & set(flags)


def test_the_compiled_body_test_answers_as_the_shapes_do():
    """tests/planning_core/worlds/test_body_tests.py's seeded walks, with the compiled
    build (the unit run imports the interpreted source) and its C kernel."""
    fresh_or_skip()
    probe = ("from rrt_startup.compiled import activate\nactivate()\n"
             "from tests.planning_core.worlds.test_body_tests import check_random_walks\n"
             "check_random_walks(seed=7)\n"
             "import planning_core.worlds.body_tests as t\nprint(t.__file__)\n"
             "from planning_core.worlds.continuous import ContinuousWorld\n"
             "from planning_core.worlds.shapes import body_polygon\n"
             "test = ContinuousWorld(None, ()).body_tester(body_polygon('rect', [2, 1]))\n"
             "print(test.meets.__self__.__class__.__module__)\n")
    done = run_probe(probe, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == [os.path.join(compiled.BUILD_DIR, "planning_core", "worlds",
                                                "body_tests" + compiled.extension_suffix()),
                                   "planning_core.worlds._body_kernel"]


@pytest.mark.parametrize("motions, segments", unit_sample([(300, 2000), (800, 5000)]))
def test_the_compiled_link_and_segment_tests_answer_as_the_code_they_replaced(motions,
                                                                             segments):
    """tests/planning_core/worlds/test_link_tests.py's seeded states and motions and
    test_segment_tests.py's segments, with the compiled build (the unit run imports
    the interpreted source)."""
    fresh_or_skip()
    probe = ("from rrt_startup.compiled import activate\nactivate()\n"
             "from tests.planning_core.worlds.test_link_tests import check_against_reference\n"
             "from tests.planning_core.test_angles import check_remainder\n"
             "from tests.planning_core.worlds.test_segment_tests import check_segments\n"
             f"check_against_reference(seed=7, count={motions})\n"
             f"check_segments(seed=8, count={segments})\n"
             "check_remainder(seed=9)\n"
             "import planning_core.worlds.link_tests as t\nprint(t.__file__)\n")
    done = run_probe(probe, timeout=120)
    assert done.returncode == 0 and done.stdout.startswith(compiled.BUILD_DIR), done.stderr


def built_copy(tmp_path: Path) -> Path:
    """A copy of the checkout with a copy of the fresh compiled build (skips without)."""
    fresh_or_skip()
    copy = checkout_copy(tmp_path)
    shutil.copytree(compiled.BUILD_DIR, copy / ".build" / "compiled")
    return copy


@lru_cache(maxsize=1)  # one run serves every damaged build's comparison
def interpreted_answer() -> str:
    done = launch([str(ROOT / "run.sh"), "-seed", "1"], ROOT, {compiled.DISABLE_VARIABLE: "1"})
    assert done.returncode == 0, done.stderr
    return done.stdout


def cut(path: Path, size: int) -> None:
    with open(path, "r+b") as file:
        file.truncate(size)


def cut_to_a_third(path: Path) -> None:
    cut(path, path.stat().st_size // 3)


def overwrite_start(path: Path) -> None:
    with open(path, "r+b") as file:
        file.write(bytes(4096))  # the ELF header gone, the size the same


@pytest.mark.parametrize("damage, where", [
    (cut_to_a_third, LIBRARY), (overwrite_start, LIBRARY),
    (cut_to_a_third, f"planning_core/worlds/grid{compiled.extension_suffix()}")])
def test_a_damaged_build_runs_interpreted_after_one_line(tmp_path, damage, where):
    """A library cut short (which killed the run with SIGBUS) or overwritten (a
    traceback): the same answer, interpreted, and one line on stderr."""
    copy = built_copy(tmp_path)
    target = copy / ".build" / "compiled" / where
    damage(target)
    done = launch(["./run.sh", "-seed", "1", "-stats"], copy, {compiled.DISABLE_VARIABLE: ""})
    assert done.returncode == 0, done.stderr
    assert done.stdout == interpreted_answer()
    first, build, stats, kernels = done.stderr.splitlines()
    assert first.startswith("rrt_cli: the compiled build is damaged: ")
    assert first.endswith("; running interpreted (./make.sh rebuilds it)")
    assert build == f"rrt_cli build: interpreted: {first[len('rrt_cli: '):].split('; ')[0]}"
    assert stats.startswith("rrt_cli stats: status=solved")
    assert kernels == "rrt_cli kernels: segment test=GridWorld's own, interpreted"


def same_size_edit(source: Path) -> None:
    """Changes a letter's case in ``source``'s first line and puts its times back
    (as ``cp -p`` or ``tar x`` of an edited copy would)."""
    status = source.stat()
    text = source.read_bytes()
    at = next(i for i, byte in enumerate(text) if chr(byte).isalpha())
    source.write_bytes(text[:at] + text[at:at + 1].swapcase() + text[at + 1:])
    os.utime(source, ns=(status.st_atime_ns, status.st_mtime_ns))
    assert source.stat().st_size == status.st_size


def test_an_edit_that_keeps_size_and_time_is_not_run_compiled(tmp_path):
    copy = built_copy(tmp_path)
    path = compiled.source_path("planning_core.heap")
    same_size_edit(copy / path)
    done = launch(["./run.sh", "-seed", "1", "-stats"], copy, {compiled.DISABLE_VARIABLE: ""})
    assert done.returncode == 0, done.stderr
    assert (f"rrt_cli build: interpreted: {path} changed since the compiled modules were "
            "built (./make.sh rebuilds)") in done.stderr.splitlines()


@pytest.mark.slow
def test_make_sh_rebuilds_a_damaged_build(tmp_path):
    copy = built_copy(tmp_path)
    for name in ("make.sh", "pyproject.toml"):
        shutil.copy2(ROOT / name, copy / name)
    shutil.copytree(ROOT / "tools", copy / "tools", ignore=shutil.ignore_patterns("__pycache__"))
    (copy / ".venv").symlink_to(ROOT / ".venv")  # installed already: make.sh only builds
    library = copy / ".build" / "compiled" / LIBRARY
    size = library.stat().st_size
    cut(library, 100_000)
    env = dict(os.environ)
    env.pop(compiled.DISABLE_VARIABLE, None)
    done = subprocess.run(["./make.sh"], cwd=copy, env=env, capture_output=True, text=True,
                          timeout=1200)
    assert done.returncode == 0, done.stderr
    assert (f"make.sh: note: the compiled build is damaged: {LIBRARY} has 100000 bytes, "
            f"built {size}: removed, to be rebuilt") in done.stderr.splitlines()
    again = launch(["./run.sh", "-seed", "1", "-stats"], copy, {compiled.DISABLE_VARIABLE: ""})
    assert f"rrt_cli build: compiled ({len(compiled.MODULES)} modules" in again.stderr
