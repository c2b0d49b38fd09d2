"""The guide's draws (rrt_cli.planners.guide): lazy keys, the nearest node first."""

from __future__ import annotations

import random

from planning_core.problem_text import parse_problem
from planning_core.setups import grid_setup
from rrt_cli.planners.guide import Guide
from tests.conftest import ROOT

SUITE = ROOT / "benchmarks" / "problems"


def point_setup(name: str):
    return grid_setup(parse_problem((SUITE / f"{name}.sw").read_text()), "point")


def free_states(problem, rng: random.Random, count: int) -> list[tuple[float, float]]:
    states = []
    while len(states) < count:
        x, y = rng.uniform(0, problem.width), rng.uniform(0, problem.height)
        if not problem.is_blocked_cell(int(x), int(y)):
            states.append((x, y))
    return states


def test_each_draw_is_the_waiting_node_nearest_the_goal():
    """Nodes wait under a bound and are measured only near the front, yet each draw
    is the node whose distance down the free cells is least among those waiting, and
    each node that has a way (an eager field's) is drawn once."""
    for name, seed in (("maze-50", 1), ("random-d35-50", 2), ("narrow-50", 3)):
        setup = point_setup(name)
        problem, rng = setup.problem, random.Random(seed)
        states = [setup.pdef.start] + free_states(problem, rng, 300)
        guide = Guide.begin(setup.si, setup.pdef.goal, 1.0, states[0])
        eager = setup.si.world.distance_along_cells(setup.pdef.goal.point)
        for node, state in enumerate(states[1:], 1):
            guide.add(node, state)
        waiting, drawn = set(range(len(states))), []
        guided = guide.draw(rng, states)
        measured_first = len(guide.measured)
        while guided is not None:
            node = guided[0]
            along = guide.along  # its values do not hang on the order cells are asked in
            assert along(*states[node]) == min(along(*states[other]) for other in waiting)
            waiting.remove(node)
            drawn.append(node)
            guided = guide.draw(rng, states)
        reachable = {node for node in range(len(states))
                     if eager(*states[node]) < eager.unreachable}
        assert set(drawn) == reachable and len(drawn) == len(set(drawn))
        assert measured_first < len(states) // 10  # the first draw measured a few: lazy


def test_a_guide_whose_measuring_runs_out_of_time_stops_guiding():
    """The lazy field asks the planner's stop while it measures; when the time is up
    mid-draw, the draw is None and the guide guides no more (the planner's loop then
    ends the run with its tree)."""
    setup = point_setup("maze-200")
    guide = Guide.begin(setup.si, setup.pdef.goal, 1.0, setup.pdef.start, lambda: True)
    assert guide.draw(random.Random(1), [setup.pdef.start]) is None
    assert guide.share == 0.0
