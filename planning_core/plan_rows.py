"""The rows of the plan format (SPEC 2), made from a planner's states and controls.

The one place that knows the layout: a geometric system prints its path's states
and its edges as ``from + to``; a kinodynamic one prints each path state with the
control applied from it (the last control leads into the goal, and the state it
reaches is not printed) and its edges as ``parent state + control``. A system
whose motions are curves (the Dubins car) prints its own rows: it declares
``row_names`` and makes ``trajectory_rows(path)`` and ``tree_rows(edges)``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

Row = tuple[float, ...]


def trajectory_rows(system, path: Sequence[Row], path_controls: Sequence[Row]) -> tuple[Row, ...]:
    if hasattr(system, "row_names"):
        return system.trajectory_rows(path) if path else ()
    if not system.kinodynamic:
        return tuple(path)
    if len(path) == 1 and not path_controls:
        # Start already at the goal: one line, the control that keeps it there. (A
        # kinoplan planner gives that control itself: SpaceInformation.start_in_goal_controls.)
        return (path[0] + system.rest_control,)
    return tuple(state + control for state, control in zip(path, path_controls))


def tree_rows(system, edges: Iterable[tuple]) -> tuple[Row, ...]:
    if hasattr(system, "row_names"):
        return system.tree_rows(edges)
    if system.kinodynamic:
        return tuple(parent + control for parent, control, _ in edges)
    return tuple(parent + child for parent, _, child in edges)


def row_widths(system) -> tuple[int, int]:
    """Numbers per trajectory line and per tree line."""
    states = len(getattr(system, "row_names", system.state_names))
    if system.kinodynamic:
        return states + len(system.control_names), states + len(system.control_names)
    return states, 2 * states
