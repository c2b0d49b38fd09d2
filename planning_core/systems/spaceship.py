"""The spaceship of SPEC section 2: state <x, y, dx, dy>, control <theta, s>.

A control is held for one timestep, integrated in ``SLICES`` slices of
``1 / SLICES``; theta is measured from the direction of motion. The planner and
the validator both integrate through :meth:`Spaceship.propagate_while`, so their
numbers agree bit for bit. The left-only ship (``left_spaceship``) is this
system with half the theta range.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from planning_core.samplers import uniform

TYPE_CHECKING = False
if TYPE_CHECKING:  # for the annotation only: nothing more imported at run time
    from typing import ClassVar, Final, Optional
    from planning_core.worlds.grid import GridWorld

# Final: compiled code reads these as constants, not from the module's dict per slice.
SLICES: Final = 20
DT: Final = 1.0 / SLICES
MAX_THRUST: Final = 0.5
FULL_TURN: Final = 2.0 * math.pi

State = tuple[float, float, float, float]
Control = tuple[float, float]


class SpaceshipVariables:
    """What every ship declares, whatever its parameters. (Class constants live in
    this plain base: mypyc drops ``ClassVar`` from a dataclass's own annotations.)"""

    kinodynamic: ClassVar[bool] = True
    state_names: ClassVar[tuple[str, ...]] = ("x", "y", "dx", "dy")
    control_names: ClassVar[tuple[str, ...]] = ("theta", "s")
    position_indices: ClassVar[tuple[int, ...]] = (0, 1)
    velocity_indices: ClassVar[tuple[int, ...]] = (2, 3)
    slices: ClassVar[int] = SLICES
    rest_control: ClassVar[Control] = (0.0, 0.0)


@dataclass(frozen=True)
class Spaceship(SpaceshipVariables):
    """A kinodynamic system: a control held for one step of ``SLICES`` slices."""

    name: str = "spaceship"
    """The name the registry and the validator's report use."""
    theta_range: float = FULL_TURN
    """Random thetas are drawn from ``[0, theta_range)``; below a full turn, a
    printed theta (mod 2 pi) must lie in the closed ``[0, theta_range]``."""
    max_thrust: float = MAX_THRUST
    """Thrust ``s`` is in ``[0, max_thrust]``."""

    @property
    def full_turn(self) -> bool:
        return self.theta_range >= FULL_TURN

    def state_space(self, width: float, height: float, velocity_weight: float = 0.0):
        """Positions within the map, velocities unbounded; distance by position
        (the grid planners' nearest node is the nearest by position), plus
        ``velocity_weight`` times the velocities' distance."""
        from planning_core.spaces import StateSpace, Variable
        metric = {"x,y": 1.0}
        if velocity_weight > 0.0:
            metric["dx,dy"] = velocity_weight
        return StateSpace.from_metric(
            (Variable("x", 0.0, width), Variable("y", 0.0, height), Variable("dx"),
             Variable("dy")), metric)

    def start_state(self, x: float, y: float) -> State:
        """SPEC 2: the ship starts at rest."""
        return (x, y, 0.0, 0.0)

    def sample_control(self, rng: random.Random) -> Control:
        """Theta uniform in ``[0, theta_range)``, then thrust uniform in ``[0, s_max)``."""
        return (uniform(rng) * self.theta_range, uniform(rng) * self.max_thrust)

    def control_violation(self, control: Control) -> str | None:
        """Why a printed control is out of bounds (SPEC 3), or None. (A ship with
        less than a full turn is the left-only one, theta in ``[0, pi]``.)"""
        theta, thrust = control
        if not 0.0 <= thrust <= self.max_thrust:
            return f"thrust s = {thrust:.6g} is outside [0, {self.max_thrust}]"
        if not self.full_turn and not theta % FULL_TURN <= self.theta_range:
            return (f"theta = {theta:.6g} (mod 2 pi: {theta % FULL_TURN:.6g}) is outside "
                    f"[0, pi]: the left-only spaceship cannot thrust to the right")
        return None

    # -- what RG-RRT asks of a kinodynamic system ------------------------------------
    def reachable_controls(self, angles: int, thrusts: tuple[float, ...]) -> list[Control]:
        """A fixed reachable set: coasting, then every thrust at ``angles`` thetas
        evenly spaced over the range. A full turn's ``[0, 2 pi)`` holds every
        direction once; a narrower range is closed at both ends (the left-only
        ship's ``[0, pi]``: straight ahead and full braking)."""
        if not all(0.0 < thrust <= self.max_thrust for thrust in thrusts):
            raise ValueError(f"thrusts must be in (0, {self.max_thrust}]")
        controls = [(0.0, 0.0)]
        spacing = self.theta_range / (angles if self.full_turn or angles == 1 else angles - 1)
        for k in range(angles):
            theta = min(spacing * k, self.theta_range)
            controls.extend((theta, thrust) for thrust in thrusts)
        return controls

    def step_reach(self, state: State) -> float:
        """How far the position can get in one step, at most (speed plus thrust)."""
        return math.hypot(state[2], state[3]) + self.max_thrust

    def stopping_point(self, state: State) -> tuple[float, float]:
        """Where full braking would bring the ship to rest: ``v**2 / (2 a)`` ahead
        along its velocity."""
        x, y, dx, dy = state
        ahead = math.hypot(dx, dy) * (1.0 / (2.0 * self.max_thrust))
        return x + dx * ahead, y + dy * ahead

    def propagate_while(self, state: State, control: Control, grid: Optional[GridWorld] = None,
                        slices_out: list[State] | None = None) -> State | None:
        """Apply ``control`` from ``state`` for one timestep, slice by slice.

        Each slice thrusts at theta from the direction of motion: in motion, the
        velocity's unit vector turned by theta, whose cos and sin are taken once
        per control, so a slice costs one square root and no other transcendental
        call (docs/hot-paths.md); at rest, ``atan2(dy, dx) + theta`` as SPEC
        writes it (theta from +x, or from -x for a velocity of -0.0).

        ``grid``: the occupancy grid the ship flies over (typed, so that compiled
        code reads its row-major ``cells``, ``width`` and ``height`` natively): None is
        returned as soon as a slice's position is outside it or in a blocked cell
        (SPEC 1). The test is written inline, not called: this loop is the ship
        planners' hot path (docs/parameter-history.md). With ``slices_out``, the
        state after every slice is appended to it.
        """
        x, y, dx, dy = state
        theta, thrust = control
        step = DT * thrust
        # A slice's thrust from the +x axis; in motion it is turned by the velocity's
        # direction (its unit vector: divided by the speed below).
        push_x, push_y = step * math.cos(theta), step * math.sin(theta)
        tested = grid is not None
        if grid is not None:
            cells, width, height = grid.cells, grid.width, grid.height
        else:
            cells, width, height = b"", 0, 0
        right, top = float(width), float(height)  # compared as floats, converted once
        for _slice in range(SLICES):
            speed = math.sqrt(dx * dx + dy * dy)
            if speed > 0.0:
                dx, dy = (dx + (dx * push_x - dy * push_y) / speed,
                          dy + (dy * push_x + dx * push_y) / speed)
            else:  # at rest: SPEC's own formula, so a printed -0.0 turns theta by pi
                a = math.atan2(dy, dx) + theta
                dx, dy = dx + step * math.cos(a), dy + step * math.sin(a)
            x = x + DT * dx
            y = y + DT * dy
            if tested and (not (0.0 <= x < right and 0.0 <= y < top)
                           or cells[int(y) * width + int(x)]):
                return None
            if slices_out is not None:
                slices_out.append((x, y, dx, dy))
        return (x, y, dx, dy)

    def propagate(self, state: State, control: Control) -> State:
        """The state one timestep later (no validity test)."""
        return self.propagate_while(state, control)  # type: ignore[return-value]

    def slice_states(self, state: State, control: Control) -> list[State]:
        """The states after each of the ``SLICES`` slices, last one included."""
        out: list[State] = []
        self.propagate_while(state, control, slices_out=out)
        return out


SYSTEM = Spaceship()
