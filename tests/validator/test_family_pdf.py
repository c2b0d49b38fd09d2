"""The family's PDF (SPEC 5.5; issues 14 and 15): pages per system, what they say,
and colours where the obstacles, the C-space's invalid region and a wrapping
segment must be."""

import io
import json
import math

import pypdfium2 as pdfium

from planning_core.kinoplan_text import parse_kinoplan
from planning_core.plan_text import format_plan
from planning_core.setups import kinoplan_setup
from tests.validator.test_family_checks import PROBLEM as CAR2, answer as car2_answer
from tests.validator.test_family_checks import printing, validator
from tests.validator.test_family_geometric_checks import RIGID, answer as path_answer
from validator.checks import validate_plan
from validator.render_page import FamilyOptions, RenderOptions
from validator.render_pdf import render_pdf
from validator.render_plot import frame_in, page_for, plot_area, polyline_ops

ARM = """kinoplan 1
system arm2
world -2.2 -2.2 2.2 2.2
circle 0 1.5 0.3
start theta1 -1.5 theta2 0
goal theta1 -0.5 theta2 0.5 within 0.05
"""
PENDULUM = """kinoplan 1
system pendulum
start theta 3 omega 2
goal theta pi/2 omega 0 within 0.1
"""


def render(problem_text: str, output: str, options: RenderOptions = RenderOptions(),
           cells: int = 60):
    problem = parse_kinoplan(problem_text)
    report = validate_plan(kinoplan_setup(problem), output)
    out = io.BytesIO()
    summary = render_pdf(out, problem, None, report, report.verdict, ["a note"], "test.kp",
                         options, FamilyOptions(cspace_cells=cells))
    return report, summary, pdfium.PdfDocument(out.getvalue())


def text(document, page: int) -> str:
    return document[page].get_textpage().get_text_range()


def pixel(document, page: int, frame, x: float, y: float) -> tuple[int, int, int]:
    """The colour at data point (x, y) of ``frame`` on the page, rendered at 2x."""
    image = document[page].render(scale=2).to_pil().convert("RGB")
    px, py = frame.to_page(x, y)
    return image.getpixel((round(2 * px), round(2 * (document[page].get_height() - py))))


def workspace_frame(x0, y0, x1, y1, **angles):
    """A plot of the box at one scale, on a page of its shape (render_plot.new_page)."""
    box = (x0, y0, x1, y1)
    return frame_in(box, plot_area(page_for(box)), **angles)


def grey(rgb) -> bool:
    return max(rgb) - min(rgb) < 8 and 100 < rgb[0] < 180


def test_car2_workspace_and_time_pages():
    problem = CAR2 + "rect 8 14 12 18\n"
    rows, _ = car2_answer(problem)
    report, summary, document = render(problem, format_plan(rows, rows[:2]))
    assert report.valid and len(document) == 2
    first = text(document, 0)
    assert "Solution trajectory appears valid." in first
    assert "Workspace (x, y): 2 tree edges; solution re-simulated slice by slice (3 lines, " \
        "the body at every slice); duration 3 s" in first
    assert "pink: body along the solution (dark edge: its front)" in first
    assert "State and control against time" in text(document, 1)
    assert "control omega" in text(document, 1)
    assert (summary.tree_edges_drawn, summary.solution_lines_drawn) == (2, 3)
    frame = workspace_frame(0, 0, 20, 20)
    assert grey(pixel(document, 0, frame, 10, 16))         # the obstacle
    assert pixel(document, 0, frame, 5, 5) == (255, 255, 255)
    r, g, b = pixel(document, 0, frame, 6, 10)             # the solution, along y = 10
    assert r > 150 and g < 80 and b < 80


