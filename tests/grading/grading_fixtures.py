"""A class of fake submissions for the grading tests, made in a tmp folder."""

from __future__ import annotations

import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
COURSE = ROOT / "benchmarks" / "problems" / "course"
OUR_RUN = ROOT / "run.sh"

# name -> (make.sh body, run.sh body); {outside} and {run} are filled in.
CLASS = {
    "good": ("echo building", 'exec "{run}" "$@"'),
    "garbage": ("", "echo hello world"),
    "hang": ("", "sleep 100"),
    "crash": ("", "kill -SEGV $$"),
    "flood": ("", "exec yes 1.0 2.0"),
    "nobuild": ("echo oops >&2; exit 3", "exit 0"),
    "forks": ("", "sleep 60 & echo $! >> pids\n(setsid sleep 60 & echo $! >> pids)\n"
                  'exec "{run}" "$@"'),
    "escape": ("", 'echo x > "{outside}" 2>/dev/null\nexec "{run}" "$@"'),
}


def make_submission(base: Path, name: str, make: str, run: str, outside: Path) -> Path:
    folder = base / name
    folder.mkdir(parents=True)
    for script, body in (("make.sh", make), ("run.sh", run)):
        path = folder / script
        path.write_text("#!/bin/sh\n" + body.format(run=OUR_RUN, outside=outside) + "\n")
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
        shutil.copy(COURSE / problem, problem_dir / problem)
    return submissions, problem_dir, outside
