"""The tree-viz PDF: the solution is drawn where it runs, failures are marked, big
maps and trees stay small, and bad numbers do not break the drawing."""

from __future__ import annotations

import io
import math
import random

import pypdfium2 as pdfium
import pytest

from planning_core.plan_text import format_plan
from planning_core.problem import Problem
from planning_core.vehicles import Vehicle
from validator.checks import validate_output
from validator.render_geometry import solution_points
from validator.render_grid import page_layout
from validator.render_page import FAILURE_RGB, SOLUTION_RGB, RenderOptions
from validator.render_pdf import render_pdf
from validator_testlib import CORPUS, colour_near, load_problem, run_validator

SCALE = 2.0  # pixels per PDF point when rasterising


def rasterise(pdf_bytes: bytes):
    page = pdfium.PdfDocument(pdf_bytes)[0]
    text = page.get_textpage().get_text_range()
    return page.render(scale=SCALE).to_pil().convert("RGB"), text


def near_colour(image, page_point, rgb, radius=2, tolerance=60) -> bool:
    return colour_near(image, page_point, rgb, SCALE, radius, tolerance)

def render(problem, vehicle, text, **kw) -> tuple[bytes, object]:
    report = validate_output(problem, vehicle, text, **kw)
    out = io.BytesIO()
    render_pdf(out, problem, vehicle, report, report.verdict, problem_label="test")
    return out.getvalue(), report


def test_point_solution_is_drawn_where_it_runs():
    problem = load_problem("space-0.sw")
    path = [(0.1, 1.54), (1.5, 2.5), (3.5, 2.5), (3.8, 1.1)]
    tree = [a + b for a, b in zip(path, path[1:])] + [(0.1, 1.54, 1.0, 0.5)]
    pdf, report = render(problem, Vehicle.POINT, format_plan(path, tree))
    assert report.valid
    image, text = rasterise(pdf)
    layout = page_layout(problem)
    for (x0, y0), (x1, y1) in zip(path, path[1:]):
        for t in (0.2, 0.5, 0.8):
            point = layout.to_page(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t)
            assert near_colour(image, point, SOLUTION_RGB), (x0, y0, x1, y1, t)
    # Nowhere near the solution: the blocked cell (3, 0) and the empty cell (1, 0).
    for x, y in ((3.5, 0.5), (1.5, 0.5)):
        assert not near_colour(image, layout.to_page(x, y), SOLUTION_RGB, radius=6)
    assert "Solution trajectory appears valid." in text
    assert "vehicle: point" in text


def test_spaceship_solution_follows_its_slices():
    problem = load_problem("open.sw")
    text = (CORPUS / "outputs/spaceship/valid-straight.out").read_text()
    pdf, report = render(problem, Vehicle.SPACESHIP, text)
    image, _ = rasterise(pdf)
    layout = page_layout(problem)
    points = solution_points(report)
    assert len(points) == report.trajectory_count * 21
    for x, y in points[5::17]:
        assert near_colour(image, layout.to_page(x, y), SOLUTION_RGB)
    assert not near_colour(image, layout.to_page(3.0, 2.5), SOLUTION_RGB, radius=6)


def test_first_failure_is_marked():
    problem = load_problem("space-0.sw")
    pdf, report = render(problem, Vehicle.POINT, "2\n0.1 1.54\n3.8 1.1\n0\n")
    failure = report.first_failure
    assert failure.number == 6
    image, text = rasterise(pdf)
    assert near_colour(image, page_layout(problem).to_page(*failure.where), FAILURE_RGB)
    assert "Putative solution trajectory has problems." in text
    assert "Trajectory collides with an obstacle!" in text


def page_lines(pdf: bytes) -> list[str]:
    return rasterise(pdf)[1].splitlines()


