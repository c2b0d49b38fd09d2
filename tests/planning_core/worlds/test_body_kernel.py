"""The body test's C kernel (planning_core/worlds/body_kernel.c, built with the
compiled modules) answers as its references, the shapes' test (the placed polygon's
``first_obstacle``) and ``clearance``, run interpreted here: the same placed points
and clearances bit for bit and the same verdict for every pose, touching, NaN and
infinite ones included; with it in use the body test still answers as the shapes
do. Skipped where the compiled build is not in use."""

from __future__ import annotations

import contextlib
import math
import random
import sys

import pytest

from rrt_startup import compiled
from planning_core.worlds import segment_tests
from planning_core.worlds.body_tests import (BodyTest, clearance, native_kernel,
                                             placed_coordinates)
from planning_core.worlds.continuous import ContinuousWorld
from planning_core.worlds.shapes import body_polygon
from tests.conftest import built_kernel, property_pair
from tests.planning_core.worlds.test_body_tests import (OBSTACLES, WALKS, check_random_walks,
                                                        poses_of, random_poses)
from tests.planning_core.worlds.test_continuous_world import BOX

NAME = "planning_core.worlds._body_kernel"
KERNEL = built_kernel(NAME)


def kernel_module():
    if KERNEL is None:
        pytest.skip(f"compiled build not in use: {compiled.why_not_fresh(compiled.BUILD_DIR)}")
    return KERNEL


@contextlib.contextmanager
def kernel_in_use():
    """New body tests in this block take the kernel, as the compiled build's do."""
    module = kernel_module()
    saved = sys.modules.get(NAME)
    sys.modules[NAME] = module
    try:
        yield
    finally:
        if saved is None:
            del sys.modules[NAME]
        else:
            sys.modules[NAME] = saved


def kernel_for(test: BodyTest):
    """The kernel the compiled build binds to this test's body and world."""
    with kernel_in_use():
        return native_kernel(test.world, test.body_xs, test.body_ys)


def bits(values: list[float]) -> list[str]:
    return [value.hex() for value in values]


def check_poses(test: BodyTest, poses) -> set:
    """The kernel's placed points, verdicts and clearances equal the reference's;
    the verdicts seen."""
    kernel, seen = kernel_for(test), set()
    assert not test.native  # its own meets is the reference
    for x, y, theta in poses:
        expected = test.meets(x, y, theta)
        assert kernel.meets(x, y, theta) is expected, (x, y, theta)
        xs, ys = kernel.placed(x, y, theta)
        ref_xs, ref_ys = placed_coordinates(test.body_xs, test.body_ys, x, y, theta)
        assert (bits(xs), bits(ys)) == (bits(ref_xs), bits(ref_ys)), (x, y, theta)
        assert kernel.clearance(x, y).hex() == clearance(test.world, x, y).hex(), (x, y)
        seen.add(expected)
    return seen


def test_the_kernel_knows_the_obstacle_kinds_as_the_worlds_store_them():
    module = kernel_module()
    assert (module.RECT, module.DISC, module.POLYGON) == (
        segment_tests.RECT, segment_tests.DISC, segment_tests.POLYGON)


def test_seeded_walks_meet_as_the_reference_with_the_same_placed_points():
    rng = random.Random(3)
    bodies = (body_polygon("rect", [2, 1]), body_polygon("rect", [0.3, 0.15]))
    for world in (ContinuousWorld(BOX, OBSTACLES), ContinuousWorld(None, OBSTACLES)):
        for body in bodies:
            assert check_poses(world.body_tester(body),
                               random_poses(rng, 3000, 0.05)) == {True, False}
    angles = [rng.uniform(-1e6, 1e6) for _ in range(2000)]
    angles += [k * math.pi / 4 for k in range(-16, 17)]
    test = ContinuousWorld(BOX, OBSTACLES).body_tester(body_polygon("rect", [2, 1]))
    check_poses(test, [(5.0, 5.0, theta) for theta in angles])


def check_kernel_walk(obs, body, boxed, moves):
    """The kernel meets as the reference along the walk."""
    kernel_module()
    test = ContinuousWorld(BOX if boxed else None, obs).body_tester(body)
    check_poses(test, poses_of(moves))


test_the_kernel_meets_as_the_reference_along_any_walk, \
    test_the_kernel_meets_as_the_reference_along_any_walk_full = property_pair(
        check_kernel_walk, *WALKS, unit=50, full=150)


def test_with_the_kernel_the_body_test_answers_as_the_shapes_do():
    with kernel_in_use():
        test = ContinuousWorld(BOX, OBSTACLES).body_tester(body_polygon("rect", [2, 1]))
        assert test.native and test.meets.__self__.__class__.__name__ == "BodyKernel"
        check_random_walks(seed=11, count=1000)
    assert not ContinuousWorld(BOX, OBSTACLES).body_tester(body_polygon("rect", [2, 1])).native


def test_bad_arguments_raise_a_python_error():
    module = kernel_module()
    world = ContinuousWorld(BOX, OBSTACLES).body_tester(body_polygon("rect", [2, 1])).world
    fields = (world.has_box, world.box, world.kinds, world.boxes, world.xs, world.ys, world.discs)
    with pytest.raises(ValueError):
        module.BodyKernel([], [], *fields)
    with pytest.raises(ValueError):
        module.BodyKernel([0.0, 1.0], [0.0], *fields)
    with pytest.raises(TypeError):
        module.BodyKernel([0.0, "x"], [0.0, 1.0], *fields)
    kernel = module.BodyKernel([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], *fields)
    with pytest.raises(TypeError):
        kernel.meets(1.0, 2.0)
    with pytest.raises(TypeError):
        kernel.meets(1.0, 2.0, None)
    with pytest.raises(RuntimeError):
        module.BodyKernel.__new__(module.BodyKernel).meets(1.0, 2.0, 0.0)
    failed = module.BodyKernel.__new__(module.BodyKernel)
    with pytest.raises(TypeError):
        failed.__init__([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], *fields[:-1], [None])
    with pytest.raises(RuntimeError):  # half read: never used, never read again
        failed.meets(1.0, 2.0, 0.0)
    with pytest.raises(RuntimeError):
        failed.__init__([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], *fields)
