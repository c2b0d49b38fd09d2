"""The family presets (benchmarks/family.py), their report (family_report.py), the
planner-parameter runner and the command end to end on one small run."""

import csv
import os
import subprocess
import sys
from dataclasses import replace

import pytest

from benchmarks import catalog
from benchmarks.catalog import PlannerChoice
from benchmarks.family import (FAMILY_PRESETS, FamilyPreset, FamilyTable, family_runs,
                               table_problems)
from benchmarks.family_report import NOT_AVAILABLE, markdown_report, targets_table
from benchmarks.harness import parse_stats
from benchmarks.planner_params import typed_overrides
from benchmarks.rows import FIELD_NAMES, RunRow, read_csv, write_csv
from rrt_cli.planners import rrt

FAMILY = catalog.ROOT / "benchmarks" / "problems" / "family"


def choice(name: str, *systems: str) -> PlannerChoice:
    return PlannerChoice(name, "ompl" if name.startswith("ompl-") else "ours",
                         name.removeprefix("ompl-"), frozenset(), frozenset(systems))


def test_a_table_runs_only_the_planners_that_plan_for_each_problems_system():
    preset = FamilyPreset("t", (FamilyTable("p", ("pendulum-t3", "arm2-pair1"),
                                            ("rrt", "kpiece", "prm")),), 2, 1.0)
    available = [choice("rrt", "pendulum", "arm2"), choice("prm", "arm2"),
                 choice("rgrrt", "pendulum")]
    runs = [(r.planner.id, r.problem.stem) for r in family_runs(preset, available)]
    # kpiece is not available at all; prm only for the arm; rgrrt is not in the table
    assert runs == [("rrt", "arm2-pair1"), ("prm", "arm2-pair1"), ("rrt", "pendulum-t3")]
    narrowed = family_runs(preset, available, ("pendulum-*",))
    assert [(r.planner.id, r.problem.stem) for r in narrowed] == [("rrt", "pendulum-t3")]


def test_the_presets_name_seed_000s_and_seed_004s_problems():
    tables = FAMILY_PRESETS["family"].tables
    names = [p.stem for table in tables for p in table_problems(table)]
    assert names == ["car2-corridors", "pendulum-t3", "pendulum-t5", "pendulum-t10",
                     "car1-scene1", "car1-scene2", "car1-scene3"]
    assert FAMILY_PRESETS["family"].runs == 100
    geometric = [p.stem for t in FAMILY_PRESETS["family-geometric"].tables
                 for p in table_problems(t)]
    assert [n for n in geometric if n.startswith("arm2-pair")] == [f"arm2-pair{i}"
                                                                   for i in range(1, 6)]
    sweep = FAMILY_PRESETS["family-sweep"]
    every = sorted(p.name for p in [*FAMILY.glob("*.kp"), *FAMILY.glob("variants/*.kp")])
    assert sorted(p.name for p in table_problems(sweep.tables[0])) == every
    assert len(every) >= 25  # SPEC's 16 examples and our variants


def row(planner: str, problem: str, seed: int, seconds: float, solved: bool = True,
        system: str = "pendulum", length: float = 30.0, duration: float = 6.0) -> RunRow:
    return RunRow(
        problem=problem, family=system, width=0, height=0, vehicle=system, planner=planner,
        implementation="ompl" if planner.startswith("ompl-") else "ours", seed=seed,
        time_limit=10.0, solved=solved, status="solved" if solved else "time_limit",
        exit_status=0 if solved else 3, valid=True if solved else None, failure="",
        planning_seconds=seconds, process_seconds=seconds + 0.3,
        path_length=length if solved else None, tree_nodes=100, iterations=100,
        trajectory_lines=5 if solved else None, peak_memory_mb=30.0, corner_cuts=0,
        validation_seconds=0.0, path_duration=duration if solved else None)


