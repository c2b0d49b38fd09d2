"""The plots, in one PDF: per vehicle, planning time per problem as box plots,
and the share of runs solved against time. matplotlib is imported only here,
and only when a PDF is asked for.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from benchmarks.catalog import label
from benchmarks.report import (VEHICLE_ORDER, VEHICLE_TITLES, group, planner_order,
                               problem_order)
from benchmarks.rows import RunRow

PROBLEMS_PER_PAGE = 9


def write_pdf(rows: Sequence[RunRow], path: Path, title: str = "") -> int:
    """Write the plots; returns the number of pages."""
    import matplotlib
    matplotlib.use("Agg")  # no display needed
    from matplotlib import pyplot as plt
    from matplotlib.backends.backend_pdf import PdfPages

    pages = 0
    with PdfPages(path) as pdf:
        for vehicle in VEHICLE_ORDER:
            mine = [r for r in rows if r.vehicle == vehicle]
            if not mine:
                continue
            planners = planner_order(r.planner for r in mine)
            colours = {name: plt.get_cmap("tab10")(k % 10) for k, name in enumerate(planners)}
            problems = problem_order(mine)
            by_key = group(mine, "problem", "planner")
            for start in range(0, len(problems), PROBLEMS_PER_PAGE):
                chunk = problems[start:start + PROBLEMS_PER_PAGE]
                figure, axes = plt.subplots(figsize=(11, 6))
                _time_boxes(axes, chunk, planners, by_key, colours, vehicle)
                axes.set_title(f"{title}{VEHICLE_TITLES[vehicle]}: planning time per problem "
                               f"({start // PROBLEMS_PER_PAGE + 1})")
                figure.tight_layout()
                pdf.savefig(figure)
                plt.close(figure)
                pages += 1
            figure, axes = plt.subplots(figsize=(11, 6))
            _success_curves(axes, mine, planners, colours, vehicle)
            axes.set_title(f"{title}{VEHICLE_TITLES[vehicle]}: runs solved within a time")
            figure.tight_layout()
            pdf.savefig(figure)
            plt.close(figure)
            pages += 1
        info = pdf.infodict()
        info["Title"] = f"{title}benchmark plots"
    return pages


def _time_boxes(axes, problems, planners, by_key, colours, vehicle) -> None:
    width = 0.8 / max(1, len(planners))
    for k, name in enumerate(planners):
        data, positions = [], []
        for index, problem in enumerate(problems):
            runs = by_key.get((problem, name))
            if runs:
                data.append([max(r.time_seconds, 1e-6) for r in runs])
                positions.append(index + (k - (len(planners) - 1) / 2) * width)
        if not data:
            continue
        boxes = axes.boxplot(data, positions=positions, widths=width * 0.9,
                             patch_artist=True, manage_ticks=False,
                             flierprops={"markersize": 3})
        for patch in boxes["boxes"]:
            patch.set_facecolor(colours[name])
            patch.set_alpha(0.7)
        axes.plot([], [], "s", color=colours[name], label=label(name, vehicle))
    axes.set_yscale("log")
    axes.set_xticks(range(len(problems)))
    axes.set_xticklabels(problems, rotation=30, ha="right")
    axes.set_ylabel("planning time (s), unsolved runs at the time they used")
    axes.grid(axis="y", alpha=0.3)
    axes.legend(fontsize=8)


def _success_curves(axes, rows, planners, colours, vehicle) -> None:
    limit = max(r.time_limit for r in rows)
    for name in planners:
        runs = [r for r in rows if r.planner == name]
        times = sorted(r.time_seconds for r in runs if r.solved)
        if not runs:
            continue
        xs, ys = [1e-4], [0.0]
        for count, t in enumerate(times, 1):
            xs += [max(t, 1e-4), max(t, 1e-4)]
            ys += [ys[-1], 100.0 * count / len(runs)]
        xs.append(limit)
        ys.append(ys[-1])
        axes.plot(xs, ys, color=colours[name], label=label(name, vehicle))
    axes.set_xscale("log")
    axes.set_xlim(1e-4, limit)
    axes.set_ylim(0, 101)
    axes.set_xlabel("planning time (s)")
    axes.set_ylabel("% of runs solved (all problems of this vehicle)")
    axes.grid(alpha=0.3)
    axes.legend(fontsize=8, loc="lower right")
