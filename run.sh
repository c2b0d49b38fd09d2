#!/usr/bin/env bash
# Run the planner: ./run.sh [-grad] [-left] [options] < problem.sw
# Sets up .venv first if it is missing. stdout carries only the answer.
here="$(cd "$(dirname "$0")" && pwd)"
if [ ! -x "$here/.venv/bin/python" ] || [ ! -f "$here/.venv/.installed" ]; then
    "$here/make.sh" >&2 || exit 2
fi
exec "$here/.venv/bin/python" -m rrt_cli "$@"
