"""Cost against time: an optimizing run's progress line through the harness into
runs.sqlite's progress table and the convergence report, the optimal presets, the
plots, and OMPL's RRT* and Informed RRT* in the peer planner."""

import dataclasses
import math
import sqlite3
import subprocess
import sys

import pytest

from benchmarks import catalog, convergence, optimal
from benchmarks.harness import RunSpec, parse_progress, run_one
from benchmarks.rows import read_csv
from benchmarks.store import DB_NAME, RunStore, progress_samples
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from test_bench_harness import SIMPLE, ScriptPlanner
from test_bench_report import row as made_up
from validator.checks import validate_output

PROGRESS = "0.2:5 0.7:3 1.4:2"


def optimizing(planner, problem, seed, progress, limit=10.0, cost=None, vehicle="point"):
    """A made-up solved optimizing run: its progress, its final (validated) cost."""
    pairs = parse_progress(f"x progress: {progress}")
    base = made_up(planner, problem, seed, limit, solved=bool(pairs), vehicle=vehicle)
    return dataclasses.replace(
        base, time_limit=limit, progress=progress,
        first_solution_seconds=pairs[0][0] if pairs else None,
        best_cost=(cost if cost is not None else pairs[-1][1]) if pairs else None)


@pytest.fixture(scope="module")
def answer() -> str:
    """A valid answer to course-simple-0 (our rrt's)."""
    return subprocess.run([sys.executable, "-m", "rrt_cli", "-seed", "1"],
                          stdin=open(SIMPLE), capture_output=True, text=True,
                          check=True).stdout


def fake_optimizer(answer: str, progress: str = PROGRESS) -> ScriptPlanner:
    """A stand-in optimizing planner: the answer, a stats line and a progress line."""
    script = (f"import sys; sys.stdout.write({answer!r}); sys.stderr.write("
              f"'fake stats: status=solved iterations=9 tree_nodes=9 planning_seconds=2.0 "
              f"cost=2 first_solution_seconds=0.2\\nfake kernels: x\\n"
              f"fake progress: {progress}\\n')")
    return ScriptPlanner("fake", "ours", "fake", frozenset(Vehicle), script=script)


def cells(table: list[str], planner: str) -> list[str]:
    """The cells of the table's line of ``planner`` (its label)."""
    line = next(text for text in table if f"| {planner} " in text)
    return [cell.strip() for cell in line.split("|")[1:-1]]


def test_progress_lines_are_parsed_keeping_improvements_only():
    text = ("rrt_cli stats: status=solved\nrrt_cli progress: 0.1:9 0.3:4 0.2:7 0.5:4 "
            "junk 0.6:nan -1:1 0.9:3.5\n")
    assert parse_progress(text) == ((0.1, 9.0), (0.2, 7.0), (0.3, 4.0), (0.9, 3.5))
    assert parse_progress("rrt_cli stats: status=solved\n") == ()


def test_a_fake_optimizing_run_reaches_the_row_the_store_and_the_table(tmp_path, answer):
    row = run_one(RunSpec(fake_optimizer(answer), Vehicle.POINT, SIMPLE, 1, 2.0))
    assert row.solved, row
    assert parse_progress(f"x progress: {row.progress}") == ((0.2, 5.0), (0.7, 3.0),
                                                             (1.4, 2.0))
    assert row.first_solution_seconds == 0.2
    # The final cost is the validator's, not the planner's claim (cost=2).
    expected = validate_output(parse_problem(SIMPLE.read_text()), Vehicle.POINT, answer).cost
    assert row.best_cost == pytest.approx(expected) and row.best_cost != 2.0
    with RunStore(tmp_path) as store:
        store.add(row)
        assert list(store.rows().values()) == [row]  # progress rebuilt from its samples
    with sqlite3.connect(tmp_path / DB_NAME) as db:
        samples = db.execute("SELECT time, best_cost FROM progress ORDER BY time").fetchall()
    assert samples[0] == (0.2, 5.0) and (0.7, 3.0) in samples and (1.4, 2.0) in samples
    assert {cost for t, cost in samples if 0.7 <= t < 1.4} == {3.0}
    assert max(t for t, _ in samples) <= 2.0 and len(samples) > 30  # every 0.05 s
    # The cost at 1 s is the last improvement at or before 1 s.
    assert convergence.cost_at(row, 1.0) == 3.0 and convergence.cost_at(row, 0.1) == math.inf
    assert cells(convergence.convergence_table([row], (1.0,)), "fake (ours)")[5] == "3 [3, 3]"


