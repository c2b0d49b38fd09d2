"""Where the launchers read bytecode: the checkout's ``.build/pycache``, and for the
interpreter's own files also the interpreter's own ``__pycache__``; nowhere else.

``./run.sh`` and ``./rrt-validator`` start Python with ``-B`` (CPython itself writes no
bytecode), set ``sys.pycache_prefix`` to ``.build/pycache`` before importing anything of
the checkout, and :func:`install` :class:`CheckedLoader` for every source module. A
``.pyc`` is used only when its 16-byte header names the very source and its code
unmarshals whole: the checkout's sources are keyed by their content (as CPython's
checked-hash pycs) and read only from ``.build/pycache``; any other source (the
standard library, ``.venv``'s site-packages) by size and modification time, as CPython
judges them, from its own ``__pycache__`` or else from ``.build/pycache``. Otherwise
the module is compiled from its source and written to ``.build/pycache`` by
:func:`write_verified`, whole or not at all, so a full disk leaves no short file. No
cache folder (``~/.cache``, ``$XDG_CACHE_HOME``, ``/tmp``) is read, and a bare ``.pyc``
without its source is never imported. Whoever can write the checkout or the
interpreter's install can change their sources too: a planner that cannot, cannot
change what the launchers load.
"""

from __future__ import annotations

import marshal
import os
import sys
# What importlib.machinery and importlib.util re-export, from the import system's own
# module (always loaded): importing the importlib package would import warnings too.
from _frozen_importlib_external import (EXTENSION_SUFFIXES, MAGIC_NUMBER, SOURCE_SUFFIXES,
                                        ExtensionFileLoader, FileFinder, SourceFileLoader,
                                        cache_from_source)

import _imp

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PYCACHE = os.path.join(ROOT, ".build", "pycache")
"""The checkout's bytecode folder (git-ignored)."""
_VENV = os.path.join(ROOT, ".venv", "")
_KEY = int.from_bytes(MAGIC_NUMBER, "little")  # CPython's key for its checked-hash pycs
_CODE = type((lambda: None).__code__)  # (compile() costs ms at its first call)


def content_key(data: bytes) -> bytes:
    """The 8-byte SipHash of ``data`` that CPython's checked-hash pycs carry: a
    content key far cheaper than SHA-256 (not meant to resist a forger, who would
    have to write the checkout anyway)."""
    return _imp.source_hash(_KEY, data)


def by_content(source_path: str) -> bool:
    """Whether a source is the checkout's own: its bytecode is keyed by content and
    read only from ``.build/pycache``."""
    return source_path.startswith(ROOT + os.sep) and not source_path.startswith(_VENV)


def header(source_path: str, source: bytes | None) -> bytes:
    """The 16 bytes a pyc of ``source_path`` must begin with to be used: the
    content key of ``source`` when given, else the file's size and time."""
    if source is not None:
        return MAGIC_NUMBER + b"\x03\x00\x00\x00" + content_key(source)
    status = os.stat(source_path)
    return (MAGIC_NUMBER + b"\x00\x00\x00\x00"
            + (int(status.st_mtime) & 0xFFFFFFFF).to_bytes(4, "little")
            + (status.st_size & 0xFFFFFFFF).to_bytes(4, "little"))


def own_cache(source_path: str) -> str:
    """Where CPython itself keeps a source's bytecode: ``__pycache__`` beside it."""
    head, name = os.path.split(source_path)
    stem = name.rpartition(".")[0]
    return os.path.join(head, "__pycache__", f"{stem}.{sys.implementation.cache_tag}.pyc")


def read_code(cached: str, expected: bytes):
    """The code object in the file ``cached`` if it begins with ``expected`` and
    unmarshals whole, else None (a short or damaged file is ignored)."""
    try:
        with open(cached, "rb") as file:
            data = file.read()
    except OSError:
        return None
    if data[:16] != expected:
        return None
    try:
        code = marshal.loads(memoryview(data)[16:])
    except (EOFError, ValueError, TypeError):
        return None
    return code if isinstance(code, _CODE) else None


def write_verified(path: str, data: bytes) -> bool:
    """Writes ``data`` to ``path`` whole or not at all: into a temporary file beside
    it, read back and compared, then renamed over ``path``. False, with nothing
    left behind, when a step fails (a read-only checkout, a full disk)."""
    temporary = f"{path}.{os.getpid()}.tmp"
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_NOFOLLOW, 0o644)
        try:
            view = memoryview(data)
            while view:  # a short write is continued; a full disk raises
                view = view[os.write(fd, view):]
        finally:
            os.close(fd)
        with open(temporary, "rb") as written:
            if written.read() != data:
                raise OSError(f"{temporary} reads back differently")
        os.replace(temporary, path)
        return True
    except OSError:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        return False


class CheckedLoader(SourceFileLoader):
    """A source module's loader that takes its bytecode only from a matching,
    whole ``.pyc`` (the checkout's: under ``sys.pycache_prefix``; others' also from
    their own ``__pycache__``), and writes it under the prefix with
    :func:`write_verified` when it compiled the source."""

    writes = True
    """Cleared by the first write that fails (a read-only checkout, a full disk),
    so that this process does not try again for every module."""

    def get_code(self, fullname):
        path = self.get_filename(fullname)
        own = by_content(path)
        source = self.get_data(path) if own else None
        expected = header(path, source)
        cached = cache_from_source(path)
        for candidate in (cached,) if own else (own_cache(path), cached):
            code = read_code(candidate, expected)
            if code is not None:
                return code
        return compile_and_cache(path, self.get_data(path) if source is None else source,
                                 expected)


