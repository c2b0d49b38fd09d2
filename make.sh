#!/usr/bin/env bash
# Set up by need, in a virtual environment .venv inside the checkout:
#   ./make.sh            everything: the project with the validator's reportlab, the test and
#                        benchmark tools, and OMPL's Python bindings where PyPI has a wheel
#                        (OMPL is optional: the benchmarks and their tests skip it with a note);
#                        as root with apt-get, Debian's chromium, poppler-utils and qpdf (tests)
#                        and libompl-dev (the benchmarks' OMPL C++ peers)
#   ./make.sh validator  the project and reportlab only: what the validator's PDF needs
# Both write the bytecode the launchers read into .build/pycache (rrt_startup/bytecode.py).
# "all" also compiles the hot modules with mypyc into .build/compiled where a C compiler is
# (else one line says so; ./run.sh then runs the same source interpreted), and rebuilds them
# whenever a source's content changed or a built file is not as built (SHA-256 of each).
# The planner needs none of this (./run.sh runs on a bare python3). Idempotent. Quiet: one
# progress line per step on stderr; pip's output goes to .venv/make.log, shown on failure.
# PYTHON=/path/to/python3 picks the interpreter (default: python3 on PATH, 3.10 or newer).
set -euo pipefail
cd "$(dirname "$0")"

case ${1:-all} in
    all) target=all ;;
    validator) target=validator ;;
    -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "make.sh: unknown target '$1' (use: ./make.sh [all | validator])" >&2; exit 2 ;;
esac
PYTHON=${PYTHON:-python3}
LOG=.venv/make.log

step() { echo "make.sh: $*" >&2; }

# Runs "$@" with its output appended to the log; on failure shows the log's end, exits 1.
quietly() {
    if ! "$@" >>"$LOG" 2>&1; then
        step "failed: $*"
        echo "--- the last lines of $LOG:" >&2
        tail -n 30 "$LOG" >&2
        exit 1
    fi
}

make_venv() {
    if ! command -v "$PYTHON" >/dev/null 2>&1; then
        step "needs $PYTHON (3.10 or newer) on PATH, or PYTHON=/path/to/python3"; exit 1
    fi
    if ! "$PYTHON" -c 'import sys; sys.exit(sys.version_info < (3, 10))' 2>/dev/null; then
        step "needs Python 3.10 or newer; $PYTHON is $("$PYTHON" -V 2>&1)"; exit 1
    fi
    step "creating .venv with $("$PYTHON" -V 2>&1)"
    local out
    if ! out=$("$PYTHON" -m venv .venv 2>&1); then
        rm -rf .venv
        step "failed: $PYTHON -m venv .venv"
        echo "$out" >&2
        exit 1
    fi
    echo "$out" >"$LOG"
    # Editable installs from pyproject.toml need pip 21.3 or newer.
    if ! .venv/bin/python -c 'import pip, sys
sys.exit(tuple(int(p) for p in pip.__version__.split(".")[:2]) < (21, 3))' 2>/dev/null; then
        step "upgrading pip"
        quietly "${PIP[@]}" --upgrade pip
    fi
}

# The console scripts rrt-planner, rrt-validator and rrt-grade in .venv/bin become links to
# ./run.sh, ./rrt-validator and ./rrt-grade, which start faster (-S) than pip's and read
# bytecode only from the checkout. Removed before every pip run, so
# that pip never writes through them.
unlink_scripts() { rm -f .venv/bin/rrt-planner .venv/bin/rrt-validator .venv/bin/rrt-grade; }
link_scripts() {
    unlink_scripts  # pip's own
    ln -s ../../run.sh .venv/bin/rrt-planner
    ln -s ../../rrt-validator .venv/bin/rrt-validator
    ln -s ../../rrt-grade .venv/bin/rrt-grade
}

PIP=(.venv/bin/python -m pip install --disable-pip-version-check --no-input)
[ -x .venv/bin/python ] || make_venv

install() {
    unlink_scripts
    if [ "$target" = validator ]; then
        step "installing the project and reportlab"
        quietly "${PIP[@]}" -e .
    else
        step "installing the project, reportlab, the test and benchmark tools"
        quietly "${PIP[@]}" -e ".[test,bench]"
        step "installing OMPL's Python bindings (optional)"
        if ! "${PIP[@]}" -e ".[ompl]" >>"$LOG" 2>&1; then
            step "note: ompl could not be installed (see $LOG); OMPL comparisons will be skipped"
        fi
        step "installing Dask's distributed, for rrt-grade --scheduler (optional)"
        if ! "${PIP[@]}" -e ".[grade]" >>"$LOG" 2>&1; then
            step "note: distributed could not be installed (see $LOG); rrt-grade runs locally only"
        fi
        step "installing Planner Arena, to test that it reads runs.sqlite (optional)"
        if ! "${PIP[@]}" -e ".[arena]" >>"$LOG" 2>&1; then
            step "note: plannerarena could not be installed (see $LOG); its test will be skipped"
        fi
        step "installing mypy, the hot modules' compiler (optional)"
        if ! "${PIP[@]}" -e ".[compile]" >>"$LOG" 2>&1; then
            step "note: mypy could not be installed (see $LOG); the hot modules run interpreted"
        fi
        touch .venv/.installed-validator
    fi
    link_scripts
    touch "$stamp"
    step "ready"
}

