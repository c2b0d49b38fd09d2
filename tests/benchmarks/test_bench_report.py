"""Summaries and the Markdown report, on rows made up for the purpose."""

import random
import statistics

import numpy as np

from benchmarks import report
from benchmarks.report import Spread, markdown_report, median_ratio, summary_table
from benchmarks.rows import RunRow
from benchmarks.targets import (ISSUE_5_TARGETS, TARGETS, PathLengthVsPlanner,
                                PlannerVsPlanner, SpeedVsReference, SuccessWithin)


def row(planner: str, problem: str, seed: int, seconds: float, solved: bool = True,
        vehicle: str = "point", length: float = 10.0, nodes: int = 100,
        size: int = 20, family: str = "maze", process: float | None = None) -> RunRow:
    return RunRow(
        problem=problem, family=family, width=size, height=size, vehicle=vehicle,
        planner=planner, implementation="ompl" if planner.startswith("ompl-") else "ours",
        seed=seed, time_limit=10.0, solved=solved,
        status="solved" if solved else "time_limit", exit_status=0 if solved else 3,
        valid=True if solved else None, failure="", planning_seconds=seconds,
        process_seconds=process if process is not None else seconds + 0.1,
        path_length=length if solved else None, tree_nodes=nodes, iterations=nodes,
        trajectory_lines=3 if solved else None, peak_memory_mb=20.0, corner_cuts=0,
        validation_seconds=0.0)


def test_spread_matches_numpy_and_statistics():
    rng = random.Random(2)
    for n in (1, 2, 7, 50):
        values = [rng.expovariate(3.0) for _ in range(n)]
        spread = Spread.of(values + [float("nan"), None])
        assert spread.count == n
        assert spread.mean == statistics.fmean(values)
        assert spread.std == (statistics.stdev(values) if n > 1 else 0.0)
        assert spread.median == statistics.median(values)
        assert abs(spread.p90 - float(np.percentile(values, 90))) < 1e-12


def test_median_ratio_uses_matching_problems_and_seeds():
    ours = [row("rrt", "a", s, t) for s, t in enumerate([1.0, 2.0, 3.0])]
    ours.append(row("rrt", "elsewhere", 0, 100.0))  # OMPL did not run it: left out
    theirs = [row("ompl-rrt", "a", s, t) for s, t in enumerate([4.0, 5.0, 6.0])]
    assert median_ratio(ours, theirs) == 2.0 / 5.0
    assert median_ratio(ours, theirs, process=True) == 2.1 / 5.1
    assert np.isnan(median_ratio(ours, []))


def parse_table(lines: list[str]) -> list[list[str]]:
    return [[cell.strip() for cell in line.strip("|").split("|")] for line in lines]


def test_summary_table_layout_and_values():
    rng = random.Random(4)
    rows = []
    for seed in range(10):
        rows.append(row("rrt", "p", seed, rng.uniform(0.1, 1.0), solved=seed != 0,
                        length=rng.uniform(5, 9), nodes=rng.randrange(50, 150)))
        rows.append(row("ompl-rrt", "p", seed, rng.uniform(1.0, 2.0)))
    rows.append(row("rrt", "p", 0, 5.0, vehicle="spaceship"))  # another vehicle's table
    table = parse_table(summary_table(rows, "point"))
    header = table[0]
    assert header[:5] == ["Planner", "Success %", "Time (s)", "Path length", "Tree nodes"]
    assert "Median time (s)" in header and "p90 time (s)" in header
    body = {line[0]: dict(zip(header, line)) for line in table[2:]}
    assert list(body) == ["rrt (ours)", "OMPL geometric RRT"]  # ours first
    ours = [r for r in rows if r.planner == "rrt" and r.vehicle == "point"]
    theirs = [r for r in rows if r.planner == "ompl-rrt"]
    assert body["rrt (ours)"]["Success %"] == "90"
    mean, std = statistics.fmean(r.planning_seconds for r in ours), \
        statistics.stdev(r.planning_seconds for r in ours)
    assert body["rrt (ours)"]["Time (s)"] == f"{mean:.3g} ± {std:.3g}"
    lengths = [r.path_length for r in ours if r.solved]  # solved runs only
    assert body["rrt (ours)"]["Path length"].startswith(f"{statistics.fmean(lengths):.4g} ± ")
    median = statistics.median(r.planning_seconds for r in ours)
    assert body["rrt (ours)"]["Median time (s)"] == f"{median:.3g}"
    ratio = median / statistics.median(r.planning_seconds for r in theirs)
    assert body["rrt (ours)"]["vs OMPL RRT, planning"] == f"{ratio:.2f}×"
    assert body["OMPL geometric RRT"]["vs OMPL RRT, planning"] == "1.00×"


