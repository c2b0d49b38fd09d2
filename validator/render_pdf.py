"""The validator's PDF (SPEC 3, SPEC 5.5): what validator/cli.py and grading call.

One page for a ``.sw`` problem (render_grid); for a ``kinoplan 1`` problem, the
kinodynamic systems' pages (render_kinodynamic) or the geometric ones'
(render_geometric), over render_plot's frames. Every page's bands, colours and
budgets are render_page's. The rendering modules (render_*.py) are the only ones
that import reportlab; the family's are imported only to draw a family problem.

Given a path, the PDF is written to a temporary file in the same folder and
renamed over the path only when complete (render_file): a reader (or a second
validator writing the same path) never sees half a file, and a failed render
leaves none.
"""

from __future__ import annotations

import os
from typing import BinaryIO, Sequence

from reportlab import rl_config
from reportlab.pdfgen.canvas import Canvas

from planning_core.kinoplan import KinoplanProblem
from planning_core.problem import Problem
from planning_core.vehicles import Vehicle
from validator.checks import ValidationReport
from validator.render_file import write_atomically
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
        return write_atomically(os.fspath(out), lambda file: render_pdf(
            file, problem, vehicle, report, verdict, notes, problem_label, options, family))
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
    from validator.render_geometry import family_heading
    from validator.render_plot import PAGE, page_text
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
