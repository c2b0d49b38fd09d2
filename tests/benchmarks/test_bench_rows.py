"""The row schema and its CSV form."""

import csv
import math
import random

import pytest

from benchmarks.rows import FIELD_NAMES, RunRow, RunStatus, read_csv, write_csv

# The columns the issue asks for, by the names the CSV uses.
REQUIRED = ("solved", "planning_seconds", "process_seconds", "path_length", "tree_nodes",
            "iterations", "peak_memory_mb", "exit_status", "problem", "vehicle", "planner",
            "seed", "valid", "status")


def random_row(rng: random.Random, solved: bool) -> RunRow:
    return RunRow(
        problem=rng.choice(["maze-10", "course-space-1", "open-500"]), family="maze",
        width=rng.randrange(1, 500), height=rng.randrange(1, 500),
        vehicle=rng.choice(["point", "spaceship", "left"]),
        planner=rng.choice(["rrt", "ompl-rrt"]), implementation="ours", seed=rng.randrange(99),
        time_limit=10.0, solved=solved,
        status=(RunStatus.SOLVED if solved else RunStatus.TIME_LIMIT).value,
        exit_status=0 if solved else 3, valid=True if solved else None,
        failure="" if solved else 'no solution, "quoted", with, commas',
        planning_seconds=rng.random() / 7, process_seconds=rng.random() * 3,
        path_length=rng.random() * 100 if solved else None,
        tree_nodes=rng.randrange(10 ** 6), iterations=rng.randrange(10 ** 7),
        trajectory_lines=rng.randrange(1, 999) if solved else None,
        peak_memory_mb=rng.random() * 100, corner_cuts=rng.randrange(3),
        validation_seconds=rng.random())


def test_schema_is_flat_and_has_the_required_columns():
    for name in REQUIRED:
        assert name in FIELD_NAMES
    assert len(set(FIELD_NAMES)) == len(FIELD_NAMES)


def test_csv_round_trip_is_exact(tmp_path):
    rng = random.Random(5)
    rows = [random_row(rng, solved=k % 3 != 0) for k in range(40)]
    path = tmp_path / "runs.csv"
    write_csv(rows, path)
    assert read_csv(path) == rows
    with open(path, newline="") as handle:
        records = list(csv.DictReader(handle))
    assert len(records) == len(rows)
    assert tuple(records[0]) == FIELD_NAMES
    # Missing values are empty cells; booleans are 0/1; floats keep every digit.
    unsolved = next(r for r, row in zip(records, rows) if not row.solved)
    assert unsolved["path_length"] == "" and unsolved["valid"] == ""
    assert unsolved["solved"] == "0"
    solved_index = next(k for k, row in enumerate(rows) if row.solved)
    assert float(records[solved_index]["planning_seconds"]) == rows[solved_index].planning_seconds


def test_time_falls_back_to_the_process_time_without_stats():
    row = random_row(random.Random(1), solved=False)
    assert row.time_seconds == row.planning_seconds
    bare = RunRow(**{**row.__dict__, "planning_seconds": None})
    assert bare.time_seconds == row.process_seconds
    nan = RunRow(**{**row.__dict__, "planning_seconds": math.nan})
    assert nan.time_seconds == row.process_seconds


def test_reading_rejects_a_file_without_the_schema(tmp_path):
    path = tmp_path / "other.csv"
    path.write_text("problem,planner\nmaze-10,rrt\n")
    with pytest.raises(ValueError, match="missing columns"):
        read_csv(path)
    empty = tmp_path / "empty.csv"
    empty.write_text("")
    assert read_csv(empty) == []
