"""report.html and its plots: every run a point when runs are few, a box from ten runs, one
colour per planner in every plot, a self-contained page with the report's tables."""

import re
import xml.etree.ElementTree as ET

import pytest

pytest.importorskip("matplotlib")

from test_bench_report import row  # noqa: E402

from benchmarks.html_report import html_report  # noqa: E402
from benchmarks.plots import BOX_MIN_RUNS, render  # noqa: E402
from benchmarks.report import markdown_report  # noqa: E402

SVG = "{http://www.w3.org/2000/svg}"


def made_up_rows():
    """rrt: 3 runs on p0 (one unsolved); OMPL's RRT: 12; both on the spaceship too."""
    rows = [row("rrt", "p0", seed, 0.01 * seed, solved=seed != 3) for seed in (1, 2, 3)]
    rows += [row("ompl-rrt", "p0", seed, 0.02 * seed, length=12.0 + seed)
             for seed in range(1, BOX_MIN_RUNS + 3)]
    rows += [row(planner, "p1", 1, 0.5, vehicle="spaceship") for planner in ("rrt", "ompl-rrt")]
    return rows


@pytest.fixture(scope="module")
def rendered():
    return render(made_up_rows())


@pytest.fixture(scope="module")
def svgs(rendered):
    return {plot.name: ET.fromstring(svg) for plot, svg in rendered}


def element(svg, suffix):
    found = [e for e in svg.iter() if e.get("id", "").endswith(suffix)]
    assert len(found) <= 1
    return found[0] if found else None


def points(svg, suffix) -> int:
    """The marks drawn in the element whose id ends with ``suffix``: each a <use> of a
    defined marker or a <path> of its own (matplotlib writes one of the two)."""
    def drawn(node) -> int:
        if node.tag == f"{SVG}defs":
            return 0
        own = node.tag in (f"{SVG}use", f"{SVG}path")
        return own + sum(drawn(child) for child in node)
    group = element(svg, suffix)
    return 0 if group is None else drawn(group)


def colour(node, key) -> str:
    styled = [e.get("style") for e in node.iter() if key + ":" in (e.get("style") or "")]
    return re.search(key + r": (#[0-9a-f]{6})", styled[0]).group(1)


def test_few_runs_are_points_and_many_runs_get_a_box_behind_theirs(svgs):
    assert sorted(svgs) == ["cost-point-1", "cost-spaceship-1", "success-point",
                            "success-spaceship", "time-point-1", "time-spaceship-1"]
    time = svgs["time-point-1"]
    assert points(time, "time-point-rrt-p0-solved") == 2
    assert points(time, "time-point-rrt-p0-unsolved") == 1
    assert element(time, "time-point-rrt-p0-box") is None  # 3 runs: no box
    assert points(time, "time-point-ompl-rrt-p0-solved") == BOX_MIN_RUNS + 2
    assert element(time, "time-point-ompl-rrt-p0-box") is not None
    # One run: still a point, in the planner's colour.
    assert points(svgs["time-spaceship-1"], "time-spaceship-rrt-p1-solved") == 1
    cost = svgs["cost-point-1"]  # solved runs only
    assert points(cost, "cost-point-rrt-p0") == 2
    assert points(cost, "cost-point-ompl-rrt-p0") == BOX_MIN_RUNS + 2
    texts = " ".join(t.text or "" for t in time.iter(f"{SVG}text"))
    assert "rrt (ours)" in texts and "OMPL geometric RRT" in texts and "planning time" in texts


def test_a_planner_keeps_its_colour_in_every_plot(svgs):
    seen = {}
    for planner in ("rrt", "ompl-rrt"):
        marks = [colour(element(svgs["time-point-1"], f"time-point-{planner}-p0-solved"),
                        "fill"),
                 colour(element(svgs["time-spaceship-1"],
                                f"time-spaceship-{planner}-p1-solved"), "fill"),
                 colour(element(svgs["success-point"], f"success-point-{planner}"), "stroke"),
                 colour(element(svgs["cost-point-1"], f"cost-point-{planner}-p0"), "fill")]
        assert len(set(marks)) == 1, (planner, marks)
        seen[planner] = marks[0]
    assert seen["rrt"] != seen["ompl-rrt"]


def test_report_html_is_one_self_contained_page_with_the_tables_and_plots(rendered):
    markdown = markdown_report(made_up_rows(), {"preset": "test", "date": "2026-01-01"})
    page = html_report(markdown, rendered)
    for fetched in ("<script", "<link", " src=", "url(http", "@import"):
        assert fetched not in page
    tables = sum(1 for line, rule in zip(markdown.splitlines(), markdown.splitlines()[1:])
                 if line.startswith("|") and rule.startswith("|:") or rule.startswith("|-"))
    assert page.count("<table>") == tables > 3
    assert page.count("<svg") == len(rendered) == 6
    ids = re.findall(r'\bid="([^"]+)"', page)
    assert len(ids) == len(set(ids))  # several SVGs, no id twice
    references = re.findall(r'(?:href="#|url\(#)([^")]+)', page)
    assert references and set(references) <= set(ids)
    assert "<strong>no</strong>" in page or "not judged" in page
    assert '<h2 id="plots">Plots</h2>' in page and '<a href="#plots">' in page


def test_without_plots_the_page_says_so():
    markdown = markdown_report(made_up_rows(), {"preset": "test"})
    page = html_report(markdown, [], "Plots left out (--no-plots).")
    assert "<svg" not in page and "Plots left out (--no-plots).</p>" in page
