"""The kinoplan family (SPEC 5) solved with OMPL's Python bindings, as an OMPL user in
Python would write it, with our problem's own pieces as the callbacks:

* State space: a compound of OMPL subspaces, one per metric group, weighted as the
  group (``SO2StateSpace`` for a one-angle group, ``RealVectorStateSpace`` bounded by
  the problem for a group without angles), so OMPL's distance is our metric. A group
  that mixes angles with other variables, or holds two angles (the arm's
  ``theta1,theta2``), becomes one subspace per variable with the group's weight:
  OMPL then sums where we take the Euclidean norm (nearest neighbours only; the
  goal and the motion checks below use our metric). Variables in no group
  (the unicycle's v, omega) sit in a subspace of weight 0.
* Validity: ``planning_core.kinoplan.state_validator`` (bounds, body in the box, off
  every obstacle).
* Kinodynamic systems: a Python ``StatePropagator`` that runs our system's
  ``propagate`` for one slice; OMPL's propagation step size is the problem's DT and
  its control duration KMIN..KMAX steps, so OMPL's ``propagateWhileValid`` steps
  slice by slice, testing each slice as SPEC 5.2 does, and a motion is a control
  held for K whole slices (fewer when a slice is invalid, as OMPL keeps the valid
  part). Controls: ``RealVectorControlSpace`` with the problem's bounds. Planners:
  control RRT (goal bias 0.05) and KPIECE1 (projection on the system's
  ``position_indices``: (x, y), or (theta, omega) for the pendulum; cells a 20th of
  each projected extent).
* Geometric systems: a Python ``MotionValidator`` that tests our
  ``system.motion_samples`` (``n + 1`` samples at the ``check`` step in our metric,
  SPEC 5.2). Planners: RRT (goal bias 0.05, OMPL's default range), RRTConnect, PRM.
* Goal: a Python ``GoalSampleableRegion``: our ``FamilyGoal`` distance and a
  threshold a hair inside its tolerance; samples the goal's values (the rest uniform).

Answers are printed in our format (SPEC 5.4): kinodynamic lines re-propagated from
the start with OMPL's controls through our ``propagate`` (K = duration / DT), which
gives OMPL's own states bit for bit (``tests/benchmarks/test_bench_ompl_family.py``).
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

from benchmarks.ompl_adapters import (OPTIMIZING_PLANNERS, OmplResult, geometric_tree, inside,
                                      make_bounds, ompl_modules, ompl_planner,
                                      optimizing_planner, solve_with)

if TYPE_CHECKING:  # imported where used: a grid problem's peer run should not load the family
    from planning_core.kinoplan import KinoplanProblem

KINODYNAMIC_PLANNERS = ("rrt", "kpiece1")
GEOMETRIC_PLANNERS = ("rrt", "rrtconnect", "prm")


@dataclass(frozen=True)
class FamilyOmplParams:
    goal_bias: float = 0.05
    """Probability of sampling the goal (RRT; KPIECE1's default is the same)."""
    kpiece_cells: int = 20
    """KPIECE1's grid: each projected variable's extent cut into this many cells."""


def planners_for_system(system) -> tuple[str, ...]:
    return KINODYNAMIC_PLANNERS if system.kinodynamic else GEOMETRIC_PLANNERS + OPTIMIZING_PLANNERS


class Layout:
    """Where each of our state variables lives in OMPL's compound state, and the
    generated accessors between our tuples and OMPL's states."""

    def __init__(self, ob, space):
        self.space = ob.CompoundStateSpace()
        self.exact_metric = True
        """OMPL's distance is our metric (no group was split into one subspace per
        variable)."""
        where: dict[int, str] = {}
        grouped = {i for indices, _ in space.groups for i in indices}
        parts = [(indices, weight) for indices, weight in space.groups]
        loose = tuple(i for i in range(space.dimension) if i not in grouped)
        if loose:
            parts.append((loose, 0.0))
        for indices, weight in parts:
            angles = [space.variables[i].angle for i in indices]
            if any(angles) and len(indices) > 1:  # per variable (see the module's note)
                self.exact_metric = False
                for i in indices:
                    self._add(ob, space, (i,), weight, where)
            else:
                self._add(ob, space, indices, weight, where)
        self.extents = [(-math.pi, math.pi) if v.angle else (v.low, v.high)
                        for v in space.variables]
        order = [where[i] for i in range(space.dimension)]
        namespace: dict = {}
        exec(f"def get(s):\n    return ({', '.join(order)},)\n"  # noqa: S102 (our own text)
             "def put(s, q):\n" + "".join(f"    {slot} = q[{i}]\n" for i, slot in
                                          enumerate(order)), namespace)
        self.get, self.put = namespace["get"], namespace["put"]

    def _add(self, ob, space, indices, weight, where) -> None:
        k = self.space.getSubspaceCount()
        if space.variables[indices[0]].angle:
            self.space.addSubspace(ob.SO2StateSpace(), weight)
            where[indices[0]] = f"s[{k}].value"
            return
        sub = ob.RealVectorStateSpace(len(indices))
        sub.setBounds(make_bounds(ob, [space.variables[i].low for i in indices],
                                  [space.variables[i].high for i in indices]))
        self.space.addSubspace(sub, weight)
        for j, i in enumerate(indices):
            where[i] = f"s[{k}][{j}]"


def solve_family(problem: KinoplanProblem, planner: str, time_limit: float, seed: int,
                 params: FamilyOmplParams = FamilyOmplParams(),
                 optimize: bool = False) -> OmplResult:
    """Plan with OMPL; ``planner`` is one of :func:`planners_for_system`."""
    system = problem.system
    ob, oc, og = ompl_modules(planner, planners_for_system(system), f"{system.name} system",
                              seed)
    began = time.perf_counter()
    layout = Layout(ob, system.space)
    if system.kinodynamic:
        return _solve_kinodynamic(ob, oc, problem, layout, planner, time_limit, params, began)
    return _solve_geometric(ob, og, problem, layout, planner, time_limit, params, began,
                            optimize)


def _goal(ob, info, problem: KinoplanProblem, layout: Layout):
    """Our goal region: its distance, a threshold a hair inside its tolerance."""
    goal, get, put = problem.goal, layout.get, layout.put
    sample = problem.system.space.sample_uniform
    rng = random.Random(0)  # fills the variables a partial goal leaves free

    class FamilyGoalRegion(ob.GoalSampleableRegion):
        def distanceGoal(self, state) -> float:
            return goal.distance(get(state))

        def sampleGoal(self, state) -> None:
            put(state, goal.target if goal.full else goal.complete(sample(rng)))

        def maxSampleCount(self) -> int:
            return 1 if goal.full else 1_000_000

    region = FamilyGoalRegion(info)
    region.setThreshold(inside(goal.tolerance))
    return region


def _start(layout: Layout, problem: KinoplanProblem):
    start = layout.space.allocState()
    layout.put(start, problem.start)
    return start


def _projection(ob, layout: Layout, indices, cells: int):
    get, (i, j) = layout.get, indices

    class Projection(ob.ProjectionEvaluator):
        def getDimension(self) -> int:
            return 2

        def project(self, state, out) -> None:
            q = get(state)
            out[0], out[1] = q[i], q[j]

    projection = Projection(layout.space)
    for dim, k in enumerate(indices):
        projection.setCellSizes(dim, (layout.extents[k][1] - layout.extents[k][0]) / cells)
    return projection


def control_space_information(ob, oc, problem: KinoplanProblem, layout: Layout):
    """OMPL's control SpaceInformation for a kinodynamic problem (not yet set up):
    our validity test, our slice as the propagator, DT steps, KMIN..KMAX of them."""
    from planning_core.kinoplan import state_validator
    system = problem.system
    controls = oc.RealVectorControlSpace(layout.space, len(system.controls))
    controls.setBounds(make_bounds(ob, [lo for lo, _ in system.controls],
                                   [hi for _, hi in system.controls]))
    info = oc.SpaceInformation(layout.space, controls)
    valid, get, put, one = state_validator(system, problem.world), layout.get, layout.put, \
        system.propagate
    held = range(len(system.controls))

    def propagate(start, control, duration, result) -> None:
        # duration is one step of DT: our slice, held control for K = 1.
        put(result, one(get(start), tuple(control[c] for c in held) + (1,)))

    info.setStateValidityChecker(lambda state: valid(get(state)))
    info.setStatePropagator(propagate)
    info.setPropagationStepSize(system.dt)
    info.setMinMaxControlDuration(system.kmin, system.kmax)
    return info


def _solve_kinodynamic(ob, oc, problem, layout, planner, time_limit, params, began):
    system, get = problem.system, layout.get
    held = range(len(system.controls))
    info = control_space_information(ob, oc, problem, layout)
    if planner == "kpiece1":
        projection = _projection(ob, layout, system.position_indices, params.kpiece_cells)
        layout.space.registerDefaultProjection(projection)
    info.setup()
    setup = oc.SimpleSetup(info)
    setup.setStartState(_start(layout, problem))
    setup.setGoal(_goal(ob, info, problem, layout))
    chosen = ompl_planner(oc, planner, info, params.goal_bias)
    status, termination, solved = solve_with(ob, setup, chosen, time_limit)
    trajectory = ()
    if solved:
        path = setup.getSolutionPath()
        steps = [round(d / system.dt) for d in path.getControlDurations()]
        trajectory = replay(problem, [tuple(c[k] for k in held) for c in path.getControls()],
                            steps)
        solved = bool(trajectory)
    data = ob.PlannerData(info)
    setup.getPlannerData(data)
    tree = _control_tree(data, get, held, system.dt)
    return OmplResult(solved, status.asString(), trajectory, tree, termination.polls,
                      data.numVertices(), time.perf_counter() - began)


def replay(problem: KinoplanProblem, controls, steps) -> tuple[tuple[float, ...], ...]:
    """Trajectory lines (SPEC 5.4) re-propagated from the start with OMPL's controls;
    empty when OMPL's path has no control (its start already in the goal)."""
    state, lines = problem.start, []
    for held, k in zip(controls, steps):
        control = tuple(held) + (k,)
        lines.append(tuple(state) + control)
        state = problem.system.propagate(state, control)
    return tuple(lines)


def _control_tree(data, get, held, dt) -> tuple[tuple[float, ...], ...]:
    """Tree lines (parent state, control, K) from OMPL's planner data."""
    rows = []
    for v in range(data.numVertices()):
        parent = get(data.getVertex(v).getState())
        for child in data.getEdges(v):
            edge = data.getEdge(v, child)
            try:
                control, duration = edge.getControl(), edge.getDuration()
            except AttributeError:  # a binding without control edges: no tree
                return ()
            rows.append(parent + tuple(control[k] for k in held)
                        + (max(1, round(duration / dt)),))
    return tuple(rows)


def path_objective(ob, info, problem: KinoplanProblem, layout: Layout, informed: bool):
    """Path length in our metric: OMPL's own objective where its distance is our metric
    (rigid2), else (arm2) a Python objective that calls our metric. Informed RRT*
    always gets the Python objective: OMPL's direct informed sampler for its own
    objective takes only RealVector, SE2 and SE3 spaces, not our compound of subspaces
    (it raises), while with another objective OMPL's Informed RRT* falls back to its
    generic informed sampling."""
    if layout.exact_metric and not informed:
        return ob.PathLengthOptimizationObjective(info)
    distance, get = problem.system.space.distance, layout.get

    class OurPathLength(ob.OptimizationObjective):
        def motionCost(self, a, b):
            return ob.Cost(distance(get(a), get(b)))

        def stateCost(self, state):
            return ob.Cost(0.0)

    return OurPathLength(info)


def _solve_geometric(ob, og, problem, layout, planner, time_limit, params, began,
                     optimize=False):
    from planning_core.kinoplan import state_validator
    system = problem.system
    info = ob.SpaceInformation(layout.space)
    valid, get = state_validator(system, problem.world), layout.get
    samples = system.motion_samples

    class SampledMotions(ob.MotionValidator):
        def checkMotion(self, a, b) -> bool:
            return all(valid(q) for q in samples(get(a), get(b))[1:])

    info.setStateValidityChecker(lambda state: valid(get(state)))
    info.setMotionValidator(SampledMotions(info))
    info.setup()
    setup = og.SimpleSetup(info)
    setup.setStartState(_start(layout, problem))
    setup.setGoal(_goal(ob, info, problem, layout))
    if planner in OPTIMIZING_PLANNERS:
        chosen = optimizing_planner(ob, og, info, setup, planner,
                                    path_objective(ob, info, problem, layout, planner == "informed"),
                                    optimize)
    else:
        chosen = ompl_planner(og, planner, info, params.goal_bias)
    # PRM: OMPL's own timer (see the module's note: PRM's threads and a Python condition).
    status, termination, solved = solve_with(ob, setup, chosen, time_limit,
                                             timed=planner == "prm", began=began)
    trajectory = tuple(get(s) for s in setup.getSolutionPath().getStates()) if solved else ()
    vertices, tree = geometric_tree(ob, info, setup, get)
    return OmplResult(solved, status.asString(), trajectory, tree, termination.polls,
                      vertices, time.perf_counter() - began, tuple(termination.improvements))
