"""The one command: regenerate the suite, run the harness, write the reports.

    python -m benchmarks [--preset smoke|quick|course|sweep|full|grid-sweep|grid-optimize|
                                   family|family-geometric|family-quick|family-sweep|
                                   family-optimize] [--vehicles point spaceship left]
                         [--planners rrt ompl-rrt ...] [--problems PATTERN ...]
                         [--max-size N] [--seeds N] [--time S] [--workers 2]
                         [--out DIR] [--no-ompl] [--no-plots] [--report-only]
                         [--scheduler tcp://HOST:PORT] [--rerun]

Writes into ``--out`` (default ``benchmarks/results/<preset>``): ``runs.csv``
(one row per run), ``report.md`` (tables), ``report.html`` (the tables and the plots as
inline SVG), ``plots.pdf`` (the same plots), ``ompl-logs/`` (OMPL's benchmark log format,
for ompl_benchmark_statistics.py), ``runs.sqlite`` (every run as it finishes, in OMPL's
database layout, which Planner Arena opens: a rerun of the same command keeps the runs
stored there unless ``--rerun``; see ``benchmarks/store.py``) and ``meta.json``. Progress
goes to stderr; the path of the report is the only line on stdout. The ``family*``
presets (``benchmarks/family.py``) run the kinoplan problems of
``benchmarks/problems/family/`` and write their own report
(``benchmarks/family_report.py``).

Ctrl-C or SIGTERM stops within a second: ``runs.csv`` (written row by row as
runs finish) keeps the finished runs, and the report is made from them (without
the shortest-path yardstick and the plots, which take seconds; ``--report-only``
adds them later).

Exit status: 0 the runs completed (whatever they found), 2 bad usage, 130 or 143
stopped by Ctrl-C or SIGTERM (the report of the finished runs written).
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import importlib.util
import json
import os
import platform
import signal
import subprocess
import sys
import time
from pathlib import Path

from benchmarks import catalog, family, generator, optimal, presets
from benchmarks.family_report import markdown_report as family_markdown_report
from benchmarks.html_report import html_report
from benchmarks.harness import (HarnessOptions, Interrupted, RunSpec, interrupt_on_sigterm,
                                run_all)
from benchmarks.ompl_log import LogHeader, write_logs
from benchmarks.report import markdown_report
from benchmarks.rows import CsvAppender, read_csv, write_csv
from cli_common import EXIT_USAGE, OneLineErrorParser, add_switches
from planning_core.vehicles import Vehicle

RESULTS_DIR = Path(__file__).resolve().parent / "results"
EXIT_OK = 0


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineErrorParser(prog="benchmarks",
                     description="Regenerate the problem suite, run planners x vehicles x "
                                 "problems x seeds, and write CSV, Markdown, PDF and OMPL "
                                 "logs.")
    parser.add_argument("--preset", choices=sorted(presets.PRESETS) + sorted(
                        family.FAMILY_PRESETS) + sorted(optimal.OPTIMAL_PRESETS),
                        default="quick",
                        help="which problems, vehicles, seeds and limits (default: quick); "
                             "family*: the kinoplan family (SPEC 5); optimal*: cost against "
                             "time of the optimizing planners")
    parser.add_argument("--vehicles", nargs="+", choices=[v.value for v in Vehicle],
                        help="only these vehicles of the preset")
    parser.add_argument("--planners", nargs="+", metavar="ID",
                        help="only these planners (ours by -planner name, OMPL's as "
                             "ompl-rrt, ompl-rrtconnect, ompl-kpiece1); default: all")
    parser.add_argument("--problems", nargs="+", metavar="PATTERN",
                        help="only problems whose name matches (shell patterns)")
    parser.add_argument("--max-size", type=int, help="override the preset's largest map side")
    parser.add_argument("--seeds", type=int, help="override the preset's number of seeds "
                        "(runs per planner and problem)")
    parser.add_argument("--time", type=float, help="override the per-run time limit (s)")
    parser.add_argument("--workers", type=int, default=2,
                        help="runs at a time, each in its own worker process (default: 2)")
    parser.add_argument("--out", type=Path, help="output directory "
                        "(default: benchmarks/results/<preset>)")
    add_switches(parser, {
        "--no-ompl": "leave OMPL's planners out",
        "--no-plots": "skip the plots (plots.pdf and report.html's SVG)",
        "--no-generate": "use the problem files as they are (no regeneration)",
        "--report-only": "rebuild the reports from --out/runs.csv without running",
        "--strict": "validate with -strict (a cut corner is a failure)"})
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="run on the Dask cluster of this scheduler (tcp://HOST:PORT), "
                             "--workers runs at a time; default: local worker processes")
    add_switches(parser, {
        "--rerun": "redo the runs already in --out/runs.sqlite (default: keep them)"})
    return parser


def _load_average() -> str:
    try:
        return " ".join(f"{value:.2f}" for value in os.getloadavg())
    except OSError:
        return "unknown"


def _ompl_version() -> str:
    try:
        from importlib.metadata import version
        return version("ompl")
    except Exception:  # noqa: BLE001 (any failure means: not installed)
        return "not installed"


def _git(*args: str) -> str:
    try:
        return subprocess.run(["git", *args], cwd=catalog.ROOT, capture_output=True,
                              text=True, timeout=5).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""


def _git_commit() -> str:
    """The checkout's commit (40 hex digits), and whether tracked files differ from it."""
    commit = _git("rev-parse", "HEAD") or "unknown"
    if commit != "unknown" and _git("status", "--porcelain", "--untracked-files=no"):
        commit += " (with uncommitted changes)"
    return commit


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def script_meta(started: datetime.datetime, workers: int, command: str) -> dict:
    """When, where and how a measuring script's runs were made, before they start
    (``results_page.run_table``'s keys; the caller adds the load after, the wall
    seconds and the runs when they end)."""
    return {"date": started.isoformat(timespec="seconds"), "commit": _git_commit(),
            "host": platform.node(), "cpu": f"{os.cpu_count()} x {_cpu_model()}",
            "workers": str(workers), "load average (1, 5, 15 min) before": _load_average(),
            "load average after": "unknown (interrupted)", "wall seconds": "unknown",
            "python": platform.python_version(), "ompl": "not used", "command": command}


