"""Gradescope's autograder format: each results.json checked against a JSON Schema
written from Gradescope's autograder specification (docs "Autograder Specifications",
"Output format"), for a class (--format gradescope) and for the one submission of an
/autograder-like tree (rrt-grade gradescope, through ./rrt-grade as run_autograder
calls it)."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest

from grading.cli import main
from grading_fixtures import CLASS, ROOT, make_class, make_submission, problem_file

jsonschema = pytest.importorskip("jsonschema")

VISIBILITY = {"enum": ["hidden", "after_due_date", "after_published", "visible"]}
FORMAT = {"enum": ["text", "html", "simple_format", "md", "ansi"]}
# Every key the specification names, with its type; the score is required at the top or
# on every test, and a test's status is passed or failed.
SCHEMA = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "type": "object",
    "properties": {
        "score": {"type": "number"},
        "execution_time": {"type": "number", "minimum": 0},
        "output": {"type": "string"},
        "output_format": FORMAT,
        "test_output_format": FORMAT,
        "test_name_format": FORMAT,
        "visibility": VISIBILITY,
        "stdout_visibility": VISIBILITY,
        "extra_data": {"type": "object"},
        "tests": {"type": "array", "items": {
            "type": "object",
            "properties": {
                "score": {"type": "number"},
                "max_score": {"type": "number"},
                "status": {"enum": ["passed", "failed"]},
                "name": {"type": "string"},
                "name_format": FORMAT,
                "number": {"type": "string"},
                "output": {"type": "string"},
                "output_format": FORMAT,
                "tags": {"type": "array", "items": {"type": "string"}},
                "visibility": VISIBILITY,
                "extra_data": {"type": "object"},
            },
            "additionalProperties": False,
        }},
        "leaderboard": {"type": "array", "items": {
            "type": "object", "required": ["name", "value"],
            "properties": {"name": {"type": "string"},
                           "value": {"type": ["number", "string"]},
                           "order": {"enum": ["asc", "desc"]}}}},
    },
    "anyOf": [{"required": ["score"]},
              {"required": ["tests"],
               "properties": {"tests": {"items": {"required": ["score"]}}}}],
    "additionalProperties": False,
}


def _checked(path: Path) -> dict:
    results = json.loads(path.read_text())
    jsonschema.validate(results, SCHEMA)
    return results


def test_the_schema_refuses_what_gradescope_would():
    jsonschema.validate({"score": 1.0}, SCHEMA)
    for bad in ({"output": "no score anywhere"}, {"score": "1"}, {"score": 1, "visibility": "x"},
                {"tests": [{"name": "t"}]}, {"score": 1, "tests": [{"score": 1, "sccore": 1}]}):
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.validate(bad, SCHEMA)


def test_format_gradescope_writes_a_valid_results_json_per_submission(tmp_path):
    names = ["good", "garbage", "nobuild"]
    submissions, problems, _ = make_class(tmp_path, names, ["simple-0.sw", "pendulum-t3.kp"])
    out = tmp_path / "out"
    assert main(["--submissions", str(submissions), "--problems", str(problems), "--out",
                 str(out), "--modes", "point", "--format", "gradescope"]) == 0
    found = {name: _checked(out / "gradescope" / name / "results.json") for name in names}
    good, garbage, nobuild = found["good"], found["garbage"], found["nobuild"]
    assert good["score"] == 100.0 and garbage["score"] == 0.0 == nobuild["score"]
    assert [t["name"] for t in good["tests"]] == [
        "build (make.sh)", "pendulum-t3.kp kinoplan", "simple-0.sw point"]
    assert [(t["score"], t["max_score"], t["status"]) for t in good["tests"][1:]] == [
        (50.0, 50.0, "passed")] * 2
    assert sum(t["score"] for t in good["tests"]) == good["score"]
    assert good["tests"][2]["output"].startswith("run 1: valid; ")
    assert "our planner's" in good["tests"][2]["output"]
    assert "got 'hello world'" in garbage["tests"][2]["output"]
    assert nobuild["tests"][0]["status"] == "failed"
    assert "make.sh exited 3" in nobuild["tests"][0]["output"]
    assert isinstance(good["execution_time"], int) and good["execution_time"] >= 1


def _autograder(tmp_path: Path, run: str) -> Path:
    """An /autograder-like tree: source (problems, rubric), submission, results."""
    root = tmp_path / "autograder"
    (root / "source" / "problems").mkdir(parents=True)
    (root / "results").mkdir()
    for name in ("simple-0.sw", "pendulum-t3.kp"):
        shutil.copy(problem_file(name), root / "source" / "problems" / name)
    (root / "source" / "rubric.toml").write_text(
        'modes = ["point", "grad"]\nvisibility = "after_due_date"\n'
        '[[problems]]\nmatch = "*.kp"\nweight = 2\nvisibility = "visible"\n')
    make_submission(root, "submission", "", run, tmp_path / "unused")
    return root


# A zero score's results.json: the --format gradescope test above; through this command in CI.
@pytest.mark.parametrize("body, score", [
    pytest.param(CLASS["good"][1], 4.0, id="good"),
    pytest.param(CLASS["garbage"][1], 0.0, id="garbage", marks=pytest.mark.slow)])
def test_rrt_grade_gradescope_grades_the_submission_of_an_autograder_tree(tmp_path, body,
                                                                          score):
    root = _autograder(tmp_path, body)
    done = subprocess.run([str(ROOT / "rrt-grade"), "gradescope", "--root", str(root),
                           "--jobs", "2"], cwd=root, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("submission ")
    results = _checked(root / "results" / "results.json")
    assert results["score"] == score and results["visibility"] == "after_due_date"
    assert [(t["name"], t["max_score"], t["visibility"]) for t in results["tests"][1:]] == [
        ("pendulum-t3.kp kinoplan", 2.0, "visible"), ("simple-0.sw point", 1.0, "after_due_date"),
        ("simple-0.sw grad", 1.0, "after_due_date")]
    assert (root / "rrt-grade" / "report.md").exists()
    assert sorted(path.name for path in (root / "results").iterdir()) == ["results.json"]


def test_rrt_grade_gradescope_without_a_submission_is_a_usage_error(tmp_path, capsys):
    root = _autograder(tmp_path, "exit 0")
    shutil.rmtree(root / "submission")
    with pytest.raises(SystemExit) as done:
        main(["gradescope", "--root", str(root)])
    assert done.value.code == 2
    assert capsys.readouterr().err.splitlines()[1] == (
        f"rrt-grade gradescope: error: --submission {root / 'submission'}: not a folder")
    assert not (root / "results" / "results.json").exists()