# The hot modules compiled into .build/compiled (tools/build_compiled.py), unless the
# build there already matches their source. Never fails the set-up: without a compiler
# or mypy the same source runs interpreted.
compile_hot_modules() {
    local python=(env -u RRT_INTERPRETED .venv/bin/python)
    local why
    why=$("${python[@]}" -c 'from rrt_startup.compiled import why_not_fresh
print(why_not_fresh(full=True) or "")' 2>&1) || why="the check failed: $why"
    [ -z "$why" ] && return 0
    case $why in
        *damaged*) step "note: $why: removed, to be rebuilt"; rm -rf .build/compiled ;;
    esac
    if ! command -v "${CC:-cc}" >/dev/null 2>&1; then
        step "note: no C compiler (${CC:-cc}); the hot modules run interpreted"; return 0
    fi
    if ! "${python[@]}" -c 'import mypyc' 2>/dev/null; then
        step "note: mypy is not installed; the hot modules run interpreted"; return 0
    fi
    step "compiling the hot modules (mypyc) and the C kernel into .build/compiled"
    if ! "${python[@]}" tools/build_compiled.py >>"$LOG" 2>&1; then
        step "note: compiling failed (see $LOG); the hot modules run interpreted"
    fi
}

# rrt-validator's launcher (tools/build_launcher.py), which starts the planner before the
# interpreter starts; without a C compiler the validator starts it itself, a little later.
build_launcher() {
    if ! .venv/bin/python tools/build_launcher.py >>"$LOG" 2>&1; then
        step "note: rrt-validator's launcher was not built (see $LOG); it starts the planner itself"
    fi
}

# The bytecode ./run.sh and ./rrt-validator read: .build/pycache, every module of the
# checkout's packages and of what they import, built afresh in a new folder (nothing already
# there is read), each file checked whole, then renamed into place. The launchers write
# what is missing there themselves; this makes a checkout that will be read-only start fast.
compile_bytecode() {
    step "writing the launchers' bytecode into .build/pycache"
    local folder=$PWD/.build/.pycache-$$
    rm -rf "$folder" && mkdir -p "$folder"
    if ! .venv/bin/python -S -I -B -X pycache_prefix="$folder" -c 'import sys
sys.path.insert(0, sys.argv[1])
from rrt_startup.bytecode import main
sys.exit(main(sys.argv[2]))' "$PWD" "$folder" >>"$LOG" 2>&1; then
        rm -rf "$folder"
        step "failed: writing .build/pycache"
        tail -n 30 "$LOG" >&2
        exit 1
    fi
}

# Debian's packages "$@" (only where apt-get is and we are root; else one line), for
# $purpose; a failure is one line too: what needs them skips.
apt_install() {
    if [ "$(id -u)" != 0 ] || ! command -v apt-get >/dev/null 2>&1; then
        step "note: $* not installed (apt-get as root installs them); $purpose will skip"
        return 0
    fi
    step "installing $* (Debian's packages: $purpose)"
    if ! { apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y \
            --no-install-recommends "$@"; } >>"$LOG" 2>&1; then
        step "note: apt-get could not install $* (see $LOG); $purpose will skip"
    fi
}

# Headless Chromium (the browser view's tests) and poppler-utils and qpdf (the strict PDF
# readers of the PDF's tests), only what is missing.
install_test_tools() {
    local missing=()
    command -v chromium >/dev/null 2>&1 || command -v chromium-browser >/dev/null 2>&1 \
        || missing+=(chromium)
    command -v pdftoppm >/dev/null 2>&1 || missing+=(poppler-utils)
    command -v qpdf >/dev/null 2>&1 || missing+=(qpdf)
    [ ${#missing[@]} -eq 0 ] && return 0
    purpose="the browser view's and strict PDF tests" apt_install "${missing[@]}"
}

# OMPL's C++ library and headers, with g++ and pkg-config to build against them: the
# benchmarks' C++ peers (benchmarks/ompl_cpp/), only what is missing.
install_ompl_cpp() {
    local missing=()
    command -v g++ >/dev/null 2>&1 || missing+=(g++)
    command -v pkg-config >/dev/null 2>&1 || missing+=(pkg-config)
    pkg-config --exists ompl 2>/dev/null || missing+=(libompl-dev)
    [ ${#missing[@]} -eq 0 ] && return 0
    purpose="the OMPL C++ comparisons and their tests" apt_install "${missing[@]}"
}

# .venv/.installed: everything; .venv/.installed-validator: the project and reportlab.
stamp=.venv/.installed
[ "$target" = validator ] && stamp=.venv/.installed-validator
if [ ! -f "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
    install
fi
[ "$target" = all ] && compile_hot_modules
[ "$target" = all ] && install_test_tools
[ "$target" = all ] && install_ompl_cpp
build_launcher
compile_bytecode
exit 0
