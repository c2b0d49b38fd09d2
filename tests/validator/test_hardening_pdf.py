"""Issue 16 and 17, the PDF: drawing is bounded whatever the planner printed, the
file is written atomically, and the page carries axes in map units, a legend of
what is drawn (with swatches) and the map's own shape.

Pages are rasterised with pypdfium2 (as test_validator_pdf.py does); text is read
back with its position, so a tick label is checked where it should be.
"""

from __future__ import annotations

import errno
import io
import math
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

import pypdfium2 as pdfium
import pytest

from planning_core.plan_text import format_plan
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from validator.checks import validate_output
from validator.render_geometry import solution_points
from validator.render_grid import page_layout
from validator.render_page import (BLOCKED_GRAY, CORNER_RGB, FAILURE_RGB, GOAL_RGB,
                                   SOLUTION_RGB, START_RGB, TREE_RGB, RenderOptions)
from validator.render_pdf import render_pdf
from validator_testlib import CORPUS, PROBLEMS, ROOT

SCALE = 3.0  # pixels per PDF point
SPACE2 = parse_problem((PROBLEMS / "space-2.sw").read_text())  # 10 x 9, start (0.1, 0.1)
FAILING_POINT = "3\n0.1 0.1\n3.037 0.778\n4.5 0.1\n0\n"  # check 6 fails at (2.0259, 0.54459)


def rasterise(pdf: bytes):
    page = pdfium.PdfDocument(pdf)[0]
    return page.render(scale=SCALE).to_pil().convert("RGB"), page.get_textpage()


def pixel_near(image, page_point, rgb, radius=2, tolerance=50) -> bool:
    width, height = image.size
    cx, cy = round(page_point[0] * SCALE), round(height - page_point[1] * SCALE)
    target = [round(c * 255) for c in rgb]
    return any(all(abs(a - b) <= tolerance for a, b in zip(image.getpixel((x, y)), target))
               for x in range(cx - radius, cx + radius + 1)
               for y in range(cy - radius, cy + radius + 1)
               if 0 <= x < width and 0 <= y < height)


def render(problem, vehicle, output, options=RenderOptions(), **kw):
    report = validate_output(problem, vehicle, output, **kw)
    out = io.BytesIO()
    summary = render_pdf(out, problem, vehicle, report, report.verdict, problem_label="t",
                         options=options)
    return out.getvalue(), report, summary


# Tree edges fly 0.5 straight up from these, in free cells of space-2 (rows 0 and 1).
EDGE_XS = (0.3, 0.9, 1.5, 3.3, 3.9, 4.5, 5.1, 5.7, 6.3, 6.9)


def edge_start(k: int) -> tuple[float, float]:
    return EDGE_XS[k % 10], 0.2 + k // 10


def ship_output(n_lines: int, n_edges: int) -> str:
    """A spaceship answer on space-2 whose lines and edges fly in separate, known places:
    line k from (0.5 + 0.9 k, 4.5) one unit right, edge k from edge_start(k) 0.5 up."""
    path = [(0.5 + 0.9 * k, 4.5, 1.0, 0.0, 0.0, 0.0) for k in range(n_lines)]
    tree = [edge_start(k) + (0.0, 0.5, 0.0, 0.0) for k in range(n_edges)]
    return format_plan(path, tree)


# bounded drawing ---------------------------------------------------------------

