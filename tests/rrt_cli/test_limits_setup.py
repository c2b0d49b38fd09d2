"""Issue 16, item 1: the time limit covers the planners' set-up, and memory stays
bounded. The set-up loops (the start-goal proof, the free-cell index, Dijkstra
over the free cells) ask the stop condition and give way to it; a planner that
runs out of memory ends with a result, not a traceback; on a 3000 x 3000 map
``-time 2`` ends every planner within 3.5 s and 600 MB (slow tests)."""

from __future__ import annotations

import random
import tracemalloc

import pytest

from benchmarks.bench_setup import measured_run
from planning_core.interrupt import POLL_EVERY, Interrupted
from planning_core.problem import Problem
from planning_core.setups import grid_setup
from tests.conftest import solve_on
from planning_core.worlds.grid import GridWorld, cells_joined, connected_free_cells
from planning_core.worlds.grid_cells import FreeCells
from planning_core.worlds.grid_distance import CellDistanceToGoal
from rrt_cli.planners import PLANNERS
from rrt_cli.planners.base import PlanStatus, StopCondition

RUNS = [("point", "rrt"), ("point", "rrtconnect"), ("point", "prm"), ("point", "prmstar"),
        ("point", "rrtstar"), ("point", "informed"),
        ("spaceship", "rrt"), ("spaceship", "kpiece"), ("spaceship", "rgrrt"),
        ("left", "rrt"), ("left", "kpiece"), ("left", "rgrrt")]
FLAGS = {"point": [], "spaceship": ["-grad"], "left": ["-grad", "-left"]}


def random_blocked(size: int, density: float, seed: int) -> bytearray:
    """Row-major from the bottom; the bottom-left and top-right cells free."""
    rng = random.Random(seed)
    cut = round(256 * density)
    blocked = bytearray(rng.randbytes(size * size).translate(
        bytes(1 if byte < cut else 0 for byte in range(256))))
    blocked[0] = blocked[-1] = 0
    return blocked


def walled(size: int = 300) -> Problem:
    """Open but for a wall across the middle row: two halves of ~size^2/2 cells."""
    blocked = bytearray(size * size)
    middle = size // 2
    blocked[middle * size:(middle + 1) * size] = b"\x01" * size
    return Problem(size, size, bytes(blocked), (0.5, 0.5), (size - 0.5, size - 0.5))


def open_map(size: int = 300) -> Problem:
    return Problem(size, size, bytes(size * size), (0.5, 0.5), (size - 0.5, size - 0.5))