def test_report_has_a_table_per_vehicle_targets_and_failures():
    rows = [row("rrt", "course-space-1", s, 0.01 * (s + 1), family="course", size=10)
            for s in range(3)]
    rows += [row("ompl-rrt", "course-space-1", s, 0.05, family="course", size=10)
             for s in range(3)]
    rows += [row("rrt", "maze-100", s, 30.0, solved=False, vehicle="spaceship", size=100)
             for s in range(2)]
    bad = row("rrt", "maze-500", 9, 0.3, size=500)
    bad = RunRow(**{**bad.__dict__, "solved": False, "valid": False, "status": "invalid",
                    "failure": "Trajectory collides with an obstacle! | line 4"})
    rows.append(bad)
    text = markdown_report(rows, {"preset": "test", "date": "2025-01-01", "host": "h"})
    assert "## Point vehicle" in text and "## Spaceship (-grad)" in text
    assert "## Left-only" not in text
    headers = [line for line in parse_table(text.splitlines())
               if line[:5] == ["Planner", "Success %", "Time (s)", "Path length", "Tree nodes"]]
    assert len(headers) == 2
    assert "Trajectory collides with an obstacle!" in text and "invalid" in text
    targets = {check.target: check for check in report.check_targets(rows)}
    success = targets["point: rrt solves 100% within 10 s up to 500x500"]
    assert success.met is False and success.detail == "3/4 runs; short on maze-500 0/1"
    ship = targets["spaceship: rrt solves 100% within 30 s up to 100x100"]
    assert ship.met is False
    assert "spaceship: rrt solves 100% within 120 s up to 200x200" not in targets  # no 200x200
    speed = targets["point: rrt median planning time on all problems at most OMPL RRT's"]
    assert speed.met is True  # 0.02 s median (course) ... vs OMPL's 0.05 s


def test_targets_without_runs_to_judge_are_left_out():
    # As the smoke preset runs: small course maps only, ours and OMPL's on the same seeds.
    rows = [row(planner, f"course-space-{k}", seed, 0.1, family="course", size=10,
                vehicle=vehicle)
            for vehicle in ("point", "spaceship") for planner in ("rrt", "ompl-rrt")
            for k in range(2) for seed in (1, 2)]
    listed = [check.target for check in report.check_targets(rows)]
    assert listed == [
        "point: rrt median planning time on all problems at most OMPL RRT's",
        "spaceship: rrt median planning time on all problems at most 0.5× OMPL RRT's",
        "point: rrt median whole-process time on course problems at most OMPL RRT's",
        "spaceship: rrt median whole-process time on course problems at most OMPL RRT's"]
    text = markdown_report(rows, {"preset": "smoke"})
    assert "solves 100%" not in text and "from 100x100 up" not in text
    # A map as large as the target's: the success target is judged on every map up to it.
    big = rows + [row("rrt", "open-500", 1, 2.0, family="open", size=500)]
    success = [c for c in report.check_targets(big) if "solves 100%" in c.target]
    assert [(c.target, c.met, c.detail) for c in success] == [
        ("point: rrt solves 100% within 10 s up to 500x500", True, "5/5 runs")]
    # OMPL's RRT on other seeds than ours: nothing to compare, no speed target.
    apart = [r for r in rows if r.planner == "rrt"]
    apart += [row("ompl-rrt", "course-space-0", 3, 0.1, family="course", size=10,
                  vehicle=vehicle) for vehicle in ("point", "spaceship")]
    assert report.check_targets(apart) == []


