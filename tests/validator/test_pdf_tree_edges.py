"""The tree-viz PDF draws every tree edge (SPEC 3: "every tree edge (spaceship
edges drawn as their 20-slice curves)"): rasterised, the page shows the tree
colour along edges that run far from the solution, and nowhere there when the
tree section is empty or away from every edge.

Uses the validator's public pieces (``validate_output``, ``render_pdf``, the
colour and layout it exports, and the command with ``-o``) and rasterises with
pypdfium2, as test_validator_pdf.py does, at a finer scale so the thin tree
line covers whole pixels.
"""

from __future__ import annotations

import io
import math
import os
import subprocess
import sys
from pathlib import Path

import pypdfium2 as pdfium

from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from validator.checks import validate_output
from validator.render_grid import page_layout
from validator.render_page import TREE_RGB
from validator.render_pdf import render_pdf
from validator_testlib import colour_near

ROOT = Path(__file__).resolve().parents[2]
SCALE = 4.0  # pixels per PDF point: the 0.4 pt tree line is 1.6 px wide

# 8 x 5, blocked cells (1, 1) and (4, 2) away from everything drawn; the solution
# runs along the bottom row, the tree's far edges through the free cells above it.
MAP = """8
5
________
________
____#___
_#______
________
{sx}
{sy}
{gx}
{gy}
"""
POINT_PROBLEM = MAP.format(sx=0.5, sy=0.5, gx=7.5, gy=0.5)
POINT_PATH = [(0.5, 0.5), (3.5, 0.5), (7.5, 0.5)]
# Far from the solution (at least 2.5 units above it), in free cells.
FAR_EDGES = [((3.5, 0.5), (1.25, 3.5)), ((1.25, 3.5), (6.5, 3.5)),
             ((6.5, 3.5), (7.25, 4.75)), ((1.25, 3.5), (0.5, 4.5))]
QUIET = [(5.5, 1.5), (6.5, 2.5), (3.0, 4.6)]  # no edge, path or marker near these


def point_output(tree) -> str:
    lines = [str(len(POINT_PATH))] + [f"{x!r} {y!r}" for x, y in POINT_PATH]
    lines.append(str(len(tree)))
    lines += [" ".join(repr(v) for v in a + b) for a, b in tree]
    return "\n".join(lines) + "\n"


def point_tree():
    return [(POINT_PATH[0], POINT_PATH[1]), (POINT_PATH[1], POINT_PATH[2])] + FAR_EDGES


def rasterise(pdf_bytes: bytes):
    page = pdfium.PdfDocument(pdf_bytes)[0]
    return page.render(scale=SCALE).to_pil().convert("RGB")


def has_colour(image, page_point, rgb, radius=2, tolerance=40) -> bool:
    return colour_near(image, page_point, rgb, SCALE, radius, tolerance)

def render(problem_text: str, vehicle: Vehicle, output: str):
    problem = parse_problem(problem_text)
    report = validate_output(problem, vehicle, output, strict=True)
    assert report.valid, report.first_failure
    out = io.BytesIO()
    render_pdf(out, problem, vehicle, report, report.verdict, problem_label="tree-edges")
    return rasterise(out.getvalue()), page_layout(problem)


def along(a, b, fractions=(0.25, 0.4, 0.55, 0.7, 0.85)):
    return [(a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t) for t in fractions]


def test_point_tree_edges_are_drawn_far_from_the_solution():
    image, layout = render(POINT_PROBLEM, Vehicle.POINT, point_output(point_tree()))
    points = [(a, b, p) for a, b in FAR_EDGES for p in along(a, b)]
    missing = [(a, b, p) for a, b, p in points
               if not has_colour(image, layout.to_page(*p), TREE_RGB)]
    assert not missing, (f"no tree colour at {len(missing)} of {len(points)} points along "
                         f"the tree's edges, e.g. edge {missing[0][:2]} at {missing[0][2]}")
    for p in QUIET:
        assert not has_colour(image, layout.to_page(*p), TREE_RGB, radius=4), p


def test_no_tree_colour_where_the_tree_section_is_empty():
    image, layout = render(POINT_PROBLEM, Vehicle.POINT, point_output([]))
    for a, b in FAR_EDGES:
        for p in along(a, b):
            assert not has_colour(image, layout.to_page(*p), TREE_RGB, radius=4), (a, b, p)


def ship_slices(state, control):
    """SPEC 2's one step of 20 slices, written out here: the positions after each."""
    x, y, dx, dy = state
    theta, s = control
    dt = 1 / 20
    points = []
    for _ in range(20):
        a = math.atan2(dy, dx) + theta
        dx += dt * s * math.cos(a)
        dy += dt * s * math.sin(a)
        x += dt * dx
        y += dt * dy
        points.append((x, y))
    return points


def test_spaceship_tree_edges_are_drawn_as_their_curves():
    # Start within 0.1 of the goal: the one-line answer (start at rest, zero thrust)
    # is valid, and the tree's edges fly far from it.
    problem_text = MAP.format(sx=0.5, sy=0.5, gx=0.55, gy=0.5)
    edges = [((1.0, 3.2, 2.5, 0.0), (math.pi / 2, 0.5)),   # bends left
             ((6.5, 4.0, -1.0, -2.0), (3 * math.pi / 2, 0.5))]  # bends right
    lines = ["1", "0.5 0.5 0.0 0.0 0.0 0.0", str(len(edges))]
    lines += [" ".join(repr(v) for v in state + control) for state, control in edges]
    image, layout = render(problem_text, Vehicle.SPACESHIP, "\n".join(lines) + "\n")
    for state, control in edges:
        curve = ship_slices(state, control)
        for k in (3, 7, 10, 13, 17):
            assert has_colour(image, layout.to_page(*curve[k]), TREE_RGB), (
                f"no tree colour after slice {k + 1} of the edge from {state} under {control}")
        # The curve, not its chord: half-way along the chord is well off the curve
        # (0.06 units, over 5 points on this page).
        (x0, y0), (x1, y1) = state[:2], curve[-1]
        chord_middle = layout.to_page((x0 + x1) / 2, (y0 + y1) / 2)
        assert not has_colour(image, chord_middle, TREE_RGB, radius=2), (
            f"the edge from {state} under {control} is drawn as a straight chord")


def test_validator_command_pdf_shows_the_tree(tmp_path):
    answer = tmp_path / "answer.out"
    answer.write_text(point_output(point_tree()))
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "validator", "-strict", "-o", "viz.pdf", "--",
                           "cat", str(answer)], input=POINT_PROBLEM.encode(),
                          capture_output=True, cwd=tmp_path, env=env, timeout=60)
    assert done.returncode == 0, done.stdout + done.stderr
    image = rasterise((tmp_path / "viz.pdf").read_bytes())
    layout = page_layout(parse_problem(POINT_PROBLEM))
    for a, b in FAR_EDGES:
        for p in along(a, b, (0.3, 0.6)):
            assert has_colour(image, layout.to_page(*p), TREE_RGB), (a, b, p)
