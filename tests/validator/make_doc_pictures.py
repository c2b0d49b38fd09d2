"""Regenerate the docs' pictures (docs/tree-viz.png, docs/img/*.png) from the validator's
browser view: each run planned by ./run.sh, checked by ./rrt-validator -o FILE.html, and
the view (the tab named) taken in headless Chromium (tests/validator/browser.py).

    .venv/bin/python tests/validator/make_doc_pictures.py [NAME ...]

prints each picture's run and the counts the view shows; NAME picks some by file name.
"""

from __future__ import annotations

import io
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from PIL import Image  # noqa: E402

from tests.validator.browser import Chromium, find_chromium  # noqa: E402

PROBLEMS = ROOT / "benchmarks" / "problems"
# picture, problem, the planner's flags, the validator's flags, the view's tab (from 0)
PICTURES = [
    ("tree-viz.png", "course/space-2.sw", ["-grad", "-seed", "1"], ["-grad"], 0),
    ("img/family-pendulum-phase.png", "family/pendulum-t3.kp", ["-planner", "rrt"], [], 0),
    ("img/family-pendulum-time.png", "family/pendulum-t3.kp", ["-planner", "rrt"], [], 1),
    ("img/family-pendulum-rgrrt.png", "family/pendulum-t3.kp", ["-planner", "rgrrt"], [], 0),
    ("img/family-car1-footprints.png", "family/car1-scene1.kp", ["-planner", "rrt"], [], 0),
    ("img/family-car1-blossom.png", "family/car1-scene2.kp", ["-planner", "blossom"], [], 0),
    ("img/family-car2-footprints.png", "family/car2-corridors.kp", ["-planner", "rrt"], [], 0),
    ("img/family-car2-kpiece.png", "family/car2-corridors.kp", ["-planner", "kpiece"], [], 0),
    ("img/family-unicycle-footprints.png", "family/unicycle-circles.kp",
     ["-planner", "kpiece"], [], 0),
    ("img/family-unicycle-time.png", "family/unicycle-circles.kp", ["-planner", "kpiece"], [], 1),
    ("img/family-arm2-workspace.png", "family/arm2-pair1.kp", ["-planner", "rrt"], [], 0),
    ("img/family-arm2-cspace.png", "family/arm2-pair1.kp", ["-planner", "rrt"], [], 1),
    ("img/family-arm2-prmstar-workspace.png", "family/arm2-pair1.kp", ["-planner", "prmstar"],
     [], 0),
    ("img/family-arm2-prmstar-cspace.png", "family/arm2-pair1.kp", ["-planner", "prmstar"], [],
     1),
    ("img/family-rigid2-poses.png", "family/rigid2-scene1.kp", ["-planner", "rrt"], [], 0),
    ("img/family-rigid2-scene2-smooth.png", "family/rigid2-scene2.kp",
     ["-planner", "rrtconnect", "-smooth"], [], 0),
    ("img/family-rigid2-scene3.png", "family/rigid2-scene3.kp", ["-planner", "rrtconnect"], [],
     0),
    ("img/family-rigid2-slot-smooth.png", "family/variants/rigid2-slot.kp",
     ["-planner", "rrtconnect", "-smooth"], [], 0),
    # docs/optimal-planning.md: RRT's first answer against RRT*'s best in 1 s, same seed
    ("img/course-space-1-rrt.png", "course/space-1.sw", ["-planner", "rrt"], [], 0),
    ("img/course-space-1-rrtstar.png", "course/space-1.sw",
     ["-planner", "rrtstar", "-optimize", "-time", "1"], [], 0),
    ("img/course-space-1-dubins-rrt.png", "course/space-1.sw",
     ["-dubins", "-radius", "0.5", "-planner", "rrt"], ["-dubins", "-radius", "0.5"], 0),
    ("img/course-space-1-dubins-rrtstar.png", "course/space-1.sw",
     ["-dubins", "-radius", "0.5", "-planner", "rrtstar", "-optimize", "-time", "1"],
     ["-dubins", "-radius", "0.5"], 0),
]
SEED = ["-seed", "1"]


def view_of(problem: Path, planner: list[str], flags: list[str], folder: Path) -> Path:
    """The run's page: the problem on stdin as a file (the view names it)."""
    answer = folder / "answer.txt"
    with open(problem, "rb") as stdin:
        answer.write_bytes(subprocess.run([str(ROOT / "run.sh"), *planner], stdin=stdin,
                                          capture_output=True, check=True, timeout=300).stdout)
    page = folder / "view.html"
    with open(problem, "rb") as stdin:
        subprocess.run([str(ROOT / "rrt-validator"), *flags, "-o", str(page), "--", "cat",
                        str(answer)], stdin=stdin, capture_output=True, timeout=300)
    return page


def main(names: list[str]) -> int:
    chromium = find_chromium()
    if chromium is None:
        print("no Chromium: ./make.sh installs Debian's chromium where it can", file=sys.stderr)
        return 1
    with Chromium(chromium, 1280, 860) as browser, tempfile.TemporaryDirectory() as folder:
        for picture, problem, planner, flags, tab in PICTURES:
            if names and Path(picture).name not in names:
                continue
            planner = planner if "-seed" in planner else [*planner, *SEED]
            page = view_of(PROBLEMS / problem, planner, flags, Path(folder))
            browser.open(f"{page.as_uri()}#view={tab}")
            browser.wait_for(lambda: browser.evaluate("window.rrtView && window.rrtView.ready"))
            errors = browser.console_errors()
            if errors:
                print(f"{picture}: {errors}", file=sys.stderr)
                return 1
            image = Image.open(io.BytesIO(browser.screenshot())).convert("RGB")
            image.quantize(256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE).save(
                ROOT / "docs" / picture, optimize=True)
            counts = browser.evaluate("document.getElementById('counts').textContent")
            print(f"{picture}: {problem} {' '.join(planner)}: {counts}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