def test_samples_hold_the_best_cost_so_far():
    run = optimizing("rrtstar", "p", 1, "0.12:4 0.31:2", limit=0.5)
    samples = progress_samples(run, interval=0.1)
    assert samples == [(0.12, 4.0), (0.2, 4.0), (0.3, 4.0), (0.31, 2.0),
                       (0.4, 2.0), (0.5, 2.0)]
    assert progress_samples(made_up("rrt", "p", 1, 0.3)) == []  # no progress: no samples
    # Times are the planner's word: samples stop at the time limit whatever it claims.
    liar = dataclasses.replace(optimizing("rrtstar", "p", 1, "0.1:4 1e12:2", limit=1.0),
                               planning_seconds=1e15)
    samples = progress_samples(liar)
    assert len(samples) == 20 and samples[-2:] == [(1.0, 4.0), (1e12, 2.0)]


def test_the_table_gives_medians_at_each_checkpoint_and_ratios_to_ompl():
    ours = [optimizing("rrtstar", "p", 1, "0.2:5 0.7:3 1.4:2"),
            optimizing("rrtstar", "p", 2, "0.5:6 1.0:4 3:1"),
            optimizing("rrtstar", "p", 3, "0.9:7")]
    theirs = [optimizing("ompl-rrtstar", "p", s, "0.1:8 5:5") for s in (1, 2, 3)]
    table = convergence.convergence_table(ours + theirs, (1.0, 10.0))
    # At 1 s: 3, 4 (an improvement at exactly 1 s counts), 7; at 10 s: 2, 1, 7.
    assert cells(table, "rrtstar (ours)")[3:] == ["3/3", "0.5", "4 [3, 7]", "2 [1, 7]", "0.50×", "0.40×", "5.00×"]
    # Against the shortest path (point vehicle): the median at the last checkpoint.
    table = convergence.convergence_table(ours + theirs, (1.0, 10.0), {"p": 1.6})
    assert cells(table, "rrtstar (ours)")[-1] == "1.25×"
    assert cells(table, "OMPL RRT*")[-1] == "3.12×"
    # arm2 has a yardstick too; the ships, whose costs are not a point's, have none.
    arm = [optimizing("rrtstar", "arm2-pair1", s, "0.5:6 2:5.5", vehicle="arm2")
           for s in (1, 2)]
    ship = [optimizing("sst", "p", 1, "0.5:3", vehicle="spaceship")]
    table = convergence.convergence_table(arm + ship, (1.0, 10.0), {"p": 1.6,
                                                                   "arm2-pair1": 5.0})
    assert next(c for c in table if "arm2-pair1" in c).split("|")[-2].strip() == "1.10×"
    assert next(c for c in table if "spaceship" in c).split("|")[-2].strip() == "–"


def test_the_table_compares_with_ompl_in_cpp_when_it_ran():
    ours = [optimizing("rrtstar", "p", s, "0.5:4 5:2") for s in (1, 2, 3)]
    python = [optimizing("ompl-rrtstar", "p", s, "0.1:8") for s in (1, 2, 3)]
    cpp = [optimizing("ompl-cpp-rrtstar", "p", s, "0.25:5 2:1") for s in (1, 2, 3)]
    assert not any("C++" in line for line in convergence.convergence_table(ours + python, (1.0,)))
    table = convergence.convergence_table(ours + python + cpp, (1.0, 10.0))
    assert [cell.strip() for cell in table[0].split("|")[11:14]] == [
        "vs OMPL C++ at 1 s", "vs OMPL C++ at 10 s", "First solution vs OMPL C++"]
    # Ours 4 and 2 against C++'s 5 and 1; first solutions 0.5 s against 0.25 s.
    assert cells(table, "rrtstar (ours)")[7:] == ["0.50×", "0.25×", "5.00×",
                                                  "0.80×", "2.00×", "2.00×"]
    assert cells(table, "OMPL C++ RRT*")[2] == "OMPL C++ RRT*"