def finish_script_meta(meta: dict, clock: float, runs: int | None = None) -> None:
    """:func:`script_meta`'s figures known at the end: the load after, the wall seconds
    since ``clock`` (``time.monotonic()`` at the start) and, given, the runs made."""
    meta.update({"load average after": _load_average(),
                 "wall seconds": f"{time.monotonic() - clock:.1f}"})
    if runs is not None:
        meta["runs"] = str(runs)


def build_specs(args, planners: list[catalog.PlannerChoice]) -> list[RunSpec]:
    preset = presets.PRESETS[args.preset]
    specs = []
    for plan in preset.plans:
        if args.vehicles and plan.vehicle.value not in args.vehicles:
            continue
        if args.max_size is not None:
            plan = dataclasses.replace(plan, max_size=args.max_size, extra=())
        if args.problems:
            plan = dataclasses.replace(plan, patterns=tuple(args.problems), extra=(),
                                       exclude=())
        seeds = args.seeds if args.seeds is not None else plan.seeds
        limit = args.time if args.time is not None else plan.time_limit
        for problem in presets.select_problems(plan):
            for planner in planners:
                if plan.vehicle not in planner.vehicles or (
                        plan.planners and planner.id not in plan.planners):
                    continue
                if preset.optimize:
                    planner = dataclasses.replace(planner, optimize=True)
                specs.extend(RunSpec(planner, plan.vehicle, problem, seed, limit)
                             for seed in range(1, seeds + 1))
    return specs


