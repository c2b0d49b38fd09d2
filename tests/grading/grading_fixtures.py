"""A class of fake submissions for the grading tests, made in a tmp folder."""

from __future__ import annotations

import shutil
import zlib
from functools import lru_cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
COURSE = ROOT / "benchmarks" / "problems" / "course"
FAMILY = ROOT / "benchmarks" / "problems" / "family"
OUR_RUN = ROOT / "run.sh"
EMPTIED = ("/tmp", "/var/tmp", "/run", "/dev/shm")
"""What the sandbox empties for every submission's program (grading/jail.py)."""


@lru_cache(maxsize=1)
def _checkout_hidden() -> bool:
    """The sandbox empties the folder this checkout is in, so a submission's program
    cannot exec its run.sh (no sandbox here: it can)."""
    if not any(str(ROOT) == f or str(ROOT).startswith(f + "/") for f in EMPTIED):
        return False
    from grading.sandbox import probe
    return probe().level != "none"


@lru_cache(maxsize=1)
def closed_folder() -> Path | None:
    """The outermost folder on the way to this checkout that other users may not
    enter (``mktemp -d`` makes one, mode 0700), else None: a submission's program,
    run by the sandbox as a uid of its own, or nobody, cannot reach our files."""
    closed = [folder for folder in (ROOT, *ROOT.parents) if not folder.stat().st_mode & 0o001]
    return closed[-1] if closed else None


def closed_message(closed: Path) -> str:
    return (f"other users may not enter {closed} (mode {closed.stat().st_mode & 0o777:o}), "
            "so the sandbox's runs cannot reach this checkout: clone it where others may "
            "enter to run this test")


def our_run() -> Path:
    """This checkout's run.sh, which the fake submissions exec; skips the test where
    the sandbox hides the checkout (a clone under /tmp: clone elsewhere to run it) or
    a submission's uid cannot reach it (a clone inside a folder of mode 0700)."""
    if _checkout_hidden():
        pytest.skip(f"the sandbox empties the folder of this checkout ({ROOT}) for every "
                    "submission, whose run.sh execs ours: clone it outside "
                    + ", ".join(EMPTIED) + " to run this test")
    if closed_folder() is not None:
        from grading.sandbox import probe
        if probe().level == "full":  # each run its own uid
            pytest.skip(closed_message(closed_folder()))
    return OUR_RUN

# Two copies of one submission under different names (a fixed seed: the same answers),
# and a third of its own (its own seed and words; it says its flags on stderr).
_COPIED = ("# Team Hydra's planner: a fixed seed, so that every run repeats exactly.\n"
           "seed=4242\nattempt=1\n"
           'echo "hydra: attempt $attempt with seed $seed" >&2\n'
           'exec "{run}" -seed "$seed" "$@"')
_OTHER = ("# Team Kraken's planner: its own seed, its own words.\n"
          'for flag in "$@"; do echo "kraken: flag $flag" >&2; done\n'
          'exec "{run}" -seed 777 "$@"')

# name -> (make.sh body, run.sh body); {outside}, {run} and {nap} are filled in.
# "asleep" sorts first: its runs, which wait out the timeout, start with the grading and
# the others run beside them (rrt-grade runs the submissions in the order of their names).
# The submissions that run our planner each pin a seed of their own: unseeded, two of them
# gave byte-identical answers on simple-0 now and then, a pair the report then flagged.
CLASS = {
    "good": ("echo building", 'exec "{run}" -seed 1 "$@"'),
    "garbage": ("", "echo hello world"),
    "asleep": ("", "sleep {nap}3"),
    "crash": ("", "kill -SEGV $$"),
    "flood": ("", "exec yes 1.0 2.0"),
    "nobuild": ("echo oops >&2; exit 3", "exit 0"),
    "forks": ("", "sleep {nap}1 &\n(setsid sleep {nap}2 &)\n"
                  'exec "{run}" -seed 2 "$@"'),
    "escape": ("", 'echo x > "{outside}" 2>/dev/null\nexec "{run}" -seed 3 "$@"'),
    "copy-a": ("", _COPIED),
    "copy-b": ("", _COPIED),
    "other": ("", _OTHER),
}

# Valid on alternate runs of each problem and mode: each run takes the next number of its
# own (mkdir is atomic: repeats running at once never share one) in its folder, so only
# without the sandbox, whose runs' writes are thrown away; odd numbers print garbage.
FLAKY = ("", 'problem=$(cat)\n'
             'key=$(printf "%s %s" "$problem" "$*" | cksum | cut -d" " -f1)\n'
             'n=0\nwhile ! mkdir "run-$key-$n" 2>/dev/null; do n=$((n + 1)); done\n'
             'if [ $((n % 2)) -eq 1 ]; then echo garbage; exit 0; fi\n'
             'printf "%s\\n" "$problem" | exec "{run}" "$@"')


