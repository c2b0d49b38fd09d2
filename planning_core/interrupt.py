"""How a long computation over a world's cells gives way to its caller's limit.

A world capability that may walk every cell of a big map (flood fill, Dijkstra,
the free-cell index) takes an optional ``stop``: a function of no arguments
that answers True once the caller's time is up. The computation asks it every
:data:`POLL_EVERY` cells and raises :class:`Interrupted` when it says so; the
planner turns that into its time-limit result. The world never reads a clock
itself, and a computation given no ``stop`` runs to the end.
"""

from __future__ import annotations

from collections.abc import Callable

Stop = Callable[[], bool] | None

POLL_EVERY = 1024
"""Cells (or heap pops) between two calls of ``stop``: a few milliseconds of work."""


class Interrupted(Exception):
    """A world computation was cut short because its ``stop`` answered True."""


def check(stop: Stop) -> None:
    """Raise :class:`Interrupted` when ``stop`` says the time is up."""
    if stop is not None and stop():
        raise Interrupted("the time limit fell during set-up")
