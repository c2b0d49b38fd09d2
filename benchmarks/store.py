"""The resumable SQLite store of benchmark runs, in OMPL's benchmark database layout.

The tables are those ``ompl_benchmark_statistics`` makes from OMPL's logs (so Planner
Arena's loader reads the file): ``experiments`` (one per problem and vehicle, as in
``ompl_log``), ``plannerConfigs`` (one per planner label and settings), ``enums``
(the status names), ``runs``, whose columns are OMPL's run properties (``time``,
``solved``, ``memory``, ...) followed by every field of a :class:`RunRow` not among them
(``harness_status`` and ``harness_planner`` for the fields whose names OMPL's loader
gives other values), and ``progress``: an optimizing run's best cost over time, as
OMPL's Benchmark samples its planners' ``best cost`` progress property (every
``convergence.PROGRESS_INTERVAL`` seconds, from the first solution to the run's end), plus the
instants of the improvements themselves, from which the row's ``progress`` field is
rebuilt (that field has no column in ``runs``). A row is
written, in its own transaction, as its run finishes; a run is known by problem,
vehicle, planner, seed and time limit. The store remembers what its runs were made
with (:func:`code_fingerprint`: the source of our packages and ``--strict``); opened
with anything else, or holding another layout of the tables, it starts afresh.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import platform
import sqlite3
from pathlib import Path

from benchmarks.catalog import label
from benchmarks.convergence import progress_samples
from benchmarks.generator import problem_id
from benchmarks.harness import RunSpec, progress_text
from benchmarks.ompl_log import LIBRARY, PROPERTIES, STATUS_NAMES, VERSION, experiment_name
from benchmarks.rows import FIELD_NAMES, Closing, RunRow
from cli_common import parse_any_problem

DB_NAME = "runs.sqlite"
_RENAMED = {"status": "harness_status", "planner": "harness_planner"}
"""RunRow fields whose name OMPL uses for another value (its loader names the planner
configuration's label ``planner``)."""
_OMPL_COLUMNS = tuple((name.replace(" ", "_"), kind, get) for name, kind, get in PROPERTIES)
_SQL_TYPES = {"bool": "BOOLEAN", "int": "INTEGER", "float": "REAL", "str": "TEXT"}
_SAME = {"process_time": "process_seconds", "solved": "solved", "correct_solution": "valid",
         "memory": "peak_memory_mb", "solution_length": "path_length",
         "graph_states": "tree_nodes", "iterations": "iterations", "seed": "seed"}
"""OMPL's columns that hold a RunRow field as it is (the field is not repeated)."""
_EXTRA_COLUMNS = tuple(
    (_RENAMED.get(field.name, field.name), _SQL_TYPES[field.type.split(" ")[0]], field.name)
    for field in dataclasses.fields(RunRow)
    if field.name not in _SAME.values() and field.name != "progress")
_KEY = ("problem", "vehicle", "planner", "seed", "time_limit")
_KEY_COLUMNS = tuple(_RENAMED.get(name, name) for name in _KEY)
_RUN_TABLES = ("progress", "runs", "plannerConfigs", "experiments")

_SCHEMA = f"""
CREATE TABLE IF NOT EXISTS experiments
    (id INTEGER PRIMARY KEY AUTOINCREMENT, name VARCHAR(512), totaltime REAL,
    timelimit REAL, memorylimit REAL, runcount INTEGER, version VARCHAR(128),
    hostname VARCHAR(1024), cpuinfo TEXT, date DATETIME, seed VARCHAR(24), setup TEXT);
CREATE TABLE IF NOT EXISTS plannerConfigs
    (id INTEGER PRIMARY KEY AUTOINCREMENT, name VARCHAR(512) NOT NULL, settings TEXT);
CREATE TABLE IF NOT EXISTS enums
    (name VARCHAR(512), value INTEGER, description TEXT, PRIMARY KEY (name, value));
CREATE TABLE IF NOT EXISTS runs
    (id INTEGER PRIMARY KEY AUTOINCREMENT, experimentid INTEGER, plannerid INTEGER,
    {", ".join(f'"{name}" {kind}' for name, kind, _ in _OMPL_COLUMNS + _EXTRA_COLUMNS)},
    FOREIGN KEY (experimentid) REFERENCES experiments(id) ON DELETE CASCADE,
    FOREIGN KEY (plannerid) REFERENCES plannerConfigs(id) ON DELETE CASCADE);
CREATE UNIQUE INDEX IF NOT EXISTS runs_key ON runs ({", ".join(_KEY_COLUMNS)});
CREATE TABLE IF NOT EXISTS progress
    (runid INTEGER, time REAL, best_cost REAL, PRIMARY KEY (runid, time),
    FOREIGN KEY (runid) REFERENCES runs(id) ON DELETE CASCADE);
CREATE TABLE IF NOT EXISTS harness (name TEXT PRIMARY KEY, value TEXT);
"""
_RUNS_COLUMNS = ("id", "experimentid", "plannerid",
                 *(name for name, _, _ in _OMPL_COLUMNS + _EXTRA_COLUMNS))
_PROGRESS_COLUMNS = ("runid", "time", "best_cost")
PACKAGES = ("planning_core", "cli_common", "rrt_cli", "validator", "benchmarks")
"""Whose source a stored run's result depends on."""


def code_fingerprint(strict: bool, root: Path = Path(__file__).resolve().parent.parent) -> str:
    """What a run's result depends on besides its key: every ``.py`` of ``PACKAGES``
    (name and bytes) and the validation's strictness."""
    digest = hashlib.sha256(b"strict" if strict else b"default")
    for package in PACKAGES:
        for path in sorted((root / package).rglob("*.py")):
            digest.update(str(path.relative_to(root)).encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


class RunStore(Closing):
    """``runs.sqlite`` of one ``--out`` folder."""

    def __init__(self, out: Path, date: str = ""):
        out.mkdir(parents=True, exist_ok=True)
        self.path = out / DB_NAME
        self.date = date
        self.db = sqlite3.connect(self.path, timeout=30)
        self.db.execute("PRAGMA FOREIGN_KEYS = ON")
        with self.db:
            if (self._columns("runs") not in ([], list(_RUNS_COLUMNS))  # another layout
                    or self._columns("progress") not in ([], list(_PROGRESS_COLUMNS))):
                for table in _RUN_TABLES:
                    self.db.execute(f"DROP TABLE IF EXISTS {table}")
            self.db.executescript(_SCHEMA)
            self.db.executemany("INSERT OR IGNORE INTO enums VALUES (?, ?, ?)",
                                [("status", value, name)
                                 for value, name in enumerate(STATUS_NAMES)])

    def close(self) -> None:
        self.db.close()

    def _columns(self, table: str) -> list[str]:
        return [found[1] for found in self.db.execute(f"PRAGMA table_info({table})")]

    def clear(self) -> None:
        """Forget every run (``--rerun``)."""
        with self.db:
            for table in _RUN_TABLES:
                self.db.execute(f"DELETE FROM {table}")

    def made_with(self, fingerprint: str) -> bool:
        """Keep the stored runs only if they were made with ``fingerprint``; else
        forget them. True when runs made with something else were forgotten."""
        found = self.db.execute("SELECT value FROM harness WHERE name = 'code'").fetchone()
        stale = found is not None and found[0] != fingerprint
        if stale:
            self.clear()
        with self.db:
            self.db.execute("INSERT OR REPLACE INTO harness VALUES ('code', ?)", (fingerprint,))
        return stale

    def rows(self) -> dict[tuple, RunRow]:
        """Every stored run by its key (:func:`key_of`)."""
        columns = {column: field for column, _, field in _EXTRA_COLUMNS}
        columns.update(_SAME)
        found = {}
        progress = self._progress()
        for run_id, *values in self.db.execute(
                f"SELECT id, {', '.join(map(_quoted, columns))} FROM runs"):
            record = dict(zip(columns.values(), values), progress=progress.get(run_id, ""))
            row = _to_row(record)
            found[key_of(row)] = row
        return found

    def _progress(self) -> dict[int, str]:
        """Each run's improvements, rebuilt from its samples: the instants where its
        best cost fell."""
        pairs: dict[int, list[tuple[float, float]]] = {}
        for run_id, seconds, cost in self.db.execute(
                "SELECT runid, time, best_cost FROM progress ORDER BY runid, time"):
            mine = pairs.setdefault(run_id, [])
            if not mine or cost < mine[-1][1]:
                mine.append((seconds, cost))
        return {run_id: progress_text(found) for run_id, found in pairs.items()}

    def add(self, row: RunRow) -> None:
        """Store one finished run (replacing an earlier run of the same key)."""
        columns = _OMPL_COLUMNS + _EXTRA_COLUMNS
        with self.db:
            experiment = self._experiment(row)
            planner = self._planner(row)
            self.db.execute("DELETE FROM runs WHERE "
                            + " AND ".join(f"{k} = ?" for k in _KEY_COLUMNS), key_of(row))
            values = [get(row) for _, _, get in _OMPL_COLUMNS] + [
                getattr(row, field) for _, _, field in _EXTRA_COLUMNS]
            run_id = self.db.execute(
                f"INSERT INTO runs (experimentid, plannerid, "
                f"{', '.join(_quoted(name) for name, _, _ in columns)}) "
                f"VALUES ({', '.join('?' for _ in range(len(columns) + 2))})",
                [experiment, planner, *values]).lastrowid
            self.db.executemany("INSERT INTO progress VALUES (?, ?, ?)",
                                [(run_id, seconds, cost)
                                 for seconds, cost in progress_samples(row)])
            self.db.execute("UPDATE experiments SET runcount = (SELECT COUNT(*) FROM runs "
                            "WHERE experimentid = ?1) WHERE id = ?1", (experiment,))

    def _experiment(self, row: RunRow) -> int:
        name = experiment_name(row.problem, row.vehicle)
        found = self.db.execute("SELECT id FROM experiments WHERE name = ? AND timelimit = ?",
                                (name, row.time_limit)).fetchone()
        if found:
            return found[0]
        return self.db.execute(
            "INSERT INTO experiments (name, totaltime, timelimit, memorylimit, runcount, "
            "version, hostname, cpuinfo, date, seed, setup) VALUES (?, 0, ?, 0, 0, ?, ?, '', "
            "?, '', ?)",
            (name, row.time_limit, f"{LIBRARY} {VERSION}", platform.node(), self.date,
             f"problem {row.problem} ({row.width}x{row.height}), vehicle {row.vehicle}")
        ).lastrowid

    def _planner(self, row: RunRow) -> int:
        name = label(row.planner, row.vehicle)
        # As ompl_benchmark_statistics stores a log's common properties.
        settings = f"implementation = {row.implementation}\n;harness id = {row.planner}\n;"
        found = self.db.execute("SELECT id FROM plannerConfigs WHERE name = ? AND settings = ?",
                                (name, settings)).fetchone()
        if found:
            return found[0]
        return self.db.execute("INSERT INTO plannerConfigs (name, settings) VALUES (?, ?)",
                               (name, settings)).lastrowid


def key_of(row: RunRow) -> tuple:
    """A run's identity in the store: problem, vehicle, planner, seed, time limit."""
    return tuple(getattr(row, name) for name in _KEY)


def spec_key(spec: RunSpec) -> tuple:
    """The key of the row ``spec``'s run will have (a family problem's vehicle is the
    system it names)."""
    vehicle = spec.vehicle.value if spec.vehicle is not None else _system(spec.problem)
    return (problem_id(spec.problem), vehicle, spec.planner.id, spec.seed,
            float(spec.time_limit))


@functools.lru_cache(maxsize=None)
def _system(path: Path) -> str:
    return parse_any_problem(path.read_text()).system_name


def _quoted(name: str) -> str:
    return f'"{name}"'


def _to_row(record: dict) -> RunRow:
    values = {name: record[name] for name in FIELD_NAMES}
    for field in dataclasses.fields(RunRow):
        if field.type.startswith("bool") and values[field.name] is not None:
            values[field.name] = bool(values[field.name])
    return RunRow(**values)
