#!/usr/bin/env bash
# Set up everything: a virtual environment in .venv with the project, its test
# tools, the benchmark tools and (where a wheel exists) OMPL's Python bindings for
# the side-by-side benchmarks. Idempotent; quiet on stdout (progress on stderr).
set -euo pipefail
cd "$(dirname "$0")"
PYTHON=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    echo "make.sh: creating .venv" >&2
    "$PYTHON" -m venv .venv >&2
fi
stamp=.venv/.installed
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
    echo "make.sh: installing the project, its test and benchmark tools into .venv" >&2
    pip=(.venv/bin/python -m pip install --quiet --disable-pip-version-check)
    "${pip[@]}" --upgrade pip >&2
    "${pip[@]}" -e ".[test,bench]" >&2
    # OMPL is optional (benchmarks and their tests skip it with a note): a platform
    # without an ompl wheel still gets a working set-up.
    if ! "${pip[@]}" -e ".[ompl]" >&2; then
        echo "make.sh: note: ompl could not be installed; OMPL comparisons will be skipped" >&2
    fi
    touch "$stamp"
fi
