"""./run.sh and ./rrt-validator as a new user runs them: a bare python3, no set-up,
nothing imported but the standard library and the checkout, nothing written into
the checkout but its bytecode (.build/pycache, git-ignored); the validator's PDF asks
for reportlab in one line."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SPACE1 = ROOT / "benchmarks" / "problems" / "course" / "space-1.sw"
PACKAGES = ("planning_core", "cli_common", "rrt_cli", "validator")
# What a fake rrt_cli/cli.py reports about the interpreter the launcher started.
PROBE = '''import os, sys
def entry_point():
    outside = sorted(name for name, module in sys.modules.items()
                     if getattr(module, "__file__", None)
                     and not module.__file__.startswith((sys.prefix, sys.base_prefix, HERE)))
    print(sys.flags.no_site, sys.flags.ignore_environment, sys.path[0], "site" in sys.modules,
          ",".join(outside) or "-", " ".join(sys.argv[1:]))
HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
'''


def checkout_copy(tmp_path: Path, packages=PACKAGES) -> Path:
    """The launchers, their start-up package and the packages, without .venv,
    .build and __pycache__."""
    copy = tmp_path / "checkout"
    copy.mkdir()
    for script in ("run.sh", "rrt-validator"):
        shutil.copy2(ROOT / script, copy / script)
    for package in ("rrt_startup", *packages):
        shutil.copytree(ROOT / package, copy / package,
                        ignore=shutil.ignore_patterns("__pycache__"))
    return copy


def files_under(folder: Path) -> set[Path]:
    return {path for path in folder.rglob("*")}


def launch(command: list[str], cwd: Path, env_extra: dict | None = None,
           stdin: Path = SPACE1) -> subprocess.CompletedProcess:
    env = dict(os.environ, **(env_extra or {}))
    with open(stdin, "rb") as problem:
        return subprocess.run(command, stdin=problem, capture_output=True, text=True,
                              cwd=cwd, env=env, timeout=120)


def python_on_path(tmp_path: Path, python: str = sys.executable) -> str:
    """A PATH whose python3 is ``python`` (no shim), the system's tools after it."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir(exist_ok=True)
    (bin_dir / "python3").symlink_to(python)
    return f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '/usr/bin:/bin')}"


def test_run_sh_starts_python_without_site_and_without_the_environment(tmp_path):
    copy = checkout_copy(tmp_path, packages=())
    (copy / "rrt_cli").mkdir()
    (copy / "rrt_cli" / "__init__.py").write_text("")
    (copy / "rrt_cli" / "cli.py").write_text(PROBE)
    # A package of the same name on PYTHONPATH must not shadow the checkout's.
    decoy = tmp_path / "decoy" / "rrt_cli"
    decoy.mkdir(parents=True)
    (decoy / "__init__.py").write_text("raise SystemExit('the decoy was imported')")
    done = launch([str(copy / "run.sh"), "-grad", "-seed", "3"], tmp_path, {
        "PATH": python_on_path(tmp_path), "PYTHONPATH": str(decoy.parent),
        "XDG_CACHE_HOME": str(tmp_path / "cache")})
    assert done.returncode == 0, done.stderr
    no_site, no_env, first_path, site_loaded, outside, args = done.stdout.split(" ", 5)
    assert (no_site, no_env, site_loaded) == ("1", "1", "False")
    assert first_path == str(copy)
    assert outside == "-"  # nothing but the standard library and the checkout
    assert args.strip() == "-grad -seed 3"


def test_run_sh_plans_on_a_bare_python3_and_writes_only_its_bytecode(tmp_path):
    """Into the checkout's .build/pycache, git-ignored: nothing else in the checkout,
    nothing in the user's cache folders."""
    copy = checkout_copy(tmp_path, packages=("planning_core", "cli_common", "rrt_cli"))
    before = files_under(copy)
    home, cache = tmp_path / "home", tmp_path / "cache"
    home.mkdir()
    env = {"PATH": python_on_path(tmp_path), "XDG_CACHE_HOME": str(cache), "HOME": str(home)}
    first = launch(["./run.sh", "-seed", "1"], copy, env)
    again = launch(["./run.sh", "-seed", "1"], copy, env)
    assert first.returncode == again.returncode == 0, first.stderr
    assert first.stdout == again.stdout and first.stdout.startswith("3\n")
    pycache = copy / ".build" / "pycache"
    assert {path for path in files_under(copy) if pycache not in path.parents} == before | {
        copy / ".build", pycache}  # no .venv, no __pycache__
    assert any(pycache.rglob("cli.cpython-*.pyc"))  # the bytecode went there
    assert not cache.exists() and not any(home.iterdir())
    assert "/.build/\n" in (ROOT / ".gitignore").read_text()  # so git status stays clean


def test_run_sh_without_python3_says_so_in_one_line(tmp_path):
    copy = checkout_copy(tmp_path, packages=())
    empty = tmp_path / "empty"
    empty.mkdir()
    done = launch(["/bin/sh", str(copy / "run.sh")], tmp_path, {"PATH": str(empty)})
    assert done.returncode == 127 and done.stdout == ""
    assert done.stderr == "run.sh: needs python3 (3.10 or newer) on PATH\n"


def test_validator_noviz_needs_no_site_packages(tmp_path):
    copy = checkout_copy(tmp_path)
    env = {"PATH": python_on_path(tmp_path), "XDG_CACHE_HOME": str(tmp_path / "cache")}
    done = launch(["./rrt-validator", "-noviz", "--", "./run.sh", "-seed", "1"], copy, env)
    assert done.returncode == 0, done.stderr
    assert done.stdout == "Solution trajectory appears valid.\n"


def test_validator_pdf_without_reportlab_is_one_line_and_status_2(tmp_path):
    copy = checkout_copy(tmp_path)
    # A set-up whose site-packages hold nothing: what a python3 without reportlab sees.
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(copy / ".venv")],
                   check=True, timeout=120)
    env = {"XDG_CACHE_HOME": str(tmp_path / "cache")}
    done = launch(["./rrt-validator", "--", "./run.sh", "-seed", "1"], copy, env)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr == ("rrt-validator: drawing the PDF needs reportlab: run ./make.sh "
                           "validator (or pip install reportlab), or pass -noviz\n")
    assert not (copy / "tree-viz.pdf").exists()
    done = launch(["./rrt-validator", "-noviz", "--", "./run.sh", "-seed", "1"], copy, env)
    assert done.returncode == 0, done.stderr


def test_validator_draws_the_pdf_with_the_set_up_reportlab(tmp_path):
    pytest.importorskip("reportlab")
    if not (ROOT / ".venv" / "bin" / "python").exists():
        pytest.skip("no .venv: ./make.sh has not run")
    pdf = tmp_path / "tree.pdf"
    done = launch([str(ROOT / "rrt-validator"), "-o", str(pdf), "--", str(ROOT / "run.sh"),
                   "-seed", "1"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert pdf.read_bytes().startswith(b"%PDF")