def test_pendulum_phase_portrait_and_a_wrapping_segment_split_at_the_edges():
    problem = parse_kinoplan(PENDULUM)
    rows = [problem.start + (3.0, 10)]
    report, _, document = render(PENDULUM, format_plan(rows, rows))
    assert len(document) == 2
    assert "Phase portrait (theta, omega)" in text(document, 0)
    frame = frame_in((-math.pi, -10, math.pi, 10), plot_area(), equal=False, angle_x=True)
    ops: list[str] = []
    polyline_ops(frame, [(3.0, 0.0), (-3.0, 0.0)], ops)
    moves = [op for op in ops if op.endswith(" m")]
    assert len(moves) == 2  # drawn twice: out of the right edge and into the left one
    right, left = frame.left + frame.width, frame.left
    starts = sorted(float(op.split()[0]) for op in moves)
    assert starts[0] < left + 0.1 * frame.width and starts[1] > right - 0.1 * frame.width
    # The solution leaves at theta = pi and comes back at -pi, at the omega of the wrap.
    slices = problem.system.slice_states(problem.start, rows[0][2:])
    a, b = next((a, b) for a, b in zip(slices, slices[1:]) if b[0] < a[0])
    omega = a[1] + (math.pi - a[0]) / (b[0] + 2 * math.pi - a[0]) * (b[1] - a[1])
    for theta in (math.pi - 0.01, -math.pi + 0.01):
        near = [pixel(document, 0, frame, theta, omega + d) for d in (-0.05, 0.0, 0.05)]
        assert any(p[0] > 150 and p[1] < 80 for p in near), (theta, near)


def test_arm_workspace_and_configuration_space_shaded_where_invalid():
    path = [(-1.5, 0.0), (-1.0, 0.3), (-0.5, 0.5)]
    report, _, document = render(ARM, path_answer(path))
    assert report.valid and len(document) == 2
    assert "Workspace: the arm at" in text(document, 0)
    cspace = text(document, 1)
    assert "Configuration space (theta1, theta2)" in cspace and "60 x 60 cells" in cspace
    frame = workspace_frame(-math.pi, -math.pi, math.pi, math.pi)
    assert grey(pixel(document, 1, frame, math.pi / 2, 0.0))    # the stretched arm up: disc
    assert pixel(document, 1, frame, 2.5, 2.5) == (255, 255, 255)
    world = workspace_frame(-2.2, -2.2, 2.2, 2.2)
    assert grey(pixel(document, 0, world, 0.0, 1.5))            # the disc in the workspace


def test_a_failure_is_named_and_the_arm_drawn_at_it():
    report, _, document = render(ARM.replace("theta1 -0.5 theta2 0.5", "theta1 2.5 theta2 0"),
                                 path_answer([(-1.5, 0.0), (0.5, 0.0), (2.5, 0.0)]))
    assert report.first_failure.number == 6
    page = text(document, 0)
    assert "First failure (check 6, line 3): Trajectory collides with an obstacle!" in page
    assert "magenta: the arm at the first failure" in page


def test_rigid2_page_and_a_huge_tree_thinned_and_said_so():
    path = [(0.5, 0.5, 0.0), (0.5, 1.2, 0.0), (1.5, 1.2, math.pi / 2), (1.5, 0.5, 0.0)]
    tree = [(0.5, 0.5, 0.0, 0.5 + k * 1e-4, 0.6, 0.1) for k in range(5000)]
    report, summary, document = render(RIGID, format_plan(path, tree),
                                       RenderOptions(max_tree_points=1000))
    assert report.valid and len(document) == 1
    page = text(document, 0)
    assert "the body at 24 poses along the path" in page
    assert "5000 tree edges (thinned: one in 10 drawn)" in page
    assert summary.tree_edges_drawn == 500
    assert grey(pixel(document, 0, workspace_frame(0, 0, 2, 2), 1.0, 0.2))  # the wall


def test_render_pdf_writes_the_family_pages_to_a_path(tmp_path):
    problem = parse_kinoplan(RIGID)
    out = tmp_path / "rigid.pdf"
    render_pdf(str(out), problem, None, None, "Putative solution trajectory has problems.",
               ["Solver timed out."], "rigid.kp")
    document = pdfium.PdfDocument(str(out))
    assert len(document) == 1 and "Solver timed out." in text(document, 0)


def test_cli_writes_the_family_pdf(tmp_path):
    rows, _ = car2_answer()
    pdf = tmp_path / "out.pdf"
    done = validator(["-o", str(pdf), "-json", "--", *printing(tmp_path, rows)], CAR2)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["pdf"] == str(pdf)
    assert len(pdfium.PdfDocument(str(pdf))) == 2
