"""``report.md``: the rubric with our planner's times, the class summary (scores'
distribution, pass rate per problem and mode, the slowest, flaky and failing runs,
similar pairs to look at), then each submission's score, table and failures (each
distinct failure once, with its count). Whatever a submission or a planner wrote is
shown as text (grading.text)."""

from __future__ import annotations

import statistics
from collections import Counter
from pathlib import Path
from typing import Iterable

from grading.scores import Key, Results, Scored, flaky, key, modes_used, relative_time
from grading.text import link, text

SLOWEST = 10     # runs in the class summary's table of the slowest
NAMES_SHOWN = 8  # submissions named for one failure in the class summary


def failure_label(row: dict) -> str:
    """``invalid (parse)``, ``timed out``, ``planner failed``, ``build failed``."""
    if row["verdict"] == "invalid":
        return f"invalid ({row['failed_check']})"
    if row.get("timed_out"):
        return "timed out"
    return row["verdict"]


def failure_text(row: dict) -> str:
    """The failure as text: its label, message and detail."""
    found = text(failure_label(row))
    if row.get("message"):
        found += f": {text(row['message'])}"
    if row.get("detail"):
        found += f" ({text(row['detail'])})"
    return found


def seconds(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f} s"


def times(value: float | None) -> str:
    return "-" if value is None else f"x{value:.2f}"


def rubric_section(report: Results) -> list[str]:
    """The items: points, time limit, repeats, our planner's time on each."""
    full = report.rubric.full_score(report.items)
    lines = ["## Rubric", "",
             f"Scores out of {full:g}: each item's points times the share of its repeats "
             "that were valid.", ""]
    if report.calibration:
        lines += ["Our planner (this checkout's `run.sh -seed 1`, outside the sandbox) was "
                  "timed on each item first; each run's time is also given relative to it "
                  "(x2.00: twice as long as ours), which compares across machines.", ""]
    lines += ["| problem | mode | points | time limit | repeats | our planner |",
              "|---|---|---|---|---|---|"]
    points = report.rubric.points(report.items)
    for item in report.items:
        ours = report.calibration.get(key(item))
        shown = "-" if ours is None else (seconds(ours["wall_time"]) if ours["valid"]
                                          else text(failure_label(ours)))
        lines.append(f"| {text(item.problem)} | {item.mode} | {points[key(item)]:.4g} | "
                     f"{item.timeout:g} s | {item.repeats} | {shown} |")
    return lines + [""]


def distribution(scores: list[float], full: float, digits: int) -> list[str]:
    """The scores' summary line and a table of ten bins, highest first."""
    if not scores:
        return ["No submissions.", ""]
    lines = [f"{len(scores)} submissions; scores out of {full:g}: mean "
             f"{statistics.mean(scores):.{digits}f}, median "
             f"{statistics.median(scores):.{digits}f}, lowest {min(scores):.{digits}f}, "
             f"highest {max(scores):.{digits}f}.", "",
             "| score | submissions | |", "|---|---|---|"]
    bins = Counter(min(int(10 * score / full), 9) if full > 0 else 0 for score in scores)
    for index in range(9, -1, -1):
        low, high = full * index / 10, full * (index + 1) / 10
        lines.append(f"| {low:g} to {high:g} | {bins[index]} | {'#' * bins[index]} |")
    return lines + [""]


def pass_rates(report: Results, graded: list[Scored]) -> list[str]:
    """Valid runs over runs, per problem and mode, over the class (repeats counted)."""
    modes = modes_used(report.items)
    valid: Counter = Counter()
    runs: Counter = Counter()
    for one in graded:
        for k, rows in one.runs.items():
            valid[k] += sum(row["valid"] for row in rows)
            runs[k] += len(rows)
    lines = ["### Pass rate per problem and mode", "",
             "| problem | " + " | ".join(modes) + " |", "|---|" + "---|" * len(modes)]
    for problem in dict.fromkeys(item.problem for item in report.items):
        cells = [f"{valid[problem, mode]}/{runs[problem, mode]} "
                 f"({100 * valid[problem, mode] / runs[problem, mode]:.0f}%)"
                 if runs[problem, mode] else "-" for mode in modes]
        lines.append(f"| {text(problem)} | " + " | ".join(cells) + " |")
    return lines + [""]


def slowest(report: Results, graded: list[Scored]) -> list[str]:
    rows = sorted((row for one in graded for row in one.all_runs()
                   if row.get("wall_time") is not None),
                  key=lambda row: -row["wall_time"])[:SLOWEST]
    lines = ["### Slowest runs", "",
             "| submission | problem | mode | repeat | time | relative to ours | verdict |",
             "|---|---|---|---|---|---|---|"]
    for row in rows:
        verdict = "valid" if row["valid"] else text(failure_label(row))
        lines.append(f"| {text(row['submission'])} | {text(row['problem'])} | {row['mode']} | "
                     f"{row['repeat'] + 1} | {seconds(row['wall_time'])} | "
                     f"{times(relative_time(row, report.calibration))} | {verdict} |")
    return lines + [""]


def flaky_runs(graded: list[Scored]) -> list[str]:
    found = [(one.name, k, rows) for one in graded for k, rows in one.runs.items()
             if flaky(rows)]
    lines = ["### Flaky: valid on some repeats only", ""]
    if not found:
        return lines + ["None.", ""]
    lines += ["| submission | problem | mode | valid repeats |", "|---|---|---|---|"]
    lines += [f"| {text(name)} | {text(problem)} | {mode} | "
              f"{sum(row['valid'] for row in rows)} of {len(rows)} |"
              for name, (problem, mode), rows in found]
    return lines + [""]


