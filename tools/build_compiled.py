"""Compile the hot modules (rrt_startup.compiled.MODULES) with mypyc, and the C
kernels (rrt_startup.compiled.KERNELS), into .build/compiled/.

Usage: ``python tools/build_compiled.py`` (``./make.sh`` runs it when mypy and a C
compiler are there). Needs mypy (mypyc) and a C compiler; exit 1 with one line
when the build fails, 2 when a tool is missing. The build goes to a fresh
temporary folder and replaces ``.build/compiled/`` only when complete, its
manifest (interpreter suffix, each compiled source's content key and SHA-256, each
built file's size and SHA-256) written last.

Flags are pinned so every build computes the same bits as the interpreter:
``-ffp-contract=off`` (no fused multiply-adds), never ``-march=native`` or
``-ffast-math``. Imports of modules outside the compile list are typed ``Any``
(``--follow-imports=skip``), so a compiled module depends on no other source.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from rrt_startup import compiled  # noqa: E402

CFLAGS = "-O2 -ffp-contract=off -fno-fast-math"
"""Pinned C flags (appended after Python's own, so they win)."""
MYPY_FLAGS = ["--follow-imports=skip", "--ignore-missing-imports",
              f"--cache-dir={ROOT / '.build' / 'mypy-cache'}"]

_SETUP = """
import sys
from setuptools import Extension, setup
from mypyc.build import mypycify
kernels = [Extension(name, [source]) for name, source in {kernels!r}.items()]
setup(name="rrt-hot", ext_modules=mypycify(sys.argv.pop(1).split(",") + {mypy_flags!r},
                                          opt_level="2", group_name={group!r},
                                          target_dir={target!r}) + kernels)
"""


def _missing_tool() -> str | None:
    try:
        import mypyc  # noqa: F401
    except ImportError:
        return "mypy (mypyc) is not installed (pip install mypy)"
    compiler = os.environ.get("CC", "cc").split()[0]
    if shutil.which(compiler) is None:
        return f"no C compiler ({compiler}) on PATH"
    return None


def _compile(work: Path) -> None:
    """Run mypyc and the C compiler with the sources in ROOT, output in ``work``."""
    setup = work / "setup_hot.py"
    setup.write_text(_SETUP.format(mypy_flags=MYPY_FLAGS, group=compiled.GROUP,
                                   target=str(work / "c"), kernels=compiled.KERNELS))
    paths = ",".join(compiled.source_path(module) for module in compiled.MODULES)
    env = dict(os.environ, CFLAGS=CFLAGS, PYTHONHASHSEED="0")
    env.pop("PYTHONPATH", None)
    done = subprocess.run([sys.executable, str(setup), paths, "build_ext",
                           "--build-lib", str(work / "out"), "--build-temp", str(work / "tmp")],
                          cwd=ROOT, env=env, capture_output=True, text=True)
    (work / "build.log").write_text(done.stdout + done.stderr)
    if done.returncode != 0:
        lines = (done.stdout + done.stderr).splitlines()
        errors = [line for line in lines if ": error:" in line]  # mypy's notes can be many
        tail = "\n".join((errors or lines)[-30:])
        raise RuntimeError(f"mypyc build failed:\n{tail}")


def _manifest(sources: list[str], out: Path) -> str:
    """The manifest's text: its format, the suffix, the flags, each compiled source's
    line (as read before compiling: a source edited meanwhile reads as changed) and
    each built file's, then its end."""
    built = sorted(str(path.relative_to(out)) for path in out.rglob("*")
                   if path.is_file() and path.name not in (compiled.MANIFEST, "build.log"))
    lines = [compiled.FORMAT, f"suffix {compiled.extension_suffix()}", f"cflags {CFLAGS}",
             *sources,
             *(compiled.file_line(str(out), path) for path in built), compiled.END]
    return "\n".join(lines) + "\n"


def build(target: Path = Path(compiled.BUILD_DIR)) -> Path:
    """Compile into ``target`` (replaced whole); returns it."""
    sources = [compiled.source_line(path) for path in compiled.sources()]
    target.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=target.parent, prefix=".tmp-") as temporary:
        work = Path(temporary)
        _compile(work)
        out = work / "out"
        shutil.copy2(work / "build.log", out / "build.log")
        (out / compiled.MANIFEST).write_text(_manifest(sources, out))
        old = work / "old"
        if target.exists():
            target.rename(old)
        out.rename(target)
    return target


def main() -> int:
    missing = _missing_tool()
    if missing:
        print(f"build_compiled: not built: {missing}", file=sys.stderr)
        return 2
    try:
        target = build()
    except (RuntimeError, OSError) as error:
        print(f"build_compiled: {error}", file=sys.stderr)
        return 1
    print(f"build_compiled: {len(compiled.MODULES)} modules and {len(compiled.KERNELS)} C "
          f"kernels compiled into {target}",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