def test_the_table_counts_the_answers_that_cut_corners_when_any_did():
    ours = [optimizing("rrtstar", "p", s, "0.5:4") for s in (1, 2)]
    theirs = [dataclasses.replace(optimizing("ompl-rrtstar", "p", s, "0.5:3"), corner_cuts=cuts)
              for s, cuts in ((1, 0), (2, 5))]
    assert "cutting corners" not in convergence.convergence_table(ours, (1.0,))[0]
    table = convergence.convergence_table(ours + theirs, (1.0,))
    assert table[0].split("|")[-2].strip() == "Answers cutting corners"
    assert cells(table, "rrtstar (ours)")[-1] == "0/2"
    assert cells(table, "OMPL RRT*")[-1] == "1/2"


def test_an_unsolved_majority_has_no_median():
    runs = [optimizing("rrtstar", "p", 1, "0.5:3"), optimizing("rrtstar", "p", 2, ""),
            optimizing("rrtstar", "p", 3, "")]
    assert convergence.median_interval([convergence.cost_at(r, 1.0) for r in runs])[0] \
        == math.inf
    assert convergence.median_interval(list(range(1, 21))) == (10.5, 6, 15)


def test_planner_arena_loads_a_store_with_progress(tmp_path):
    database = pytest.importorskip(
        "plannerarena.database", reason="plannerarena is not installed (the project's "
        "[arena] extra)")
    rows = [optimizing(planner, "open-20", seed, "0.2:5 0.7:3 1.4:2", limit=2.0)
            for planner in ("rrtstar", "ompl-rrtstar") for seed in (1, 2)]
    with RunStore(tmp_path) as store:
        for run in rows:
            store.add(run)
    data = database.load_database(tmp_path / DB_NAME)
    progress = data["progress"]
    assert progress.columns == ["runid", "time", "best cost"]  # OMPL's, "_" read as " "
    assert len(progress) == 4 * len(progress_samples(rows[0]))
    assert set(progress["runid"].to_list()) == set(data["runs"]["id"].to_list())
    assert len(data["runs"]) == 4 and "best cost" in data["attributes"]


def test_the_preset_skips_what_it_cannot_run_with_one_line_each():
    said = []
    preset = dataclasses.replace(optimal.OPTIMAL_PRESETS["optimal-smoke"],
                                 planners=("nosuch", "rrt", "ompl-sst", "ompl-rrtstar"))
    chosen = optimal.optimal_planners(preset, True, said.append)
    assert len(said) == 3 and all(line.endswith("skipped") for line in said)
    assert [line.split(":")[2].strip() for line in said] == ["nosuch", "rrt", "ompl-sst"]
    if catalog.ompl_installed():
        assert [(p.id, p.optimize) for p in chosen] == [("ompl-rrtstar", True)]
        assert chosen[0].command(Vehicle.POINT, 1, 1.0)[-1] == "-optimize"


# Slow: choosing a C++ peer builds the C++ programs (half a minute on a loaded machine).
@pytest.mark.slow
def test_the_cpp_sst_peer_plans_for_both_ships_and_every_kinodynamic_system():
    said = []
    cpp = optimal._ompl_cpp_choice("ompl-cpp-sst", said.append)
    if cpp is None:
        pytest.skip("; ".join(said) or "the OMPL C++ programs do not build here")
    assert cpp.vehicles == {Vehicle.SPACESHIP, Vehicle.LEFT_SPACESHIP}
    assert cpp.systems == set(catalog.KINODYNAMIC_SYSTEMS)
    assert cpp.command(None, 1, 2.0)[2:4] == ["benchmarks.ompl_cpp_planner", "-planner"]


