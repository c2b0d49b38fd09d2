"""The hot modules compiled ahead of time (mypyc), used only while they match their source.

``tools/build_compiled.py`` compiles the modules of :data:`MODULES` from their
annotated Python source, and the C kernels of :data:`KERNELS`, into
``.build/compiled/`` (outside the source tree, so nothing ever picks up a compiled
module by accident) and writes a manifest: the interpreter's extension suffix and
the SHA-256, size and modification time of every compiled source.
:func:`activate` checks that manifest against the sources and only then puts the
compiled folder first on the packages' ``__path__``; otherwise the same source
runs interpreted, with the same bytes out, and :func:`activate` says why.
"""

from __future__ import annotations

import os
import sys

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
    "planning_core.worlds.segment_tests",
    "planning_core.worlds.body_tests",
    "planning_core.worlds.link_tests",
    "planning_core.worlds.body_motion",
    "planning_core.grid_space_information",
    "planning_core.samplers",
    "planning_core.angles",
    "planning_core.heap",
    "planning_core.nearest.index",
    "planning_core.goal",
    "planning_core.projections",
    "rrt_cli.planners.base",
    "rrt_cli.planners.tree",
    "rrt_cli.planners.rrtconnect",
)
"""The compile list: hot modules whose source is annotated for mypyc."""

KERNELS = {"planning_core.worlds._body_kernel": "planning_core/worlds/body_kernel.c"}
"""Hand-written C kernels built with them (module: source), each with a Python
reference that runs without the build (``BodyTest.meets``)."""

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD_DIR = os.path.join(ROOT, ".build", "compiled")
MANIFEST = "manifest.txt"
DISABLE_VARIABLE = "RRT_INTERPRETED"
"""Set to 1 in the environment to run interpreted although the build is fresh."""

state = "interpreted: activate() was not called"
_manifest_fields: dict = {}  # the last manifest why_not_fresh read
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


STAMP = "stamp:"
"""Manifest key prefix of a source's size and modification time at the build."""


def source_stamp(path: str) -> str:
    """A source's size and modification time (ns): when both are as at the build,
    the source is taken as unchanged without hashing it, as CPython's own bytecode
    cache judges a ``.py`` file; otherwise its digest decides."""
    status = os.stat(path)
    return f"{status.st_size} {status.st_mtime_ns}"


def source_digest(path: str) -> str:
    try:
        from _sha256 import sha256  # type: ignore[import-not-found]  # faster to import
    except ImportError:
        from hashlib import sha256
    with open(path, "rb") as source:
        return sha256(source.read()).hexdigest()


GENERATED_PREFIX = "rrt_generated_"
generated_names: frozenset = frozenset()
"""The generated modules the build in use holds (its manifest's ``generated`` line)."""


def generated_name(source: str) -> str:
    """The module name of generated source (integrators.advance_source,
    kdtree.metric_source): named by its digest, so a compiled one is always of this
    very text."""
    try:
        from _sha256 import sha256  # type: ignore[import-not-found]  # faster to import
    except ImportError:
        from hashlib import sha256
    return GENERATED_PREFIX + sha256(source.encode()).hexdigest()[:24]


def generated_module(source: str):
    """The compiled module of generated ``source`` when the compiled build is in
    use and holds it (``tools/build_compiled.py`` compiles the texts of
    ``planning_core.systems.family.generated_sources``), else None."""
    name = generated_name(source) if generated_names else ""
    if name not in generated_names:
        return None
    import importlib
    return importlib.import_module(name)


def why_not_fresh(build_dir: str) -> str | None:
    """None when the build in ``build_dir`` is fresh, else why it cannot be used."""
    if os.environ.get(DISABLE_VARIABLE, "") not in ("", "0"):
        return f"{DISABLE_VARIABLE} is set"
    try:
        with open(os.path.join(build_dir, MANIFEST), encoding="utf-8") as manifest:
            lines = manifest.read().splitlines()
    except OSError:
        return "no compiled modules built (./make.sh builds them where a C compiler is)"
    fields = dict(line.split(" ", 1) for line in lines if " " in line)
    global _manifest_fields
    _manifest_fields = fields
    if fields.get("suffix") != extension_suffix():
        return f"the compiled modules were built for another interpreter ({fields.get('suffix')})"
    compiled_sources = {key for key in fields
                        if key.endswith((".py", ".c")) and not key.startswith(STAMP)}
    if compiled_sources != set(sources()):
        return "the compile list changed since the compiled modules were built (./make.sh rebuilds)"
    for path in sources():
        full = os.path.join(ROOT, path)
        if fields.get(STAMP + path) == source_stamp(full):
            continue  # untouched since the build: no need to hash it
        if fields.get(path) != source_digest(full):
            return f"{path} changed since the compiled modules were built (./make.sh rebuilds)"
    return None


def activate(build_dir: str = BUILD_DIR) -> str:
    """Use the compiled modules if their build is fresh; returns (and keeps in
    :data:`state`) ``compiled (...)`` or ``interpreted: why``."""
    global state
    why = why_not_fresh(build_dir)
    imported = [module for module in MODULES if module in sys.modules]
    if why is None and imported:
        why = f"{imported[0]} was imported before activate()"
    if why is not None:
        state = f"interpreted: {why}"
        return state
    sys.path.append(build_dir)  # mypyc's shared library of the group, a top-level module
    for package in sorted({module.rpartition(".")[0] for module in (*MODULES, *KERNELS)}):
        folder = os.path.join(build_dir, *package.split("."))
        __import__(package)
        sys.modules[package].__path__.insert(0, folder)
    global generated_names
    generated_names = frozenset(_manifest_fields.get("generated", "").split())
    state = f"compiled ({len(MODULES)} modules, {len(KERNELS)} C kernel, from {build_dir})"
    return state
