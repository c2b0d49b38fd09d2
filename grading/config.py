"""What a grading run is asked to do: folders, modes, limits, the score rule."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from planning_core.vehicles import Vehicle

# The course's modes: how each reaches run.sh, and which vehicle the validator checks.
MODE_FLAGS: dict[str, tuple[str, ...]] = {"point": (), "grad": ("-grad",),
                                          "left": ("-grad", "-left")}
MODE_VEHICLES: dict[str, Vehicle] = {"point": Vehicle.POINT, "grad": Vehicle.SPACESHIP,
                                     "left": Vehicle.LEFT_SPACESHIP}


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
class ScoreRule:
    """score = scale x (weighted valid runs) / (weighted runs), rounded to ``digits``."""

    weights: tuple[tuple[str, float], ...] = ()  # (mode, weight); a mode not named: 1
    scale: float = 100.0   # the score of a submission whose every run is valid
    digits: int = 1        # decimals kept in gradebook.csv

    def weight(self, mode: str) -> float:
        return dict(self.weights).get(mode, 1.0)

    def score(self, valid: dict[str, int], runs: dict[str, int]) -> float:
        """The score from valid and total runs per mode."""
        total = sum(self.weight(mode) * count for mode, count in runs.items())
        if total <= 0:
            return 0.0
        got = sum(self.weight(mode) * valid.get(mode, 0) for mode in runs)
        return round(self.scale * got / total, self.digits)


@dataclass(frozen=True)
class GradeConfig:
    """One grading run: every submission x problem x mode."""

    submissions: Path       # each subfolder: one submission with make.sh and run.sh
    problems: Path          # the *.sw problems graded (every mode each)
    out: Path               # grades.sqlite, gradebook.csv, report.md, logs/, pdf/
    modes: tuple[str, ...] = ("point", "grad", "left")
    jobs: int = 2           # runs at once (local pool size; cap on a Dask cluster)
    timeout: float = 60.0   # seconds per run (the validator's time limit)
    build_timeout: float = 600.0  # seconds for a submission's make.sh
    scheduler: str | None = None  # a Dask scheduler's address; None: a local pool
    rerun: bool = False     # redo every build and run, finished or not
    sandbox: bool = True    # use namespaces where the kernel allows them
    limits: Limits = field(default_factory=Limits)
    build_limits: Limits = field(default_factory=lambda: Limits(
        memory_bytes=4 << 30, file_bytes=1 << 30, processes=256, disk_bytes=1 << 30,
        entries=262144))
    score: ScoreRule = field(default_factory=ScoreRule)

    def built(self, submission: str) -> Path:
        """Where a submission's folder is kept after its make.sh (namespaces): its runs'
        read-only layer."""
        return self.out / "built" / submission

    def submission_names(self) -> list[str]:
        """The submissions: subfolders of ``submissions``, sorted, hidden ones skipped."""
        return sorted(entry.name for entry in self.submissions.iterdir()
                      if entry.is_dir() and not entry.name.startswith("."))

    def problem_names(self) -> list[str]:
        """The problem files graded, sorted."""
        return sorted(entry.name for entry in self.problems.iterdir()
                      if entry.is_file() and entry.suffix == ".sw")
