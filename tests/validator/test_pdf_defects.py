"""The PDF's defects found by trying it as a new user would: paths that strict readers
drop, a square workspace on a landscape page, bodies without a front, a start and goal
lost under a dense tree, the arm's goal pose under its last pose, strips with one tick,
a duration called a path length, a planner's refusal and a run without an answer that
the page did not explain."""

from __future__ import annotations

import io
import math
import random
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pypdfium2 as pdfium
import pytest

from planning_core.kinoplan_text import parse_kinoplan
from planning_core.plan_text import format_plan
from planning_core.problem_text import parse_problem
from planning_core.setups import kinoplan_setup
from planning_core.vehicles import Vehicle
from tests.conftest import ROOT
from tests.validator.test_family_checks import PROBLEM as CAR2, answer as car2_answer
from tests.validator.test_family_geometric_checks import answer as path_answer
from tests.validator.test_family_pdf import ARM
from tests.validator.validator_testlib import run_validator
from validator.checks import validate_output, validate_plan
from validator.render_pdf import render_pdf

FAMILY = ROOT / "benchmarks" / "problems" / "family"


def family_pdf(problem_text: str, output: str, notes=()) -> bytes:
    problem = parse_kinoplan(problem_text)
    report = validate_plan(kinoplan_setup(problem), output)
    out = io.BytesIO()
    render_pdf(out, problem, None, report, report.verdict, list(notes), "test.kp")
    return out.getvalue()


def image(pdf: bytes, page: int = 0, scale: float = 2.0):
    return pdfium.PdfDocument(pdf)[page].render(scale=scale).to_pil().convert("RGB")


def page_text(pdf: bytes, page: int = 0) -> str:
    return pdfium.PdfDocument(pdf)[page].get_textpage().get_text_range()


def close(rgb, want, tolerance=45) -> bool:
    return all(abs(a - 255 * b) <= tolerance for a, b in zip(rgb, want))


def count_close(pixels: np.ndarray, want, tolerance=45) -> int:
    """How many of ``pixels`` (rows, columns, RGB) are :func:`close` to ``want``."""
    return int(np.all(np.abs(pixels - 255 * np.array(want)) <= tolerance, axis=2).sum())


def strict_reader_complaints(pdf: bytes, tmp_path: Path) -> list[str]:
    """What Poppler's pdftoppm and qpdf --check say of the file (nothing when whole)."""
    tools = [tool for tool in ("pdftoppm", "qpdf") if shutil.which(tool)]
    if not tools:
        pytest.skip("no strict PDF reader (poppler-utils' pdftoppm, qpdf): ./make.sh "
                    "installs them where it can")
    path = tmp_path / "check.pdf"
    path.write_bytes(pdf)
    said = []
    if "pdftoppm" in tools:
        done = subprocess.run(["pdftoppm", "-r", "20", "-png", str(path), str(tmp_path / "p")],
                              capture_output=True, text=True, timeout=120)
        said += done.stderr.splitlines() + ([f"exit {done.returncode}"] if done.returncode else [])
    if "qpdf" in tools:
        done = subprocess.run(["qpdf", "--check", str(path)], capture_output=True, text=True,
                              timeout=120)
        if done.returncode:
            said += done.stdout.splitlines() + done.stderr.splitlines()
    return said


def car2_tree(count: int, k: int = 5) -> list[tuple[float, ...]]:
    """``count`` tree edges of K = ``k`` slices spread over the corridor world."""
    rng = random.Random(7)
    return [(rng.uniform(2, 18), rng.uniform(2, 18), rng.uniform(-3, 3), 4.0, 1.0, 0.0, k)
            for _ in range(count)]


def test_family_tree_paths_cut_anywhere_still_parse_strictly(tmp_path):
    rows, _ = car2_answer()
    pdf = family_pdf(CAR2, format_plan(rows, car2_tree(2500)))  # 15 000 path operators
    assert strict_reader_complaints(pdf, tmp_path) == []


def test_a_square_workspace_gets_a_page_of_its_shape():
    rows, _ = car2_answer()
    document = pdfium.PdfDocument(family_pdf(CAR2, format_plan(rows, [])))
    width, height = document[0].get_size()
    assert height > width  # 20 x 20: the page stands up; the time page stays landscape
    assert document[1].get_size() == (792.0, 612.0)
    # The square spans the page's width less its margins: 504 pt, 415 on a landscape page.
    picture = image(family_pdf(CAR2, format_plan(rows, [])), scale=1)
    row = int(height / 2)
    frame = [x for x in range(int(width)) if picture.getpixel((x, row))[0] < 100]
    assert frame[-1] - frame[0] >= 480


def test_bodies_show_which_way_they_face():
    rows, _ = car2_answer()
    picture = image(family_pdf(CAR2, format_plan(rows, [])))
    front = count_close(np.asarray(picture, dtype=float)[::2, ::2], (0.45, 0.0, 0.20), 40)
    assert front > 20