def build_family_specs(args, planners: list[catalog.PlannerChoice]) -> list[RunSpec]:
    """A family preset's runs: every (planner, problem) of its tables x seeds."""
    preset = family.FAMILY_PRESETS[args.preset]
    seeds = args.seeds if args.seeds is not None else preset.runs
    limit = args.time if args.time is not None else preset.time_limit
    return [RunSpec(dataclasses.replace(run.planner, optimize=preset.optimize), None,
                    run.problem, seed, limit)
            for run in family.family_runs(preset, planners, tuple(args.problems or ()))
            for seed in range(1, seeds + 1)]


def build_optimal_specs(args, planners: list[catalog.PlannerChoice]) -> list[RunSpec]:
    """An optimal preset's runs: each planner on every problem of the preset it plans for."""
    preset = optimal.OPTIMAL_PRESETS[args.preset]
    return optimal.optimal_specs(
        preset, planners, args.seeds if args.seeds is not None else preset.seeds,
        args.time if args.time is not None else preset.time_limit,
        tuple(args.problems or ()), tuple(args.vehicles or ()))


def _markdown(rows, meta: dict, shortest) -> str:
    """The report of the preset's kind: the family's, the optimal presets' or the grid's."""
    name = meta.get("preset", "")
    if name in family.FAMILY_PRESETS:
        return family_markdown_report(rows, meta, family.FAMILY_PRESETS[name])
    if name in optimal.OPTIMAL_PRESETS:
        from benchmarks.convergence import markdown_report as convergence_report
        return convergence_report(rows, meta, optimal.OPTIMAL_PRESETS[name].checkpoints,
                                  shortest)
    return markdown_report(rows, meta, shortest=shortest,
                           acceptance=name in presets.ACCEPTANCE_PRESETS)


def write_reports(rows, out: Path, meta: dict, plots: bool, yardstick: bool = True) -> Path:
    """runs.csv, report.md, report.html, meta.json, the OMPL logs and (``plots``) the
    plots, in plots.pdf and in report.html, from ``rows``; with ``yardstick`` the point
    vehicle's and arm2's shortest paths (shortest.csv). A family preset's report is the
    family's (no yardstick)."""
    out.mkdir(parents=True, exist_ok=True)
    write_csv(rows, out / "runs.csv")
    shortest = None
    if yardstick and meta.get("preset", "") not in family.FAMILY_PRESETS:  # s at 100x100
        from benchmarks.arm2_shortest_path import arm2_shortest_lengths  # numpy: only here
        from benchmarks.shortest_path import shortest_lengths
        shortest = shortest_lengths(r.problem for r in rows if r.vehicle == "point")
        shortest.update(arm2_shortest_lengths(r.problem for r in rows if r.vehicle == "arm2"))
        (out / "shortest.csv").write_text("problem,shortest_path_length\n" + "".join(
            f"{problem},{length!r}\n" for problem, length in sorted(shortest.items())))
    report = out / "report.md"
    markdown = _markdown(rows, meta, shortest)
    report.write_text(markdown + "\n")
    (out / "meta.json").write_text(json.dumps(meta, indent=2) + "\n")
    header = LogHeader(hostname=meta.get("host", "unknown"), date=meta.get("date", ""),
                       cpu_info=meta.get("cpu", ""),
                       total_seconds=float(meta.get("wall seconds", 0.0) or 0.0))
    write_logs(rows, out / "ompl-logs", header)
    _write_html(rows, out, markdown, plots)
    return report


def _write_html(rows, out: Path, markdown: str, plots: bool) -> None:
    """report.html; with ``plots``, the plots in it and in plots.pdf (else no plots.pdf:
    an earlier run's would not be these rows')."""
    plotted, note = [], "Plots left out (--no-plots, or the run was stopped)."
    (out / "plots.pdf").unlink(missing_ok=True)
    if plots:
        try:
            from benchmarks.plots import render
            plotted = render(rows, out / "plots.pdf")
        except ImportError as error:
            note = f"No plots: {error} (pip install matplotlib)."
            sys.stderr.write(f"benchmarks: no plots ({error}); pip install matplotlib\n")
    (out / "report.html").write_text(html_report(markdown, plotted, note))


