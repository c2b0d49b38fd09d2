"""The benchmark plots, per vehicle (or family system): planning time per problem (every
run a point; from ``BOX_MIN_RUNS`` runs a box behind them), the share of runs solved
against time, and cost (path length, or a kinodynamic answer's control duration) against
time per problem. Each planner keeps one colour in every plot of a run. Drawn with
matplotlib, imported only here: as inline SVG for report.html and as pages of plots.pdf.
"""

from __future__ import annotations

import contextlib
import io
import math
import re
import statistics
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator, Sequence

from benchmarks.catalog import label
from benchmarks.report import (VEHICLE_ORDER, VEHICLE_TITLES, group, planner_order,
                               problem_order)
from benchmarks.rows import RunRow

BOX_MIN_RUNS = 10
"""Runs of a planner on a problem from which its box is drawn (fewer: points only)."""
PROBLEMS_PER_FIGURE = 9
PANELS_PER_FIGURE = 12
PANEL_COLUMNS = 4
FLOOR_SECONDS = 1e-4
"""Times below this are drawn at it (log axes)."""


@dataclass(frozen=True)
class Plot:
    """One figure: the vehicle (or system) it shows, what it shows, the figure."""

    vehicle: str
    caption: str
    figure: object  # matplotlib.figure.Figure
    name: str
    """Unique within a run: prefixes the SVG's ids."""


def vehicle_title(vehicle: str) -> str:
    return VEHICLE_TITLES.get(vehicle, vehicle)


def vehicles_of(rows: Sequence[RunRow]) -> list[str]:
    """The grid's vehicles in their order, then the family's systems alphabetically."""
    present = {r.vehicle for r in rows}
    return ([v for v in VEHICLE_ORDER if v in present]
            + sorted(present - set(VEHICLE_ORDER)))


def planner_colours(rows: Sequence[RunRow]) -> dict[str, tuple]:
    """One colour per planner of the run (tab10, then tab20), the same in every plot."""
    from matplotlib import colormaps
    planners = planner_order(r.planner for r in rows)
    palette = colormaps["tab10" if len(planners) <= 10 else "tab20"]
    return {name: palette(k % palette.N) for k, name in enumerate(planners)}


def plots(rows: Sequence[RunRow], title: str = "") -> Iterator[Plot]:
    """Every figure of the run, vehicle by vehicle, each titled with its caption; the
    caller closes them."""
    import matplotlib
    matplotlib.use("Agg")  # no display needed
    colours = planner_colours(rows)
    for vehicle in vehicles_of(rows):
        mine = [r for r in rows if r.vehicle == vehicle]
        heading = f"{title}{vehicle_title(vehicle)}"
        if any(r.progress for r in mine):  # optimizing runs: their limit is their time
            yield from convergence_plots(mine, colours, heading)
            continue
        problems = problem_order(mine)
        for page, part, chunk in _chunks(problems, PROBLEMS_PER_FIGURE):
            caption = f"{heading}: planning time per problem{part}"
            yield Plot(vehicle, caption, time_figure(mine, chunk, colours, caption),
                       f"time-{vehicle}-{page}")
        caption = f"{heading}: runs solved within a time"
        yield Plot(vehicle, caption, success_figure(mine, colours, caption),
                   f"success-{vehicle}")
        cost, what = cost_of(mine)
        costed = [p for p in problems if any(r.solved and cost(r) is not None
                                             for r in mine if r.problem == p)]
        for page, part, chunk in _chunks(costed, PANELS_PER_FIGURE):
            caption = f"{heading}: {what} against planning time, solved runs{part}"
            yield Plot(vehicle, caption, cost_figure(mine, chunk, colours, (cost, what),
                                                     caption), f"cost-{vehicle}-{page}")


