"""The C++ OMPL programs of ``benchmarks/ompl_cpp/`` (OMPL with C++ callbacks, the
fastest OMPL can be run): built on first use into ``.build/`` with g++ and Debian's
``libompl-dev`` (``apt-get install libompl-dev``), and the flat text each reads on stdin.

* ``grid_ompl``: a ``.sw`` problem (:func:`grid_input`), point, ship and left modes;
* ``family_ompl``: a ``kinoplan`` problem of any system (:func:`family_input`).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SOURCES = ROOT / "benchmarks" / "ompl_cpp"
BUILD = ROOT / ".build"
FLAGS = ("-O2", "-ffp-contract=off", "-std=c++17")
"""As the compiled modules: no -march=native, no fused multiply-adds."""


def binary(name: str) -> Path | None:
    """``.build/NAME`` from ``benchmarks/ompl_cpp/NAME.cpp``, compiled when missing or
    older than its source or a header beside it (common.h); None (one line on stderr when
    the build fails) without g++ or OMPL's headers."""
    source, target = SOURCES / f"{name}.cpp", BUILD / name
    newest = max(path.stat().st_mtime for path in (source, *SOURCES.glob("*.h")))
    if target.exists() and target.stat().st_mtime >= newest:
        return target
    flags = subprocess.run(["pkg-config", "--cflags", "ompl"], capture_output=True, text=True)
    if flags.returncode != 0 or shutil.which("g++") is None:
        return None
    BUILD.mkdir(exist_ok=True)
    # Built under a name of its own and renamed whole: a process building it beside us
    # (two test workers) never runs a half-written program.
    handle, partial_name = tempfile.mkstemp(prefix=f".{name}.", suffix=".partial", dir=BUILD)
    os.close(handle)
    partial = Path(partial_name)
    built = subprocess.run(["g++", *FLAGS, *flags.stdout.split(), str(source), "-o",
                            str(partial), "-lompl", "-lpthread"], capture_output=True, text=True)
    if built.returncode != 0:
        partial.unlink(missing_ok=True)
        print(f"ompl_cpp_programs: {name} not built: {built.stderr.strip()[-300:]}",
              file=sys.stderr)
        return None
    partial.chmod(0o755)  # mkstemp's 0600 plus the linker's x bits otherwise
    os.replace(partial, target)
    return target


def grid_input(problem_text: str) -> bytes:
    """``grid_ompl``'s input: W H, the cells as 0/1 (bottom row first), start, goal."""
    from planning_core.problem_text import parse_problem
    parsed = parse_problem(problem_text)
    cells = "".join("1" if cell else "0" for cell in parsed.blocked)
    return (f"{parsed.width} {parsed.height}\n{cells}\n"
            f"{parsed.start[0]!r} {parsed.start[1]!r} {parsed.goal[0]!r} {parsed.goal[1]!r}\n"
            ).encode()


def family_input(problem_text: str) -> bytes:
    """``family_ompl``'s input: keyword-led lines of numbers (floats by ``repr``, so
    exact): the variables (angle flag, low, high), the metric groups (weight, count,
    indices), the check step (geometric) or the dynamics (scheme, DT, KMIN, KMAX, the
    pendulum's g or car1's L), the controls' bounds, our SST's radii and our KPIECE1's grid
    (each axis: variable, low, scale: the cell is floor((value - low) * scale)) (kinodynamic), the
    arm's params or the body's vertices (none for the pendulum), the world box, the
    obstacles (R x0 y0 x1 y1 | C cx cy r | P n x y ...), the start, the goal (tolerance,
    count, index value ...)."""
    from planning_core.kinoplan_text import parse_kinoplan
    from planning_core.worlds.shapes import Disc, Rect
    problem = parse_kinoplan(problem_text)
    system, world, space = problem.system, problem.world, problem.system.space
    lines = [f"system {system.name}", f"vars {space.dimension}"]
    lines += [f"{int(v.angle)} {_numbers((v.low, v.high))}" for v in space.variables]
    lines.append(f"groups {len(space.groups)}")
    lines += [f"{weight!r} {len(indices)} {' '.join(map(str, indices))}"
              for indices, weight in space.groups]
    lines += _system_lines(problem)
    box = world.box if world is not None else None
    lines.append("box 0" if box is None else f"box 1 {_numbers((box.x0, box.y0, box.x1, box.y1))}")
    obstacles = world.obstacles if world is not None else ()
    lines.append(f"obstacles {len(obstacles)}")
    for o in obstacles:
        if isinstance(o, Rect):
            lines.append(f"R {_numbers((o.x0, o.y0, o.x1, o.y1))}")
        elif isinstance(o, Disc):
            lines.append(f"C {_numbers((o.cx, o.cy, o.r))}")
        else:
            lines.append(f"P {len(o.points)} {_numbers(c for point in o.points for c in point)}")
    lines.append(f"start {_numbers(problem.start)}")
    goal = problem.goal
    lines.append(f"goal {goal.tolerance!r} {len(goal.values)} " + " ".join(
        f"{space.index(name)} {value!r}" for name, value in goal.values))
    return ("\n".join(lines) + "\n").encode()


def _numbers(values) -> str:
    return " ".join(repr(float(v)) for v in values)


def _system_lines(problem) -> list[str]:
    """The check step or the dynamics, controls, SST radii and KPIECE1's grid; the arm or
    the body."""
    from planning_core.setups import kinoplan_setup
    system = problem.system
    if system.kinodynamic:
        param = {"pendulum": "g", "car1": "L"}.get(system.name)
        si = kinoplan_setup(problem).si
        lines = [f"dynamics {system.scheme} {system.dt!r} {system.kmin} {system.kmax} "
                 f"{float(getattr(system, param)) if param else 0.0!r}",
                 f"controls {len(system.controls)} "
                 f"{_numbers(v for bounds in system.controls for v in bounds)}",
                 f"sst {si.selection_radius!r} {si.pruning_radius!r}"]
        axes = system.projection_axes(si.options.projection_cells)
        lines.append(f"kpiece {len(axes)} " + " ".join(
            f"{index} {float(low)!r} {float(scale)!r}" for index, low, scale in axes))
    else:
        lines = [f"check {system.check!r}"]
    if system.name == "arm2":
        return lines + [f"arm {_numbers((system.base_x, system.base_y, system.l1, system.l2))}"]
    points = system.body.points if system.body is not None else ()
    return lines + [f"body {len(points)} {_numbers(c for point in points for c in point)}"]