def nearly_open_map(size: int = 300) -> Problem:
    """Open but for one blocked cell mid-map: the free-cell index is built as for any
    map (one without a blocked cell needs none)."""
    blocked = bytearray(size * size)
    blocked[(size // 2) * size + size // 2] = 1
    return Problem(size, size, bytes(blocked), (0.5, 0.5), (size - 0.5, size - 0.5))


def map_text(size: int, density: float = 0.2, seed: int = 1) -> str:
    """The `.sw` text of a random field, start bottom-left, goal top-right."""
    blocked = random_blocked(size, density, seed)
    rows = [blocked[row * size:(row + 1) * size].translate(bytes([95, 35]) + bytes(254))
            .decode() for row in range(size - 1, -1, -1)]
    return f"{size}\n{size}\n" + "\n".join(rows) + f"\n0.5 0.5\n{size - 0.5} {size - 0.5}\n"


class CountingStop:
    """A ``stop`` that counts its calls and answers True from call ``fire_at`` on."""

    def __init__(self, fire_at: float = float("inf")):
        self.calls = 0
        self.fire_at = fire_at

    def __call__(self) -> bool:
        self.calls += 1
        return self.calls >= self.fire_at


# -- the two-sided proof ------------------------------------------------------------
@pytest.mark.parametrize("diagonal", [False, True])
def test_two_sided_proof_agrees_with_one_full_fill(diagonal):
    rng = random.Random(7)
    for trial in range(400):
        width, height = rng.randint(1, 12), rng.randint(1, 12)
        blocked = bytes(rng.random() < rng.choice((0.2, 0.4, 0.6)) for _ in range(width * height))
        problem = Problem(width, height, blocked, (0.5, 0.5), (0.5, 0.5))
        a = (rng.randrange(width), rng.randrange(height))
        b = (rng.randrange(width), rng.randrange(height))
        reach = connected_free_cells(problem, a, diagonal)
        expected = bool(reach[b[1] * width + b[0]])
        assert cells_joined(problem, a, b, diagonal) == expected, (trial, a, b)
        assert cells_joined(problem, b, a, diagonal) == expected, (trial, a, b)


def test_two_sided_proof_stops_when_the_fills_meet():
    # An open map joins at once: no full fill, so no call of stop at all.
    stop = CountingStop()
    assert cells_joined(open_map(1000), (0, 0), (999, 999), True, stop)
    assert stop.calls == 0


def test_a_goal_walled_into_a_small_room_is_found_out_after_about_the_room():
    size = 1000
    blocked = bytearray(size * size)
    for column in range(size - 4, size):   # a 3 x 3 room in the top-right corner
        blocked[(size - 4) * size + column] = 1
    for row in range(size - 4, size):
        blocked[row * size + size - 4] = 1
    problem = Problem(size, size, bytes(blocked), (0.5, 0.5), (size - 0.5, size - 0.5))
    stop = CountingStop()
    assert not cells_joined(problem, (0, 0), (size - 1, size - 1), True, stop)
    assert stop.calls == 0   # the room's 9 cells, not the map's million


# -- every set-up loop asks its stop and gives way ---------------------------------
SETUP_LOOPS = {
    "full fill": lambda p, stop: connected_free_cells(p, (0, 0), True, stop),
    "two-sided proof": lambda p, stop: cells_joined(p, (0, 0), (p.width - 1, p.height - 1),
                                                    True, stop),
    "free cells": lambda p, stop: FreeCells(p.blocked, stop),
    "dijkstra": lambda p, stop: CellDistanceToGoal(p, p.goal, stop=stop),
}


@pytest.mark.parametrize("name", sorted(SETUP_LOOPS))
def test_set_up_loops_ask_stop_and_give_way(name):
    problem = walled(300)   # disconnected: the two-sided proof must fill a half
    patient = CountingStop()
    SETUP_LOOPS[name](problem, patient)
    assert patient.calls >= 1
    if name != "free cells":   # one call per POLL_EVERY cells (free cells: per chunk)
        assert patient.calls >= 40_000 // POLL_EVERY
    hasty = CountingStop(fire_at=1)
    with pytest.raises(Interrupted):
        SETUP_LOOPS[name](problem, hasty)
    assert hasty.calls == 1


def test_free_cells_is_the_list_of_free_cells():
    rng = random.Random(3)
    maps = [bytes(size) for size in (1, 63, 64, 65, 1000)]  # no blocked cell: no counts kept
    maps += [bytes([1]) * 70, bytes(199) + bytes([1])]
    for _ in range(200):
        size = rng.randrange(1, 400)
        maps.append(bytes(rng.random() < rng.random() for _ in range(size)))
    for blocked in maps:
        listed = [index for index, cell in enumerate(blocked) if not cell]
        cells = FreeCells(blocked)
        assert len(cells) == len(listed)
        assert [cells[k] for k in range(len(cells))] == listed
        if listed:
            assert cells[-1] == listed[-1]
        with pytest.raises(IndexError):
            cells[len(listed)]


def peak_bytes_per_cell(make, cells: int) -> float:
    """Peak bytes Python allocates while ``make()`` runs, per cell of the map."""
    tracemalloc.start()
    try:
        kept = make()  # noqa: F841  (what it keeps counts as well)
        return tracemalloc.get_traced_memory()[1] / cells
    finally:
        tracemalloc.stop()


def test_set_up_structures_are_compact():
    problem, small = nearly_open_map(100), open_map(60)  # (tracemalloc slows Dijkstra ~10x)
    # The world shares the problem's bytes (it used to copy them into a list: 8 B a cell).
    big = Problem(1100, 1000, bytes(1100 * 1000), (0.5, 0.5), (1.5, 1.5))
    assert peak_bytes_per_cell(lambda: GridWorld(big), 1100 * 1000) < 1
    assert peak_bytes_per_cell(lambda: GridWorld(problem), 100 * 100) < 1
    # Counts per block of cells, not a list of every free cell (36 B a cell).
    assert peak_bytes_per_cell(lambda: FreeCells(problem.blocked), 100 * 100) < 1
    # A double and a byte a cell, plus the heap (it was two lists of floats: ~98 B).
    assert peak_bytes_per_cell(lambda: CellDistanceToGoal(small, small.goal), 60 * 60) < 20
    # One byte a cell and an array for a stack (the list stack made it ~26 B).
    assert peak_bytes_per_cell(lambda: connected_free_cells(small, (0, 0), True), 60 * 60) < 6


# -- planners: a set-up cut short by the time limit is a time-limit result -------------
def expired() -> StopCondition:
    return StopCondition(time_limit=0.0)


TREE_PROOF = ("rrt", "rrtstar", "informed")
"""Planners whose only set-up is the proof that start and goal are cut off."""


@pytest.mark.parametrize("vehicle,name", [run for run in RUNS if run[1] not in TREE_PROOF])
def test_planner_set_up_gives_way_to_an_expired_time_limit(vehicle, name):
    setup = grid_setup(nearly_open_map(300), vehicle)
    result = solve_on(PLANNERS[name].load(), setup, expired(), random.Random(1))
    assert result.status is PlanStatus.TIME_LIMIT
    assert result.message == "during set-up"
    assert result.path == () and result.stats.iterations == 0


@pytest.mark.parametrize("name", TREE_PROOF)
def test_rrt_proof_gives_way_to_an_expired_time_limit(name):
    setup = grid_setup(walled(300), "point")
    result = solve_on(PLANNERS[name].load(), setup, expired(), random.Random(1))
    assert result.status is PlanStatus.TIME_LIMIT and result.message == "during set-up"


# -- memory ---------------------------------------------------------------------------
@pytest.mark.parametrize("vehicle,name", RUNS)
def test_running_out_of_memory_is_a_result_not_a_traceback(vehicle, name, monkeypatch):
    def no_memory(*args, **kwargs):
        raise MemoryError

    setup = grid_setup(walled(50), vehicle)
    si = setup.si
    for capability in ("certainly_disconnected", "distance_along_cells", "free_cell_indices"):
        monkeypatch.setattr(si.world, capability, no_memory)
    monkeypatch.setattr(si, "sample_control", no_memory, raising=False)  # control only
    monkeypatch.setattr(si, "sample_target", no_memory)
    result = solve_on(PLANNERS[name].load(), setup, StopCondition(time_limit=30),
                      random.Random(1))
    assert result.status is PlanStatus.OUT_OF_MEMORY
    assert result.message and result.path == () and result.edges == ()


@pytest.fixture(scope="module")
def map_3000(tmp_path_factory):
    path = tmp_path_factory.mktemp("big") / "random-3000.sw"
    path.write_text(map_text(3000))
    return str(path)


@pytest.mark.slow
def test_out_of_memory_under_a_memory_limit_is_one_line(map_3000):
    # Dijkstra's 72 MB of distances do not fit in 90 MB of address space.
    status, _, _, err = measured_run(["-grad", "-planner", "kpiece", "-seed", "1", "-time", "5"],
                                     map_3000, limit_bytes=90 * 2 ** 20)
    assert status != 0 and "Traceback" not in err, err
    assert "out of memory" in err and err.count("\n") == 1, err


@pytest.mark.slow
@pytest.mark.parametrize("vehicle,name", RUNS)
def test_time_limit_bounds_a_3000_map_run(vehicle, name, map_3000):
    status, wall, rss, err = measured_run(
        [*FLAGS[vehicle], "-planner", name, "-seed", "1", "-time", "2"], map_3000)
    assert status == 0 or (status == 3 and "time limit reached" in err), err
    assert wall < 3.5, f"{wall:.2f} s: {err}"
    assert rss < 600, f"{rss:.0f} MB"
