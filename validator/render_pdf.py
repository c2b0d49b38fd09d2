"""The validator's PDF (SPEC 3, SPEC 5.5): what validator/cli.py and grading call.

One page for a ``.sw`` problem (render_grid); for a ``kinoplan 1`` problem, the
kinodynamic systems' pages (render_kinodynamic) or the geometric ones'
(render_geometric), over render_plot's frames. Every page's bands, colours and
budgets are render_page's. The rendering modules (render_*.py) are the only ones
that import reportlab; the family's are imported only to draw a family problem.

Given a path, the PDF is written to a temporary file in the same folder and
renamed over the path only when complete: a reader (or a second validator
writing the same path) never sees half a file, and a failed render leaves none.
"""

from __future__ import annotations

import os
import stat
import tempfile
from typing import BinaryIO, Sequence

from reportlab import rl_config
from reportlab.pdfgen.canvas import Canvas

from planning_core.kinoplan import KinoplanProblem
from planning_core.problem import Problem
from planning_core.vehicles import Vehicle
from validator.checks import ValidationReport
from validator.render_grid import render_grid
from validator.render_page import FamilyOptions, RenderOptions, RenderSummary


def render_pdf(out: BinaryIO | str | os.PathLike, problem: Problem | KinoplanProblem,
               vehicle: Vehicle | None, report: ValidationReport | None, verdict: str,
               notes: Sequence[str] = (), problem_label: str = "",
               options: RenderOptions = RenderOptions(), family: FamilyOptions = FamilyOptions()
               ) -> RenderSummary:
    """Write the PDF to ``out``: a binary file, or a path, written atomically (a
    temporary file in the same folder, renamed over it when complete; removed if
    the render fails, the exception then raised as it was).

    ``report`` is None when there is nothing to validate (the planner timed out or
    could not start): the pages then show the problem, ``verdict`` and ``notes``.
    ``vehicle`` is the grid's (unused for a kinoplan problem, which names its system).
    """
    if isinstance(out, (str, os.PathLike)):
        return _render_to_path(os.fspath(out), problem, vehicle, report, verdict, notes,
                               problem_label, options, family)
    # Binary (zlib only) streams: reportlab's ASCII85 step is pure Python, slower
    # than all the drawing, and makes the file a quarter bigger.
    saved_a85, rl_config.useA85 = rl_config.useA85, 0
    try:
        if isinstance(problem, KinoplanProblem):
            return _render_family(out, problem, report, verdict, notes, problem_label, options,
                                  family)
        return render_grid(out, problem, vehicle, report, verdict, notes, problem_label, options)
    finally:
        rl_config.useA85 = saved_a85


def _render_family(out: BinaryIO, problem: KinoplanProblem, report: ValidationReport | None,
                   verdict: str, notes: Sequence[str], label: str, options: RenderOptions,
                   family: FamilyOptions) -> RenderSummary:
    """The family's pages for ``problem``: its system's kind picks them."""
    from validator.render_plot import PAGE, family_heading, page_text
    canvas = Canvas(out, pagesize=PAGE, pageCompression=1, invariant=1)
    canvas.setTitle(f"rrt-validator: {label or 'problem'} ({problem.system_name})")
    canvas.setCreator("rrt-validator")
    text = page_text(report, verdict, family_heading(problem, report, label), notes)
    if problem.system.kinodynamic:
        from validator.render_kinodynamic import kinodynamic_pages
        summary = kinodynamic_pages(canvas, problem, report, text, options, family)
    else:
        from validator.render_geometric import geometric_pages
        summary = geometric_pages(canvas, problem, report, text, options, family)
    canvas.save()
    return summary


def _render_to_path(path: str, *args) -> RenderSummary:
    """render_pdf into a temporary file beside ``path``, then os.replace; the mode is
    what ``open`` would give. A device, FIFO or /proc path, or a folder we cannot
    create a file in (the file itself may still be writable), is written directly."""
    temporary = _temporary_beside(path)
    if temporary is None:
        with open(path, "wb") as out:
            return render_pdf(out, *args)
    fd, temporary_path, target = temporary
    try:
        with os.fdopen(fd, "wb") as out:
            summary = render_pdf(out, *args)
        os.chmod(temporary_path, _new_file_mode(target))
        os.replace(temporary_path, target)
    except BaseException:
        try:
            os.unlink(temporary_path)
        except OSError:
            pass
        raise
    return summary


def _temporary_beside(path: str) -> tuple[int, str, str] | None:
    """(fd, name) of a new temporary file in the folder of ``path``'s target (through
    symlinks, as ``open`` writes) and that target; None when ``path`` is not a
    regular file (nor absent) or no file can be made there."""
    if os.path.abspath(path).startswith(("/dev/", "/proc/")):
        return None
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return None
    except FileNotFoundError:
        pass
    except OSError:
        return None
    target = os.path.realpath(path)
    folder, name = os.path.split(target)
    try:
        fd, temporary_path = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=folder)
    except OSError:
        return None
    return fd, temporary_path, target


def _new_file_mode(target: str) -> int:
    """The existing file's permissions, or 0o666 less the umask (mkstemp gives 0o600)."""
    try:
        return os.stat(target).st_mode & 0o7777
    except OSError:
        pass
    umask = os.umask(0o022)
    os.umask(umask)
    return 0o666 & ~umask