def test_report_has_seed_layout_not_available_lines_and_the_targets():
    rows = [row("rrt", "pendulum-t3", s, t) for s, t in ((1, 0.02), (2, 0.04), (3, 0.03))]
    rows += [row("ompl-rrt", "pendulum-t3", s, t) for s, t in ((1, 0.1), (2, 0.08), (3, 0.2))]
    rows += [row("ompl-kpiece1", "pendulum-t3", 1, 10.0, solved=False)]
    text = markdown_report(rows, {"preset": "family"}, FAMILY_PRESETS["family"])
    table = [line for line in text.splitlines() if line.startswith("| rrt (ours)")][0]
    cells = [c.strip() for c in table.strip("|").split("|")]
    assert cells[1:6] == ["100", "0.03 ± 0.01", "6 ± 0", "30 ± 0", "100 ± 0"]
    assert cells[7] == "0.30×"  # median 0.03 over OMPL RRT's 0.1
    kpiece_ours = [line for line in text.splitlines() if line.startswith("| kpiece (ours)")]
    assert len(kpiece_ours) == 1 and NOT_AVAILABLE in kpiece_ours[0]
    assert "OMPL RRT (seed 000, C++)" in text and "0.0123 ± 0.0072" in text
    kpiece = [line for line in text.splitlines() if "OMPL control KPIECE1 " in line][0]
    # One run: its value alone, no "± 0".
    assert [c.strip() for c in kpiece.strip("|").split("|")][1:3] == ["0", "10"]
    targets = "\n".join(targets_table(rows, min_runs=3))
    assert "pendulum-t3: rrt median time ≤ 0.5× OMPL RRT's" in targets
    assert "0.30×" in targets and "yes" in targets
    # best median 0.03 s > 2 x 0.0123 s: not met
    assert "pendulum-t3: best planner median" in targets and "**no**" in targets
    # Three runs of each planner are too few to judge by default (five).
    default = parse_rows(targets_table(rows))
    assert default and all(cells[1:] == ["not judged: 3 runs (need 5)", "–"]
                           for cells in default)
    assert "not judged: 3 runs (need 5)" in text


def test_prmstar_first_solution_target_is_judged_per_problem_against_prm():
    # prmstar's whole run (its refinement) is long; only its first answer's time counts.
    rows = []
    for seed in range(1, 6):
        for problem, star_first in (("arm2-pair1", 0.0015), ("arm2-pair2", 0.0031)):
            rows.append(replace(row("prm", problem, seed, 0.001, system="arm2"),
                                first_solution_seconds=0.001))
            rows.append(replace(row("prmstar", problem, seed, 9.0, system="arm2"),
                                first_solution_seconds=star_first))
    rows.append(replace(row("prmstar", "arm2-pair1", 6, 9.0, system="arm2"),
                        first_solution_seconds=5.0))  # a seed prm did not run: left out
    rows.append(replace(row("prmstar", "rigid2-scene1", 1, 9.0, system="rigid2"),
                        first_solution_seconds=0.001))  # prm did not run it: no line
    bound = "median time to the first solution at most 2× our prm's"
    lines = {cells[0]: cells[1:] for cells in parse_rows(targets_table(rows)) if bound in cells[0]}
    assert lines == {f"arm2-pair1: prmstar {bound}": ["1.50× (1.5 ms over 1 ms)", "yes"],
                     f"arm2-pair2: prmstar {bound}": ["3.10× (3.1 ms over 1 ms)", "**no**"]}
    few = {cells[0]: cells[1:] for cells in parse_rows(targets_table(rows, min_runs=6))}
    assert few[f"arm2-pair2: prmstar {bound}"] == ["not judged: 5 runs (need 6)", "–"]


def parse_rows(table: list[str]) -> list[list[str]]:
    """The body rows of a Markdown table, as cells."""
    return [[cell.strip() for cell in line.strip("|").split("|")] for line in table[2:]]


def test_a_table_without_any_available_planner_says_so():
    preset = FamilyPreset("t", (FamilyTable("Blossom", ("car1-scene1",), ("blossom",)),), 1, 1.0)
    text = markdown_report([row("rrt", "pendulum-t3", 1, 0.1)], {}, preset)
    assert "No runs: none of blossom is available" in text


