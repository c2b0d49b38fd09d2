"""benchmarks/bench_compiled.py: which problems it picks, how it reads a run and
what its table says (no planner is run here)."""

from __future__ import annotations

from pathlib import Path

from benchmarks import bench_compiled
from benchmarks.bench_compiled import Run
from benchmarks.generator import problem_id
from benchmarks.ompl_cpp_programs import grid_input


def test_point_runs_on_the_course_problems_and_big_maps_the_ships_on_their_quick_problems():
    point = [problem_id(path) for path in bench_compiled.problems_for("point", [])]
    ships = [problem_id(path) for path in bench_compiled.problems_for("spaceship", [])]
    assert "course-space-1" in point and "open-50" in point and "narrow-500" in point
    assert all(name.startswith("course-") or name.endswith(("-50", "-500")) for name in point)
    assert "course-space-1" in ships and "open-20" in ships and "maze-20" not in ships
    assert [problem_id(p) for p in bench_compiled.problems_for("left", ["course-space-*"])] == [
        f"course-space-{k}" for k in range(4)]


def test_commands_pick_the_mode():
    argv, env = bench_compiled.command("interpreted", "left", "kpiece", 2, 5.0)
    assert argv[0].endswith("run.sh") and env["RRT_INTERPRETED"] == "1"
    assert argv[1:] == ["-grad", "-left", "-planner", "kpiece", "-seed", "2", "-time", "5.0",
                        "-stats"]
    argv, env = bench_compiled.command("compiled", "point", "rrt", 1, 5.0)
    assert "RRT_INTERPRETED" not in env
    argv, _ = bench_compiled.command("ompl", "spaceship", "rrt", 1, 5.0)
    assert argv[1].endswith("ompl_planner.py")


def test_table_row_ratios_and_unsolved_runs():
    runs = {("rrt", "compiled"): [Run(0.1, True), Run(0.3, True), Run(0.2, True)],
            ("rrt", "interpreted"): [Run(0.4, True), Run(0.8, True), Run(5.0, False)],
            ("ompl", "ompl"): [Run(0.4, True)]}
    row = bench_compiled.table_rows("spaceship", Path("course/space-1.sw"), runs)
    assert row == ["| spaceship | course-space-1 | rrt | 200.0 | 800.0 (1 unsolved) | 4.00 "
                   "| 400.0 | 0.50 | 2.00 | - | - |"]
    runs[("ompl-cpp", "ompl-cpp")] = [Run(0.05, True)]
    assert bench_compiled.table_rows("spaceship", Path("course/space-1.sw"), runs)[0].endswith(
        "| 50.0 | 4.00 |")


def test_the_cpp_program_reads_the_problem_flat():
    problem = Path(__file__).resolve().parent.parent / "benchmarks/problems/course/space-1.sw"
    lines = grid_input(problem.read_text()).decode().splitlines()
    assert lines[0] == "10 9" and len(lines[1]) == 90 and set(lines[1]) == {"0", "1"}
    assert lines[1][:10] == "0001100000"  # the bottom row ("___##_____") first
    assert lines[2] == "0.1 0.1 4.0 1.0"


def test_stats_line_is_read():
    found = bench_compiled.STATS.search(
        "rrt_cli build: compiled (8 modules)\nrrt_cli stats: status=solved planner=rrt "
        "vehicle=point seed=1 iterations=4 tree_nodes=5 planning_seconds=0.000835\n")
    assert found.groups() == ("solved", "0.000835")


def test_the_geometric_family_runs_as_vehicles_against_family_ompl():
    rigid = [problem_id(path) for path in bench_compiled.problems_for("rigid2", [])]
    assert rigid == [f"rigid2-scene{k}" for k in (1, 2, 3)]
    arms = bench_compiled.problems_for("arm2", ["*pair1"])
    assert len(arms) == 1 and arms[0].suffix == ".kp"
    argv, _ = bench_compiled.command("compiled", "arm2", "rrtconnect", 4, 5.0)
    assert argv[0].endswith("run.sh") and argv[1:3] == ["-planner", "rrtconnect"]
