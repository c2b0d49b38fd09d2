"""The hot modules compiled ahead of time (mypyc), used only while they match their source.

``tools/build_compiled.py`` compiles the modules of :data:`MODULES` from their
annotated Python source, and the C kernels of :data:`KERNELS`, into
``.build/compiled/`` (outside the source tree, so nothing ever picks up a compiled
module by accident) and writes a manifest: the interpreter's extension suffix, the
content key and SHA-256 of every compiled source, and the size and SHA-256 of every
file built. :func:`activate` checks every source by its content key and every
built file by its size, loads the group's shared library, and only then puts the
compiled folder first on the packages' ``__path__``; otherwise the same source runs
interpreted, with the same bytes out, and :func:`activate` says why (a damaged build
in one line on stderr too). ``./make.sh`` checks every SHA-256 (:func:`why_not_fresh`
with ``full``) and rebuilds on any difference.
"""

from __future__ import annotations

import os
import sys

from rrt_startup.bytecode import ROOT, content_key

MODULES = (
    "planning_core.systems.spaceship",
    "planning_core.systems.left_spaceship",
    "planning_core.systems.point",
    "planning_core.worlds.grid",
    "planning_core.worlds.grid_distance",
    "planning_core.worlds.grid_frontier",
    "planning_core.worlds.grid_cells",
    "planning_core.nearest.quadtree",
    "rrt_cli.planners.steering",
    "rrt_cli.planners.rrt",
    "rrt_cli.planners.kpiece",
    "rrt_cli.planners.rgrrt",
    "rrt_cli.planners.blossom",
    "planning_core.nearest.kdtree",
    "planning_core.nearest.metric",
    "planning_core.generated_kernels",
    "planning_core.worlds.segment_tests",
    "planning_core.worlds.body_tests",
    "planning_core.worlds.link_tests",
    "planning_core.worlds.body_motion",
    "planning_core.grid_space_information",
    "planning_core.samplers",
    "planning_core.angles",
    "planning_core.heap",
    "planning_core.nearest.index",
    "planning_core.nearest.directed",
    "planning_core.dubins",
    "planning_core.dubins_space_information",
    "planning_core.goal",
    "planning_core.projections",
    "rrt_cli.planners.base",
    "rrt_cli.planners.tree",
    "rrt_cli.planners.rrtconnect",
    "rrt_cli.planners.sst",
)
"""The compile list: hot modules whose source is annotated for mypyc."""

KERNELS = {"planning_core.worlds._body_kernel": "planning_core/worlds/body_kernel.c",
           "planning_core.systems._ship_kernel": "planning_core/systems/ship_kernel.c"}
"""Hand-written C kernels built with them (module: source), each with a Python
reference that runs without the build (``BodyTest.meets``,
``Spaceship.propagate_while``)."""

GROUP = "rrt_hot"
"""mypyc's group: one shared library, ``rrt_hot__mypyc``, at the build's top level,
that every compiled module's own small library loads."""

BUILD_DIR = os.path.join(ROOT, ".build", "compiled")
MANIFEST = "manifest.txt"
DISABLE_VARIABLE = "RRT_INTERPRETED"
"""Set to 1 in the environment to run interpreted although the build is fresh."""

state = "interpreted: activate() was not called"
"""What the last :func:`activate` found: ``compiled (...)`` or ``interpreted: why``."""


def source_path(module: str) -> str:
    """The repository-relative path of a module's source."""
    return module.replace(".", "/") + ".py"


def extension_suffix() -> str:
    """The interpreter's ABI tag as its extension modules' file suffix."""
    import _imp  # built in: importlib.machinery's own source of the suffixes
    return _imp.extension_suffixes()[0]


def sources() -> list[str]:
    """The repository-relative paths of every source the build compiles."""
    return [source_path(module) for module in MODULES] + list(KERNELS.values())


def sha256_of(path: str) -> str:
    """The SHA-256 of a file, hex (the manifest's full check)."""
    try:
        from _sha256 import sha256  # type: ignore[import-not-found]  # faster to import
    except ImportError:
        from hashlib import sha256
    with open(path, "rb") as file:
        return sha256(file.read()).hexdigest()


def source_line(path: str) -> str:
    """The manifest's line of a compiled source (repository-relative ``path``)."""
    with open(os.path.join(ROOT, path), "rb") as file:
        key = content_key(file.read()).hex()
    return f"source {path} {key} {sha256_of(os.path.join(ROOT, path))}"


def file_line(build_dir: str, path: str) -> str:
    """The manifest's line of a built file (``path`` relative to ``build_dir``)."""
    full = os.path.join(build_dir, path)
    return f"file {path} {os.path.getsize(full)} {sha256_of(full)}"


def read_manifest(build_dir: str) -> list[str] | None:
    """The manifest's lines, or None when there is none."""
    try:
        with open(os.path.join(build_dir, MANIFEST), encoding="utf-8") as manifest:
            return manifest.read().splitlines()
    except (OSError, UnicodeDecodeError):
        return None


FORMAT = "format 2"
"""The manifest's first line; a build without it is of an older build tool."""
END = "end"
"""The manifest's last line: a manifest without it was cut short."""