def _check_args(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    if args.workers < 1:
        parser.error("--workers must be at least 1")
    if args.seeds is not None and args.seeds < 1:
        parser.error("--seeds must be at least 1")
    if args.time is not None and not args.time > 0:
        parser.error("--time must be positive")
    if args.vehicles and args.preset in family.FAMILY_PRESETS:
        parser.error("--vehicles is for the grid presets (a family problem names its "
                     "system: narrow with --problems)")
    if args.max_size is not None and args.preset not in presets.PRESETS:
        parser.error("--max-size is for the grid presets")
    if args.scheduler and importlib.util.find_spec("distributed") is None:
        parser.error("--scheduler needs Dask's distributed (pip install distributed)")


def _report_only(parser: argparse.ArgumentParser, args: argparse.Namespace, out: Path) -> int:
    csv_path = out / "runs.csv"
    if not csv_path.exists():
        parser.error(f"{csv_path} does not exist")
    meta_path = out / "meta.json"
    meta = json.loads(meta_path.read_text()) if meta_path.exists() else {}
    print(write_reports(read_csv(csv_path), out, meta, not args.no_plots))
    return EXIT_OK


def _regenerate_suite() -> None:
    before = {p: p.read_bytes() for p in generator.suite_files()}
    paths = generator.write_suite()
    changed = [generator.problem_id(p) for p in paths if before.get(p) != p.read_bytes()]
    sys.stderr.write(f"benchmarks: suite of {len(paths)} problems regenerated; "
                     + (f"{len(changed)} files changed: {', '.join(changed[:5])}"
                        if changed else "identical byte for byte") + "\n")


def _choose_planners(parser: argparse.ArgumentParser, args: argparse.Namespace
                     ) -> tuple[list[catalog.PlannerChoice], str]:
    """The planners to run (the family's for a family preset), and a note when OMPL's
    were asked for but are missing."""
    ompl_note = ""
    if not args.no_ompl and not catalog.ompl_installed():
        ompl_note = ("the ompl package is not installed (pip install ompl, or the project's "
                     "[ompl] extra): OMPL's planners were skipped")
        sys.stderr.write(f"benchmarks: note: {ompl_note}\n")
    if args.preset in family.FAMILY_PRESETS:
        planners = catalog.family_planners(not args.no_ompl)
    elif args.preset in optimal.OPTIMAL_PRESETS:
        planners = optimal.optimal_planners(optimal.OPTIMAL_PRESETS[args.preset],
                                            not args.no_ompl)
    else:
        planners = catalog.all_planners(not args.no_ompl)
    if args.planners:
        known = {p.id for p in planners}
        unknown = [name for name in args.planners if name not in known]
        if unknown:
            parser.error(f"unknown planner(s) {', '.join(unknown)}; available: "
                         f"{', '.join(sorted(known))}")
        planners = [p for p in planners if p.id in args.planners]
    return planners, ompl_note


def _run(specs: list[RunSpec], args: argparse.Namespace, out: Path
         ) -> tuple[list, Interrupted | None, int]:
    """Every run not in runs.sqlite already (all with ``--rerun``), each row stored and
    appended to runs.csv as it finishes; the rows in the order of ``specs``, how a
    Ctrl-C or SIGTERM stopped them if one did, and how many rows were kept."""
    # Imported here: the progress bar's library is needed only for a run.
    from benchmarks.progress import Progress
    from benchmarks.store import DB_NAME, RunStore, code_fingerprint, key_of, spec_key

    out.mkdir(parents=True, exist_ok=True)
    with RunStore(out, datetime.datetime.now().astimezone().isoformat(timespec="seconds")
                  ) as store, CsvAppender(out / "runs.csv") as csv_file:
        if args.rerun:
            store.clear()
        if store.made_with(code_fingerprint(args.strict)):
            sys.stderr.write(f"benchmarks: the runs in {out / DB_NAME} were made by other code "
                             "or another --strict: all run again\n")
        stored = store.rows()
        keys = [spec_key(spec) for spec in specs]
        rows = {key: stored[key] for key in keys if key in stored}
        for row in rows.values():
            csv_file.append(row)
        todo = [spec for spec, key in zip(specs, keys) if key not in rows]
        if rows:
            sys.stderr.write(f"benchmarks: {len(rows)} runs kept from {out / DB_NAME} "
                             f"(--rerun redoes them), {len(todo)} to run\n")
        progress = Progress(len(todo))

        def finished(done: int, total: int, row) -> None:
            store.add(row)
            csv_file.append(row)
            progress(done, total, row)
        options = HarnessOptions(workers=args.workers, strict=args.strict,
                                 scheduler=args.scheduler)
        stop, kept = None, len(rows)
        try:
            if todo:
                rows.update((key_of(row), row) for row in run_all(todo, options, finished))
        except Interrupted as interrupted:
            rows.update((key_of(row), row) for row in interrupted.rows)
            stop = interrupted
        finally:
            progress.close()
    return [rows[key] for key in keys if key in rows], stop, kept


def _meta(args: argparse.Namespace, argv: list[str] | None, include_ompl: bool,
          started: datetime.datetime, load_before: str, wall: float, runs: int) -> dict:
    return {
        "preset": args.preset,
        "date": started.isoformat(timespec="seconds"),
        "host": platform.node(),
        "cpu": f"{os.cpu_count()} x {_cpu_model()}",
        "workers": str(args.workers),
        "load average (1, 5, 15 min) before": load_before,
        "load average after": _load_average(),
        "wall seconds": f"{wall:.1f}",
        "runs": str(runs),
        "python": platform.python_version(),
        "ompl": _ompl_version() if include_ompl else "left out (--no-ompl)",
        "commit": _git_commit(),
        "command": "python -m benchmarks " + " ".join(sys.argv[1:] if argv is None else argv),
        **({"planners": " ".join(args.planners)} if args.planners else {}),
    }


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    _check_args(parser, args)
    out = args.out or RESULTS_DIR / args.preset
    if args.report_only:
        return _report_only(parser, args, out)
    is_family = args.preset in family.FAMILY_PRESETS
    if not args.no_generate and not is_family:
        _regenerate_suite()
    planners, ompl_note = _choose_planners(parser, args)
    build = (build_family_specs if is_family else build_optimal_specs
             if args.preset in optimal.OPTIMAL_PRESETS else build_specs)
    specs = build(args, planners)
    if not specs:
        parser.error("no runs selected (check --vehicles, --planners and --problems)")

    started = datetime.datetime.now().astimezone()
    load_before = _load_average()
    sys.stderr.write(f"benchmarks: {len(specs)} runs, {args.workers} workers, "
                     f"planners {', '.join(p.id for p in planners)}; load {load_before}\n")
    began = time.perf_counter()
    try:
        rows, stop, kept = _run(specs, args, out)
    except OSError as error:  # the scheduler cannot be reached
        if not args.scheduler:
            raise
        parser.error(f"--scheduler {args.scheduler}: {error}")
    meta = _meta(args, argv, not args.no_ompl, started, load_before,
                 time.perf_counter() - began, len(rows))
    if kept:
        meta["kept"] = f"{kept} runs kept from runs.sqlite (not rerun)"
    if ompl_note:
        meta["note"] = ompl_note
    if stop is not None:
        (out / "shortest.csv").unlink(missing_ok=True)  # an earlier run's, not these rows'
        meta["interrupted"] = (f"by {signal.Signals(stop.signum).name} after {len(rows)} of "
                               f"{len(specs)} runs: the report covers the finished ones")
        sys.stderr.write(f"benchmarks: {meta['interrupted']}\n")
    print(write_reports(rows, out, meta, plots=stop is None and not args.no_plots,
                        yardstick=stop is None))
    return EXIT_OK if stop is None else 128 + stop.signum


def entry_point() -> None:
    interrupt_on_sigterm()
    try:
        status = main()
    except KeyboardInterrupt:  # outside the runs (generating the suite, writing reports)
        sys.stderr.write("benchmarks: interrupted\n")
        status = 130
    raise SystemExit(status)


if __name__ == "__main__":
    entry_point()