def test_a_target_with_too_few_runs_is_not_judged_and_one_run_has_no_spread():
    def runs(seeds):
        return [row(planner, f"course-space-{k}", seed, seconds, family="course", size=10)
                for planner, seconds in (("rrt", 0.1), ("ompl-rrt", 0.2))
                for k in range(2) for seed in range(1, seeds + 1)]
    target = "point: rrt median planning time on all problems at most OMPL RRT's"
    for seeds, verdict in ((1, ["–", "not judged: 1 run (need 5)"]),
                           (4, ["–", "not judged: 4 runs (need 5)"]),
                           (5, ["yes", "ratio 0.50×"])):
        text = markdown_report(runs(seeds), {"preset": "smoke"})
        lines = [line for line in parse_table(text.splitlines()) if line[0] == target]
        assert [line[1:] for line in lines] == [verdict]
        assert "at least 5 runs (seeds) of each planner" in text
    # One problem with a single run is enough to leave the target unjudged.
    short = [r for r in runs(5) if not (r.planner == "rrt" and r.problem == "course-space-1"
                                        and r.seed > 1)]
    table = parse_table(report.targets_table(short))
    assert [line[1:] for line in table if line[0] == target] == [
        ["–", "not judged: 1 run (need 5)"]]
    # One run: the summary table gives its value alone, never "± 0".
    summary = {line[0]: line for line in parse_table(summary_table(runs(1)[:1], "point"))}
    assert summary["rrt (ours)"][2] == "0.1"
    assert "±" not in " ".join(summary["rrt (ours)"])


def test_targets_come_from_the_table():
    assert TARGETS[-len(ISSUE_5_TARGETS):] == ISSUE_5_TARGETS
    assert {type(target) for target in TARGETS} == {
        SuccessWithin, SpeedVsReference, PlannerVsPlanner, PathLengthVsPlanner}
    rows = [row(planner, "maze-20", seed, seconds, length=length)
            for planner, seconds, length in (("rrt", 0.5, 10.0), ("prm", 0.2, 9.5),
                                             ("rrtconnect", 0.3, 12.0))
            for seed in (1, 2)]
    rows.append(row("prm", "maze-20", 3, 0.9, solved=False))
    own = (SuccessWithin("point", max_size=20, seconds=0.4),
           PlannerVsPlanner("point", "maze", ("prm", "rrtconnect"), factor=0.5, strict=True),
           PathLengthVsPlanner("point", "prm", factor=0.9),
           SpeedVsReference("point", min_size=1, factor=1.0))  # no OMPL rows: left out
    checks = report.check_targets(rows, targets=own)
    assert [(c.target, c.met, c.detail) for c in checks] == [
        ("point: prm solves 100% within 0.4 s up to 20x20", False,
         "2/3 runs; short on maze-20 2/3"),
        ("point: rrt solves 100% within 0.4 s up to 20x20", False,
         "0/2 runs; short on maze-20 0/2"),
        ("point: rrtconnect solves 100% within 0.4 s up to 20x20", True, "2/2 runs"),
        ("point: prm or rrtconnect median planning time on maze problems below 0.5× our rrt's",
         True, "prm 0.40×, rrtconnect 0.60×"),
        ("point: prm paths at least 10% shorter than our rrt's (mean over problems of the "
         "median-length ratio)", False, "mean ratio 0.95×; 10% shorter on 0/1 problems")]


