#!/usr/bin/env bash
# Set up everything: a virtual environment in .venv with the project and its test
# tools. Idempotent; quiet on stdout (progress goes to stderr).
set -euo pipefail
cd "$(dirname "$0")"
PYTHON=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    echo "make.sh: creating .venv" >&2
    "$PYTHON" -m venv .venv >&2
fi
stamp=.venv/.installed
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
    echo "make.sh: installing the project and its test tools into .venv" >&2
    .venv/bin/python -m pip install --quiet --disable-pip-version-check --upgrade pip >&2
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -e ".[test]" >&2
    touch "$stamp"
fi
