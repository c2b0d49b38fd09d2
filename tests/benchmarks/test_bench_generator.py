"""The problem generator: solvability proof, family shapes, byte-for-byte regeneration."""

import random

import pytest

from benchmarks import generator
from benchmarks.generator import ProblemSpec, four_connected, generate
from planning_core.problem import Problem
from planning_core.problem_text import format_problem, parse_problem

SMALL_SIZES = (10, 13, 20)


def cell(problem: Problem, column: int, row: int) -> int:
    return problem.blocked[row * problem.width + column]


def bfs_path_exists(problem: Problem) -> bool:
    """An independent check of the proof: breadth-first search over free cells."""
    (sx, sy), (gx, gy) = problem.start, problem.goal
    start, goal = (int(sx), int(sy)), (int(gx), int(gy))
    frontier, seen = [start], {start}
    while frontier:
        column, row = frontier.pop(0)
        if (column, row) == goal:
            return True
        for dc, dr in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            c, r = column + dc, row + dr
            if 0 <= c < problem.width and 0 <= r < problem.height and (c, r) not in seen \
                    and not cell(problem, c, r):
                seen.add((c, r))
                frontier.append((c, r))
    return False


@pytest.mark.parametrize("family", generator.FAMILIES)
@pytest.mark.parametrize("seed", range(4))
def test_every_family_is_solvable_and_well_formed(family, seed):
    for size in SMALL_SIZES:
        problem = generate(ProblemSpec(family, size, seed))
        assert (problem.width, problem.height) == (size, size)
        assert not problem.point_in_collision(*problem.start)
        assert not problem.point_in_collision(*problem.goal)
        assert problem.start != problem.goal
        assert four_connected(problem)
        assert bfs_path_exists(problem)
        # What is written is what is read back.
        assert parse_problem(format_problem(problem)) == problem


def test_the_proof_rejects_a_wall_without_a_gap_and_diagonal_only_contact():
    walled = Problem(5, 3, bytes([0, 0, 1, 0, 0] * 3), (0.5, 0.5), (4.5, 2.5))
    assert not four_connected(walled)
    assert not bfs_path_exists(walled)
    # Free cells touching only at a corner do not count as connected.
    diagonal = Problem(2, 2, bytes([0, 1, 1, 0]), (0.5, 0.5), (1.5, 1.5))
    assert not four_connected(diagonal)


def test_random_fields_have_the_asked_density():
    for family, density in (("random-d20", 0.20), ("random-d35", 0.35)):
        problem = generate(ProblemSpec(family, 100))
        share = sum(problem.blocked) / len(problem.blocked)
        assert abs(share - density) < 0.02, (family, share)


def test_random_field_redraws_until_connected():
    # Dense enough that most draws are disconnected; the result must still be proven.
    problem = generator.random_field(12, 0.45, random.Random(3))
    assert four_connected(problem) and bfs_path_exists(problem)


def test_maze_corridors_and_walls_are_one_cell_wide():
    problem = generate(ProblemSpec("maze", 21))
    for column in range(problem.width - 1):
        for row in range(problem.height - 1):
            block = [cell(problem, column + dc, row + dr) for dc in (0, 1) for dr in (0, 1)]
            assert any(block), f"2x2 free block at ({column}, {row})"
    # A perfect maze on r x r rooms has r*r rooms and r*r - 1 openings: a tree.
    rooms = (21 + 1) // 2
    free = len(problem.blocked) - sum(problem.blocked)
    assert free == rooms * rooms + rooms * rooms - 1


def test_narrow_passage_has_exactly_one_gap_between_start_and_goal():
    for seed in range(5):
        problem = generate(ProblemSpec("narrow", 30, seed))
        wall = problem.width // 2
        gaps = [row for row in range(problem.height) if not cell(problem, wall, row)]
        assert len(gaps) == 1
        assert problem.start[0] < wall < problem.goal[0]


def test_generation_is_deterministic_and_seed_dependent():
    spec = ProblemSpec("random-d35", 20, 7)
    assert format_problem(generate(spec)) == format_problem(generate(spec))
    other = ProblemSpec("random-d35", 20, 8)
    assert generate(spec).blocked != generate(other).blocked


def test_committed_small_problems_match_a_fresh_generation():
    texts = generator.suite_texts(max_size=50)
    assert len([name for name in texts if not name.startswith("course/")]) == \
        len(generator.FAMILIES) * len([s for s in generator.SIZES if s <= 50])
    for name, text in texts.items():
        path = generator.PROBLEMS_DIR / name
        assert path.exists(), f"{name} is not in benchmarks/problems"
        assert path.read_text() == text, f"{name} differs from a fresh generation"


def test_write_suite_into_an_empty_directory_reproduces_the_files(tmp_path, monkeypatch):
    # Only the small sizes, to stay fast; the big ones are checked by --check in docs.
    monkeypatch.setattr(generator, "SIZES", (10, 20))
    course = tmp_path / "course"
    course.mkdir()
    (course / "tiny.sw").write_bytes(b"2\n1\n__\n0.5\n0.5\n1.5\n0.5\n")
    out = tmp_path / "problems"
    paths = generator.write_suite(out, course_dir=course)
    assert len(paths) == 2 * len(generator.FAMILIES) + 1
    assert (out / "course" / "tiny.sw").read_bytes() == (course / "tiny.sw").read_bytes()
    assert generator.problem_id(out / "course" / "tiny.sw") == "course-tiny"
    for path in paths:
        if path.parent == out:
            assert path.read_bytes() == (generator.PROBLEMS_DIR / path.name).read_bytes()
    assert generator.check_suite(out, course_dir=course) == []
    (out / "maze-10.sw").write_text("10\n10\n")
    assert any("maze-10" in line for line in generator.check_suite(out, course_dir=course))


def test_family_names_are_recovered_from_problem_names():
    assert generator.family_of("random-d20-100") == "random-d20"
    assert generator.family_of("maze-500") == "maze"
    assert generator.family_of("course-space-1") == "course"
