"""What a grading run is asked to do: folders, the rubric, limits."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from grading.rubric import (KINOPLAN, MODE_FLAGS, MODE_VEHICLES,  # noqa: F401
                            PROBLEM_SUFFIXES, Item, Rubric)


@dataclass(frozen=True)
class Limits:
    """What a submission's program may use, set before it starts."""

    cpu_seconds: int = 0        # RLIMIT_CPU; 0: the run's timeout rounded up, plus one
    memory_bytes: int = 2 << 30  # RLIMIT_AS (address space)
    file_bytes: int = 64 << 20   # RLIMIT_FSIZE: the largest file it may write
    processes: int = 64          # RLIMIT_NPROC: binds per run under the sandbox's own uid
    output_bytes: int = 64 << 20  # the cap on its stdout (the validator's cap)
    stderr_bytes: int = 1 << 20  # its stderr kept in the log; one line says what was dropped
    disk_bytes: int = 256 << 20  # namespaces: its folder's changes and /tmp, one private tmpfs
    entries: int = 65536         # namespaces: files and folders on that tmpfs


@dataclass(frozen=True)
class GradeConfig:
    """One grading run: every submission x the rubric's items (problem x mode) x repeats."""

    submissions: Path       # each subfolder: one submission with make.sh and run.sh
    problems: Path          # the *.sw and *.kp problems graded
    out: Path               # grades.sqlite, gradebook.csv, report.md, logs/, pdf/
    rubric: Rubric = field(default_factory=Rubric)  # modes, weights, time limits, repeats
    jobs: int = 2           # runs at once (local pool size; cap on a Dask cluster)
    build_timeout: float = 600.0  # seconds for a submission's make.sh
    scheduler: str | None = None  # a Dask scheduler's address; None: a local pool
    rerun: bool = False     # redo every build and run, finished or not
    sandbox: bool = True    # use namespaces where the kernel allows them
    limits: Limits = field(default_factory=Limits)
    build_limits: Limits = field(default_factory=lambda: Limits(
        memory_bytes=4 << 30, file_bytes=1 << 30, processes=256, disk_bytes=1 << 30,
        entries=262144))
    names: tuple[str, ...] | None = None  # the submissions graded; None: every subfolder
    calibrate: bool = True  # time our own planner on each item first (relative times)
    formats: tuple[str, ...] = ()  # more outputs: "gradescope" (results.json each)

    def built(self, submission: str) -> Path:
        """Where a submission's folder is kept after its make.sh (namespaces): its runs'
        read-only layer."""
        return self.out / "built" / submission

    def submission_names(self) -> list[str]:
        """The submissions: ``names``, or the subfolders of ``submissions``, sorted, hidden
        ones skipped."""
        if self.names is not None:
            return sorted(self.names)
        return sorted(entry.name for entry in self.submissions.iterdir()
                      if entry.is_dir() and not entry.name.startswith("."))

    def problem_names(self) -> list[str]:
        """The problem files (``*.sw``, ``*.kp``), sorted."""
        return sorted(entry.name for entry in self.problems.iterdir()
                      if entry.is_file() and entry.suffix in PROBLEM_SUFFIXES)

    def items(self) -> list[Item]:
        """The rubric's items on these problems."""
        return self.rubric.items(self.problem_names())
