"""Gradescope's autograder output: a ``results.json`` per submission (the overall
``score``, ``execution_time``, ``output``, ``visibility``, and one test per rubric item,
plus one for the build), as Gradescope's autograder specification describes it."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

from grading.rubric import Item
from grading.scores import Results, Scored, key, relative_time
from grading.summary import failure_label

MAX_OUTPUT = 4000  # characters of a test's output
RESULTS = "results.json"


def _run_line(number: int, row: dict, results: Results) -> str:
    """One repeat of an item, in words: verdict, message, time (and relative to ours)."""
    line = f"run {number}: " + ("valid" if row["valid"] else failure_label(row))
    if not row["valid"] and row.get("message"):
        line += f": {row['message']}" + (f" ({row['detail']})" if row.get("detail") else "")
    if row.get("wall_time") is not None:
        line += f"; {row['wall_time']:.2f} s"
        ratio = relative_time(row, results.calibration)
        if ratio is not None:
            ours = results.calibration[key(row)]["wall_time"]
            line += f" (x{ratio:.2f} our planner's {ours:.2f} s on the same machine)"
    return line


def _test(number: int, item: Item, rows: list[dict], worth: float, results: Results) -> dict:
    valid = sum(row["valid"] for row in rows)
    share = valid / len(rows) if rows else 0.0
    output = "\n".join(_run_line(n, row, results) for n, row in enumerate(rows, 1))
    if len(rows) > 1:
        output = f"{valid} of {len(rows)} runs valid\n" + output
    return {"name": item.label, "number": str(number), "score": round(worth * share, 4),
            "max_score": round(worth, 4), "status": "passed" if share == 1 else "failed",
            "output": output[:MAX_OUTPUT] or "not run", "output_format": "text",
            "tags": [item.mode], "visibility": item.visibility}


def _build_test(build: dict) -> dict:
    ok = bool(build.get("ok"))
    return {"name": "build (make.sh)", "number": "0", "score": 0.0, "max_score": 0.0,
            "status": "passed" if ok else "failed",
            "output": "ok" if ok else str(build.get("reason") or "the build failed")[:MAX_OUTPUT],
            "output_format": "text", "visibility": "visible"}


def results_json(results: Results, one: Scored) -> dict:
    """One submission's results.json, as a dict."""
    points = results.rubric.points(results.items)
    build = results.builds.get(one.name, {})
    tests = [_build_test(build)] + [
        _test(number, item, one.runs.get(key(item), []), points[key(item)], results)
        for number, item in enumerate(results.items, 1)]
    runs = one.all_runs()
    seconds = sum(row.get("wall_time") or 0.0 for row in runs) + (build.get("wall_time") or 0.0)
    valid = sum(row["valid"] for row in runs)
    return {"score": one.score, "execution_time": math.ceil(seconds),
            "output": f"Score {one.score:g} out of {results.rubric.full_score(results.items):g}: "
                      f"{valid} of {len(runs)} runs valid. A run's time is also given "
                      "relative to our own planner's on the same machine.",
            "output_format": "text", "visibility": results.rubric.visibility,
            "stdout_visibility": "hidden", "tests": tests}


def write_results(path: Path, results: Results, one: Scored) -> Path:
    """``results.json`` at ``path``, written whole (a temporary file renamed)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_name(f".{path.name}.{os.getpid()}")
    partial.write_text(json.dumps(results_json(results, one), indent=1, allow_nan=False) + "\n")
    os.replace(partial, path)
    return path


def write_class(results: Results) -> Path:
    """``gradescope/SUBMISSION/results.json`` for each submission under the results' folder."""
    folder = results.out / "gradescope"
    for one in results.graded:
        write_results(folder / one.name / RESULTS, results, one)
    return folder
