#!/bin/sh
# Run the planner: ./run.sh [-grad] [-left] [options] < problem.sw
#
# Needs only python3 (3.10 or newer), no set-up: the planner uses the standard library
# alone. It runs the interpreter ./make.sh set up (.venv) when there is one, else python3
# from PATH, with -S -I: no site-packages and no PYTHON* variables, so nothing but the
# standard library and this checkout is imported. The hot modules ./make.sh compiled
# (.build/compiled, planning_core/compiled.py) are used when they match their source, else
# the same source runs interpreted; -stats says which. Bytecode is cached under
# ~/.cache/rrt-gridplan (XDG_CACHE_HOME), so the checkout is left as it was. inspect and
# copy, which dataclasses imports but uses only for a class without a docstring (and
# for deep copies), are imported on first use (docs/setup-and-startup.md).
# stdout carries only the answer.
case $0 in */*) here=${0%/*} ;; *) here=. ;; esac
if [ -L "$0" ]; then here=$(dirname "$(readlink -f "$0")"); fi

cache=${XDG_CACHE_HOME:-${HOME:+$HOME/.cache}}
case $cache in
    /*) keep="-Xpycache_prefix=$cache/rrt-gridplan" ;;
    *) keep=-B ;;  # no absolute cache folder: compile in memory, write nothing
esac
python=$here/.venv/bin/python
if [ ! -x "$python" ]; then
    python=python3
    if ! command -v python3 >/dev/null 2>&1; then
        echo "run.sh: needs python3 (3.10 or newer) on PATH" >&2
        exit 127
    fi
fi
exec "$python" -S -I "$keep" -c '
import os, sys
if sys.version_info < (3, 10):
    sys.stderr.write("run.sh: needs Python 3.10 or newer, %s is %s\n"
                     % (sys.executable, sys.version.split()[0]))
    sys.exit(127)
import types
class OnFirstUse(types.ModuleType):
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
for name in ("inspect", "copy"):  # dataclasses imports them, rarely uses them
    sys.modules[name] = OnFirstUse(name)
sys.path.insert(0, os.path.abspath(sys.argv.pop(1)))
try:
    from planning_core.compiled import activate
    build = activate()
except ImportError:  # a checkout without the loader
    build = "interpreted: no planning_core.compiled"
if "-stats" in sys.argv:
    sys.stderr.write("rrt_cli build: %s\n" % build)
from rrt_cli.cli import entry_point
entry_point()
' "$here" "$@"