def test_plots_draw_with_one_run_and_with_twenty(tmp_path):
    pytest.importorskip("matplotlib")
    from benchmarks.plots import render
    for seeds in (1, 20):
        rows = [optimizing(planner, problem, seed, f"{0.1 * seed}:{9 - seed * 0.1} "
                           f"{0.5 + seed * 0.1}:{5 - seed * 0.05}", limit=10.0)
                for planner in ("rrtstar", "ompl-rrtstar") for problem in ("a", "b")
                for seed in range(1, seeds + 1)]
        done = render(rows, tmp_path / f"plots-{seeds}.pdf")
        names = [plot.name for plot, _ in done]
        assert names == ["success-point", "convergence-point-1"]
        svg = done[1][1]
        for planner in ("rrtstar", "ompl-rrtstar"):
            assert f'id="convergence-point-1-median-point-{planner}-a"' in svg
            assert f'id="convergence-point-1-band-point-{planner}-b"' in svg
        assert (tmp_path / f"plots-{seeds}.pdf").stat().st_size > 1000


# A long end-to-end run (the command, both planners, OMPL's): CI only.
@pytest.mark.slow
def test_the_smoke_preset_runs_ompl_rrtstar_end_to_end(tmp_path):
    pytest.importorskip("ompl", reason="the ompl package is not installed")
    from benchmarks.cli import main
    out = tmp_path / "out"
    assert main(["--preset", "optimal-smoke", "--planners", "ompl-rrtstar", "--problems",
                 "course-simple-0", "--seeds", "2", "--time", "1", "--no-generate",
                 "--workers", "1", "--out", str(out)]) == 0
    rows = read_csv(out / "runs.csv")
    assert len(rows) == 2 and all(r.solved and r.progress for r in rows)
    assert all(parse_progress(f"x progress: {r.progress}")[-1][1] == pytest.approx(
        r.best_cost, rel=1e-8) for r in rows)  # OMPL's best cost is our cost
    report = (out / "report.md").read_text()
    assert "| point    | course-simple-0 | OMPL RRT*" in report
    with sqlite3.connect(out / DB_NAME) as db:
        assert db.execute("SELECT COUNT(*) FROM progress").fetchone()[0] > 2
    assert 'id="convergence-point-1-median-point-ompl-rrtstar-course-simple-0"' in (
        out / "report.html").read_text()


@pytest.mark.slow
def test_the_smoke_preset_runs_ompl_in_cpp_end_to_end(tmp_path):
    from benchmarks.cli import main
    from benchmarks.ompl_cpp_programs import binary
    if binary("grid_ompl") is None or binary("family_ompl") is None:
        pytest.skip("no g++ or OMPL headers (apt-get install libompl-dev)")
    out = tmp_path / "out"
    assert main(["--preset", "optimal-smoke", "--planners", "ompl-cpp-rrtstar",
                 "ompl-cpp-informed", "--seeds", "2", "--time", "1", "--no-generate",
                 "--workers", "1", "--out", str(out)]) == 0
    rows = read_csv(out / "runs.csv")
    assert len(rows) == 8 and {r.implementation for r in rows} == {"ompl-cpp"}
    assert {r.problem for r in rows} == {"course-simple-0", "arm2-pair1"}
    assert all(r.solved and r.progress for r in rows)
    assert all(parse_progress(f"x progress: {r.progress}")[-1][1] == pytest.approx(
        r.best_cost, rel=1e-8) for r in rows)
    report = (out / "report.md").read_text()
    assert "| arm2     | arm2-pair1      | OMPL C++ Informed RRT*" in report


def test_the_ompl_peer_refuses_optimize_for_a_planner_that_stops(tmp_path):
    pytest.importorskip("ompl", reason="the ompl package is not installed")
    done = subprocess.run([sys.executable, "-m", "benchmarks.ompl_planner", "-planner", "rrt",
                           "-optimize"], stdin=open(SIMPLE), capture_output=True, text=True)
    assert done.returncode == 2 and done.stdout == ""  # usage, then the one error line
    assert done.stderr.splitlines()[-1] == ("ompl_planner: error: -optimize works with "
                                            "-planner rrtstar or informed")


