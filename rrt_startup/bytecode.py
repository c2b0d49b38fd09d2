"""Where the launchers read bytecode: only ``.build/pycache`` inside the checkout.

``./run.sh`` and ``./rrt-validator`` start Python with ``-B`` (CPython itself writes
no bytecode) and ``-X pycache_prefix=`` that folder, so the few modules Python loads
before any of ours (``encodings``) are read from there too; :func:`install` then
puts :class:`CheckedLoader` in front of every source module. A ``.pyc`` there is
used only when its 16-byte header names the very source (the checkout's sources by
their content, as CPython's checked-hash pycs; the interpreter's own files by size
and modification time, as CPython judges them) and its code unmarshals; otherwise
the module is compiled from its source and the result written back by
:func:`write_verified`, whole or not at all, so a full disk leaves no short file.
No folder outside the checkout (``~/.cache``, ``$XDG_CACHE_HOME``, ``/tmp``) is read,
and a bare ``.pyc`` without its source is never imported. Whoever can write the
checkout can change its sources too: a planner that cannot, cannot change what the
launchers load.
"""

from __future__ import annotations

import marshal
import os
import sys
# importlib.util re-exports these two, but imports contextlib and its dependencies.
from importlib._bootstrap_external import MAGIC_NUMBER, cache_from_source
from importlib.machinery import (EXTENSION_SUFFIXES, SOURCE_SUFFIXES, ExtensionFileLoader,
                                 FileFinder, SourceFileLoader)

import _imp

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PYCACHE = os.path.join(ROOT, ".build", "pycache")
"""The only folder the launchers read bytecode from (git-ignored)."""
_KEY = int.from_bytes(MAGIC_NUMBER, "little")  # CPython's key for its checked-hash pycs
_CODE = type((lambda: None).__code__)  # (compile() costs ms at its first call)


def content_key(data: bytes) -> bytes:
    """The 8-byte SipHash of ``data`` that CPython's checked-hash pycs carry: a
    content key far cheaper than SHA-256 (not meant to resist a forger, who would
    have to write the checkout anyway)."""
    return _imp.source_hash(_KEY, data)


def by_content(source_path: str) -> bool:
    """Whether a source's bytecode is keyed by content (the checkout's, .venv
    included) rather than by size and modification time (the interpreter's)."""
    return source_path.startswith(ROOT + os.sep)


def header(source_path: str, source: bytes | None) -> bytes:
    """The 16 bytes a pyc of ``source_path`` must begin with to be used: the
    content key of ``source`` when given, else the file's size and time."""
    if source is not None:
        return MAGIC_NUMBER + b"\x03\x00\x00\x00" + content_key(source)
    status = os.stat(source_path)
    return (MAGIC_NUMBER + b"\x00\x00\x00\x00"
            + (int(status.st_mtime) & 0xFFFFFFFF).to_bytes(4, "little")
            + (status.st_size & 0xFFFFFFFF).to_bytes(4, "little"))


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
    whole ``.pyc`` under ``sys.pycache_prefix``, and writes it with
    :func:`write_verified` when it compiled the source."""

    writes = True
    """Cleared by the first write that fails (a read-only checkout, a full disk),
    so that this process does not try again for every module."""

    def get_code(self, fullname):
        path = self.get_filename(fullname)
        source = self.get_data(path) if by_content(path) else None
        expected = header(path, source)
        cached = cache_from_source(path)
        code = read_code(cached, expected)
        if code is None:
            code = self.source_to_code(self.get_data(path) if source is None else source, path)
            if CheckedLoader.writes:
                CheckedLoader.writes = write_verified(cached, expected + marshal.dumps(code))
        return code


def install(prefix: str = PYCACHE, check_loaded: bool = False) -> None:
    """Loads every source module imported from now on with :class:`CheckedLoader`,
    its bytecode in ``prefix``, and writes the bytecode of the modules Python
    loaded before where it is missing (``check_loaded``: or does not load)."""
    sys.pycache_prefix = prefix
    sys.path_hooks.insert(0, FileFinder.path_hook((CheckedLoader, SOURCE_SUFFIXES),
                                                   (ExtensionFileLoader, EXTENSION_SUFFIXES)))
    sys.path_importer_cache.clear()  # the finders made so far use CPython's loader
    for module in list(sys.modules.values()):
        spec = getattr(module, "__spec__", None)
        if (spec is not None and type(spec.loader) is SourceFileLoader
                and not _cached_header_matches(spec.origin, check_loaded)):
            CheckedLoader(spec.name, spec.origin).get_code(spec.name)


def _cached_header_matches(path: str, whole: bool) -> bool:
    """Whether the pyc of ``path`` under the prefix begins as it must (``whole``:
    and unmarshals)."""
    expected = header(path, _read(path) if by_content(path) else None)
    cached = cache_from_source(path)
    if whole:
        return read_code(cached, expected) is not None
    try:
        with open(cached, "rb") as file:
            return file.read(16) == expected
    except OSError:
        return False


def _read(path: str) -> bytes:
    with open(path, "rb") as file:
        return file.read()


def warm(packages: tuple[str, ...]) -> list[str]:
    """Imports every module of ``packages`` (after :func:`install`), so that their
    bytecode, and that of every module they import, is in the prefix and whole;
    returns the modules that could not be imported (one line each)."""
    import importlib
    failed = []
    for package in packages:
        folder = os.path.join(ROOT, package)
        for directory, subdirectories, files in os.walk(folder):
            subdirectories[:] = sorted(d for d in subdirectories if d != "__pycache__")
            for name in sorted(files):
                if not name.endswith(".py") or name == "__main__.py":
                    continue
                relative = os.path.relpath(os.path.join(directory, name), ROOT)[:-3]
                module = relative.replace(os.sep, ".").removesuffix(".__init__")
                try:
                    importlib.import_module(module)
                except Exception as error:  # noqa: BLE001  (e.g. needs what is not installed)
                    failed.append(f"{module}: {type(error).__name__}: {error}")
    return failed


PACKAGES = ("rrt_startup", "planning_core", "rrt_cli", "validator")
"""The packages the launchers import from."""


def main(packages: tuple[str, ...] = PACKAGES) -> int:
    """``./make.sh``'s step, in an interpreter started with ``-S -I -B``: the bytecode
    of every module of ``packages`` and of what they import (the PDF's reportlab
    too) in :data:`PYCACHE`, whole, and of the modules loaded before, checked whole;
    a module that cannot be imported is one line on stderr (status 0 all the same:
    it runs compiled from source)."""
    install(check_loaded=True)
    import site
    site.main()  # reportlab, as the validator's PDF imports it
    for line in warm(packages):
        sys.stderr.write(f"rrt_startup.bytecode: not imported: {line}\n")
    return 0
