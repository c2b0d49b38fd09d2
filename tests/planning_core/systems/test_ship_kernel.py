"""The grid ship's sampled extension in C (planning_core/systems/ship_kernel.c, built
with the compiled modules) answers as its references, run interpreted here: its one
step as ``Spaceship.propagate_while`` over the grid (the same end state bit for bit,
or None, from states in motion, at rest with signed zeros, nearly at rest with a speed
whose square underflows, and not finite), its extension as the control RRT's
``ControlSamplingSteering.extend`` (the same end and control bit for bit, and the
generator left in the same state, for either ship and any number of controls); the
same error for an infinite theta after the same draws; Python errors for bad
arguments. With the build in use RRT's steering takes it and ``-stats`` says so.
Skipped where the compiled build is not in use."""

from __future__ import annotations

import math
import os
import random
import subprocess

import pytest

from rrt_startup import compiled
from planning_core.problem_text import parse_problem
from planning_core.setups import grid_setup
from planning_core.systems.spaceship import SYSTEM
from planning_core.worlds.grid import GridWorld
from rrt_cli.planners.steering import ControlSamplingSteering
from tests.conftest import COURSE_DIR, ROOT, built_kernel

NAME = "planning_core.systems._ship_kernel"
KERNEL = built_kernel(NAME)
MAPS = ("space-2", "space-3", "simple-0")


def kernel_module():
    if KERNEL is None:
        pytest.skip(f"compiled build not in use: {compiled.why_not_fresh(compiled.BUILD_DIR)}")
    return KERNEL


def world_of(name: str) -> GridWorld:
    return GridWorld(parse_problem((COURSE_DIR / f"{name}.sw").read_text()))


def kernel_of(world: GridWorld, count: int = 10, system=SYSTEM):
    return kernel_module().ShipKernel(world.cells, world.width, world.height, count,
                                      system.theta_range, system.max_thrust)


def velocity(rng: random.Random) -> float:
    """Mostly a plain speed; now and then a zero of either sign, a subnormal-squared
    one, a huge one or not a number."""
    kind = rng.random()
    if kind < 0.7:
        return rng.uniform(-2.0, 2.0)
    return rng.choice([0.0, -0.0, 1e-200, -1e-200, 1e200, math.inf, math.nan])


def check_same(kernel, world: GridWorld, state, control) -> bool:
    ours = kernel.propagate_while(state, control)
    reference = SYSTEM.propagate_while(state, control, world)
    if reference is None:
        assert ours is None, (state, control, ours)
        return False
    assert ours is not None, (state, control, reference)
    assert [v.hex() for v in ours] == [v.hex() for v in reference], (state, control)
    return True


@pytest.mark.parametrize("name", MAPS)
def test_the_kernel_propagates_as_the_reference(name):
    world = world_of(name)
    kernel = kernel_of(world)
    rng = random.Random(name)
    ended = 0
    for _ in range(20000):
        state = (rng.uniform(-0.5, world.width + 0.5), rng.uniform(-0.5, world.height + 0.5),
                 velocity(rng), velocity(rng))
        control = (rng.uniform(-7.0, 7.0) if rng.random() < 0.1
                   else rng.random() * 2 * math.pi, rng.random() * 0.5)
        ended += check_same(kernel, world, state, control)
    assert ended > 2000  # many full steps, not only early stops


def test_the_kernel_follows_a_planner_s_states_from_rest():
    """Chains of steps from the start at rest, as a planner grows them."""
    world = world_of("space-2")
    kernel = kernel_of(world)
    rng = random.Random(7)
    start = (0.5, 0.5, 0.0, 0.0) if world.point_free(0.5, 0.5) else None
    for _ in range(300):
        state = start or (rng.uniform(0, world.width), rng.uniform(0, world.height), 0.0, -0.0)
        for _ in range(20):
            control = SYSTEM.sample_control(rng)
            if not check_same(kernel, world, state, control):
                break
            state = kernel.propagate_while(state, control)


@pytest.mark.parametrize("vehicle", ["spaceship", "left"])
@pytest.mark.parametrize("count", [1, 10, 16, 37])
@pytest.mark.parametrize("name", MAPS)
def test_the_kernel_extends_as_the_steering_does(name, count, vehicle):
    """From a tree grown from the start, toward uniform targets and the goal: the same
    answer, bit for bit, and the same draws (more controls than are propagated
    together, 16, too)."""
    kernel_module()
    setup = grid_setup(parse_problem((COURSE_DIR / f"{name}.sw").read_text()), vehicle)
    si = setup.si
    assert si.native_extension(count) is None  # interpreted here: the reference
    steering = ControlSamplingSteering(si, count)
    kernel = kernel_of(si.world, count, si.system)
    rng = random.Random(count)
    states, found = [setup.pdef.start], 0
    for _ in range(1500):
        state = states[rng.randrange(len(states))]
        target = si.sample_target(rng) if rng.random() < 0.9 else si.goal_target(
            setup.pdef.goal, rng)
        ours_rng, reference_rng = random.Random(), random.Random()
        ours_rng.setstate(rng.getstate())
        reference_rng.setstate(rng.getstate())
        ours = kernel.extend(state, target, ours_rng)
        reference = steering.extend(state, target, reference_rng)
        assert ours_rng.getstate() == reference_rng.getstate()
        rng.setstate(reference_rng.getstate())
        if reference is None:
            assert ours is None
            continue
        found += 1
        assert [v.hex() for v in ours[0] + ours[1]] == \
            [v.hex() for v in reference[0] + reference[1]], (state, target)
        states.append(reference[0])
    assert found > 300


