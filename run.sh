#!/bin/sh
# Run the planner: ./run.sh [-grad] [-left] [options] < problem.sw
#
# Needs only python3 (3.10 or newer), no set-up: the planner uses the standard library
# alone. It runs the interpreter ./make.sh set up (.venv) when there is one, else python3
# from PATH, with -S -I: no site-packages and no PYTHON* variables, so nothing but the
# standard library and this checkout is imported. Bytecode is read only from the checkout's
# .build/pycache (git-ignored) and the interpreter's own, and written there whole or not at
# all; CPython writes none (-B), and no cache folder is read (rrt_startup/bytecode.py). The
# hot modules ./make.sh compiled (.build/compiled, rrt_startup/compiled.py) are used when
# they match their source, else the same source runs interpreted; -stats says which.
# stdout carries only the answer.
case $0 in */*) here=${0%/*} ;; *) here=. ;; esac
if [ -L "$0" ]; then here=$(dirname "$(readlink -f "$0")"); fi

case $here in /*) ;; *) here=$PWD/$here ;; esac
if [ -d /dev/stdin ]; then  # Python itself would stop: "<stdin> is a directory"
    echo "run.sh: stdin is a folder, not a problem file (use < problem.sw)" >&2
    exit 2
fi
python=$here/.venv/bin/python
if [ ! -x "$python" ]; then
    python=python3
    if ! command -v python3 >/dev/null 2>&1; then
        echo "run.sh: needs python3 (3.10 or newer) on PATH" >&2
        exit 127
    fi
fi
exec "$python" -S -I -B -c '
import sys
if sys.version_info < (3, 10):
    sys.stderr.write("run.sh: needs Python 3.10 or newer, %s is %s\n"
                     % (sys.executable, sys.version.split()[0]))
    sys.exit(127)
import os
here = os.path.abspath(sys.argv.pop(1))
sys.pycache_prefix = os.path.join(here, ".build", "pycache")  # before any import of ours
sys.path.insert(0, here)
try:
    from rrt_startup.launch import planner
except (EOFError, ValueError, TypeError, ImportError):  # a damaged file in .build/pycache:
    sys.pycache_prefix = os.devnull  # read none, compile these few (and write them again)
    from rrt_startup.launch import planner
planner()
' "$here" "$@"
