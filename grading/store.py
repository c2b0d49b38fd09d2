"""The SQLite store of a grading run, ``grades.sqlite``: one ``builds`` row per
submission, one ``runs`` row per submission x problem x mode x repeat, one
``calibration`` row per problem x mode (our planner's time), each written when it
finishes (so an interrupted run resumes from what is there)."""

from __future__ import annotations

import sqlite3
from pathlib import Path

DB_NAME = "grades.sqlite"

BUILD_COLUMNS = ("submission", "ok", "reason", "exit_status", "wall_time", "log", "sandbox")
RUN_COLUMNS = ("submission", "problem", "mode", "repeat", "verdict", "valid",
               "failed_check", "message", "detail", "exit_status", "signal", "timed_out",
               "wall_time", "path_length", "trajectory_size", "tree_size", "output_bytes",
               "output_sha256", "sandbox", "pdf", "view", "log")
CALIBRATION_COLUMNS = ("problem", "mode", "verdict", "valid", "wall_time", "command")

_SCHEMA = """
CREATE TABLE IF NOT EXISTS builds (
    submission TEXT PRIMARY KEY, ok INTEGER NOT NULL, reason TEXT, exit_status INTEGER,
    wall_time REAL, log TEXT, sandbox TEXT,
    finished TEXT NOT NULL DEFAULT (datetime('now')));
CREATE TABLE IF NOT EXISTS runs (
    submission TEXT NOT NULL, problem TEXT NOT NULL, mode TEXT NOT NULL,
    repeat INTEGER NOT NULL DEFAULT 0,  -- 0, 1, ...: the runs of one problem and mode
    verdict TEXT NOT NULL,          -- valid, invalid, planner failed, build failed
    valid INTEGER NOT NULL, failed_check TEXT, message TEXT, detail TEXT,
    exit_status INTEGER, signal INTEGER, timed_out INTEGER, wall_time REAL,
    path_length REAL, trajectory_size INTEGER, tree_size INTEGER, output_bytes INTEGER,
    output_sha256 TEXT,             -- of its stdout, when it printed something
    sandbox TEXT, pdf TEXT, log TEXT,
    view TEXT,                      -- a failing run's browser view (html/SUBMISSION/...)
    finished TEXT NOT NULL DEFAULT (datetime('now')),
    PRIMARY KEY (submission, problem, mode, repeat));
CREATE TABLE IF NOT EXISTS calibration (
    problem TEXT NOT NULL, mode TEXT NOT NULL, verdict TEXT NOT NULL, valid INTEGER NOT NULL,
    wall_time REAL, command TEXT,
    finished TEXT NOT NULL DEFAULT (datetime('now')),
    PRIMARY KEY (problem, mode));
"""
# A store written before runs were repeated: its rows become repeat 0.
_UPGRADE = """
ALTER TABLE runs RENAME TO runs_before_repeats;
{schema}
INSERT INTO runs ({columns}) SELECT {columns} FROM runs_before_repeats;
DROP TABLE runs_before_repeats;
"""


class Store:
    """The database of one ``--out`` folder; every write is its own transaction."""

    def __init__(self, out: Path):
        self.path = out / DB_NAME
        self.db = sqlite3.connect(self.path, timeout=30)
        self.db.row_factory = sqlite3.Row
        columns = [row[1] for row in self.db.execute("PRAGMA table_info(runs)")]
        if columns and "repeat" not in columns:
            kept = ", ".join(column for column in columns if column in RUN_COLUMNS
                             or column == "finished")
            self.db.executescript("BEGIN;" + _UPGRADE.format(schema=_SCHEMA, columns=kept)
                                  + "COMMIT;")
        elif columns and "view" not in columns:  # written before runs had views
            self.db.execute("ALTER TABLE runs ADD COLUMN view TEXT")
        self.db.executescript(_SCHEMA)

    def close(self) -> None:
        self.db.close()

    def clear(self) -> None:
        """Forget every build and run (``--rerun``)."""
        with self.db:
            for table in ("runs", "builds", "calibration"):
                self.db.execute(f"DELETE FROM {table}")

    def builds(self) -> dict[str, dict]:
        return {row["submission"]: dict(row) for row in self.db.execute("SELECT * FROM builds")}

    def finished_runs(self) -> set[tuple[str, str, str, int]]:
        return {tuple(row) for row in
                self.db.execute("SELECT submission, problem, mode, repeat FROM runs")}

    def calibration(self) -> dict[tuple[str, str], dict]:
        return {(row["problem"], row["mode"]): dict(row)
                for row in self.db.execute("SELECT * FROM calibration")}

    def add_calibration(self, row: dict) -> None:
        self._insert("calibration", CALIBRATION_COLUMNS, row)

    def add_build(self, row: dict) -> None:
        self._insert("builds", BUILD_COLUMNS, row)

    def add_run(self, row: dict) -> None:
        self._insert("runs", RUN_COLUMNS, row)

    def runs(self) -> list[dict]:
        return [dict(row) for row in
                self.db.execute("SELECT * FROM runs ORDER BY submission, problem, mode, repeat")]

    def _insert(self, table: str, columns: tuple[str, ...], row: dict) -> None:
        marks = ", ".join("?" for _ in columns)
        with self.db:
            self.db.execute(f"INSERT OR REPLACE INTO {table} ({', '.join(columns)}) "
                            f"VALUES ({marks})", [row.get(name) for name in columns])