def nap(base: Path) -> str:
    """The first digits of the class's sleeps (``sleep {nap}1``): which class a sleeping
    process is from, when several are graded at once."""
    return str(600 + zlib.crc32(str(base).encode()) % 300)


def make_submission(base: Path, name: str, make: str, run: str, outside: Path) -> Path:
    folder = base / name
    folder.mkdir(parents=True)
    for script, body in (("make.sh", make), ("run.sh", run)):
        path = folder / script
        path.write_text("#!/bin/sh\n" + body.format(run=our_run(), outside=outside,
                                                     nap=nap(base)) + "\n")
        path.chmod(0o755)
    return folder


def make_class(base: Path, names: list[str], problems: list[str]) -> tuple[Path, Path, Path]:
    """``(submissions, problems, outside)`` folders under ``base``."""
    submissions, problem_dir, outside = base / "subs", base / "problems", base / "outside"
    problem_dir.mkdir(parents=True)
    outside.mkdir()
    for name in names:
        make_submission(submissions, name, *CLASS[name], outside / f"{name}.txt")
    for problem in problems:
        shutil.copy(problem_file(problem), problem_dir / problem)
    return submissions, problem_dir, outside


def problem_file(name: str) -> Path:
    """A course problem (.sw) or a family one (.kp) of the checkout."""
    return (FAMILY if name.endswith(".kp") else COURSE) / name


# Hostile submissions: each tries what docs/grading.md says it cannot do, says on
# stderr (its log) what it saw and what worked, then runs our planner (a valid answer).
# {sentinel}: the pid of a process of the test's; {fifos}, {sockets}: paths the test
# listens on outside the folder; {out}, {subs}: the grading's --out and --submissions.
_PY_OPEN = ('python3 -c \'import os, sys\nfor path in sys.argv[1:]:\n    try:\n'
            '        os.close(os.open(path, os.O_WRONLY | os.O_NONBLOCK))\n'
            '        print("opened", path, file=sys.stderr)\n    except OSError as e:\n'
            '        print("refused", path, e.strerror, file=sys.stderr)\' ')
_PY_CONNECT = ('python3 -c \'import socket, sys\nfor path in sys.argv[1:]:\n'
               '    s = socket.socket(socket.AF_UNIX)\n    try:\n        s.connect(path)\n'
               '        print("connected", path, file=sys.stderr)\n    except OSError as e:\n'
               '        print("refused", path, e.strerror, file=sys.stderr)\' {sockets}\n')
_PY_FORKS = ('python3 -c \'import os, signal, sys\nn = 0\ntry:\n    while n < 500:\n'
             '        if os.fork() == 0:\n            signal.pause()\n            os._exit(0)\n'
             '        n += 1\nexcept OSError:\n    pass\nprint("forked", n, file=sys.stderr)\' '
             '"{subs}"\n')  # in its command line: which grading's it is
_IN_OURS = ('grep -q jail.py /proc/1/cmdline 2>/dev/null || '
            '{{ echo "not in the grader\'s namespace: no attack" >&2; exit 1; }}\n')
HOSTILE = {
    "good": ("", 'exec "{run}" "$@"'),
    "killall": ("", 'kill -9 {sentinel} 2>/dev/null && echo "killed the sentinel" >&2\n'
                + _IN_OURS + 'kill -9 -1 2>/dev/null\nfor p in /proc/[0-9]*; do '
                '[ "${{p#/proc/}}" = $$ ] || kill -9 "${{p#/proc/}}" 2>/dev/null; done\n'
                'echo attacked >&2\nexec "{run}" "$@"'),
    "killparents": ("", 'p=$PPID; g=$(cut -d" " -f4 /proc/$p/stat)\n'
                    'echo "parent $p grandparent $g" >&2\nkill -9 "$p" 2>/dev/null\n'
                    '[ "$g" -gt 0 ] && kill -9 "$g" 2>/dev/null\nexec "{run}" "$@"'),
    "ipc": ("", 'for f in {fifos}; do (echo attack > "$f") 2>/dev/null && echo "wrote $f" >&2; '
            'done\n' + _PY_CONNECT + 'exec "{run}" "$@"'),
    "devices": ("", _PY_OPEN + "/dev/kmsg /dev/loop0 /dev/loop-control /dev/tty0 "
                "/proc/sys/kernel/hostname /proc/sys/vm/drop_caches /proc/sysrq-trigger "
                "/sys/kernel/mm/transparent_hugepage/enabled\nexec \"{run}\" \"$@\""),
    "looks": ("", 'for d in /tmp /var/tmp /run /dev/shm /dev "{subs}"; do '
              'echo "seen $d:" $(ls -A "$d" 2>/dev/null) >&2; done\n'
              '[ -e "{out}" ] && echo "sees --out" >&2\n'
              'echo "uid $(id -u) groups $(id -G) home $HOME tmp $TMPDIR" >&2\n'
              'grep -E "^(CapEff|CapBnd|NoNewPrivs):" /proc/self/status >&2\n'
              'exec "{run}" "$@"'),
    "forkbomb": ("", _PY_FORKS + 'exec "{run}" "$@"'),
}


