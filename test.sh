#!/usr/bin/env bash
# Set up (if needed) and run the whole test suite on all cores. The golden test replays the
# pinned outputs interpreted and, when ./make.sh could compile the hot modules, compiled too;
# the first line says which.
set -euo pipefail
cd "$(dirname "$0")"
./make.sh
env -u RRT_INTERPRETED .venv/bin/python -c 'from rrt_startup.compiled import activate
print("test.sh: hot modules:", activate())' >&2
# The run's own bytecode (pytest's rewritten test modules, the commands the tests start
# without -I) goes to .build/pycache-tests whatever PYTHONDONTWRITEBYTECODE says: the next
# run starts warm, and no __pycache__ lands in the source tree.
export PYTHONPYCACHEPREFIX="$PWD/.build/pycache-tests"
unset PYTHONDONTWRITEBYTECODE
exec .venv/bin/python -m pytest -n auto -q "$@"
