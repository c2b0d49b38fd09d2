"""The resumable SQLite store of benchmark runs (runs.sqlite, OMPL's database layout):
its rows for a tiny run, resume, --rerun, and the same runs on a Dask cluster."""

import sqlite3

import pytest

from benchmarks.cli import main
from benchmarks.rows import read_csv
from benchmarks.store import DB_NAME, RunStore, key_of

TINY = ["--preset", "smoke", "--planners", "rrt", "--problems", "course-simple-0",
        "--vehicles", "point", "--seeds", "2", "--no-generate", "--no-plots", "--no-ompl"]


def bench(out, *extra) -> int:
    return main([*TINY, "--workers", "1", "--out", str(out), *extra])


def verdicts(rows) -> dict:
    return {key_of(row): (row.status, row.valid) for row in rows}


def stored_ids(out) -> list[int]:
    with sqlite3.connect(out / DB_NAME) as db:
        return [row[0] for row in db.execute("SELECT id FROM runs ORDER BY id")]


def test_store_holds_every_run_in_ompl_layout(tmp_path, capsys):
    assert bench(tmp_path) == 0
    csv_rows = read_csv(tmp_path / "runs.csv")
    with RunStore(tmp_path) as store:
        stored = store.rows()
    assert sorted(stored.values(), key=key_of) == sorted(csv_rows, key=key_of)
    assert len(stored) == 2 and all(row.solved and row.valid for row in stored.values())
    with sqlite3.connect(tmp_path / DB_NAME) as db:
        runs = db.execute("SELECT experiments.name, plannerConfigs.name, time, solved, "
                          "memory, harness_status, runcount FROM runs JOIN experiments ON "
                          "experiments.id = experimentid JOIN plannerConfigs ON "
                          "plannerConfigs.id = plannerid").fetchall()
        status = db.execute("SELECT description FROM enums WHERE value = 6").fetchone()
    assert {run[:2] for run in runs} == {("course-simple-0_point", "rrt (ours)")}
    assert all(run[2] > 0 and run[3] == 1 and run[4] > 0 and run[5] == "solved"
               and run[6] == 2 for run in runs)
    assert status == ("Exact solution",)


def test_a_rerun_keeps_the_stored_runs_unless_asked(tmp_path, capsys):
    assert bench(tmp_path) == 0
    first = stored_ids(tmp_path)
    capsys.readouterr()
    assert bench(tmp_path) == 0
    assert "2 runs kept" in capsys.readouterr().err and stored_ids(tmp_path) == first
    assert len(read_csv(tmp_path / "runs.csv")) == 2  # the report still has every run
    assert bench(tmp_path, "--seeds", "3") == 0  # one run more: only it runs
    assert "2 runs kept" in capsys.readouterr().err
    assert stored_ids(tmp_path)[:2] == first and len(stored_ids(tmp_path)) == 3
    assert bench(tmp_path, "--rerun") == 0
    assert "kept" not in capsys.readouterr().err
    assert len(stored_ids(tmp_path)) == 2 and not set(stored_ids(tmp_path)) & set(first)



def test_runs_made_by_other_code_or_strictness_are_not_kept(tmp_path, capsys, monkeypatch):
    from benchmarks import store
    assert bench(tmp_path) == 0
    first = stored_ids(tmp_path)
    capsys.readouterr()
    assert bench(tmp_path, "--strict") == 0  # another validation: nothing kept
    err = capsys.readouterr().err
    assert "made by other code or another --strict" in err and "kept" not in err
    assert not set(stored_ids(tmp_path)) & set(first)
    strict_ids = stored_ids(tmp_path)
    fingerprint = store.code_fingerprint
    monkeypatch.setattr(store, "code_fingerprint", lambda strict: fingerprint(strict) + "x")
    assert bench(tmp_path, "--strict") == 0  # the same options, other source: nothing kept
    assert "made by other code" in capsys.readouterr().err
    assert not set(stored_ids(tmp_path)) & set(strict_ids)


def test_the_fingerprint_follows_the_source(tmp_path):
    from benchmarks.store import PACKAGES, code_fingerprint
    for package in PACKAGES:
        (tmp_path / package).mkdir()
        (tmp_path / package / "a.py").write_text("x = 1\n")
    before = code_fingerprint(False, tmp_path)
    assert code_fingerprint(False, tmp_path) == before != code_fingerprint(True, tmp_path)
    (tmp_path / "rrt_cli" / "a.py").write_text("x = 2\n")
    assert code_fingerprint(False, tmp_path) != before

