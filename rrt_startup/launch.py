"""The Python side of ``./run.sh`` and ``./rrt-validator``: bytecode only from the
checkout (:func:`rrt_startup.bytecode.install`), then the planner with the compiled
build when it is fresh and whole, or the validator with the site-packages only for
its PDF.

Both launchers start Python with ``-S -I -B``, set ``sys.pycache_prefix`` to the
checkout's ``.build/pycache`` and put the checkout first on ``sys.path``: no
site-packages, no ``PYTHON*`` variables, no user site, no current folder, and bytecode
only from the checkout and the interpreter's own install.
"""

from __future__ import annotations

import os
import sys

from rrt_startup.bytecode import ROOT, content_key, install


class OnFirstUse(type(sys)):  # a module type (types.ModuleType, without importing types)
    """Stands for a module until one of its names is used, then imports it (a
    look-up of a missing __dunder__, e.g. a scan of sys.modules, does not)."""

    def __getattr__(self, name):
        if name.startswith("__") and name.endswith("__"):
            raise AttributeError(name)
        if sys.modules.get(self.__name__) is self:
            del sys.modules[self.__name__]
        module = __import__(self.__name__)
        self.__dict__.update(module.__dict__)
        return getattr(module, name)


def defer_dataclasses_imports() -> None:
    """``inspect`` and ``copy``, which dataclasses imports but uses only for a class
    without a docstring and for deep copies, are imported on first use."""
    for name in ("inspect", "copy"):
        sys.modules.setdefault(name, OnFirstUse(name))


def planner() -> None:
    """``./run.sh``: the planner, with the compiled hot modules when their build is
    fresh and whole (``-stats`` says which ran); the process ends by :func:`exit_now`."""
    install()
    defer_dataclasses_imports()
    from rrt_startup.compiled import activate
    build = activate()
    if "-stats" in sys.argv:
        sys.stderr.write(f"rrt_cli build: {build}\n")
    from rrt_cli.cli import entry_point
    try:
        entry_point()
    except SystemExit as done:
        exit_now(done.code)


def draws_picture(argv: list[str]) -> bool:
    """Whether the validator's command line (before ``--``) asks for a picture: no
    ``-noviz`` (or an abbreviation of it), no ``-h``."""
    own = argv[:argv.index("--")] if "--" in argv else argv
    return not any(a in ("-h", "--help") or len(a) > 2 and "-noviz".startswith(a) for a in own)


def validator() -> None:
    """``./rrt-validator``: the validator; ``inspect`` and ``copy`` are stand-ins as
    for the planner; the interpreter's site-packages are added only to draw a picture
    (the PDF's reportlab); the validator says in one line, with status 2, when the
    format -o asks for needs what is not installed. Without a picture the process
    ends by :func:`exit_now`."""
    install()
    defer_dataclasses_imports()
    if sys.argv[1:2] and sys.argv[1].startswith("--rrt-validator-launched="):
        from validator.launched import receive  # the planner validator/launch.c started
        receive(sys.argv.pop(1), launcher_key())
    picture = draws_picture(sys.argv[1:])
    if picture:
        import site
        site.main()  # the PDF: reportlab from the site-packages (-I: never the user's)
    from validator.cli import entry_point
    try:
        entry_point()
    except SystemExit as done:
        if picture:
            raise  # the drawing libraries may have clean-up to do at the interpreter's exit
        exit_now(done.code)


def launcher_key() -> str:
    """The content key of the launcher's source (validator/launch.c), which a launcher
    built from it carries in its token ("" when the source is missing)."""
    try:
        with open(os.path.join(ROOT, "validator", "launch.c"), "rb") as source:
            return content_key(source.read()).hex()
    except OSError:
        return ""


def exit_now(code: object) -> None:
    """End the process as ``raise SystemExit(code)`` would, without the interpreter's
    tear-down of every module (milliseconds a grader waits for on every run): the
    atexit functions run, the standard streams flushed (status 120 if that fails, as
    CPython's), then ``os._exit``. Only for a process with nothing else to finish: no
    other thread, no file left open for writing (the validator without a picture)."""
    import atexit
    if code is None:
        status = 0
    elif isinstance(code, int):
        status = code
    else:  # as CPython: the object printed on stderr, status 1
        status = 1
        if sys.stderr is not None:
            sys.stderr.write(f"{code}\n")
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            if stream is not None:
                stream.flush()
        except Exception:
            status = 120
    os._exit(status & 0xFF)