def test_solution_and_tree_stop_at_their_point_budgets_and_say_so():
    # 21 vertices a spaceship line: 3 lines and 5 edges fit these budgets.
    options = RenderOptions(max_solution_points=3 * 21 + 20, max_tree_points=5 * 21 + 20)
    pdf, report, summary = render(SPACE2, Vehicle.SPACESHIP, ship_output(10, 20), options)
    assert (summary.solution_lines_drawn, summary.solution_lines_total) == (3, 10)
    assert (summary.tree_edges_drawn, summary.tree_edges_total) == (5, 20)
    image, text = rasterise(pdf)
    lines = text.get_text_range().splitlines()
    assert lines[2] == "10 trajectory lines (first 3 drawn), 20 tree edges (first 5 drawn)"
    layout = page_layout(SPACE2)
    points = solution_points(report)  # every line's state and 20 slices: 21 a line
    assert len(points) == 10 * 21
    for line in range(10):
        drawn = pixel_near(image, layout.to_page(*points[line * 21 + 10]), SOLUTION_RGB)
        assert drawn == (line < 3), f"solution line {line + 1}: drawn {drawn}"
    for edge in range(20):
        x, y = edge_start(edge)
        drawn = pixel_near(image, layout.to_page(x, y + 0.25), TREE_RGB, tolerance=40)
        assert drawn == (edge < 5), f"tree edge {edge + 1}: drawn {drawn}"


def test_point_solution_budget_counts_one_vertex_a_line():
    path = [(0.1, 0.1)] + [(0.5 + 0.9 * k, 4.5) for k in range(10)] + [(4.5, 0.1)]
    _, _, summary = render(SPACE2, Vehicle.POINT, format_plan(path, []),
                           RenderOptions(max_solution_points=4))
    assert (summary.solution_lines_drawn, summary.solution_lines_total) == (4, 12)


def worst_case_output(path: Path, lines: int = 1_000_000, edges: int = 250_000) -> None:
    """About 41 MB (under the 64 MiB cap): a million spaceship lines and the most
    tree rows the reader keeps, every one a distinct curve over space-2."""
    with open(path, "w") as out:
        out.write(f"{lines}\n0.1 0.1 0 0 0 0\n")
        for k in range(1, lines):
            out.write(f"{0.5 + (k * 0.37) % 9:.3f} {0.5 + (k * 0.61) % 8:.3f} "
                      f"{(k % 200) / 100 - 1:.2f} {(k % 170) / 85 - 1:.2f} "
                      f"{(k % 600) / 100:.2f} {(k % 50) / 100:.2f}\n")
        out.write(f"{edges}\n")
        for k in range(edges):
            out.write(f"{0.5 + (k * 0.53) % 9:.3f} {0.5 + (k * 0.29) % 8:.3f} "
                      f"{(k % 190) / 95 - 1:.2f} {(k % 210) / 105 - 1:.2f} "
                      f"{(k % 620) / 100:.2f} {(k % 51) / 100:.2f}\n")


@pytest.mark.slow
def test_pdf_of_a_million_line_answer_in_bounded_memory(tmp_path):
    """The issue's case (68 s and 3.16 GB before): peak memory of the whole validator,
    as ru_maxrss of a wrapper's child, under an address-space limit of 2 GiB so
    that a regression fails here instead of taking the machine's memory."""
    answer = tmp_path / "answer.out"
    worst_case_output(answer)
    wrapper = ("import resource, subprocess, sys\n"
               "limit = lambda: resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))\n"
               "done = subprocess.run(sys.argv[1:], stdin=sys.stdin, capture_output=True,\n"
               "                      preexec_fn=limit)\n"
               "sys.stderr.write(done.stderr.decode())\n"
               "print(done.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    done = subprocess.run([sys.executable, "-c", wrapper, sys.executable, "-m", "validator",
                           "-grad", "-o", "viz.pdf", "--", "cat", str(answer)],
                          input=(PROBLEMS / "space-2.sw").read_bytes(), capture_output=True,
                          timeout=300, cwd=tmp_path, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    status, max_rss_kib = map(int, done.stdout.split())
    assert status == 1, done.stderr  # the answer is invalid (it misses the goal)
    pdf = (tmp_path / "viz.pdf").read_bytes()
    assert pdf.startswith(b"%PDF") and pdf.count(b"%%EOF") == 1, done.stderr
    text = pdfium.PdfDocument(pdf)[0].get_textpage().get_text_range()
    assert "1000000 trajectory lines (first 23809 drawn), 250000 tree edges (first 47619 " \
           "drawn)" in text
    assert max_rss_kib < 512 * 1024, f"peak memory {max_rss_kib} KiB"


