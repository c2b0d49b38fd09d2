"""Similar pairs: a course's template shared by the class is no evidence; the reading of
a submission's folder follows no link and opens no FIFO; identical answers count only
valid ones."""

from __future__ import annotations

import os
from pathlib import Path

from grading.scores import Scored
from grading.similar import identical_answers, near_identical_sources, read_sources

TEMPLATE = "\n".join(f"def helper_{n}(grid, start, goal):\n    return plan(grid, start, "
                     f"goal, {n} * steps, tolerance={n}.5)" for n in range(40))


def _own(words: str) -> str:
    return "\n".join(f"value_{n} = compute('{words}', {n}, limit={n * 7})" for n in range(12))


def _write(base: Path, name: str, text: str) -> Path:
    folder = base / name
    folder.mkdir()
    (folder / "planner.py").write_text(TEMPLATE + "\n" + text)
    return folder


def test_the_class_template_is_no_evidence_and_own_code_is(tmp_path):
    for name in ("ann", "bob", "cyd", "dee"):
        _write(tmp_path, name, _own(name))
    _write(tmp_path, "eve", _own("ann"))  # ann's own code under another name
    pairs = near_identical_sources({name: read_sources(tmp_path / name)
                                    for name in ("ann", "bob", "cyd", "dee", "eve")})
    assert [(p.first, p.second) for p in pairs] == [("ann", "eve")]
    assert "most alike: planner.py and planner.py" in pairs[0].evidence


def test_reading_the_sources_follows_no_link_and_opens_no_fifo(tmp_path):
    folder = _write(tmp_path, "ann", _own("ann"))
    secret = tmp_path / "secret.py"
    secret.write_text("the grader's own\n" * 100)
    (folder / "linked.py").symlink_to(secret)
    (folder / "folder-link").symlink_to(tmp_path)
    os.mkfifo(folder / "pipe.py")  # opening it for reading would wait for a writer
    (folder / ".hidden.py").write_text("x = 1\n" * 100)
    (folder / "binary.bin").write_bytes(b"\0" * 100)
    assert sorted(read_sources(folder)) == ["planner.py"]


def _run(problem: str, valid: int, digest: str) -> dict:
    return {"problem": problem, "mode": "point", "repeat": 0, "valid": valid,
            "output_sha256": digest}


def test_identical_answers_count_only_valid_ones():
    graded = [Scored("ann", {("a.sw", "point"): [_run("a.sw", 1, "x")],
                             ("b.sw", "point"): [_run("b.sw", 0, "err")]}, 50.0),
              Scored("bob", {("a.sw", "point"): [_run("a.sw", 1, "y")],
                             ("b.sw", "point"): [_run("b.sw", 0, "err")]}, 50.0),
              Scored("cyd", {("a.sw", "point"): [_run("a.sw", 1, "x")],
                             ("b.sw", "point"): [_run("b.sw", 1, "z")]}, 100.0)]
    pairs = identical_answers(graded)
    assert [(p.first, p.second, p.strength) for p in pairs] == [("ann", "cyd", 1.0)]
    assert "on 1 of the 1 problem-modes both solved: a.sw point" in pairs[0].evidence