def _chunks(items: Sequence[str], size: int) -> Iterator[tuple[int, str, Sequence[str]]]:
    """(page number, " (page of pages)" or "", items) per ``size`` items."""
    pages = -(-len(items) // size)
    for page in range(1, pages + 1):
        yield (page, f" ({page} of {pages})" if pages > 1 else "",
               items[(page - 1) * size:page * size])


def cost_of(rows: Sequence[RunRow]):
    """A run's cost and its name: control duration where the rows have it (the
    kinodynamic family), else path length."""
    if any(r.path_duration is not None for r in rows):
        return (lambda r: r.path_duration), "control duration (s)"
    return (lambda r: r.path_length), "path length"


def _log_seconds(axes, which: str, values: Sequence[float]) -> None:
    """A log axis (``which``: "x" or "y") of seconds over ``values``, padded, labelled
    at powers of ten, or also at 2 and 5 times them where the range is narrow."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    low, high = min(values) / 1.6, max(values) * 1.6
    getattr(axes, f"set_{which}scale")("log")
    axis = getattr(axes, f"{which}axis")
    subs = (1.0, 2.0, 5.0) if math.log10(high / low) < 1.5 else (1.0,)
    axis.set_major_locator(LogLocator(subs=subs, numticks=7))
    axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(NullFormatter())
    getattr(axes, f"set_{which}lim")(low, high)


def _seconds(row: RunRow) -> float:
    return max(row.time_seconds, FLOOR_SECONDS)


def _spread(count: int, width: float) -> list[float]:
    """Offsets of ``count`` points side by side within ``width`` (no random jitter)."""
    if count == 1:
        return [0.0]
    return [width * (k / (count - 1) - 0.5) for k in range(count)]


def _legend(axes, planners, colours, vehicle, extra=()) -> None:
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color=colours[name], marker="o", linestyle="",
                      label=label(name, vehicle)) for name in planners]
    axes.legend(handles=handles + list(extra), fontsize=8, loc="upper left",
                bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)


def _runs_marks(axes, x: float, runs: Sequence[RunRow], colour, width: float,
                gid: str) -> None:
    """Every run a point: filled if solved, a cross if not; a median tick (few runs)
    or a box (many) behind them."""
    ordered = sorted(runs, key=_seconds)
    times = [_seconds(r) for r in ordered]
    offsets = _spread(len(times), width * 0.6)
    if len(times) >= BOX_MIN_RUNS:
        boxes = axes.boxplot([times], positions=[x], widths=width * 0.9, patch_artist=True,
                             manage_ticks=False, showfliers=False, zorder=1)
        for patch in boxes["boxes"]:
            patch.set(facecolor=colour, alpha=0.25, edgecolor=colour, gid=f"{gid}-box")
        for median in boxes["medians"]:
            median.set(color=colour, linewidth=2)
    else:
        axes.plot([x - width * 0.45, x + width * 0.45], [statistics.median(times)] * 2,
                  color=colour, linewidth=2, zorder=1)
    for solved, marker in ((True, "o"), (False, "x")):
        points = [(x + dx, t) for dx, t, r in zip(offsets, times, ordered) if r.solved == solved]
        if points:
            xs, ys = zip(*points)
            axes.scatter(xs, ys, s=16, marker=marker, color=colour, zorder=2,
                         gid=f"{gid}-{'solved' if solved else 'unsolved'}",
                         edgecolors="none" if solved else None)


def time_figure(rows: Sequence[RunRow], problems: Sequence[str], colours: dict,
                caption: str):
    """Planning time of every run, per problem, the planners side by side (log scale)."""
    from matplotlib import pyplot as plt
    from matplotlib.lines import Line2D
    vehicle = rows[0].vehicle
    planners = planner_order(r.planner for r in rows if r.problem in problems)
    by_key = group(rows, "problem", "planner")
    figure, axes = plt.subplots(figsize=(11, 4.8))
    width = 0.8 / max(1, len(planners))
    for index, problem in enumerate(problems):
        for k, name in enumerate(planners):
            runs = by_key.get((problem, name))
            if runs:
                _runs_marks(axes, index + (k - (len(planners) - 1) / 2) * width, runs,
                            colours[name], width, f"time-{vehicle}-{name}-{problem}")
    _log_seconds(axes, "y", [_seconds(r) for r in rows if r.problem in problems])
    axes.set_xticks(range(len(problems)))
    axes.set_xticklabels(problems, rotation=30, ha="right")
    axes.set_xlim(-0.6, len(problems) - 0.4)
    axes.set_ylabel("planning time (s)")
    axes.grid(axis="y", alpha=0.3)
    key = [Line2D([], [], color="0.3", marker="x", linestyle="", label="unsolved (time used)"),
           Line2D([], [], color="0.3", linewidth=2,
                  label=f"median (box: quartiles, from {BOX_MIN_RUNS} runs)")]
    _legend(axes, planners, colours, vehicle, key)
    return _titled(figure, caption)


def _titled(figure, caption: str):
    figure.suptitle(caption, fontsize=10)
    figure.tight_layout()
    return figure


def success_figure(rows: Sequence[RunRow], colours: dict, caption: str, seconds=_seconds):
    """The share of runs solved within a planning time (every problem of the vehicle);
    ``seconds``: a run's time to its (first) solution."""
    from matplotlib import pyplot as plt
    vehicle = rows[0].vehicle
    planners = planner_order(r.planner for r in rows)
    limit = max(r.time_limit for r in rows)
    start = min([seconds(r) for r in rows] + [limit]) / 2
    figure, axes = plt.subplots(figsize=(9, 4.2))
    for name in planners:
        runs = [r for r in rows if r.planner == name]
        times = sorted(seconds(r) for r in runs if r.solved)
        xs, ys = [start], [0.0]
        for count, t in enumerate(times, 1):
            xs += [t, t]
            ys += [ys[-1], 100.0 * count / len(runs)]
        xs.append(limit)
        ys.append(ys[-1])
        axes.plot(xs, ys, color=colours[name], linewidth=2, gid=f"success-{vehicle}-{name}")
    _log_seconds(axes, "x", [start * 1.6, limit / 1.6])
    axes.set_ylim(0, 102)
    axes.set_xlabel("planning time (s)")
    axes.set_ylabel("runs solved (% of all runs)")
    axes.grid(alpha=0.3)
    _legend(axes, planners, colours, vehicle)
    return _titled(figure, caption)


def cost_figure(rows: Sequence[RunRow], problems: Sequence[str], colours: dict, cost_name,
                caption: str):
    """Per problem, a panel: each solved run's cost against its planning time
    (``cost_name``: :func:`cost_of`'s)."""
    vehicle = rows[0].vehicle
    cost, what = cost_name
    figure, grid = _panel_grid(len(problems))
    by_key = group([r for r in rows if r.solved and cost(r) is not None], "problem", "planner")
    planners = planner_order(p for (_, p) in by_key)
    for axes, problem in zip(grid.flat, problems):
        for name in planners:
            runs = by_key.get((problem, name), [])
            if runs:
                axes.scatter([_seconds(r) for r in runs], [cost(r) for r in runs], s=18,
                             color=colours[name], edgecolors="none",
                             gid=f"cost-{vehicle}-{name}-{problem}")
        _log_seconds(axes, "x", [_seconds(r) for name in planners
                                  for r in by_key.get((problem, name), [])])
    _label_panels(grid, problems, what)
    _legend(grid[0, -1], planners, colours, vehicle)
    return _titled(figure, caption)


def _panel_grid(count: int):
    """A figure of ``count`` panels, ``PANEL_COLUMNS`` to a line: (figure, axes grid)."""
    from matplotlib import pyplot as plt
    columns = min(PANEL_COLUMNS, count)
    lines = -(-count // columns)
    return plt.subplots(lines, columns, figsize=(2.9 * columns + 2, 2.4 * lines),
                        squeeze=False)


def _label_panels(grid, problems: Sequence[str], what: str) -> None:
    """Each panel titled with its problem; the spare panels hidden; the axes named."""
    for axes, problem in zip(grid.flat, problems):
        axes.set_title(problem, fontsize=9)
        axes.tick_params(labelsize=7)
        axes.grid(alpha=0.3)
    for axes in grid.flat[len(problems):]:
        axes.set_visible(False)
    for axes in grid[:, 0]:
        axes.set_ylabel(what, fontsize=8)
    for axes in grid[-1, :]:
        axes.set_xlabel("planning time (s)", fontsize=8)


def _first_seconds(row: RunRow) -> float:
    first = row.first_solution_seconds
    return max(first, FLOOR_SECONDS) if first is not None else _seconds(row)


def convergence_plots(rows: Sequence[RunRow], colours: dict, heading: str) -> Iterator[Plot]:
    """An optimizing run's figures: runs solved against time to the first solution,
    and per problem the median cost against time with its 95% interval."""
    vehicle = rows[0].vehicle
    caption = f"{heading}: runs solved within a time (first solution)"
    yield Plot(vehicle, caption, success_figure(rows, colours, caption, _first_seconds),
               f"success-{vehicle}")
    what = cost_of(rows)[1].replace("path length", "cost: path length").replace(
        "control duration (s)", "cost: duration (s)")
    for page, part, chunk in _chunks(problem_order(rows), PANELS_PER_FIGURE):
        caption = f"{heading}: median {what} against planning time{part}"
        yield Plot(vehicle, caption, convergence_figure(rows, chunk, colours, what, caption),
                   f"convergence-{vehicle}-{page}")


CONVERGENCE_POINTS = 120
"""Times (log-spaced) at which a convergence curve is evaluated."""


def _curve(runs: Sequence[RunRow], times: Sequence[float]):
    """Median, low and high of the runs' costs at each time (NaN where infinite; an
    unbounded high is NaN too, drawn at the panel's top)."""
    from benchmarks.convergence import cost_at, median_interval
    found = [median_interval([cost_at(r, t) for r in runs]) for t in times]
    return [[v if math.isfinite(v) else math.nan for v in column] for column in zip(*found)]


def convergence_figure(rows: Sequence[RunRow], problems: Sequence[str], colours: dict,
                       what: str, caption: str):
    """Per problem, a panel: each planner's median cost against planning time (a step
    line), its 95% confidence interval by order statistics as a band."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    vehicle = rows[0].vehicle
    figure, grid = _panel_grid(len(problems))
    by_key = group(rows, "problem", "planner")
    planners = planner_order(r.planner for r in rows)
    for axes, problem in zip(grid.flat, problems):
        mine = [r for r in rows if r.problem == problem]
        limit = max(r.time_limit for r in mine)
        start = min([_first_seconds(r) for r in mine if r.solved] + [limit]) / 1.2
        times = [start * (limit / start) ** (k / (CONVERGENCE_POINTS - 1))
                 for k in range(CONVERGENCE_POINTS)]
        top = max([c for r in mine for _, c in _improvements(r)] + [1e-9]) * 1.05
        for name in planners:
            runs = by_key.get((problem, name))
            if not runs:
                continue
            median, low, high = _curve(runs, times)
            high = [top if math.isnan(h) and not math.isnan(m) else h
                    for h, m in zip(high, median)]
            axes.fill_between(times, low, high, step="post", color=colours[name], alpha=0.2,
                              linewidth=0, gid=f"band-{vehicle}-{name}-{problem}")
            axes.step(times, median, where="post", color=colours[name], linewidth=1.8,
                      gid=f"median-{vehicle}-{name}-{problem}")
        _log_seconds(axes, "x", [start * 1.6, limit / 1.6])
        axes.set_ylim(top=top)
    _label_panels(grid, problems, what)
    key = [Line2D([], [], color="0.3", linewidth=1.8,
                  label="median over all runs (unsolved = infinite)"),
           Patch(color="0.3", alpha=0.2, label="95% CI of the median (order statistics)")]
    _legend(grid[0, -1], planners, colours, vehicle, key)
    return _titled(figure, caption)


def _improvements(row: RunRow):
    from benchmarks.convergence import improvements
    return improvements(row)


def svg_text(plot: Plot) -> str:
    """The figure as an ``<svg>`` element to inline in HTML: text kept as text, no date,
    every id prefixed with the plot's name (several SVGs share one page)."""
    import matplotlib
    buffer = io.StringIO()
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "rrt-gridplan"}):
        plot.figure.savefig(buffer, format="svg", metadata={"Date": None})
    text = buffer.getvalue()
    text = text[text.index("<svg"):]
    return re.sub(r'(\bid="|href="#|url\(#)', rf"\g<1>{plot.name}-", text)


def render(rows: Sequence[RunRow], pdf: Path | None = None,
           title: str = "") -> list[tuple[Plot, str]]:
    """Every plot of the run with its SVG text; with ``pdf``, the same plots a page each
    in that file."""
    from matplotlib import pyplot as plt
    from matplotlib.backends.backend_pdf import PdfPages

    done = []
    with PdfPages(pdf) if pdf is not None else contextlib.nullcontext() as pages:
        for plot in plots(rows, title):
            done.append((plot, svg_text(plot)))
            if pages is not None:
                pages.savefig(plot.figure)
            plt.close(plot.figure)
        if pages is not None:
            pages.infodict()["Title"] = f"{title}benchmark plots"
    return done
