"""The validator's browser view (-o FILE.html) in a real headless Chromium: for a grid
run, a spaceship run, the pendulum, car1, the arm and the rigid body, the page loads
without a console error, its screenshot shows the map, the tree and the answer (by
pixels), the growth slider changes how many edges are drawn, and a failing answer
shows its marker and message. Skipped, with one line, where there is no Chromium
(./make.sh installs Debian's where it can)."""

from __future__ import annotations

import functools
import io
import subprocess

import numpy as np
import pytest
from PIL import Image

from tests.conftest import ROOT, unit_sample
from tests.validator.browser import Chromium, find_chromium
from tests.validator.validator_testlib import run_validator

CHROMIUM = find_chromium()
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="no Chromium: ./make.sh installs "
                                "Debian's chromium where it can (apt-get, as root)")
PROBLEMS = ROOT / "benchmarks" / "problems"
TREE = (128, 158, 209)
ANSWER = (217, 13, 13)
FAILURE = (217, 0, 217)
CASES = {  # problem, planner flags, validator flags, obstacle colour (None: no obstacle)
    # The unit run draws the first two, the grid and a family system (the arm, at its
    # configuration space), and fails the grid's answer; CI runs all six both ways.
    "grid": ("course/space-2.sw", ["-seed", "1"], [], (77, 77, 77)),
    "arm2": ("family/arm2-pair1.kp", ["-planner", "rrt", "-seed", "1"], [], (140, 140, 140)),
    "spaceship": ("course/space-2.sw", ["-grad", "-seed", "1"], ["-grad"], (77, 77, 77)),
    "pendulum": ("family/pendulum-t3.kp", ["-planner", "rrt", "-seed", "1"], [], None),
    "car1": ("family/car1-scene1.kp", ["-planner", "rrt", "-seed", "1"], [], (140, 140, 140)),
    "rigid2": ("family/rigid2-scene1.kp", ["-planner", "rrt", "-seed", "1"], [],
               (140, 140, 140)),
}


@pytest.fixture(scope="module")
def browser():
    with Chromium(CHROMIUM) as chromium:
        yield chromium


