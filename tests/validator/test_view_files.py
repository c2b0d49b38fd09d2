"""-o FILE picks the picture's format by its extension (.pdf, .html, .svg, .png; an
unknown one is exit 2 with the list, before the planner runs); the HTML view is one
self-contained file that needs no reportlab, keeps what a planner wrote as text, and
shows why a planner refused; the SVG and the PNG are whole pictures."""

from __future__ import annotations

import html
import io
import json
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

import pytest

from planning_core.kinoplan_text import parse_kinoplan
from planning_core.setups import kinoplan_setup
from tests.conftest import ROOT
from tests.test_launch_scripts import checkout_copy, launch
from tests.validator.validator_testlib import VALID_POINT_PLAN, run_validator
from validator.checks import validate_plan
from validator.render_html import html_text
from validator.render_scene import SceneOptions, build_scene
from validator.render_svg import SvgOptions, svg_text

SPACE0 = (ROOT / "tests/validator/corpus/problems/space-0.sw").read_text()
FAMILY = ROOT / "benchmarks" / "problems" / "family"
MAGIC = {".pdf": b"%PDF-", ".html": b"<!DOCTYPE html>", ".svg": b"<svg ",
         ".png": b"\x89PNG\r\n\x1a\n"}


def answer_file(tmp_path, text: str = VALID_POINT_PLAN) -> list[str]:
    (tmp_path / "answer.txt").write_text(text)
    return ["--", "cat", "answer.txt"]


def scene_json(page: str) -> dict:
    found = re.search(r'<script type="application/json" id="scene">(.*?)</script>', page, re.S)
    return json.loads(found.group(1))


@pytest.fixture(scope="module")
def plain_verdict(tmp_path_factory) -> bytes:
    """The validator's stdout for the valid answer with -noviz (once per worker)."""
    folder = tmp_path_factory.mktemp("plain")
    return run_validator(["-noviz", *answer_file(folder)], SPACE0, folder).stdout


@pytest.mark.parametrize("extension", [".pdf", ".html", ".svg", ".png", ".HTML"])
def test_o_writes_the_format_its_extension_names(extension, plain_verdict, tmp_path):
    target = tmp_path / f"picture{extension}"
    done = run_validator(["-o", str(target), *answer_file(tmp_path)], SPACE0, tmp_path)
    assert done.returncode == 0 and done.stdout == plain_verdict  # the verdict as without
    assert target.read_bytes().startswith(MAGIC[extension.lower()])
    assert done.stderr.decode().endswith(f"wrote {target}\n")


def test_an_unknown_extension_is_exit_2_with_the_list_and_no_run(tmp_path):
    marker = tmp_path / "ran"
    done = run_validator(["-o", "picture.jpg", "--", "touch", str(marker)], SPACE0, tmp_path,
                         pipe=True)  # (in a file: test_validator_launcher.py)
    assert done.returncode == 2 and done.stdout == b"" and not marker.exists()
    assert done.stderr.decode().splitlines()[-1] == (
        "rrt-validator: error: -o 'picture.jpg': unknown picture format '.jpg': use one of "
        ".pdf, .html, .svg, .png")
    assert not (tmp_path / "picture.jpg").exists()


def test_the_view_and_the_svg_need_no_reportlab(tmp_path):
    copy = checkout_copy(tmp_path)
    # A set-up whose site-packages hold nothing: what a python3 without reportlab sees.
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(copy / ".venv")],
                   check=True, timeout=120)
    env = {"XDG_CACHE_HOME": str(tmp_path / "cache")}
    for name in ("view.html", "view.svg"):
        done = launch(["./rrt-validator", "-o", name, "--", "./run.sh", "-seed", "1"], copy, env)
        assert done.returncode == 0, done.stderr
        assert done.stdout == "Solution trajectory appears valid.\n"
        assert (copy / name).stat().st_size > 1000
    done = launch(["./rrt-validator", "-o", "view.png", "--", "./run.sh", "-seed", "1"], copy, env)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr == ("rrt-validator: drawing the PNG needs reportlab and pypdfium2: run "
                           "./make.sh (or pip install reportlab pypdfium2), or pass -noviz\n")


HOSTILE = "</script><script>alert(1)</script><!-- <b>x</b> \u2028"


def test_the_page_is_self_contained_and_keeps_planner_text_as_text(tmp_path):
    planner = tmp_path / "hostile.sh"
    planner.write_text(f"#!/bin/sh\necho '{HOSTILE}'\necho '{HOSTILE}' >&2\nexit 5\n")
    planner.chmod(0o755)
    done = run_validator(["-o", "view.html", "--", str(planner)], SPACE0, tmp_path)
    assert done.returncode == 1
    page = (tmp_path / "view.html").read_text()
    assert page.count("<script") == 2 and page.count("</script>") == 2  # the scene and ours
    assert "alert(1)" in page and "<script>alert" not in page
    for reference in ("http:", "https:", " src=", " href=", "url(", "@import", "fetch(",
                      "XMLHttpRequest", "WebSocket", "import("):
        assert reference not in page, reference
    assert "default-src 'none'" in page
    scene = scene_json(page)
    assert scene["failure"]["message"] == "Error parsing planner output!"
    assert HOSTILE.strip() in scene["failure"]["detail"]
    assert scene["notes"] == ["Solver returned non-zero exit code 5.",
                              f"Its stderr ends: {HOSTILE.strip()}".replace(
                                  "\u2028", "\\u2028")]


