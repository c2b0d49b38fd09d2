"""RRT-Connect grows BOTH trees: the start tree and the goal tree take turns
at extending toward a random target, and the other one connects toward the
node just added (Kuffner & LaValle 2000; the module docstring of
``rrt_cli.planners.rrtconnect``).

The observable, from the printed tree alone: a tree that only ever *connects*
adds nodes toward the other tree's newest node, so each of its nodes lies on
the segment from its parent toward some node of the other tree (the node
itself when the connect reaches it, short of it when a wall stops the step,
whatever ``max_step``, clearance or target sampling say). A tree that also
*extends* has nodes at (or toward) random targets, off every such segment.
If the two trees stopped swapping roles, every goal-tree node would be a
connect node and this test fails.

The tree section lists start-tree edges as ``parent child`` and goal-tree
edges as ``child parent`` (toward the goal, as the final path travels them).
So the start tree is what ``parent -> child`` reaches from the start, the
goal tree what ``child -> parent`` reaches back from the goal. The two meet
at the meeting point, so the solution path's edges read both ways; only the
edges off the path are classified (enough: most of both trees is off it).

Runs the planner in-process through ``rrt_cli.cli.main`` (fast), and checks
every output with the validator (``strict``).
"""

from __future__ import annotations

import math

from tests.conftest import plan_in_process
from planning_core.problem_text import parse_problem
from planning_core.vehicles import Vehicle
from validator.checks import validate_output

# Two rooms joined by a gap at the top of the wall: neither tree sees the other
# at first, so the search takes a few dozen iterations (space-3 of the course
# works as well; this map keeps the test self-contained).
ROOMS = """12
8
____________
____________
_____#______
_____#______
_____#______
___#_#______
___#_#_##___
___#_#______
0.5
0.5
10.5
0.5
"""
SEEDS = range(1, 11)




def parse_point_output(text: str):
    lines = text.splitlines()
    n = int(lines[0])
    trajectory = [tuple(map(float, line.split())) for line in lines[1:1 + n]]
    m = int(lines[1 + n])
    rows = [tuple(map(float, line.split())) for line in lines[2 + n:2 + n + m]]
    assert len(rows) == m
    return trajectory, [((r[0], r[1]), (r[2], r[3])) for r in rows]


def split_trees(start, goal, edges):
    """Nodes reachable parent -> child from the start, and child -> parent back
    from the goal; the edges of each tree that are not ambiguous (off the path)."""
    start_nodes, goal_nodes = {start}, {goal}
    changed = True
    while changed:
        changed = False
        for a, b in edges:
            if a in start_nodes and b not in start_nodes:
                start_nodes.add(b)
                changed = True
            if b in goal_nodes and a not in goal_nodes:
                goal_nodes.add(a)
                changed = True
    start_edges = [(a, b) for a, b in edges if a in start_nodes and b not in goal_nodes]
    goal_edges = [(b, a) for a, b in edges if b in goal_nodes and a not in start_nodes]
    return start_nodes, goal_nodes, start_edges, goal_edges  # edges as (parent, child)


def on_the_way(parent, child, target, rel=1e-9) -> bool:
    """``child`` lies on the segment from ``parent`` to ``target`` (a different point)."""
    ux, uy = child[0] - parent[0], child[1] - parent[1]
    vx, vy = target[0] - parent[0], target[1] - parent[1]
    lu, lv = math.hypot(ux, uy), math.hypot(vx, vy)
    if lv == 0.0:
        return False
    return (abs(ux * vy - uy * vx) <= rel * lu * lv
            and -rel * lu * lv <= ux * vx + uy * vy <= lv * lv * (1 + rel))


def test_problem_needs_several_iterations(monkeypatch):
    # Guards the test below: on a map solved at the first iteration no tree would
    # ever get a second turn.
    for seed in SEEDS:
        status, _, err = plan_in_process(
            monkeypatch, ["-planner", "rrtconnect", "-seed", str(seed), "-stats"], ROOMS)
        assert status == 0, err
        iterations = int(err.split("iterations=")[1].split()[0])
        assert iterations >= 5, (seed, iterations)


def test_goal_tree_extends_toward_random_targets_not_only_connects(monkeypatch):
    problem = parse_problem(ROOMS)
    extended = {}  # seed -> goal-tree nodes that no connect toward a start node explains
    for seed in SEEDS:
        status, out, err = plan_in_process(
            monkeypatch, ["-planner", "rrtconnect", "-seed", str(seed)], ROOMS)
        assert status == 0, err
        report = validate_output(problem, Vehicle.POINT, out, strict=True)
        assert report.valid, (seed, report.first_failure)
        trajectory, edges = parse_point_output(out)
        assert trajectory[0] == problem.start and trajectory[-1] == problem.goal
        start_nodes, goal_nodes, start_edges, goal_edges = split_trees(
            trajectory[0], trajectory[-1], edges)
        # Every edge of the output belongs to one tree or to the path.
        path_edges = set(zip(trajectory, trajectory[1:]))
        classified = len(start_edges) + len(goal_edges)
        assert classified + sum(1 for e in edges if e in path_edges) >= len(edges), (
            f"seed {seed}: some tree edges are neither parent -> child from the start nor "
            "child -> parent toward the goal (goal-tree edges must point toward the goal)")
        # start_nodes also holds the goal tree's path nodes (the path reads both ways):
        # extra candidate targets can only make a goal-tree node look like a connect node.
        extended[seed] = sum(
            1 for parent, child in goal_edges
            if not any(on_the_way(parent, child, target) for target in start_nodes))
    assert sum(extended.values()) >= 10 and sum(1 for n in extended.values() if n) >= 4, (
        f"goal-tree nodes off every segment toward a start-tree node, per seed: {extended} "
        "(0 everywhere: the goal tree only ever connected, it never extended toward a random "
        "target: do the trees still swap roles every iteration?)")
