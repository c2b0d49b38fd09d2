"""The facts both reports show, computed once: the scores' distribution, the pass rate
per problem and mode, the slowest runs, the flaky items, each distinct failure with its
runs and submissions. report.md (grading.markdown) and report.html (grading.html_report)
only format them. Failures keep what submissions and planners wrote raw (one line each);
each format escapes it its own way."""

from __future__ import annotations

import statistics
from collections import Counter
from dataclasses import dataclass
from typing import Iterable

from grading.rubric import Item
from grading.scores import Key, Results, Scored, flaky, key, relative_time

SLOWEST = 10  # runs in the class summary's table of the slowest
BINS = 10     # the scores' distribution: bins of a tenth of the full score each


def failure_label(row: dict) -> str:
    """``invalid (parse)``, ``timed out``, ``planner failed``, ``build failed``."""
    if row["verdict"] == "invalid":
        return f"invalid ({row['failed_check']})"
    if row.get("timed_out"):
        return "timed out"
    return row["verdict"]


@dataclass(frozen=True)
class Failure:
    """A failing run's reason: its label, message and detail, each on one line (None:
    not given). Runs that failed for the same reason have equal Failures."""

    label: str
    message: str | None
    detail: str | None


def one_line(value) -> str | None:
    """What a run wrote, its white space runs as one space; None when it wrote nothing."""
    return " ".join(str(value).split()) if value else None


def failure(row: dict) -> Failure:
    return Failure(failure_label(row), one_line(row.get("message")), one_line(row.get("detail")))


def problems(items: list[Item]) -> list[str]:
    """The problems in the rubric's order, each once."""
    return list(dict.fromkeys(item.problem for item in items))


@dataclass(frozen=True)
class Distribution:
    """The class's scores: their summary and ten bins, the highest first."""

    count: int
    mean: float
    median: float
    lowest: float
    highest: float
    bins: list[tuple[float, float, int]]  # (from, to, submissions), highest first


def distribution(scores: list[float], full: float) -> Distribution | None:
    """None for no submissions."""
    if not scores:
        return None
    counts = Counter(min(int(BINS * score / full), BINS - 1) if full > 0 else 0
                     for score in scores)
    bins = [(full * index / BINS, full * (index + 1) / BINS, counts[index])
            for index in range(BINS - 1, -1, -1)]
    return Distribution(len(scores), statistics.mean(scores), statistics.median(scores),
                        min(scores), max(scores), bins)


def pass_counts(graded: list[Scored]) -> dict[Key, tuple[int, int]]:
    """Valid runs and runs per problem and mode over the class (repeats counted)."""
    valid: Counter = Counter()
    runs: Counter = Counter()
    for one in graded:
        for k, rows in one.runs.items():
            valid[k] += sum(row["valid"] for row in rows)
            runs[k] += len(rows)
    return {k: (valid[k], runs[k]) for k in runs}


def slowest_runs(graded: list[Scored]) -> list[dict]:
    """The SLOWEST runs with a wall time, the slowest first."""
    return sorted((row for one in graded for row in one.all_runs()
                   if row.get("wall_time") is not None),
                  key=lambda row: -row["wall_time"])[:SLOWEST]


def flaky_items(graded: list[Scored]) -> list[tuple[str, Key, list[dict]]]:
    """(submission, item, its runs) of each item valid on some repeats, not all."""
    return [(one.name, k, rows) for one in graded for k, rows in one.runs.items()
            if flaky(rows)]


def class_failures(graded: list[Scored]) -> list[tuple[Failure, int, list[str]]]:
    """Each distinct failure over the class, the most frequent first: its runs' count and
    the submissions that had it (in the class's order)."""
    runs: Counter = Counter()
    names: dict[Failure, list[str]] = {}
    for one in graded:
        for row in one.all_runs():
            if not row["valid"]:
                what = failure(row)
                runs[what] += 1
                names.setdefault(what, [])
                if one.name not in names[what]:
                    names[what].append(one.name)
    return [(what, count, names[what]) for what, count in runs.most_common()]


def submission_failures(report: Results, one: Scored) -> list[tuple[Failure, list[dict]]]:
    """Each distinct failure of a submission once, with its runs (in the rubric's order)."""
    groups: dict[Failure, list[dict]] = {}
    for item in report.items:
        for row in one.runs.get(key(item), []):
            if not row["valid"]:
                groups.setdefault(failure(row), []).append(row)
    return list(groups.items())


def where(rows: Iterable[dict], items: list[Item]) -> list[tuple[str, list[str]]]:
    """The runs of one failure by problem: ``[("simple-0.sw", ["point", "left (2 of 4)"])]``
    (a repeated item says how many of its repeats)."""
    counts = Counter(key(row) for row in rows)
    by_problem: dict[str, list[str]] = {}
    for item in items:
        if key(item) in counts:
            shown = item.mode if item.repeats == 1 else \
                f"{item.mode} ({counts[key(item)]} of {item.repeats})"
            by_problem.setdefault(item.problem, []).append(shown)
    return list(by_problem.items())


@dataclass(frozen=True)
class Standing:
    """A submission's score and runs as both reports state them."""

    score: str      # with the rubric's digits
    full: str       # the full score
    counts: str     # ``4 of 6 runs valid; 2 flaky``
    build: dict     # its ``builds`` row ({} when there is none)
    median: tuple[float, int] | None  # median_time


def standing(report: Results, one: Scored) -> Standing:
    runs = one.all_runs()
    flakes = len(flaky_items([one]))
    counts = f"{sum(row['valid'] for row in runs)} of {len(runs)} runs valid" + (
        f"; {flakes} flaky" if flakes else "")
    return Standing(f"{one.score:.{report.rubric.digits}f}",
                    f"{report.rubric.full_score(report.items):g}", counts,
                    report.builds.get(one.name, {}), median_time(report, one))


def median_time(report: Results, one: Scored) -> tuple[float, int] | None:
    """The median of a submission's valid runs' times relative to our planner's, and
    over how many runs; None without any."""
    ratios = [r for r in (relative_time(row, report.calibration) for row in one.all_runs()
                          if row["valid"]) if r is not None]
    return (statistics.median(ratios), len(ratios)) if ratios else None


def item_verdict(rows: list[dict]) -> tuple[str, dict | None]:
    """An item's verdict over its repeats (``valid``, ``valid 3/3``, ``flaky: 2/4 valid``,
    ``invalid (parse)``, ``timed out 0/2``, ``not run``) and its first failing run."""
    if not rows:
        return "not run", None
    valid = sum(row["valid"] for row in rows)
    if valid == len(rows):
        return ("valid" if len(rows) == 1 else f"valid {valid}/{len(rows)}"), None
    failing = next(row for row in rows if not row["valid"])
    if valid:
        return f"flaky: {valid}/{len(rows)} valid", failing
    return failure_label(failing) + (f" 0/{len(rows)}" if len(rows) > 1 else ""), failing