def manifest_entries(lines: list[str]) -> dict[str, list[list[str]]]:
    """The manifest's lines by their first word: each line's other words."""
    entries: dict[str, list[list[str]]] = {}
    for line in lines:
        kind, _, rest = line.partition(" ")
        entries.setdefault(kind, []).append(rest.split())
    return entries


def why_not_fresh(build_dir: str = BUILD_DIR, full: bool = False) -> str | None:
    """None when the build in ``build_dir`` may be used, else why not: built for
    another interpreter or compile list, a source whose content changed, a built
    file missing or not of its size; ``full``: the SHA-256 of every source and
    built file too (``./make.sh``)."""
    return _check(build_dir, full)[0]


def _check(build_dir: str, full: bool) -> tuple[str | None, bool, dict]:
    """:func:`why_not_fresh`'s answer, whether it says the build is damaged, and
    the manifest."""
    if os.environ.get(DISABLE_VARIABLE, "") not in ("", "0"):
        return f"{DISABLE_VARIABLE} is set", False, {}
    lines = read_manifest(build_dir)
    if lines is None:
        return "no compiled modules built (./make.sh builds them where a C compiler is)", False, {}
    if lines[:1] != [FORMAT]:
        return ("the compiled modules were built by an older tools/build_compiled.py "
                "(./make.sh rebuilds)"), False, {}
    if lines[-1:] != [END]:
        return "the compiled build is damaged: its manifest is cut short", True, {}
    manifest = manifest_entries(lines)
    suffix = " ".join(sum(manifest.get("suffix", []), []))
    if suffix != extension_suffix():
        return f"the compiled modules were built for another interpreter ({suffix})", False, {}
    try:
        return (*_changed_or_damaged(build_dir, manifest, full), manifest)
    except ValueError:  # a line without its fields
        return "the compiled build is damaged: its manifest does not read", True, {}


def _changed_or_damaged(build_dir: str, manifest: dict, full: bool) -> tuple[str | None, bool]:
    """Why the sources are not those compiled (a source edited, the compile list
    changed), or the built files not as built (missing, another size; ``full``:
    another SHA-256); and whether the build is damaged."""
    recorded = {path: (key, digest) for path, key, digest in manifest.get("source", [])}
    if set(recorded) != set(sources()):
        return ("the compile list changed since the compiled modules were built "
                "(./make.sh rebuilds)"), False
    for path, (key, digest) in recorded.items():
        full_path = os.path.join(ROOT, path)
        try:
            with open(full_path, "rb") as file:
                data = file.read()
        except OSError:
            return f"{path} is missing", False
        if content_key(data).hex() != key or full and sha256_of(full_path) != digest:
            return (f"{path} changed since the compiled modules were built "
                    "(./make.sh rebuilds)"), False
    for relative, size, digest in manifest.get("file", []):
        path = os.path.join(build_dir, relative)
        try:
            found = os.stat(path).st_size
        except OSError:
            return f"the compiled build is damaged: {relative} is missing", True
        if found != int(size):
            return (f"the compiled build is damaged: {relative} has {found} bytes, "
                    f"built {size}"), True
        if full and sha256_of(path) != digest:
            return f"the compiled build is damaged: {relative} is not as built", True
    return None, False


def _load_library(build_dir: str) -> str | None:
    """Puts ``build_dir`` on ``sys.path`` and loads the group's shared library
    there, before any compiled module does; on failure takes it off again and says
    why."""
    sys.path.append(build_dir)  # the group's library is a top-level module
    try:
        __import__(f"{GROUP}__mypyc")
    except ImportError as error:
        sys.path.remove(build_dir)
        first = (str(error).splitlines() or [""])[0]
        return f"the compiled build is damaged: its shared library does not load ({first})"
    return None


def _say(line: str) -> None:
    """One line on stderr, if there is one to write to."""
    try:
        if sys.stderr is not None:
            sys.stderr.write(line + "\n")
            sys.stderr.flush()
    except (OSError, ValueError):
        pass


def activate(build_dir: str = BUILD_DIR) -> str:
    """Use the compiled modules if their build is fresh and whole; returns (and
    keeps in :data:`state`) ``compiled (...)`` or ``interpreted: why``. A damaged
    build is also one line on stderr."""
    global state
    why, damaged, manifest = _check(build_dir, full=False)
    imported = [module for module in MODULES if module in sys.modules]
    if why is None and imported:
        why = f"{imported[0]} was imported before activate()"
    if why is None:
        why = _load_library(build_dir)
        damaged = why is not None
    if why is not None:
        if damaged:
            _say(f"rrt_cli: {why}; running interpreted (./make.sh rebuilds it)")
        state = f"interpreted: {why}"
        return state
    for package in sorted({module.rpartition(".")[0] for module in (*MODULES, *KERNELS)}):
        folder = os.path.join(build_dir, *package.split("."))
        __import__(package)
        sys.modules[package].__path__.insert(0, folder)
    state = f"compiled ({len(MODULES)} modules, {len(KERNELS)} C kernels, from {build_dir})"
    return state