@functools.lru_cache(maxsize=None)
def plan(case: str) -> tuple[str, list[str], str]:
    """The case's problem, validator flags and our planner's answer (planned once per
    worker: the tests that draw it and the ones that fail it share the run)."""
    problem, planner_flags, flags, _ = CASES[case]
    text = (PROBLEMS / problem).read_text()
    done = subprocess.run([str(ROOT / "run.sh"), *planner_flags], input=text, text=True,
                          capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return text, flags, done.stdout


def view(text: str, flags: list[str], answer: str, tmp_path, name: str = "view.html"):
    (tmp_path / "answer.txt").write_text(answer)
    page = tmp_path / name
    done = run_validator([*flags, "-o", str(page), "--", "cat", "answer.txt"], text, tmp_path)
    assert done.returncode in (0, 1), done.stderr
    assert page.exists(), done.stderr
    return page


def load(browser: Chromium, page, case: str = "") -> dict:
    """Open the page (the arm at its configuration space, where its tree is)."""
    browser.open(page.as_uri() + ("#view=1" if case == "arm2" else ""))
    browser.wait_for(lambda: browser.evaluate("window.rrtView && window.rrtView.ready"))
    return browser.evaluate("JSON.parse(JSON.stringify(window.rrtView))")


def canvas_pixels(browser: Chromium) -> np.ndarray:
    """The screenshot's pixels within the canvas (rows, columns, RGB)."""
    box = browser.evaluate("(() => { const r = document.querySelector('canvas')"
                           ".getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom]"
                           "; })()")
    shot = Image.open(io.BytesIO(browser.screenshot())).convert("RGB")
    return np.asarray(shot.crop(tuple(round(v) for v in box)), dtype=np.int16)


def count(pixels: np.ndarray, rgb, tolerance: int = 40) -> int:
    return int(np.all(np.abs(pixels - np.array(rgb)) <= tolerance, axis=2).sum())


def slide(browser: Chromium, value: int) -> None:
    draws = browser.evaluate("window.rrtView.draws")
    browser.evaluate(f"(() => {{ const s = document.getElementById('grow'); s.value = {value}; "
                     "s.dispatchEvent(new Event('input')); })()")
    browser.wait_for(lambda: browser.evaluate("window.rrtView.draws") > draws)


@pytest.mark.parametrize("case", unit_sample(CASES, keep=2))
def test_the_view_draws_the_run_and_grows_the_tree(case, browser, tmp_path):
    text, flags, answer = plan(case)
    stats = load(browser, view(text, flags, answer, tmp_path), case)
    assert browser.console_errors() == [] and stats["error"] is None
    pixels = canvas_pixels(browser)
    assert count(pixels, TREE) > 200 and count(pixels, ANSWER) > 200
    obstacle = CASES[case][3]
    if obstacle is not None:
        assert count(pixels, obstacle, 6) > 500
    full = stats["edgesDrawn"]
    kept = browser.evaluate("Number(document.getElementById('grow').max)")
    assert full > 0 and kept > 0
    slide(browser, kept // 10)
    fewer = browser.evaluate("window.rrtView.edgesDrawn")
    assert 0 < fewer < full
    assert count(canvas_pixels(browser), TREE) < count(pixels, TREE)
    slide(browser, 0)
    assert browser.evaluate("window.rrtView.edgesDrawn") == 0
    assert browser.console_errors() == []


def shifted(answer: str, by: float = 0.3) -> str:
    """The answer with its first line's first number moved: check 4 fails there."""
    lines = answer.splitlines()
    numbers = lines[1].split()
    numbers[0] = repr(float(numbers[0]) + by)
    lines[1] = " ".join(numbers)
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("case", unit_sample(CASES, keep=1))
def test_a_failing_answer_shows_its_marker_and_message(case, browser, tmp_path):
    text, flags, answer = plan(case)
    load(browser, view(text, flags, shifted(answer), tmp_path), case)
    assert browser.console_errors() == []
    message = browser.evaluate("document.getElementById('failure').textContent")
    assert message.startswith("First failure (check 4, line 2): Trajectory doesn't start at "
                              "start!")
    assert browser.evaluate("document.getElementById('verdict').className") == "invalid"
    assert count(canvas_pixels(browser), FAILURE) > 40


def test_what_a_planner_wrote_is_shown_as_text(browser, tmp_path):
    hostile = "</script><img src=x onerror=alert(1)><b>bold</b>"
    text, flags, _ = plan("grid")
    page = view(text, flags, f"1\n{hostile}\n0\n", tmp_path)
    load(browser, page)
    assert browser.console_errors() == []
    assert hostile in browser.evaluate("document.getElementById('failure').textContent")
    assert browser.evaluate("document.querySelectorAll('img, b').length") == 0


@pytest.mark.slow
def test_a_million_edge_tree_opens_in_under_3_s_in_under_60_mb(browser, tmp_path):
    """A point tree of 1 000 000 edges on a 500 x 500 map, all kept (the library's
    Limits; the command line keeps 250 000): the file's size and the time from
    navigation to the first complete draw."""
    import random
    from planning_core.problem_text import parse_problem
    from planning_core.setups import grid_setup
    from planning_core.vehicles import Vehicle
    from validator.checks import Limits, validate_plan
    from validator.render_html import write_html
    from validator.render_scene import build_scene
    rng = random.Random(1)
    rows = ["".join("#" if rng.random() < 0.1 else "_" for _ in range(500)) for _ in range(500)]
    rows[-1] = "_" + rows[-1][1:]
    problem = parse_problem("500\n500\n" + "\n".join(rows) + "\n0.5\n0.5\n499.5\n499.5\n")
    edges = []
    for _ in range(1_000_000):
        x, y = rng.uniform(1, 499), rng.uniform(1, 499)
        edges.append(f"{x:.3f} {y:.3f} {x + rng.uniform(-1, 1):.3f} {y + rng.uniform(-1, 1):.3f}")
    output = "1\n0.5 0.5\n1000000\n" + "\n".join(edges) + "\n"
    report = validate_plan(grid_setup(problem, Vehicle.POINT), output,
                           limits=Limits(max_tree_rows_kept=1_000_000))
    page = tmp_path / "big.html"
    write_html(str(page), build_scene(problem, Vehicle.POINT, report, report.verdict))
    assert page.stat().st_size < 60e6
    stats = load(browser, page)
    assert browser.console_errors() == [] and stats["edgesDrawn"] == 1_000_000
    assert stats["firstDrawMs"] < 3000


def mouse(browser: Chromium, kind: str, x: float, y: float, **more) -> None:
    browser.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, **more)


def test_zoom_pan_layers_and_the_pointer_coordinates(browser, tmp_path):
    text, flags, answer = plan("grid")
    load(browser, view(text, flags, answer, tmp_path))
    left, top, right, bottom = browser.evaluate(
        "(() => { const r = document.querySelector('canvas').getBoundingClientRect();"
        " return [r.left, r.top, r.right, r.bottom]; })()")
    x, y = (left + right) / 2, (top + bottom) / 2
    mouse(browser, "mouseMoved", x, y)
    said = browser.evaluate("document.getElementById('pointer').textContent")
    assert said.startswith("x ") and ", y " in said and "(cell " in said
    before = browser.evaluate("window.rrtView.plots[0]")
    draws = browser.evaluate("window.rrtView.draws")
    mouse(browser, "mouseWheel", x, y, deltaX=0, deltaY=-400)
    browser.wait_for(lambda: browser.evaluate("window.rrtView.draws") > draws)
    zoomed = browser.evaluate("window.rrtView.plots[0]")
    assert zoomed[0] > 1.5 * before[0] and zoomed[1] > 1.5 * before[1]
    mouse(browser, "mousePressed", x, y, button="left", clickCount=1)
    mouse(browser, "mouseMoved", x + 80, y + 30, button="left", buttons=1)
    mouse(browser, "mouseReleased", x + 80, y + 30, button="left", clickCount=1)
    browser.wait_for(lambda: browser.evaluate("window.rrtView.plots[0][2]") != zoomed[2])
    panned = browser.evaluate("window.rrtView.plots[0]")
    assert (round(panned[2] - zoomed[2]), round(panned[3] - zoomed[3])) == (80, 30)
    assert count(canvas_pixels(browser), TREE) > 0
    draws = browser.evaluate("window.rrtView.draws")
    browser.evaluate("document.getElementById('layer-tree').click()")
    browser.wait_for(lambda: browser.evaluate("window.rrtView.draws") > draws)
    assert count(canvas_pixels(browser), TREE, 10) == 0
    assert browser.console_errors() == []