def make_hostile(base: Path, names: list[str], problems: list[str], **paths) -> tuple[Path, Path]:
    """``(submissions, problems)`` folders under ``base``: the HOSTILE submissions named,
    their scripts filled in with ``paths``."""
    submissions, problem_dir = base / "subs", base / "problems"
    problem_dir.mkdir(parents=True)
    for name in names:
        make, run = HOSTILE[name]
        folder = submissions / name
        folder.mkdir(parents=True)
        for script, body in (("make.sh", make), ("run.sh", run)):
            (folder / script).write_text("#!/bin/sh\n" + body.format(
                run=our_run(), subs=submissions, **paths) + "\n")
            (folder / script).chmod(0o755)
    for problem in problems:
        shutil.copy(COURSE / problem, problem_dir / problem)
    return submissions, problem_dir


# A graded class without grading: rows as the store holds them, for the reports' tests.
# Each name's verdict per run: v valid, p invalid (parse), c invalid (collision), t timed
# out, b build failed; one letter per item x repeat, in the items' order.
HOSTILE_NAME = "x<img src=x onerror=alert(1)>\"'&amp;"
HOSTILE_TEXT = "</script><img src=x onerror=alert(2)><b>bold</b> \"q\" 'q' &amp; [l](http://e)"
SYNTHETIC = {"alice": "vvvvvv", "bob": "vvpvcv", "carol": "vcvpvt", "dave": "bbbbbb",
             "erin10": "vvvvvp", "erin9": "pppppp", HOSTILE_NAME: "ccvvvv"}


def synthetic_results(out: Path, names: dict[str, str] | None = None):
    """A ``grading.scores.Results`` of simple-0.sw in point and grad (2 repeats each) and
    pendulum-t3.kp (2 repeats) for ``names`` (SYNTHETIC), with failing runs' PDFs and
    views named (not written), calibration, a failed build and hostile text."""
    from grading.rubric import Rubric
    from grading.scores import Results, scored
    rubric = Rubric(modes=("point", "grad"), repeats=2)
    items = rubric.items(["pendulum-t3.kp", "simple-0.sw"])
    verdicts = {"v": ("valid", None, None), "p": ("invalid", "parse", "Could not parse"),
                "c": ("invalid", "collision", HOSTILE_TEXT), "t": ("planner failed", "planner",
                                                                   "timed out " + HOSTILE_TEXT),
                "b": ("build failed", "build", "make.sh exited 3: " + HOSTILE_TEXT)}
    runs = []
    for name, letters in (names or SYNTHETIC).items():
        pairs = [(item, repeat) for item in items for repeat in range(item.repeats)]
        for number, ((item, repeat), letter) in enumerate(zip(pairs, letters)):
            verdict, check, message = verdicts[letter]
            stem = f"{Path(item.problem).stem}-{item.mode}" + (f"-{repeat + 1}" if repeat else "")
            row = {"submission": name, "problem": item.problem, "mode": item.mode,
                   "repeat": repeat, "verdict": verdict, "valid": int(letter == "v"),
                   "failed_check": check, "message": message,
                   "detail": "near (1, 2) " + HOSTILE_TEXT if letter == "c" else None,
                   "timed_out": int(letter == "t"), "sandbox": "none",
                   "wall_time": None if letter == "b" else 0.5 + 0.25 * number,
                   "path_length": 3.5 if letter == "v" else None, "tree_size": 40 + number,
                   "log": str(out / "logs" / name / f"{stem}.stderr")}
            if letter != "v":
                row["pdf"] = str(out / "pdf" / name / f"{stem}.pdf")
                row["view"] = str(out / "html" / name / f"{stem}.html")
            runs.append(row)
    builds = {name: {"submission": name, "ok": int("b" not in letters), "sandbox": "none",
                     "reason": None if "b" not in letters else "make.sh exited 3: " + HOSTILE_TEXT,
                     "log": str(out / "logs" / name / "make.log")}
              for name, letters in (names or SYNTHETIC).items()}
    calibration = {(item.problem, item.mode): {"problem": item.problem, "mode": item.mode,
                                               "valid": 1, "verdict": "valid", "wall_time": 0.5}
                   for item in items}
    return Results(rubric, items, calibration, builds, scored(rubric, items, runs), out)
