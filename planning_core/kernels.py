"""Which version of each hot kernel runs, and what ``-stats`` says of it.

A hot kernel has one readable reference, its definition, and at most one fast
version that computes the same floats in the same order (tests hold the two
together bit for bit):

- the metric (distance, the kd-tree's box bound, interpolation): ``spaces.StateSpace``
  and ``nearest.metric.SpaceMetric.bound``; fast, a generated class per space shape;
- the slice loop and its valid-state test (finite, the bounds, the body):
  ``integrators.ReferenceIntegrator`` over ``StateSpace.satisfies_bounds``; fast, a
  generated class per system and scheme;
- the body test: the shapes' (``ContinuousWorld.first_obstacle`` of the placed body);
  fast, the compiled build's C kernel (``worlds/body_kernel.c``);
- the control RRT's sampled extension over the grid ships
  (``ControlSamplingSteering.extend``); fast, the compiled build's C kernel
  (``systems/ship_kernel.c``).

The generated classes (``generated_kernels``) exist for the registered family
systems' spaces (and their position goals) and dynamics; a problem's own metric
groups of another shape run the reference. A straight motion's check, the arm's
``link_tests.MotionCheck`` and the rigid body's ``body_motion.BodyMotionCheck``, is the
fast version of ``FamilyGeometricSpaceInformation.first_hit``; the ship's slice loop
(``Spaceship.propagate_while``, SPEC 2's dynamics) is a kernel of its own, one source.
"""

from __future__ import annotations

import sys
from typing import Any

GENERATED = "planning_core.generated_kernels"


def metric_key(space: Any) -> tuple:
    """What a generated metric is made for: which variables are angles, and the
    variables of each metric group (not the names, weights or bounds)."""
    return (tuple(v.angle for v in space.variables),
            tuple(indices for indices, _ in space.groups))


def integrator_key(dynamics: Any, scheme: str, body: bool) -> tuple:
    """What a generated integrator is made for: the names, rates and angles of the
    dynamics, its parameters' names (not their values), the scheme, and whether it
    tests a body."""
    return (dynamics.state_names, dynamics.control_names, dynamics.rates, dynamics.angles,
            tuple(name for name, _ in dynamics.constants), scheme, body)


def space_metric(space: Any) -> Any:
    """The metric of ``space`` for the planners' inner loops (a
    ``nearest.metric.SpaceMetric``): the generated class of its shape, else the
    reference."""
    from planning_core.generated_kernels import METRICS
    from planning_core.nearest.metric import SpaceMetric
    return METRICS.get(metric_key(space), SpaceMetric)(space)


def integrator(system: Any, body: Any = None) -> Any:
    """The slice loop of a kinodynamic family system (``slices``, ``advance``,
    ``propagate_valid``, ``valid``) with the valid-state test (finite, the bounds,
    ``body.free(x, y, theta)`` when a ``BodyTest`` is given): its generated class,
    else ``integrators.ReferenceIntegrator``."""
    from planning_core.generated_kernels import INTEGRATORS
    dynamics, variables = system.dynamics, system.space.variables
    found = INTEGRATORS.get(integrator_key(dynamics, system.scheme, body is not None))
    if found is None:
        from planning_core.integrators import ReferenceIntegrator
        return ReferenceIntegrator(dynamics, system.scheme, float(system.dt),
                                   system.space.satisfies_bounds, body)
    return found(float(system.dt), [float(value) for _, value in dynamics.constants],
                 [v.low for v in variables], [v.high for v in variables], body)


# ----- what -stats says --------------------------------------------------------------------


def mode(kind: type) -> str:
    """``compiled`` when the class comes from the compiled build, else ``interpreted``."""
    file = getattr(sys.modules.get(kind.__module__), "__file__", "") or ""
    return "interpreted" if file.endswith(".py") else "compiled"


def metric_version(metric: Any) -> str:
    """``generated, compiled``, or ``reference, <mode> (why)``."""
    kind = type(metric)
    if kind.__module__ == GENERATED:
        return f"generated, {mode(kind)}"
    return ("reference, interpreted (no generated metric for its shape: "
            "a problem's own metric groups)")  # (the space's own methods)


def integrator_version(loop: Any) -> str:
    kind = type(loop)
    if kind.__module__ == GENERATED:
        return f"generated, {mode(kind)}"
    return "reference, interpreted (no generated integrator for these dynamics and scheme)"


def body_version(body: Any) -> str:
    if body.native:
        return "C kernel"
    return "reference (shapes), interpreted (the C kernel runs only with the compiled build)"


def describe(setup: Any) -> str:
    """``name=version; ...`` for ``-stats``: every hot kernel the setup's planner runs,
    by the objects its SpaceInformation (``kernels``) and goal (``metric``) hold; a
    grid's vehicle by its own loop."""
    si = setup.si
    found = dict(getattr(si, "kernels", {}))
    goal_metric = getattr(setup.pdef.goal, "metric", None)
    if goal_metric is not None:
        found["goal metric"] = goal_metric
    if not found:  # a grid problem: the vehicle's own loop and the grid's own tests
        ship = si.system.kinodynamic
        name, owner = ("slice loop", si.system) if ship else ("segment test", si.world)
        found[name] = f"{type(owner).__name__}'s own, {mode(type(owner))}"
        if ship:
            found["RRT's extension"] = ("C kernel" if si.native_extension(1) is not None
                                        else f"the steering's loop, {mode(type(si))}")
    says = {"metric": metric_version, "goal metric": metric_version,
            "integrator": integrator_version, "body test": body_version}
    parts = [f"{name}={says[name](value)}" if name in says else f"{name}={value}"
             for name, value in found.items() if value is not None]
    return "; ".join(parts)
