"""Write the validator's corpus: problems, planner outputs and ``cases.json``.

Run it from the repository root after changing a case:
``.venv/bin/python tests/validator/corpus/make_corpus.py``. The tests only read
the files it writes. Point outputs are written out by hand below; spaceship
outputs are built from hand-picked controls with the core's ``propagate`` (no
one types 17-digit states), then edited by hand where a case needs a fault.
Two outputs come from our planner (``-seed``), as a real-world sample.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
sys.path.insert(0, str(ROOT))

from planning_core.plan_text import format_plan  # noqa: E402
from planning_core.systems import spaceship  # noqa: E402

PROBLEMS = HERE / "problems"
OUTPUTS = HERE / "outputs"
CASES: list[dict] = []

PARSE, EMPTY, BOUNDS = ("Error parsing planner output!", "Empty trajectory!",
                        "State in trajectory that goes out of bounds!")
START, LAST_EDGE = "Trajectory doesn't start at start!", "Last edge in trajectory had collision!"
GOAL = "Trajectory doesn't get close enough to goal!"
POINT_HIT, SHIP_HIT = ("Trajectory collides with an obstacle!",
                       "Trajectory collides with something!")
DYNAMICS = "Trajectory claims that control"


def problem(name: str, rows: list[str], start, goal) -> str:
    text = "\n".join([str(len(rows[0])), str(len(rows)), *rows,
                      *(repr(float(v)) for v in (*start, *goal))]) + "\n"
    (PROBLEMS / name).write_text(text)
    return name


def case(name: str, problem_name: str, output: str | bytes, flags: list[str], valid: bool,
         check: int | None = None, message: str | None = None, line: int | None = None,
         warning: str | None = None, note: str = "") -> None:
    sub = "spaceship" if any(f in ("-grad", "-left") for f in flags) else "point"
    path = OUTPUTS / sub / f"{name}.out"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(output if isinstance(output, bytes) else output.encode())
    CASES.append({"name": name, "problem": problem_name, "output": f"{sub}/{name}.out",
                  "flags": flags, "valid": valid, "check": check, "message": message,
                  "line": line, "warning": warning, "note": note})


def fly(start: tuple[float, float], controls: list[tuple[float, float]]):
    """Trajectory lines from rest at ``start`` under ``controls``; and the end state."""
    state = (start[0], start[1], 0.0, 0.0)
    rows = []
    for control in controls:
        rows.append(state + control)
        state = spaceship.SYSTEM.propagate(state, control)
    return rows, state


def planner_output(problem_name: str, args: list[str]) -> str:
    text = (PROBLEMS / problem_name).read_text()
    done = subprocess.run([sys.executable, "-m", "rrt_cli", *args], input=text.encode(),
                          capture_output=True, check=True, cwd=ROOT)
    return done.stdout.decode()


def point_cases() -> None:
    sp0 = "space-0.sw"  # 4 x 3; blocked (2, 1) and (3, 0); start (0.1, 1.54), goal (3.8, 1.1)
    good = "4\n0.1 1.54\n1.5 2.5\n3.5 2.5\n3.8 1.1\n3\n0.1 1.54 1.5 2.5\n1.5 2.5 3.5 2.5\n" \
           "3.5 2.5 3.8 1.1\n"
    case("valid-handmade", sp0, good, [], True, note="around the blocked cell, over the top")
    case("valid-ugrad-flag", sp0, good, ["-ugrad"], True)
    case("valid-goal-at-0.1", sp0, "4\n0.1 1.54\n1.5 2.5\n3.5 2.5\n3.8 1.2\n0\n", [], True,
         note="last point 0.1 from the goal (distance <= 0.1 passes)")
    case("valid-start-within-0.001", sp0, "4\n0.1009 1.5391\n1.5 2.5\n3.5 2.5\n3.8 1.1\n0\n",
         [], True, note="0.0009 from the start in x and y")
    case("valid-format-variants", sp0,
         "\r\n\r\n  4 \r\n0.100000\t1.540000\r\n1.500000   2.500000 \r\n3.5e0 25e-1\r\n"
         "+3.8 1.1\r\n\r\n0\r\n\r\n", [], True,
         note="CRLF, blank lines before the counts, tabs, %f / exponent / signed numbers")
    case("valid-trailing-text", sp0, good + "planning took 3 ms\n", [], True,
         warning="text after the tree is ignored")
    case("valid-planner-seed1", "space-2.sw", planner_output("space-2.sw", ["-seed", "1"]),
         [], True, note="our planner's output")
    corner = problem("corner.sw", ["____", "__#_", "____"], (1.0, 0.99), (3.0, 2.95))
    cut = "2\n1.0 0.99\n3.0 2.99\n1\n1.0 0.99 3.0 2.99\n"
    case("valid-corner-cut-warning", corner, cut, [], True,
         warning="cuts the corner of blocked cell (2, 1)",
         note="y = x - 0.01 enters cell (2, 1) for 0.014 units, between two samples")
    case("invalid-corner-cut-strict", corner, cut, ["-strict"], False, 6, POINT_HIT, 2)

    case("parse-empty", sp0, "", [], False, 1, PARSE, 1)
    case("parse-garbage", sp0, "hello world\n", [], False, 1, PARSE, 1)
    case("parse-negative-count", sp0, "-2\n0.1 1.54\n3.8 1.1\n0\n", [], False, 1, PARSE, 1)
    case("parse-huge-count", sp0, "184467440737095516160\n0.1 1.54\n0\n", [], False, 1,
         PARSE, 1)
    case("parse-truncated", sp0, "4\n0.1 1.54\n1.5 2.5\n3.5 2.", [], False, 1, PARSE, 1,
         note="count 4, output cut in the third line")
    case("parse-truncated-tree", sp0, good[:-12], [], False, 1, PARSE, 9,
         note="the last tree line is cut after its first number")
    case("parse-nan", sp0, "2\n0.1 1.54\nnan 1.1\n0\n", [], False, 1, PARSE, 3)
    case("parse-overflow", sp0, "2\n0.1 1.54\n3.8 1e400\n0\n", [], False, 1, PARSE, 3)
    case("parse-three-numbers", sp0, "2\n0.1 1.54\n3.8 1.1 0\n0\n", [], False, 1, PARSE, 3)
    case("parse-spaceship-answer", sp0, "1\n0.1 1.54 0.0 0.0 0.0 0.0\n0\n", [], False, 1,
         PARSE, 2, note="6 numbers a line: the message suggests -grad")
    case("parse-tree-line", sp0, "2\n0.1 1.54\n3.8 1.2\n1\n0.1 1.54 3.8\n", [], False, 1,
         PARSE, 5)
    case("parse-binary", sp0, b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe", [], False, 1,
         PARSE, 1)
    case("empty-trajectory", sp0, "0\n0\n", [], False, 2, EMPTY, 1)
    case("bounds-x-equals-width", sp0, "3\n0.1 1.54\n4.0 2.5\n3.8 1.1\n0\n", [], False, 3,
         BOUNDS, 3, note="points must be strictly inside: x = W is out")
    case("bounds-negative", sp0, "3\n0.1 1.54\n1.0 -0.5\n3.8 1.1\n0\n", [], False, 3,
         BOUNDS, 3)
    case("bounds-y-zero", sp0, "3\n0.1 1.54\n1.0 0\n3.8 1.1\n0\n", [], False, 3, BOUNDS, 3)
    case("start-wrong", sp0, "3\n0.1011 1.54\n3.5 2.5\n3.8 1.1\n0\n", [], False, 4, START, 2,
         note="0.0011 from the start in x")
    case("goal-too-far", sp0, "4\n0.1 1.54\n1.5 2.5\n3.5 2.5\n3.8 1.21\n0\n", [], False, 5,
         GOAL, 5, note="0.11 from the goal")
    case("collision-through-cell", sp0, "2\n0.1 1.54\n3.8 1.1\n0\n", [], False, 6,
         POINT_HIT, 2, note="the straight line crosses blocked cell (2, 1)")
    case("collision-vertex-in-cell", sp0, "4\n0.1 1.54\n1.5 2.5\n2.5 1.5\n3.8 1.1\n0\n", [],
         False, 6, POINT_HIT, 3, note="segment 2 -> 3 ends inside blocked cell (2, 1)")


def spaceship_cases() -> None:
    accelerate, coast, brake = (0.0, 0.5), (0.0, 0.0), (math.pi, 0.5)
    plan = [accelerate, accelerate, coast, coast, brake, brake]
    rows, end = fly((1.0, 1.5), plan)
    goal = (round(end[0], 3), round(end[1], 3))
    free = ["_______", "_______", "_______"]
    opened = problem("open.sw", free, (1.0, 1.5), goal)
    text = format_plan(rows, rows[:-1])
    case("valid-straight", opened, text, ["-grad"], True,
         note="accelerate, coast, brake (theta = pi) along y = 1.5")
    case("valid-straight-left", opened, text, ["-grad", "-left"], True,
         note="theta 0 and pi only: legal for the left-only ship")
    case("valid-left-alone", opened, text, ["-left"], True, note="-left alone implies -grad")
    nudged = [list(r) for r in rows]
    nudged[3][0] += 0.009
    case("valid-within-tolerance", opened, format_plan(nudged, []), ["-grad"], True,
         note="line 5's x is 0.009 off the propagated state: within 0.01")

    right_plan = [accelerate, (2 * math.pi - 0.2, 0.5), coast, coast, brake, brake]
    right_rows, right_end = fly((1.0, 1.5), right_plan)
    right = problem("open-right.sw", free, (1.0, 1.5),
                    (round(right_end[0], 3), round(right_end[1], 3)))
    right_text = format_plan(right_rows, right_rows[:-1])
    case("valid-right-thrust-grad", right, right_text, ["-grad"], True,
         note="line 3 thrusts at theta = 2 pi - 0.2: to the right of the motion")
    case("invalid-right-thrust-left", right, right_text, ["-grad", "-left"], False, 3, BOUNDS,
         3)

    walled = problem("wall.sw", ["_______", "___#___", "_______"], (1.0, 1.5), goal)
    case("collision-middle-line", walled, text, ["-grad"], False, 6, SHIP_HIT, 4,
         note="line 4 coasts from x = 2.03 to 3.03, into blocked cell (3, 1)")

    sp0 = "space-0.sw"
    crash, _ = fly((0.1, 1.54), [accelerate, accelerate, accelerate])
    case("last-edge-collision", sp0, format_plan(crash, crash), ["-grad"], False, 5, LAST_EDGE,
         4, note="the third full thrust reaches x = 2: blocked cell (2, 1)")
    case("goal-too-far", opened, format_plan(rows[:4], []), ["-grad"], False, 5, GOAL, 5,
         note="the valid trajectory without its braking lines")
    broken = [list(r) for r in rows]
    broken[3][0] += 0.02
    case("dynamics-wrong-state", opened, format_plan(broken, []), ["-grad"], False, 7,
         DYNAMICS, 5, note="line 5's x is 0.02 off the propagated state")
    broken = [list(r) for r in rows]
    broken[2][3] -= 0.011
    case("dynamics-wrong-velocity", opened, format_plan(broken, []), ["-grad"], False, 7,
         DYNAMICS, 4)
    moving = [list(r) for r in rows]
    moving[0][2] = 0.002
    case("start-not-at-rest", opened, format_plan(moving, []), ["-grad"], False, 4, START, 2)
    away = [list(r) for r in rows]
    away[0][1] = 1.502
    case("start-wrong-place", opened, format_plan(away, []), ["-grad"], False, 4, START, 2)
    strong = [list(r) for r in rows]
    strong[1][5] = 0.6
    case("bounds-thrust", opened, format_plan(strong, []), ["-grad"], False, 3, BOUNDS, 3)
    backward = [list(r) for r in rows]
    backward[1][5] = -0.1
    case("bounds-negative-thrust", opened, format_plan(backward, []), ["-grad"], False, 3,
         BOUNDS, 3)
    outside = [list(r) for r in rows]
    outside[2][0] = 7.0
    case("bounds-position", opened, format_plan(outside, []), ["-grad"], False, 3, BOUNDS, 4)

    case("parse-point-answer", sp0, "2\n0.1 1.54\n3.8 1.1\n0\n", ["-grad"], False, 1, PARSE,
         2, note="a -ugrad answer to a -grad problem: the message says so")
    case("parse-five-numbers", opened, text.replace(" 0.0 0.5\n", " 0.5\n", 1), ["-grad"],
         False, 1, PARSE, 2)
    case("parse-inf", opened, text.replace("0.5", "inf", 1), ["-grad"], False, 1, PARSE, 2)
    case("parse-truncated", opened, text[:text.index("\n", 80)], ["-grad"], False, 1, PARSE,
         1)
    case("parse-point-tree", opened, format_plan(rows, [])[:-2] + "1\n1 1 2 2\n",
         ["-grad"], False, 1, PARSE, 9)
    case("parse-binary", opened, bytes(range(256)) * 4, ["-grad"], False, 1, PARSE, 1)
    case("empty-trajectory", opened, "0\n3\n" + "\n".join(text.splitlines()[1:4]) + "\n",
         ["-grad"], False, 2, EMPTY, 1)
    case("valid-planner-seed2", sp0, planner_output(sp0, ["-grad", "-seed", "2"]), ["-grad"],
         True, note="our planner's output")
    case("valid-planner-left-seed3", sp0, planner_output(sp0, ["-left", "-seed", "3"]),
         ["-grad", "-left"], True, note="our planner's output")


def main() -> None:
    point_cases()
    spaceship_cases()
    (HERE / "cases.json").write_text(json.dumps(CASES, indent=1) + "\n")
    print(f"{len(CASES)} cases written to {HERE}")


if __name__ == "__main__":
    main()