# atomic writes -------------------------------------------------------------------

# Renders to a path under a file-size limit of 1000 bytes (a full disk, in effect):
# the write fails part-way with EFBIG; prints the error number.
RENDER_ON_A_FULL_DISK = r"""
import resource, signal, sys
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from validator.checks import validate_output
from validator.render_pdf import render_pdf
problem = parse_problem(open(sys.argv[1]).read())
report = validate_output(problem, Vehicle.POINT, "2\n0.1 0.1\n4.5 0.1\n0\n")
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, (1000, 1000))
try:
    render_pdf(sys.argv[2], problem, Vehicle.POINT, report, report.verdict)
except OSError as error:
    print(error.errno)
"""


@pytest.fixture
def in_memory():
    """A fresh folder in /dev/shm (ordinary files in memory, under /dev), or a skip."""
    if not os.access("/dev/shm", os.W_OK | os.X_OK):
        pytest.skip("no writable /dev/shm")
    folder = Path(tempfile.mkdtemp(dir="/dev/shm"))
    yield folder
    shutil.rmtree(folder)


@pytest.mark.parametrize("where", ["tmp_path", "in_memory"])
def test_a_render_that_fails_leaves_no_file_and_an_old_file_intact(where, request):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    folder = request.getfixturevalue(where) / "out"
    folder.mkdir()
    target = folder / "viz.pdf"

    def render_on_a_full_disk() -> str:
        return subprocess.run([sys.executable, "-c", RENDER_ON_A_FULL_DISK,
                               str(PROBLEMS / "space-2.sw"), str(target)], env=env,
                              capture_output=True, text=True, timeout=60).stdout.strip()
    assert render_on_a_full_disk() == str(errno.EFBIG)
    assert list(folder.iterdir()) == []  # neither part of a PDF nor a temporary file
    target.write_bytes(b"%PDF- an older page")
    assert render_on_a_full_disk() == str(errno.EFBIG)
    assert list(folder.iterdir()) == [target]
    assert target.read_bytes() == b"%PDF- an older page"


# Renders a page with a note of the given length (so the two pages differ in size).
# Its first write to a file in the target's folder waits until the other writer has
# got that far too: the two writes overlap every time, the shorter page's last.
CONCURRENT_RENDER = r"""
import builtins, glob, os, sys, time
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from validator.checks import validate_output
from validator.render_pdf import render_pdf
problem_path, target, note = sys.argv[1], sys.argv[2], int(sys.argv[3])
folder = os.path.dirname(target)
real_open, real_fdopen = builtins.open, os.fdopen


def when_both_write():
    real_open(f"{target}.writing{note}", "w").close()
    while len(glob.glob(f"{target}.writing*")) < 2:
        time.sleep(0.001)
    if note < 100:
        time.sleep(0.5)


class Gated:
    def __init__(self, file):
        self.file, self.waited = file, False

    def write(self, data):
        if not self.waited:
            self.waited = True
            when_both_write()
        return self.file.write(data)

    def __getattr__(self, name):
        return getattr(self.file, name)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return self.file.__exit__(*exc)


def gated_open(file, mode="r", *args, **kw):
    opened = real_open(file, mode, *args, **kw)
    in_folder = isinstance(file, str) and os.path.dirname(os.path.abspath(file)) == folder
    return Gated(opened) if "w" in mode and in_folder else opened


def gated_fdopen(fd, mode="r", *args, **kw):
    opened = real_fdopen(fd, mode, *args, **kw)
    return Gated(opened) if "w" in mode else opened


builtins.open, os.fdopen = gated_open, gated_fdopen
problem = parse_problem(real_open(problem_path).read())
report = validate_output(problem, Vehicle.POINT, "2\n0.1 0.1\n4.5 0.1\n0\n")
render_pdf(target, problem, Vehicle.POINT, report, report.verdict,
           notes=["writer " + "x" * note])
"""