def dense_point_tree(centre: tuple[float, float], count: int, reach: float = 1.5) -> str:
    rng = random.Random(3)
    rows = []
    for _ in range(count):
        a = (centre[0] + rng.uniform(-reach, reach), centre[1] + rng.uniform(-reach, reach))
        b = (centre[0] + rng.uniform(-reach, reach), centre[1] + rng.uniform(-reach, reach))
        rows.append(f"{a[0]} {a[1]} {b[0]} {b[1]}")
    return "\n".join(rows)


def test_the_grid_start_and_goal_stand_out_over_a_dense_tree():
    problem = parse_problem("10\n10\n" + "__________\n" * 10 + "3\n3\n7\n7\n")
    tree = dense_point_tree((3, 3), 4000) + "\n" + dense_point_tree((7, 7), 4000)
    output = f"2\n3 3\n7 7\n8000\n{tree}\n"
    report = validate_output(problem, Vehicle.POINT, output)
    out = io.BytesIO()
    render_pdf(out, problem, Vehicle.POINT, report, report.verdict)
    from validator.render_grid import page_layout
    layout = page_layout(problem)
    picture = image(out.getvalue())
    for (x, y), ring in (((3, 3), 5.4), ((7, 7), 0.1 * layout.scale + 1.6)):
        px, py = layout.to_page(x, y)
        # A white ring around each (off the solution's diagonal): no tree line crosses it.
        for angle in (0.5, 1.2, 2.0, 2.6, 3.7, 4.5, 5.9):
            at = (round(2 * (px + ring * math.cos(angle))),
                  round(2 * (layout.page_height - py - ring * math.sin(angle))))
            assert close(picture.getpixel(at), (1, 1, 1), 30), ((x, y), angle)
    px, py = layout.to_page(2.96, 3.04)  # 3.2 pt from the start, across the solution
    assert close(picture.getpixel((round(2 * px), round(2 * (layout.page_height - py)))),
                 (0.0, 0.6, 0.0))


def test_the_arm_goal_pose_shows_over_the_last_pose():
    # The path ends on the goal pose: it was drawn thin under the last pose, thick red.
    pdf = family_pdf(ARM, path_answer([(-1.5, 0.0), (-1.0, 0.3), (-0.5, 0.5)]))
    picture = image(pdf)
    above_the_legend = picture.height - 2 * 110
    blue = count_close(np.asarray(picture, dtype=float)[0:above_the_legend:2],
                       (0.10, 0.20, 0.95), 40)
    assert blue >= 200  # 330 in dashes over it; 90 where a thin line blended with the red


def test_time_strips_label_several_ticks_and_angles_in_pi():
    problem = (FAMILY / "car2-corridors.kp").read_text()
    pdf = family_pdf(problem, (FAMILY / "solutions" / "car2-corridors.out").read_text())
    labels = page_text(pdf, 1).split()
    # x and y run from -40 to 40 on strips 50 pt high: at least -40 ... 40 in twenties.
    for value in ("-40", "-20", "20", "40"):
        assert labels.count(value) >= 2, value
    assert labels.count("pi") >= 1 and labels.count("-pi") >= 1  # theta, as car1's


def test_a_kinodynamic_answer_is_measured_in_seconds():
    problem = (FAMILY / "pendulum-t3.kp").read_text()
    pdf = family_pdf(problem, (FAMILY / "solutions" / "pendulum-t3.out").read_text())
    text = page_text(pdf)
    assert "duration" in text and "path length" not in text


def test_a_planner_refusal_shows_its_reason_on_the_page(tmp_path):
    planner = tmp_path / "refuse.sh"
    planner.write_text("#!/bin/sh\necho 'refuse: bad problem: line 3, column 1: a width' >&2\n"
                       "exit 2\n")
    planner.chmod(0o755)
    pdf = tmp_path / "refused.pdf"
    done = run_validator(["-o", str(pdf), "--", str(planner)],
                         (ROOT / "benchmarks/problems/course/space-1.sw").read_bytes(), tmp_path)
    assert done.returncode == 1
    text = page_text(pdf.read_bytes())
    assert "Solver returned non-zero exit code 2." in text
    assert "refuse: bad problem: line 3, column 1: a width" in text


def test_a_run_without_an_answer_says_why_over_the_map():
    problem = parse_problem((ROOT / "benchmarks/problems/course/space-1.sw").read_text())
    out = io.BytesIO()
    render_pdf(out, problem, Vehicle.POINT, None, "Putative solution trajectory has problems.",
               ["Solver timed out after 60 s; its process group was killed."], "alice")
    from validator.render_grid import page_layout
    layout = page_layout(problem)
    picture = image(out.getvalue())
    px, py = layout.to_page(problem.width / 2, problem.height / 2)
    near = [picture.getpixel((round(2 * px) + dx, round(2 * (layout.page_height - py)) + dy))
            for dx in range(-200, 201, 2) for dy in range(-12, 13, 2)]
    assert any(close(p, (0.85, 0.0, 0.85), 60) for p in near)