def made_up_store(out):
    """A store written through its API: two planners on two problems, three seeds, one
    run unsolved."""
    from test_bench_report import row
    rows = [row(planner, problem, seed, 0.1 * seed + (planner == "rrt"), solved=seed != 3
                or planner == "rrt")
            for problem in ("maze-20", "open-20") for planner in ("rrt", "ompl-rrt")
            for seed in (1, 2, 3)]
    with RunStore(out, "2026-01-01T00:00:00") as store:
        for made_up in rows:
            store.add(made_up)
    return rows


# Planner Arena's loader and its plots (seconds of imports): CI only; in the unit run
# test_bench_optimal loads a store with the same loader.
@pytest.mark.slow
def test_planner_arena_loads_the_store_with_its_own_loader(tmp_path):
    database = pytest.importorskip(
        "plannerarena.database", reason="plannerarena is not installed (the project's "
        "[arena] extra; ./make.sh installs it where PyPI serves it)")
    from plannerarena.performance import boxplot, ecdf_plot, enums_plot
    rows = made_up_store(tmp_path)
    data = database.load_database(tmp_path / DB_NAME)
    assert sorted(data["problem_names"]) == ["maze-20_point", "open-20_point"]
    runs = data["runs"]
    assert len(runs) == len(rows)
    # The planner column is the configuration's label, not a column of ours beside it.
    assert sorted(runs["planner"].cast(str).unique()) == ["OMPL geometric RRT", "rrt (ours)"]
    assert not [name for name in runs.columns if name.endswith("_right")]
    assert {"time", "solved", "status", "memory", "solution length", "graph states",
            "harness planner"} <= set(data["attributes"])
    times = runs.filter(runs["experiment"] == "maze-20_point").sort("harness planner", "seed")
    expected = sorted((r for r in rows if r.problem == "maze-20"), key=lambda r: (r.planner,
                                                                                r.seed))
    assert times["time"].to_list() == [r.time_seconds for r in expected]
    assert times["solved"].to_list() == [int(r.solved) for r in expected]
    # Planner Arena's own plots of one experiment draw.
    status = data["enums"].filter(data["enums"]["name"] == "status")
    for plot in (boxplot(times, "time", [], "o", True), ecdf_plot(times, "time", []),
                 enums_plot(times, status, [])):
        plot.draw()


def test_a_store_of_another_layout_starts_afresh(tmp_path):
    with sqlite3.connect(tmp_path / DB_NAME) as db:  # runs with a column named planner
        db.execute("CREATE TABLE runs (id INTEGER PRIMARY KEY, experimentid INTEGER, "
                   "plannerid INTEGER, time REAL, planner TEXT)")
        db.execute("INSERT INTO runs VALUES (1, 1, 1, 0.5, 'rrt')")
    rows = made_up_store(tmp_path)
    with RunStore(tmp_path) as store:
        assert sorted(store.rows().values(), key=key_of) == sorted(rows, key=key_of)
    with sqlite3.connect(tmp_path / DB_NAME) as db:
        assert db.execute("SELECT COUNT(*) FROM progress").fetchone() == (0,)


def test_an_unreachable_scheduler_is_one_line_and_exit_2(tmp_path, capsys):
    dask = pytest.importorskip("dask")
    pytest.importorskip("distributed")
    capsys.readouterr()
    with dask.config.set({"distributed.comm.timeouts.connect": "0.1s"}), \
            pytest.raises(SystemExit) as stop:
        bench(tmp_path, "--scheduler", "tcp://127.0.0.1:9")
    err = capsys.readouterr().err
    assert stop.value.code == 2 and "Traceback" not in err
    assert "--scheduler tcp://127.0.0.1:9" in err.strip().splitlines()[-1]


@pytest.mark.slow
def test_a_dask_cluster_gives_the_local_pools_verdicts(tmp_path):
    distributed = pytest.importorskip("distributed")
    wider = ["--problems", "course-simple-0", "course-space-[01]", "--seeds", "2"]
    assert main([*TINY, *wider, "--workers", "2", "--out", str(tmp_path / "local")]) == 0
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        assert main([*TINY, *wider, "--workers", "2", "--out", str(tmp_path / "dask"),
                     "--scheduler", cluster.scheduler_address]) == 0
    local = read_csv(tmp_path / "local" / "runs.csv")
    assert len(local) == 6
    assert verdicts(read_csv(tmp_path / "dask" / "runs.csv")) == verdicts(local)
    with RunStore(tmp_path / "dask") as store:
        assert verdicts(store.rows().values()) == verdicts(local)
