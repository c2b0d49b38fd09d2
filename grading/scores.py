"""Each submission's runs by rubric item, and its score: an item's points times the
share of its repeats that were valid. Shared by gradebook.csv, report.md and
Gradescope's results.json."""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

from grading.rubric import KINOPLAN, MODE_FLAGS, Item, Rubric, score

Key = tuple[str, str]  # (problem, mode)


@dataclass(frozen=True)
class Scored:
    """One submission: its runs by item (each item's repeats in order) and its score."""

    name: str
    runs: dict[Key, list[dict]]
    score: float

    def share(self, key: Key) -> float:
        """The share of the item's repeats that were valid."""
        rows = self.runs.get(key, [])
        return sum(row["valid"] for row in rows) / len(rows) if rows else 0.0

    def all_runs(self) -> list[dict]:
        return [row for rows in self.runs.values() for row in rows]


def key(item_or_row) -> Key:
    if isinstance(item_or_row, dict):
        return item_or_row["problem"], item_or_row["mode"]
    return item_or_row.problem, item_or_row.mode


def scored(rubric: Rubric, items: list[Item], runs: list[dict]) -> list[Scored]:
    """Each submission that has runs, by name."""
    points = rubric.points(items)
    by_name: dict[str, dict[Key, list[dict]]] = defaultdict(lambda: defaultdict(list))
    for row in sorted(runs, key=lambda row: row["repeat"]):
        by_name[row["submission"]][key(row)].append(row)
    found = []
    for name in sorted(by_name):
        table = dict(by_name[name])
        shares = {k: sum(row["valid"] for row in rows) / len(rows) for k, rows in table.items()}
        found.append(Scored(name, table, score(points, shares, rubric.digits)))
    return found


def modes_used(items: list[Item]) -> list[str]:
    """The modes among the items, in the course's order (the .kp problems' last)."""
    present = {item.mode for item in items}
    return [mode for mode in (*MODE_FLAGS, KINOPLAN) if mode in present]


def flaky(rows: list[dict]) -> bool:
    """Valid on some of its repeats, not all."""
    valid = sum(row["valid"] for row in rows)
    return 0 < valid < len(rows)


def relative_time(row: dict, calibration: dict[Key, dict]) -> float | None:
    """A run's wall time over our planner's on the same problem and mode (None when
    either is missing or ours did not finish validly)."""
    ours = calibration.get(key(row))
    if not ours or not ours.get("valid") or not ours.get("wall_time") or row.get(
            "wall_time") is None:
        return None
    return row["wall_time"] / ours["wall_time"]


@dataclass(frozen=True)
class Results:
    """A grading's results as the reports read them."""

    rubric: Rubric
    items: list[Item]
    calibration: dict[Key, dict]   # our planner's row per item
    builds: dict[str, dict]        # by submission
    graded: list[Scored]           # by submission's name
    out: Path                      # links are relative to it


def results(config, outcome) -> Results:
    """From a GradeConfig and the Outcome of grading.grade.grade."""
    return Results(config.rubric, outcome.items, outcome.calibration, outcome.builds,
                   scored(config.rubric, outcome.items, outcome.runs), config.out)