class Endless(random.Random):
    """A generator whose draws are infinite, counted."""

    def __init__(self):
        super().__init__(1)
        self.draws = 0

    def random(self):
        self.draws += 1
        return math.inf


def test_an_infinite_theta_raises_as_math_cos_does():
    world = world_of("simple-0")
    kernel = kernel_of(world)
    for theta in (math.inf, -math.inf):
        with pytest.raises(ValueError, match="math domain error"):
            SYSTEM.propagate_while((1.5, 1.5, 0.1, 0.0), (theta, 0.3), world)
        with pytest.raises(ValueError, match="math domain error"):
            kernel.propagate_while((1.5, 1.5, 0.1, 0.0), (theta, 0.3))
    setup = grid_setup(parse_problem((COURSE_DIR / "simple-0.sw").read_text()), "spaceship")
    drawn = []
    for extend in (kernel.extend, ControlSamplingSteering(setup.si, 10).extend):
        rng = Endless()
        with pytest.raises(ValueError, match="math domain error"):
            extend((1.5, 1.5, 0.1, 0.0), (2.0, 1.0), rng)
        drawn.append(rng.draws)
    assert drawn == [2, 2]


def test_bad_arguments_raise_a_python_error():
    module = kernel_module()
    world = world_of("simple-0")
    bounds = (10, SYSTEM.theta_range, SYSTEM.max_thrust)
    with pytest.raises(ValueError):
        module.ShipKernel(world.cells[:-1], world.width, world.height, *bounds)
    with pytest.raises(ValueError):
        module.ShipKernel(b"", 0, 0, *bounds)
    with pytest.raises(ValueError):
        module.ShipKernel(world.cells, world.width, world.height, 0, *bounds[1:])
    with pytest.raises(TypeError):
        module.ShipKernel("cells", world.width, world.height, *bounds)
    kernel = module.ShipKernel(world.cells, world.width, world.height, *bounds)
    with pytest.raises(TypeError):
        kernel.extend((1.5, 1.5, 0.0, 0.0), (1.0, 1.0))
    with pytest.raises(ValueError):
        kernel.extend((1.5, 1.5, 0.0, 0.0), (1.0,), random.Random(1))
    with pytest.raises(AttributeError):
        kernel.extend((1.5, 1.5, 0.0, 0.0), (1.0, 1.0), None)
    with pytest.raises(TypeError):
        kernel.propagate_while((1.5, 1.5, 0.0, 0.0))
    with pytest.raises(ValueError):
        kernel.propagate_while((1.5, 1.5, 0.0), (0.0, 0.1))
    with pytest.raises(TypeError):
        kernel.propagate_while((1.5, 1.5, 0.0, None), (0.0, 0.1))
    with pytest.raises(TypeError):
        kernel.propagate_while(1.5, (0.0, 0.1))
    empty = module.ShipKernel.__new__(module.ShipKernel)
    with pytest.raises(RuntimeError):
        empty.propagate_while((1.5, 1.5, 0, 0), (0, 0))
    with pytest.raises(RuntimeError):
        empty.extend((1.5, 1.5, 0, 0), (0, 0), random.Random(1))
    with pytest.raises(RuntimeError):
        kernel.__init__(world.cells, world.width, world.height, *bounds)


@pytest.mark.parametrize("disable, says", [
    ("", "slice loop=Spaceship's own, compiled; RRT's extension=C kernel"),
    ("1", "slice loop=Spaceship's own, interpreted; "
          "RRT's extension=the steering's loop, interpreted")])
def test_stats_names_the_extension_that_ran(disable, says):
    """The same answer either way; ``-stats`` says which extension ran."""
    kernel_module()
    problem = (COURSE_DIR / "space-1.sw").read_text()
    runs = [subprocess.run([str(ROOT / "run.sh"), "-grad", "-seed", "2", "-stats"],
                           input=problem, capture_output=True, text=True, timeout=120,
                           env=dict(os.environ, RRT_INTERPRETED=flag))
            for flag in (disable, "1")]
    assert all(run.returncode == 0 for run in runs), runs[0].stderr
    assert runs[0].stdout == runs[1].stdout
    assert runs[0].stderr.splitlines()[-1] == f"rrt_cli kernels: {says}"