def run(args, timeout=120, **kwargs) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(catalog.ROOT))
    return subprocess.run([sys.executable, "-m", *args], capture_output=True, timeout=timeout,
                          env=env, cwd=catalog.ROOT, **kwargs)


def test_planner_params_sets_a_field_and_refuses_an_unknown_one():
    problem = (FAMILY / "pendulum-t10.kp").read_bytes()
    bad = run(["benchmarks.planner_params", "nope=1", "-planner", "rrt"], input=problem)
    assert bad.returncode == 2 and bad.stdout == b""
    assert bad.stderr.decode().count("\n") == 1 and "no parameter 'nope'" in bad.stderr.decode()
    with pytest.raises(ValueError, match="'x' is not a float"):
        typed_overrides(rrt.Params, {"goal_bias": "x"})
    assert typed_overrides(rrt.Params, {"goal_bias": "0.25"}) == {"goal_bias": 0.25}
    base = ["-planner", "rrt", "-seed", "2", "-iterations", "2000", "-stats"]

    def outcome(*head):
        done = run([*head, *base], input=problem)
        return done.stdout, parse_stats(done.stderr.decode())["tree_nodes"]
    plain = outcome("rrt_cli")
    assert outcome("benchmarks.planner_params", "goal_bias=0.05") == plain  # the default
    assert outcome("benchmarks.planner_params", "goal_bias=0.5") != plain


# A long end-to-end run (the command twice, with its plots): CI only; the tests above
# cover the preset's runs, rows and report in process.
@pytest.mark.slow
def test_the_command_runs_a_family_preset_end_to_end(tmp_path):
    done = run(["benchmarks", "--preset", "family-quick", "--planners", "rrt", "--problems",
                "pendulum-t10", "--seeds", "1", "--no-ompl", "--out", str(tmp_path)])
    assert done.returncode == 0, done.stderr
    assert done.stdout.decode().strip() == str(tmp_path / "report.md")
    with open(tmp_path / "runs.csv") as handle:
        rows = list(csv.DictReader(handle))
    assert [(r["problem"], r["vehicle"], r["planner"], r["solved"]) for r in rows] == \
        [("pendulum-t10", "pendulum", "rrt", "1")]
    assert all(float(r["path_duration"]) > 0 for r in rows)
    report = (tmp_path / "report.md").read_text()
    assert "### pendulum-t10" in report and "| rrt (ours)" in report
    assert "Blossom" in report and (tmp_path / "plots.pdf").exists()
    page = (tmp_path / "report.html").read_text()
    assert page.count("<svg") == 3 and "control duration (s)" in page  # time, success, cost
    again = run(["benchmarks", "--preset", "family-quick", "--report-only", "--out",
                 str(tmp_path)])
    assert again.returncode == 0 and (tmp_path / "report.md").read_text() == report


def test_a_row_of_an_older_csv_without_the_duration_column_reads(tmp_path):
    path = tmp_path / "runs.csv"
    write_csv([row("rrt", "pendulum-t3", 1, 0.5)], path)
    keep = [i for i, name in enumerate(FIELD_NAMES) if name != "path_duration"]
    path.write_text("\n".join(",".join(line.split(",")[i] for i in keep)
                              for line in path.read_text().splitlines()) + "\n")
    (back,) = read_csv(path)
    assert back == replace(row("rrt", "pendulum-t3", 1, 0.5), path_duration=None)


def test_a_run_narrowed_to_some_planners_lists_only_those():
    """``--planners`` left the others out: no "not available" line for them."""
    rows = [row("rrt", "pendulum-t3", s, 0.02) for s in (1, 2, 3)]
    narrowed = markdown_report(rows, {"preset": "family", "planners": "rrt"},
                               FAMILY_PRESETS["family"])
    whole = markdown_report(rows, {"preset": "family"}, FAMILY_PRESETS["family"])
    assert "| kpiece (ours)" in whole and "| kpiece (ours)" not in narrowed
    assert "| rrt (ours)" in narrowed
    assert narrowed.count(NOT_AVAILABLE) == 1 < whole.count(NOT_AVAILABLE)  # 1: the note
