"""Summaries and the Markdown report, on rows made up for the purpose."""

import random
import statistics

import numpy as np

from benchmarks import report
from benchmarks.report import Spread, markdown_report, median_ratio, summary_table
from benchmarks.rows import RunRow


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
    rows += [row("rrt", "course-space-1", s, 30.0, solved=False, vehicle="spaceship",
                 family="course", size=10) for s in range(2)]
    bad = row("rrt", "maze-20", 9, 0.3)
    bad = RunRow(**{**bad.__dict__, "solved": False, "valid": False, "status": "invalid",
                    "failure": "Trajectory collides with an obstacle! | line 4"})
    rows.append(bad)
    text = markdown_report(rows, {"preset": "test", "date": "2025-01-01", "host": "h"})
    assert "## Point vehicle" in text and "## Spaceship (-grad)" in text
    assert "## Left-only" not in text
    assert text.count("| Planner | Success % | Time (s) | Path length | Tree nodes |") == 2
    assert "Trajectory collides with an obstacle!" in text and "invalid" in text
    targets = {check.target: check for check in report.check_targets(rows)}
    success = targets["point: rrt solves 100% within 10 s up to 500x500"]
    assert success.met is False and "maze-20 0/1" in success.detail
    ship = targets["spaceship: rrt solves 100% within 30 s up to 100x100"]
    assert ship.met is False
    speed = targets["point: rrt median planning time on all problems at most OMPL RRT's"]
    assert speed.met is True  # 0.02 s median (course) ... vs OMPL's 0.05 s


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