def test_the_view_shows_why_a_planner_refused(tmp_path):
    planner = tmp_path / "refuse.sh"
    planner.write_text("#!/bin/sh\necho 'refuse: bad problem: line 3, column 1' >&2\nexit 2\n")
    planner.chmod(0o755)
    run_validator(["-o", "view.html", "--", str(planner)], SPACE0, tmp_path)
    notes = scene_json((tmp_path / "view.html").read_text())["notes"]
    assert notes == ["Solver returned non-zero exit code 2.",
                     "Its stderr ends: refuse: bad problem: line 3, column 1"]


def test_a_timed_out_run_is_a_view_of_the_problem_that_says_so(tmp_path):
    done = run_validator(["-timeout", "0.2", "-o", "view.html", "--", "sleep", "30"], SPACE0,
                         tmp_path)
    assert done.returncode == 3
    scene = scene_json((tmp_path / "view.html").read_text())
    assert scene["answer"] is False and scene["notes"][0].startswith("Solver timed out after")
    layers = {layer["id"] for layer in scene["views"][0]["plots"][0]["layers"]}
    assert layers == {"grid", "obstacles", "marks"}  # the map, start and goal: no answer


def family_scene(name: str, output: str | None = None, **options) -> dict:
    problem = parse_kinoplan((FAMILY / f"{name}.kp").read_text())
    text = output if output is not None else (FAMILY / "solutions" / f"{name}.out").read_text()
    report = validate_plan(kinoplan_setup(problem), text)
    return build_scene(problem, None, report, report.verdict, [], name, SceneOptions(**options))


@pytest.mark.parametrize("name", ["pendulum-t3", "car2-corridors", "unicycle-circles",
                                  "car1-scene1", "arm2-pair1", "rigid2-scene1"])
def test_every_system_has_its_views_and_an_svg(name):
    scene = family_scene(name)
    names = [view["name"] for view in scene["views"]]
    assert names == {"pendulum-t3": ["Phase portrait", "Against time"],
                     "arm2-pair1": ["Workspace", "Configuration space"],
                     "rigid2-scene1": ["Workspace"]}.get(name, ["Workspace", "Against time"])
    svg = ElementTree.fromstring(svg_text(scene))
    assert svg.tag == "{http://www.w3.org/2000/svg}svg"
    texts = " ".join(t.text or "" for t in svg.iter("{http://www.w3.org/2000/svg}text"))
    assert "Solution trajectory appears valid." in texts
    assert json.loads(html_text(scene).split('id="scene">')[1].split("</script>")[0])


def test_a_big_tree_is_thinned_in_the_svg_and_the_picture_says_so():
    problem = parse_kinoplan((FAMILY / "rigid2-scene1.kp").read_text())
    path = (FAMILY / "solutions" / "rigid2-scene1.out").read_text().split("\n0\n")[0]
    tree = [f"0.5 0.25 0 {0.1 + k * 1e-5} 0.3 0" for k in range(20_000)]
    output = f"{path}\n{len(tree)}\n" + "\n".join(tree) + "\n"
    report = validate_plan(kinoplan_setup(problem), output)
    scene = build_scene(problem, None, report, report.verdict)
    assert scene["tree"]["kept"] == 20_000 and scene["tree"]["stride"] == 1
    svg = svg_text(scene, SvgOptions(max_points=10_000))
    assert "(the picture: one tree edge in 4)" in html.unescape(svg)
    small = family_scene("rigid2-scene1", output, max_tree_points=10_000)
    assert small["tree"]["stride"] == 4 and "(thinned: one in 4 drawn)" in small["counts"]


def test_the_png_stacks_the_pdf_pages(tmp_path):
    from PIL import Image
    problem = (FAMILY / "car2-corridors.kp").read_text()
    (tmp_path / "answer.txt").write_text((FAMILY / "solutions/car2-corridors.out").read_text())
    done = run_validator(["-o", "car.png", "--", "cat", "answer.txt"], problem, tmp_path)
    assert done.returncode == 0, done.stderr
    image = Image.open(io.BytesIO((tmp_path / "car.png").read_bytes()))
    assert image.mode == "RGB" and image.width == 2 * 792  # the time page, landscape
    assert image.height > 2 * (612 + 612)  # the workspace page (portrait) and the time page