def test_title_counts_and_captions():
    problem = load_problem("corner.sw")
    text = (CORPUS / "outputs/point/valid-corner-cut-warning.out").read_text()
    report = validate_output(problem, Vehicle.POINT, text)
    out = io.BytesIO()
    summary = render_pdf(out, problem, Vehicle.POINT, report, report.verdict, ["a note"],
                         "corner", RenderOptions(max_tree_edges_drawn=0))
    assert (summary.tree_edges_drawn, summary.tree_edges_total) == (0, 1)
    lines = page_lines(out.getvalue())
    assert lines[:3] == ["Solution trajectory appears valid.",
                         "corner: 4 x 3 map, start (1, 0.99), goal (3, 2.95) vehicle: point",
                         "2 trajectory lines, 1 tree edges (first 0 drawn), path length 2.828"]
    assert lines[3] == "a note" and lines[4].startswith("Warning: segment from line 2 ")
    assert lines[5].startswith("red: solution")
    # With -strict the cut is the first failure: it replaces the warning, the heading says so.
    pdf, _ = render(problem, Vehicle.POINT, text, strict=True)
    lines = page_lines(pdf)
    assert lines[1].endswith("vehicle: point -strict")
    assert lines[3] == "First failure (check 6, line 2): Trajectory collides with an obstacle!"
    # Nothing to validate: the verdict, the heading and the notes, no counts line.
    out = io.BytesIO()
    summary = render_pdf(out, problem, Vehicle.SPACESHIP, None, "Planner timed out.",
                         ["timed out after 5 s"])
    assert (summary.tree_edges_drawn, summary.tree_edges_total) == (0, 0)
    assert page_lines(out.getvalue())[1:3] == [
        "problem: 4 x 3 map, start (1, 0.99), goal (3, 2.95) vehicle: spaceship",
        "timed out after 5 s"]


def big_problem(rng, size=500):
    blocked = bytearray(1 if rng.random() < 0.2 else 0 for _ in range(size * size))
    for column in range(size):
        blocked[(size // 2) * size + column] = 0
    return Problem(size, size, bytes(blocked), (0.5, size / 2 + 0.5),
                   (size - 0.5, size / 2 + 0.5))


def test_big_map_and_tree_render_small():
    rng = random.Random(7)
    problem = big_problem(rng)
    path = [(0.5 + k * 499.0 / 999, 250.5) for k in range(1000)]
    tree = []
    for _ in range(100_000):
        x, y = rng.random() * 500, rng.random() * 500
        tree.append((x, y, x + rng.uniform(-2, 2), y + rng.uniform(-2, 2)))
    pdf, report = render(problem, Vehicle.POINT, format_plan(path, tree))
    assert report.valid and report.tree_count == 100_000
    assert len(pdf) < 4_000_000, len(pdf)
    # A few path objects, not one per edge: count stroke operators in the content.
    page = pdfium.PdfDocument(pdf)[0]
    assert sum(1 for _ in page.get_objects()) < 100


def test_spaceship_tree_renders_its_curves_small():
    rng = random.Random(8)
    problem = big_problem(rng, 100)
    tree = [(rng.uniform(1, 99), rng.uniform(1, 99), rng.uniform(-0.5, 0.5),
             rng.uniform(-0.5, 0.5), rng.uniform(0, 2 * math.pi), rng.uniform(0, 0.5))
            for _ in range(20_000)]
    text = format_plan([(0.5, 50.5, 0.0, 0.0, 0.0, 0.0)], tree)
    pdf, report = render(problem, Vehicle.SPACESHIP, text)
    assert report.tree_count == 20_000 and len(pdf) < 2_000_000


@pytest.mark.parametrize("vehicle, row", [
    (Vehicle.POINT, "1e300 -1e300 5e307 1.5"),
    (Vehicle.SPACESHIP, "1.0 1.0 1e300 -1e300 0.5 0.5"),
    (Vehicle.SPACESHIP, "1e308 1.0 1e308 1e308 1e308 1e308"),
])
def test_wild_tree_numbers_do_not_break_the_drawing(vehicle, row):
    problem = load_problem("space-0.sw")
    head = "1\n0.1 1.54\n" if vehicle is Vehicle.POINT else "1\n0.1 1.54 0 0 0 0\n"
    pdf, _ = render(problem, vehicle, f"{head}1\n{row}\n")
    image, text = rasterise(pdf)
    assert image.size[0] > 100 and "problems" in text


def test_command_writes_the_pdf_where_asked(tmp_path):
    output = CORPUS / "outputs/point/valid-handmade.out"
    problem_text = (CORPUS / "problems/space-0.sw").read_text()
    done = run_validator(["-o", "viz/out.pdf", "--", "cat", str(output)], problem_text,
                         tmp_path)
    assert done.returncode == 2 and done.stdout == b""  # checked before the planner runs
    assert b"viz/out.pdf" in done.stderr and len(done.stderr.splitlines()) == 2
    (tmp_path / "viz").mkdir()
    done = run_validator(["-o", "viz/out.pdf", "--", "cat", str(output)], problem_text,
                         tmp_path)
    assert done.returncode == 0
    assert (tmp_path / "viz/out.pdf").read_bytes().startswith(b"%PDF")
    assert not (tmp_path / "tree-viz.pdf").exists()
    done = run_validator(["-noviz", "--", "cat", str(output)], problem_text, tmp_path)
    assert done.returncode == 0 and not (tmp_path / "tree-viz.pdf").exists()