@pytest.mark.slow
@pytest.mark.parametrize("planner", ["rrtstar", "informed"])
@pytest.mark.parametrize("problem", ["arm2-pair2", "rigid2-scene1"])
def test_ompl_optimizers_on_the_family_report_our_cost(planner, problem):
    pytest.importorskip("ompl", reason="the ompl package is not installed")
    choice = catalog.PlannerChoice("ompl-" + planner, "ompl", planner, frozenset(),
                                   frozenset(catalog.GEOMETRIC_SYSTEMS), optimize=True)
    path = catalog.ROOT / "benchmarks" / "problems" / "family" / f"{problem}.kp"
    run = run_one(RunSpec(choice, None, path, 1, 3.0))
    assert run.solved, run
    pairs = parse_progress(f"x progress: {run.progress}")
    # arm2 (a Python objective) and rigid2 (OMPL's own, or Informed's Python one):
    # the last best cost OMPL reports is the validator's cost of the printed answer.
    assert pairs[-1][1] == pytest.approx(run.best_cost, rel=1e-8)
    assert pairs[0][0] == run.first_solution_seconds


def test_ompl_log_reader_reads_the_progress_of_optimizing_runs(tmp_path):
    tools = pytest.importorskip("ompl.tools")
    from benchmarks.ompl_log import LogHeader, write_logs
    rows = [optimizing(planner, "open-20", seed, progress, limit=1.0)
            for planner in ("rrtstar", "ompl-rrtstar")
            for seed, progress in ((1, "0.2:5 0.7:3"), (2, ""), (3, "0.12:4"))]
    paths = write_logs(rows, tmp_path / "logs", LogHeader(hostname="h", date="d"))
    database = tmp_path / "bench.db"
    tools.readBenchmarkLog(str(database), [str(p) for p in paths], False)
    with sqlite3.connect(database) as db:
        found = db.execute("SELECT runs.seed, progress.time, progress.best_cost FROM progress "
                           "JOIN runs ON runs.id = runid JOIN plannerConfigs ON "
                           "plannerConfigs.id = runs.plannerid WHERE plannerConfigs.name = "
                           "'rrtstar (ours)' ORDER BY runs.seed, progress.time").fetchall()
    expected = [(seed, t, c) for seed, run in ((1, rows[0]), (3, rows[2]))
                for t, c in progress_samples(run)]
    assert found == expected and (1, 0.7, 3.0) in found and (3, 0.15, 4.0) in found


def test_the_preset_picks_up_an_optimizing_planner_once_registered(monkeypatch):
    from rrt_cli import planners
    monkeypatch.delitem(planners.PLANNERS, "informed", raising=False)
    monkeypatch.setitem(planners.PLANNERS, "rrtstar", planners.PlannerEntry(
        "rrt_cli.planners.rrt", planners.GEOMETRIC, "a stand-in", optimizing=True))
    monkeypatch.setitem(planners.PLANNERS, "sst", planners.PlannerEntry(
        "rrt_cli.planners.rrt", planners.KINODYNAMIC, "a stand-in", optimizing=True))
    preset = optimal.OPTIMAL_PRESETS["optimal"]
    chosen = {p.id: p for p in optimal.optimal_planners(preset, False, lambda line: None)}
    assert sorted(chosen) == ["rrtstar", "sst"]
    specs = optimal.optimal_specs(preset, list(chosen.values()), 2, 10.0)
    runs = {(s.planner.id, s.vehicle.value if s.vehicle else "family", s.problem.stem)
            for s in specs}
    assert ("rrtstar", "point", "maze-10") in runs and ("rrtstar", "family", "arm2-pair3") in runs
    assert ("sst", "left", "space-2") in runs and ("sst", "family", "car1-scene1") in runs
    assert not {r for r in runs if r[0] == "rrtstar" and r[1] in ("spaceship", "left")}
    assert not {r for r in runs if r[0] == "sst" and r[2].startswith(("arm2", "rigid2"))}
    assert len(specs) == 2 * len(runs)
    assert all(s.planner.command(s.vehicle, 1, 10.0)[-1] == "-optimize" for s in specs)