def compile_and_cache(path: str, source: bytes, expected: bytes):
    """``source``'s code, written with its header ``expected`` under the prefix
    (unless a write failed before in this process)."""
    code = compile(source, path, "exec", dont_inherit=True)
    if CheckedLoader.writes:
        CheckedLoader.writes = write_verified(cache_from_source(path),
                                              expected + marshal.dumps(code))
    return code


def install(prefix: str = PYCACHE, check_loaded: bool = False) -> None:
    """Loads every source module imported from now on with :class:`CheckedLoader`,
    its bytecode written under ``prefix``. The modules CPython loaded before with a
    prefix (this module among them) get theirs written there where it is missing or
    of another source, since CPython reads them nowhere else; checked whole when
    they were not read from ``prefix`` (the launchers then found a damaged one) or
    ``check_loaded`` (then every module loaded from source)."""
    whole = check_loaded or sys.pycache_prefix != prefix
    sys.pycache_prefix = prefix
    sys.path_hooks.insert(0, FileFinder.path_hook((CheckedLoader, SOURCE_SUFFIXES),
                                                   (ExtensionFileLoader, EXTENSION_SUFFIXES)))
    sys.path_importer_cache.clear()  # the finders made so far use CPython's loader
    for module in list(sys.modules.values()):
        spec = getattr(module, "__spec__", None)
        if (spec is None or type(spec.loader) is not SourceFileLoader
                or not check_loaded and spec.cached == own_cache(spec.origin)):
            continue  # (Python's own start-up modules, from the interpreter's cache)
        with open(spec.origin, "rb") as file:
            source = file.read()
        expected = header(spec.origin, source if by_content(spec.origin) else None)
        if not _cached_code_matches(cache_from_source(spec.origin), expected, whole):
            compile_and_cache(spec.origin, source, expected)


def _cached_code_matches(cached: str, expected: bytes, whole: bool) -> bool:
    """Whether the pyc ``cached`` begins with ``expected`` (``whole``: and unmarshals)."""
    if whole:
        return read_code(cached, expected) is not None
    try:
        with open(cached, "rb") as file:
            return file.read(16) == expected
    except OSError:
        return False


PACKAGES = ("rrt_startup", "planning_core", "rrt_cli", "validator")
"""The packages the launchers import from."""


def warm(packages: tuple[str, ...] = PACKAGES) -> list[str]:
    """Imports every module of ``packages`` (after :func:`install`), so that their
    bytecode, and that of every module they import, is in the prefix; returns the
    modules that could not be imported (one line each)."""
    import importlib
    failed = []
    for package in packages:
        for directory, subdirectories, files in os.walk(os.path.join(ROOT, package)):
            subdirectories[:] = sorted(d for d in subdirectories if d != "__pycache__")
            for name in sorted(f for f in files if f.endswith(".py") and f != "__main__.py"):
                relative = os.path.relpath(os.path.join(directory, name), ROOT)[:-3]
                module = relative.replace(os.sep, ".").removesuffix(".__init__")
                try:
                    importlib.import_module(module)
                except Exception as error:  # noqa: BLE001  (e.g. needs what is not installed)
                    failed.append(f"{module}: {type(error).__name__}: {error}")
    return failed


def main(folder: str) -> int:
    """``./make.sh``'s step, in an interpreter started with ``-S -I -B -X
    pycache_prefix=FOLDER``, ``FOLDER`` a new empty folder beside :data:`PYCACHE` (so
    that nothing already there is read): writes there the bytecode of every module
    of :data:`PACKAGES` and of what they import (the PDF's reportlab too), checks
    every file whole, then puts the folder in the place of :data:`PYCACHE`. A
    module that cannot be imported is one line on stderr (it runs compiled from
    source, status 0 all the same); a file that is not whole, status 1."""
    install(folder, check_loaded=True)
    import site
    site.main()  # reportlab, as the validator's PDF imports it
    for line in warm():
        sys.stderr.write(f"rrt_startup.bytecode: not imported: {line}\n")
    broken = [str(path) for path in _pycs(folder) if not _whole(path)]
    if broken:
        sys.stderr.write(f"rrt_startup.bytecode: not whole: {broken[0]}\n")
        return 1
    _put_in_place(folder)
    return 0


def _put_in_place(folder: str) -> None:
    """Renames ``folder`` to :data:`PYCACHE`, the old one moved aside and removed (and
    one a launcher made meanwhile: it tries three times)."""
    import shutil
    olds = [f"{folder}.old{attempt}" for attempt in range(3)]
    for old in olds:
        if os.path.isdir(PYCACHE):
            os.replace(PYCACHE, old)
        try:
            os.replace(folder, PYCACHE)
            break
        except OSError:
            continue
    for leftover in (*olds, folder):
        shutil.rmtree(leftover, ignore_errors=True)


def _pycs(folder: str) -> list[str]:
    return [os.path.join(directory, name) for directory, _, files in os.walk(folder)
            for name in files if name.endswith(".pyc")]


def _whole(path: str) -> bool:
    """Whether a pyc unmarshals whole (its header was checked when written)."""
    try:
        with open(path, "rb") as file:
            return isinstance(marshal.loads(file.read()[16:]), _CODE)
    except (OSError, EOFError, ValueError, TypeError):
        return False