def test_concurrent_renders_to_one_path_leave_one_whole_pdf(tmp_path):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    umask = os.umask(0o022)
    os.umask(umask)
    folder = tmp_path / "out"
    folder.mkdir()
    target = folder / "viz.pdf"
    writers = [subprocess.Popen([sys.executable, "-c", CONCURRENT_RENDER,
                                 str(PROBLEMS / "space-2.sw"), str(target), str(note)], env=env)
               for note in (5, 800)]
    for writer in writers:
        assert writer.wait(timeout=120) == 0
    pdf = target.read_bytes()
    assert pdf.count(b"%%EOF") == 1, "a spliced file"
    text = pdfium.PdfDocument(pdf)[0].get_textpage().get_text_range()
    assert "writer xxxxx" in text and "xxxxxx" not in text  # the last writer's page
    assert sorted(p.name for p in folder.iterdir()) == [
        "viz.pdf", "viz.pdf.writing5", "viz.pdf.writing800"]  # no temporary file left
    assert target.stat().st_mode & 0o777 == 0o666 & ~umask  # as open() would make it


# the page: its shape, axes, legend -------------------------------------------------

@pytest.mark.parametrize("name", ["space-2.sw", "wall.sw", "open.sw"])
def test_page_is_cut_to_the_map(name):
    problem = parse_problem((PROBLEMS / name).read_text())
    pdf, _, _ = render(problem, Vehicle.POINT, "1\n%r %r\n0\n" % problem.start)
    width, height = pdfium.PdfDocument(pdf)[0].get_size()
    layout = page_layout(problem)
    assert (width, height) == pytest.approx((layout.page_width, layout.page_height))
    map_w, map_h = layout.scale * problem.width, layout.scale * problem.height
    assert max(width, height) <= 792 and min(width, height) <= 612  # within US letter
    # Around the map only its bands: margins, tick labels, title, captions and legend.
    assert height - map_h <= 200, (height, map_h)
    assert width - map_w <= 80 or width == 432.0, (width, map_w)
    # As large as letter allows: one side is letter's, the one the map's scale hit.
    assert any(math.isclose(side, letter_side, abs_tol=0.01)
               for side in (width, height) for letter_side in (612, 792)), (width, height)


def text_in_box(textpage, centre, half_width, half_height) -> str:
    x, y = centre
    return textpage.get_text_bounded(x - half_width, y - half_height, x + half_width,
                                     y + half_height).strip()


def test_ticks_are_labelled_in_map_units_along_the_bottom_and_left():
    pdf, report, _ = render(SPACE2, Vehicle.POINT, FAILING_POINT)
    image, text = rasterise(pdf)
    layout = page_layout(SPACE2)
    for value in range(11):
        x, y = layout.to_page(value, 0)
        assert text_in_box(text, (x, y - 9), 7, 5) == str(value), f"x = {value}"
    for value in range(10):
        x, y = layout.to_page(0, value)
        assert text_in_box(text, (x - 12, y), 8, 3.5) == str(value), f"y = {value}"
    # The failure's point lies where the labels say: right of 2, left of 3, above 0.
    fx, fy = report.first_failure.where
    assert (fx, fy) == pytest.approx((2.0259, 0.54459), abs=1e-4)
    assert pixel_near(image, layout.to_page(fx, fy), FAILURE_RGB)


def legend(textpage) -> str:
    start = textpage.get_text_range().index("red: solution")
    return textpage.get_text_range()[start:]


def label_box(textpage, label: str):
    searcher = textpage.search(label, match_case=True)
    found = searcher.get_next()
    assert found is not None, f"{label!r} is not on the page"
    return textpage.get_charbox(found[0])  # left, bottom, right, top of its first letter


