"""The generated modules of the compiled build, as the core looks them up.

The family's systems and the kd-tree generate Python source at run time (fused
slice loops, metrics). The compiled build (``rrt_startup.compiled``, which the
launchers activate) also compiles those texts ahead of time, each into a top-level
module named by the text's digest, and when it is in use fills
:data:`generated_names`; :func:`generated_module` then gives the compiled module of
a text, or None and the caller runs the text itself.
"""

from __future__ import annotations

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
