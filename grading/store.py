"""The SQLite store of a grading run, ``grades.sqlite``: one ``builds`` row per
submission, one ``runs`` row per submission x problem x mode, each written when it
finishes (so an interrupted run resumes from what is there)."""

from __future__ import annotations

import sqlite3
from pathlib import Path

DB_NAME = "grades.sqlite"

BUILD_COLUMNS = ("submission", "ok", "reason", "exit_status", "wall_time", "log", "sandbox")
RUN_COLUMNS = ("submission", "problem", "mode", "verdict", "valid", "failed_check",
               "message", "detail", "exit_status", "signal", "timed_out", "wall_time",
               "path_length", "trajectory_size", "tree_size", "output_bytes", "sandbox", "pdf",
               "log")

_SCHEMA = """
CREATE TABLE IF NOT EXISTS builds (
    submission TEXT PRIMARY KEY, ok INTEGER NOT NULL, reason TEXT, exit_status INTEGER,
    wall_time REAL, log TEXT, sandbox TEXT,
    finished TEXT NOT NULL DEFAULT (datetime('now')));
CREATE TABLE IF NOT EXISTS runs (
    submission TEXT NOT NULL, problem TEXT NOT NULL, mode TEXT NOT NULL,
    verdict TEXT NOT NULL,          -- valid, invalid, planner failed, build failed
    valid INTEGER NOT NULL, failed_check TEXT, message TEXT, detail TEXT,
    exit_status INTEGER, signal INTEGER, timed_out INTEGER, wall_time REAL,
    path_length REAL, trajectory_size INTEGER, tree_size INTEGER, output_bytes INTEGER,
    sandbox TEXT, pdf TEXT, log TEXT,
    finished TEXT NOT NULL DEFAULT (datetime('now')),
    PRIMARY KEY (submission, problem, mode));
"""


class Store:
    """The database of one ``--out`` folder; every write is its own transaction."""

    def __init__(self, out: Path):
        self.path = out / DB_NAME
        self.db = sqlite3.connect(self.path, timeout=30)
        self.db.row_factory = sqlite3.Row
        self.db.executescript(_SCHEMA)

    def close(self) -> None:
        self.db.close()

    def clear(self) -> None:
        """Forget every build and run (``--rerun``)."""
        with self.db:
            self.db.execute("DELETE FROM runs")
            self.db.execute("DELETE FROM builds")

    def builds(self) -> dict[str, dict]:
        return {row["submission"]: dict(row) for row in self.db.execute("SELECT * FROM builds")}

    def finished_runs(self) -> set[tuple[str, str, str]]:
        return {(row[0], row[1], row[2]) for row in
                self.db.execute("SELECT submission, problem, mode FROM runs")}

    def add_build(self, row: dict) -> None:
        self._insert("builds", BUILD_COLUMNS, row)

    def add_run(self, row: dict) -> None:
        self._insert("runs", RUN_COLUMNS, row)

    def runs(self) -> list[dict]:
        return [dict(row) for row in
                self.db.execute("SELECT * FROM runs ORDER BY submission, problem, mode")]

    def _insert(self, table: str, columns: tuple[str, ...], row: dict) -> None:
        marks = ", ".join("?" for _ in columns)
        with self.db:
            self.db.execute(f"INSERT OR REPLACE INTO {table} ({', '.join(columns)}) "
                            f"VALUES ({marks})", [row.get(name) for name in columns])
