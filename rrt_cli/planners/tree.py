"""A tree of motions stored as parallel lists, and what a result needs from it."""

from __future__ import annotations

import time

from rrt_cli.planners.base import PlanResult, PlanStats, PlanStatus, StopCondition

TYPE_CHECKING = False
if TYPE_CHECKING:  # annotations only: no run imports typing (docs/setup-and-startup.md)
    from typing import Any, Callable, Optional


class MotionTree:
    """States, each node's parent (-1 for the root) and the control that reached it."""

    def __init__(self, root: tuple[float, ...]):
        self.states: list[tuple[float, ...]] = [root]
        self.parents: list[int] = [-1]
        self.controls: list[tuple[float, ...] | None] = [None]

    def __len__(self) -> int:
        return len(self.states)

    def add(self, parent: int, state: tuple[float, ...], control=None) -> int:
        self.states.append(state)
        self.parents.append(parent)
        self.controls.append(control)
        return len(self.states) - 1

    def path_to(self, node: int) -> list[int]:
        """The nodes from the root to ``node``."""
        path = []
        parents = self.parents
        while node != -1:
            path.append(node)
            node = parents[node]
        path.reverse()
        return path

    def path(self, node: int | None) -> tuple[tuple, tuple]:
        """The states from the root to ``node`` and the controls that lead along them
        (both empty when ``node`` is None)."""
        if node is None:
            return (), ()
        nodes = self.path_to(node)
        return (tuple(self.states[k] for k in nodes),
                tuple(self.controls[k] for k in nodes[1:]))

    def edges(self, toward_root: bool = False) -> list[tuple]:
        """``(parent state, control, child state)`` per non-root node; with
        ``toward_root``, ``(child, control, parent)`` (a tree grown from the goal)."""
        states, parents, controls = self.states, self.parents, self.controls
        if toward_root:
            return [(states[k], controls[k], states[parents[k]]) for k in range(1, len(states))]
        return [(states[parents[k]], controls[k], states[k]) for k in range(1, len(states))]

    def result(self, system, status: PlanStatus, goal_node: int | None, iterations: int,
               began: float, message: str = "") -> PlanResult:
        """The result: the path to ``goal_node`` (none when it is None) and every edge."""
        path, path_controls = self.path(goal_node)
        stats = PlanStats(iterations, len(self.states), time.perf_counter() - began)
        return PlanResult(status, system, path, path_controls, tuple(self.edges()), stats,
                          message)


class TreeSearch:
    """What :func:`run_tree_search` drives: one planner's run between iterations
    (a base class, so that compiled, the loop's calls are native)."""

    tree: MotionTree
    iterations: int
    """Iterations done so far."""

    def begin(self) -> Optional[int]:
        """Set out from the start; a goal node or None."""
        raise NotImplementedError

    def exhausted(self) -> str:
        """Why no node is left to extend, or ""."""
        return ""

    def iterate(self) -> Optional[int]:
        """One iteration; a goal node or None."""
        raise NotImplementedError


def run_tree_search(si: Any, pdef: Any, stop: StopCondition,
                    make_search: Callable[[], TreeSearch], name: str) -> PlanResult:
    """The loop of the kinodynamic tree planners: ``make_search()`` sets up (on the
    clock); a start in the goal region is the answer; otherwise ``search.begin()``,
    then ``search.iterate()`` until one returns a goal node, a limit of ``stop``
    falls or ``search.exhausted()`` says why no node is left to extend. ``search``
    keeps ``tree`` and ``iterations``."""
    if not si.system.kinodynamic:
        raise ValueError(f"{name} plans for kinodynamic systems only")
    began = time.perf_counter()
    search = make_search()
    tree, system = search.tree, si.system
    solved = start_in_goal(si, pdef, tree, began)
    if solved is not None:
        return solved
    goal_node = search.begin()
    while goal_node is None:
        limit = stop.status(search.iterations)
        if limit is not None:
            return tree.result(system, limit, None, search.iterations, began)
        why = search.exhausted()
        if why:
            return tree.result(system, PlanStatus.UNREACHABLE, None, search.iterations, began,
                               why)
        goal_node = search.iterate()
    return tree.result(system, PlanStatus.SOLVED, goal_node, search.iterations, began)


def start_in_goal(si, pdef, tree: MotionTree, began: float) -> PlanResult | None:
    """The answer when the start is in the goal region: the path of the start alone,
    with the controls ``si.stay_controls`` gives a kinodynamic system (a family
    start may drift out under any held control: then None, plan as usual)."""
    if not pdef.goal.reached(pdef.start):
        return None
    controls = si.stay_controls(pdef.start, pdef.goal) if si.system.kinodynamic else ()
    if controls is None:
        return None
    solved = tree.result(si.system, PlanStatus.SOLVED, 0, 0, began)
    return solved.with_path(solved.path, controls) if controls else solved