def test_planner_targets_compare_with_our_own_rrt():
    rows = []
    for seed in range(3):
        for planner, maze_time, narrow_time in (("rrt", 1.0, 1.0), ("kpiece", 0.3, 0.7),
                                                ("rgrrt", 0.8, 0.9)):
            rows.append(row(planner, "maze-20", seed, maze_time, vehicle="spaceship"))
            rows.append(row(planner, "narrow-20", seed, narrow_time, vehicle="spaceship",
                            family="narrow"))
        for problem, rrt_length, star_length in (("maze-20", 10.0, 7.0), ("open-20", 10.0, 8.4)):
            family = problem.split("-")[0]
            rows.append(row("rrt", problem, seed, 0.5, length=rrt_length, family=family))
            rows.append(row("prmstar", problem, seed, 0.9, length=star_length, family=family))
        rows.append(row("rrtconnect", "maze-20", seed, 0.6))
    # An unsolved run has no length and does not count toward it.
    rows.append(row("prmstar", "open-20", 9, 10.0, solved=False, family="open"))
    targets = {check.target: check for check in report.planner_targets(rows)}
    maze = targets["spaceship: kpiece or rgrrt median planning time on maze problems "
                   "at most 0.5× our rrt's"]
    assert maze.met is True and maze.detail == "kpiece 0.30×, rgrrt 0.80×"
    narrow = targets["spaceship: kpiece or rgrrt median planning time on narrow problems "
                     "at most 0.5× our rrt's"]
    assert narrow.met is False
    assert not any(target.startswith("left:") for target in targets)  # no left-only rows
    star = next(check for target, check in targets.items() if target.startswith("point: prmstar"))
    assert star.met is True
    assert "mean ratio 0.77×" in star.detail and "on 1/2 problems" in star.detail
    connect = targets["point: rrtconnect median planning time on maze problems below our rrt's"]
    assert connect.met is False and connect.detail == "ratio 1.20×"


def test_path_quality_table_divides_median_lengths_by_the_shortest():
    rows = []
    for seed, (rrt_length, star_length) in enumerate(((12.0, 10.5), (15.0, 11.0), (13.0, 10.0))):
        rows.append(row("rrt", "maze-20", seed, 0.5, length=rrt_length))
        rows.append(row("prmstar", "maze-20", seed, 0.5, length=star_length))
    rows.append(row("rrt", "open-20", 0, 0.1, length=21.0, family="open"))
    rows.append(row("prmstar", "open-20", 0, 0.1, solved=False, family="open"))
    rows.append(row("rrt", "maze-20", 0, 0.5, vehicle="spaceship", length=1.0))  # not point
    table = parse_table(report.path_quality_table(rows, {"maze-20": 10.0, "open-20": 20.0}))
    assert table[0] == ["Problem", "Shortest", "prmstar (ours)", "rrt (ours)"]
    body = {line[0]: line[1:] for line in table[2:]}
    assert body["maze-20"] == ["10", "1.05", "1.3"]  # medians 10.5 and 13 over 10
    assert body["open-20"] == ["20", "–", "1.05"]    # prmstar solved nothing there
    assert body["mean over problems"] == ["", "1.05", f"{(1.3 + 1.05) / 2:.4g}"]


def test_prmstar_target_says_what_the_shortest_paths_would_score():
    rows = []
    for problem, rrt_length, star_length, shortest in (("maze-20", 10.0, 7.0, 6.0),
                                                        ("open-20", 10.0, 9.8, 9.7)):
        rows.append(row("rrt", problem, 1, 0.5, length=rrt_length))
        rows.append(row("prmstar", problem, 1, 0.9, length=star_length))
    shortest = {"maze-20": 6.0, "open-20": 9.7}
    star = next(c for c in report.planner_targets(rows, shortest)
                if c.target.startswith("point: prmstar"))
    assert star.met is False  # mean of 0.7 and 0.98
    assert star.detail.endswith("the shortest paths would score 0.78×, 20% shorter on 1/2")
    # Without the lengths (or with one missing) the detail stops at the run's own ratio.
    for partial in (None, {"maze-20": 6.0}):
        star = next(c for c in report.planner_targets(rows, partial)
                    if c.target.startswith("point: prmstar"))
        assert "shortest" not in star.detail
