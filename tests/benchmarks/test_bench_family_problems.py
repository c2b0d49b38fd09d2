"""Every family problem in benchmarks/problems/family/ is proven solvable: a stored
answer (solutions/NAME.out, made by a planner run whose name and seed are in
solutions/SOURCES.txt) that the validator's checks accept."""

import pytest

from benchmarks.family import FAMILY_DIR, SOLUTIONS_DIR, family_problems
from benchmarks.family_solutions import SOURCES, check, problems_without_valid_answer

PROBLEMS = family_problems()


def test_every_problem_has_one_stored_answer_and_its_source():
    names = {p.stem for p in PROBLEMS}
    stored = {p.stem for p in SOLUTIONS_DIR.glob("*.out")}
    assert names == stored
    sources = dict(line.split(None, 1) for line in SOURCES.read_text().splitlines())
    assert set(sources) == names
    assert len(names) >= 25  # SPEC's examples (16) and our variants


@pytest.mark.parametrize("problem", PROBLEMS, ids=lambda p: p.stem)
def test_the_validator_accepts_the_stored_answer(problem):
    report = check(problem, (SOLUTIONS_DIR / f"{problem.stem}.out").read_text())
    assert report.valid, report.first_failure


def test_a_problem_whose_answer_is_missing_or_wrong_is_reported(tmp_path):
    good = FAMILY_DIR / "pendulum-t10.kp"
    (tmp_path / "solutions").mkdir()
    (tmp_path / "pendulum-t10.kp").write_text(good.read_text())
    (tmp_path / "car2-corridors.kp").write_text((FAMILY_DIR / "car2-corridors.kp").read_text())
    answer = (SOLUTIONS_DIR / "pendulum-t10.out").read_text().splitlines()
    answer[1] = " ".join(["0.5", *answer[1].split()[1:]])  # the first state moved off start
    (tmp_path / "solutions" / "pendulum-t10.out").write_text("\n".join(answer) + "\n")
    bad = problems_without_valid_answer(tmp_path)
    assert bad["car2-corridors"] == "no stored answer"
    assert bad["pendulum-t10"].startswith("rejected:")
