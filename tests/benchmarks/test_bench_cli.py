"""The one command, end to end on a tiny subset, and the PDF of plots."""

import os
import subprocess
import sys

import pytest

from benchmarks import catalog
from benchmarks.cli import main
from benchmarks.rows import FIELD_NAMES, read_csv


HEADER = ["Planner", "Success %", "Time (s)", "Path length", "Tree nodes", "Median time (s)",
          "p90 time (s)", "Process median (s)", "vs OMPL RRT, planning",
          "vs OMPL RRT, process"]


def table_headers(markdown: str) -> list[list[str]]:
    """The header cells of every Markdown table in the text."""
    lines = markdown.splitlines()
    return [[cell.strip() for cell in line.strip().strip("|").split("|")]
            for line, rule in zip(lines, lines[1:])
            if line.startswith("|") and rule.startswith("|") and set(rule) <= set("|:- ")]


def bench(*args, timeout=120) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(catalog.ROOT))
    return subprocess.run([sys.executable, "-m", "benchmarks", *args], capture_output=True,
                          text=True, timeout=timeout, env=env, cwd=catalog.ROOT)


def test_tiny_run_writes_every_report(tmp_path):
    out = tmp_path / "run"
    done = bench("--preset", "smoke", "--planners", "rrt", "--problems", "course-simple-0",
                 "course-space-0", "--seeds", "1", "--no-generate", "--no-plots",
                 "--out", str(out))
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == str(out / "report.md")  # stdout: only the answer
    assert "runs," in done.stderr  # progress on stderr
    rows = read_csv(out / "runs.csv")
    point = [r for r in rows if r.vehicle == "point"]
    ship = [r for r in rows if r.vehicle == "spaceship"]
    assert len(point) == len(ship) == 2  # two problems, one seed
    assert all(r.planner == "rrt" for r in rows)
    assert (out / "runs.csv").read_text().splitlines()[0].split(",") == list(FIELD_NAMES)
    text = (out / "report.md").read_text()
    assert HEADER in table_headers(text)
    assert "## Targets" in text
    # The point vehicle's paths against the shortest ones, kept as a CSV too.
    shortest = (out / "shortest.csv").read_text().splitlines()
    assert shortest[0] == "problem,shortest_path_length" and len(shortest) == 1 + 2
    assert ["Problem", "Shortest", "rrt (ours)"] in table_headers(text)
    logs = sorted(p.name for p in (out / "ompl-logs").iterdir())
    assert "course-space-0_spaceship.log" in logs and len(logs) == 4
    page = (out / "report.html").read_text()  # --no-plots: the tables, no plots
    assert page.count("<table>") == len(table_headers(text)) and "<svg" not in page
    assert "Plots left out" in page and not (out / "plots.pdf").exists()
    # The reports can be rebuilt from the CSV alone.
    (out / "report.md").unlink()
    assert main(["--report-only", "--no-plots", "--out", str(out)]) == 0
    assert (out / "report.md").read_text() == text


def test_bad_usage_is_one_line_and_status_2(tmp_path):
    done = bench("--planners", "no-such-planner", "--no-generate", "--out", str(tmp_path))
    assert done.returncode == 2 and "unknown planner" in done.stderr
    assert "Traceback" not in done.stderr
    done = bench("--report-only", "--out", str(tmp_path / "missing"))
    assert done.returncode == 2 and "does not exist" in done.stderr


@pytest.mark.slow  # a run and its PDF: seconds (report.html's plots are tested unmarked)
def test_plots_pdf_has_the_plots_a_page_each(tmp_path):
    pytest.importorskip("matplotlib")
    pdfium = pytest.importorskip("pypdfium2")
    from test_bench_report import row

    from benchmarks.plots import render
    rows = [row(planner, f"p{k}", seed, 0.01 * (seed + 1) * (k + 1), vehicle=vehicle,
                solved=seed != 2)
            for vehicle in ("point", "spaceship") for planner in ("rrt", "ompl-rrt")
            for k in range(3) for seed in range(3)]
    path = tmp_path / "plots.pdf"
    rendered = render(rows, path)
    assert [plot.name for plot, _ in rendered] == [  # per vehicle: time, success, cost
        name for vehicle in ("point", "spaceship")
        for name in (f"time-{vehicle}-1", f"success-{vehicle}", f"cost-{vehicle}-1")]
    document = pdfium.PdfDocument(str(path))
    assert len(document) == len(rendered)
    text = document[1].get_textpage().get_text_range()
    assert "runs solved within a time" in text and "rrt (ours)" in text


def test_presets_pick_problems_within_their_limits():
    from benchmarks import presets
    for preset in presets.PRESETS.values():
        for plan in preset.plans:
            chosen = presets.select_problems(plan)
            assert chosen, (preset.name, plan.vehicle)
            for path in chosen:
                assert presets.problem_size(path) <= plan.max_size or path.stem in plan.extra
                assert path.stem not in plan.exclude  # (no course problem is excluded)
    from benchmarks.generator import problem_id
    quick_point = {problem_id(p)
                   for p in presets.select_problems(presets.PRESETS["quick"].plans[0])}
    assert {"course-space-3", "open-500", "narrow-500", "random-d35-50"} <= quick_point
    assert "maze-50" not in quick_point and "random-d20-100" not in quick_point