@pytest.mark.parametrize("label, rgb, drawn", [
    ("red: solution", SOLUTION_RGB, True),
    ("green dot: start", START_RGB, True),
    ("blue circle: goal (radius 0.1)", GOAL_RGB, True),
    ("magenta cross: first failure", FAILURE_RGB, True),
    ("grey: blocked cell", (BLOCKED_GRAY,) * 3, True),
    ("blue-grey: tree edges", TREE_RGB, False),
    ("orange circle: corner cut", CORNER_RGB, False),
])
def test_legend_lists_what_is_drawn_with_a_swatch(label, rgb, drawn):
    pdf, _, _ = render(SPACE2, Vehicle.POINT, FAILING_POINT)  # no tree, no corner cut
    image, text = rasterise(pdf)
    assert (label in legend(text)) == drawn, legend(text)
    if drawn:
        left, bottom, _, top = label_box(text, label)
        assert pixel_near(image, (left - 10, (bottom + top) / 2), rgb, radius=12), label


def test_legend_of_a_valid_answer_with_tree_and_corner_cut():
    problem = parse_problem((PROBLEMS / "corner.sw").read_text())
    output = (CORPUS / "outputs/point/valid-corner-cut-warning.out").read_text()
    pdf, report, _ = render(problem, Vehicle.POINT, output)
    assert report.valid and report.corner_cuts
    image, text = rasterise(pdf)
    shown = legend(text)
    for label in ("blue-grey: tree edges", "orange circle: corner cut"):
        assert label in shown
        left, bottom, _, top = label_box(text, label)
        assert pixel_near(image, (left - 10, (bottom + top) / 2),
                          TREE_RGB if "tree" in label else CORNER_RGB, radius=12), label
    assert "first failure" not in shown


def test_no_light_seams_between_blocked_cells():
    pdf, _, _ = render(SPACE2, Vehicle.POINT, FAILING_POINT)
    image, _ = rasterise(pdf)
    layout = page_layout(SPACE2)
    # Column 2, rows 1 to 7 are blocked: the lines between them are blocked grey too.
    for row in range(2, 8):
        x, y = layout.to_page(2.5, row)
        assert pixel_near(image, (x, y), (BLOCKED_GRAY,) * 3, radius=0, tolerance=20), row
        for dy in (-1, 0, 1):
            px = image.getpixel((round(x * SCALE), round(image.size[1] - y * SCALE) + dy))
            assert max(px) <= BLOCKED_GRAY * 255 + 20, (row, dy, px)


def test_a_fifo_or_a_symlink_is_written_through_not_replaced(tmp_path):
    """Guards of the atomic write's own hazards (they passed before it too): a FIFO
    gets the page and stays a FIFO; a symlink stays, and its target gets the page."""
    report = validate_output(SPACE2, Vehicle.POINT, FAILING_POINT)
    fifo = tmp_path / "viz.fifo"
    os.mkfifo(fifo)
    received = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_bytes()))
    reader.start()
    render_pdf(str(fifo), SPACE2, Vehicle.POINT, report, report.verdict)
    reader.join(timeout=30)
    assert received and received[0].startswith(b"%PDF") and received[0].count(b"%%EOF") == 1
    assert stat.S_ISFIFO(fifo.lstat().st_mode)
    (tmp_path / "pages").mkdir()
    link, page = tmp_path / "viz.pdf", tmp_path / "pages" / "real.pdf"
    link.symlink_to(page)
    render_pdf(str(link), SPACE2, Vehicle.POINT, report, report.verdict)
    assert link.is_symlink() and page.read_bytes().startswith(b"%PDF")
    assert sorted(p.name for p in (tmp_path / "pages").iterdir()) == ["real.pdf"]
    page.chmod(0o640)  # an existing page keeps its permissions
    render_pdf(str(link), SPACE2, Vehicle.POINT, report, report.verdict)
    assert page.stat().st_mode & 0o777 == 0o640