def class_failures(graded: list[Scored]) -> list[str]:
    """Each distinct failure over the class: how many runs, which submissions."""
    runs: Counter = Counter()
    names: dict[str, list[str]] = {}
    for one in graded:
        for row in one.all_runs():
            if not row["valid"]:
                what = failure_text(row)
                runs[what] += 1
                names.setdefault(what, [])
                if one.name not in names[what]:
                    names[what].append(one.name)
    lines = ["### Failing runs", ""]
    if not runs:
        return lines + ["None.", ""]
    lines += ["| failure | runs | submissions |", "|---|---|---|"]
    for what, count in runs.most_common():
        shown = ", ".join(text(name) for name in names[what][:NAMES_SHOWN])
        more = len(names[what]) - NAMES_SHOWN
        lines.append(f"| {what} | {count} | {shown}{f' and {more} more' if more > 0 else ''} |")
    return lines + [""]


def similar_pairs(pairs: list) -> list[str]:
    lines = ["### Similar pairs to look at", "",
             "A flag for a person to look at, never a change of score: pairs whose valid "
             "answers are byte-identical on the same problem and mode (the same code with "
             "the same seeds), or whose sources are near-identical (shared token shingles).",
             ""]
    if not pairs:
        return lines + ["None.", ""]
    lines += ["| submissions | what | evidence |", "|---|---|---|"]
    lines += [f"| {text(pair.first)}, {text(pair.second)} | {pair.kind} | "
              f"{text(pair.evidence)} |" for pair in pairs]
    return lines + [""]


def cell(rows: list[dict], out: Path) -> str:
    """An item's verdict in a submission's table: a failing run links its PDF."""
    if not rows:
        return "not run"
    valid = sum(row["valid"] for row in rows)
    if valid == len(rows):
        return "valid" if len(rows) == 1 else f"valid {valid}/{len(rows)}"
    failing = next(row for row in rows if not row["valid"])
    label = (f"flaky: {valid}/{len(rows)} valid" if valid else text(failure_label(failing))
             + (f" 0/{len(rows)}" if len(rows) > 1 else ""))
    return link(label, failing["pdf"], out) if failing.get("pdf") else label


def where(rows: Iterable[dict], order: list[Key], repeats: dict[Key, int]) -> str:
    """``simple-0.sw: point, grad; space-0.sw: left (2 of 4)``: the runs of one failure."""
    counts = Counter(key(row) for row in rows)
    by_problem: dict[str, list[str]] = {}
    for problem, mode in (k for k in order if k in counts):
        shown = mode if repeats[problem, mode] == 1 else \
            f"{mode} ({counts[problem, mode]} of {repeats[problem, mode]})"
        by_problem.setdefault(problem, []).append(shown)
    return "; ".join(f"{text(problem)}: {', '.join(modes)}"
                     for problem, modes in by_problem.items())


def submission_failures(report: Results, one: Scored) -> list[str]:
    """Each distinct failure of a submission once, with its count and where."""
    order = [key(item) for item in report.items]
    repeats = {key(item): item.repeats for item in report.items}
    groups: dict[str, list[dict]] = {}
    for k in order:
        for row in one.runs.get(k, []):
            if not row["valid"]:
                groups.setdefault(failure_text(row), []).append(row)
    return [f"- {what}: {len(rows)} run{'s' if len(rows) > 1 else ''} "
            f"({where(rows, order, repeats)})" for what, rows in groups.items()]


def submission_section(report: Results, one: Scored) -> list[str]:
    """A submission: score, build, sandbox, times, the problem x mode table, failures."""
    build = report.builds.get(one.name, {})
    runs = one.all_runs()
    flakes = sum(flaky(rows) for rows in one.runs.values())
    built = "ok" if build.get("ok") else f"failed: {text(build.get('reason'))}"
    if build.get("log"):
        built += f" ({link('log', build['log'], report.out)})"
    lines = [f"## {text(one.name)}", "",
             f"- Score: **{one.score:.{report.rubric.digits}f}** out of "
             f"{report.rubric.full_score(report.items):g} "
             f"({sum(row['valid'] for row in runs)} of {len(runs)} runs valid"
             + (f"; {flakes} flaky" if flakes else "") + ")",
             f"- Build: {built}",
             f"- Sandbox: {text(build.get('sandbox') or 'unknown')}"]
    ratios = [r for r in (relative_time(row, report.calibration) for row in runs
                          if row["valid"]) if r is not None]
    if ratios:
        lines.append(f"- Time: median {times(statistics.median(ratios))} of our planner's "
                     f"over its {len(ratios)} valid runs")
    modes = modes_used(report.items)
    lines += ["", "| problem | " + " | ".join(modes) + " |", "|---|" + "---|" * len(modes)]
    graded = {key(item) for item in report.items}
    for problem in dict.fromkeys(item.problem for item in report.items):
        cells = [cell(one.runs.get((problem, mode), []), report.out)
                 if (problem, mode) in graded else "-" for mode in modes]
        lines.append(f"| {text(problem)} | " + " | ".join(cells) + " |")
    failures = submission_failures(report, one)
    if failures:
        lines += ["", "Failures, each once with its count:", ""] + failures
    return lines + [""]


def report_text(report: Results, pairs: list) -> str:
    """The whole of report.md."""
    graded = report.graded
    lines = ["# Grading report", ""] + rubric_section(report)
    lines += ["## Class summary", ""]
    lines += distribution([one.score for one in graded],
                          report.rubric.full_score(report.items), report.rubric.digits)
    lines += pass_rates(report, graded) + slowest(report, graded) + flaky_runs(graded)
    lines += class_failures(graded) + similar_pairs(pairs)
    for one in graded:
        lines += submission_section(report, one)
    return "\n".join(lines)
