"""``report.md``: the rubric with our planner's times, the class summary (scores'
distribution, pass rate per problem and mode, the slowest, flaky and failing runs,
similar pairs to look at), then each submission's score, table and failures (each
distinct failure once, with its count). Whatever a submission or a planner wrote is
shown as text (grading.text)."""

from __future__ import annotations

from pathlib import Path

from grading.scores import Results, Scored, key, modes_used, relative_time
from grading.summary import (Failure, class_failures, distribution, failure_label,
                             flaky_items, item_verdict, pass_counts, problems, slowest_runs,
                             standing, submission_failures, where)
from grading.text import link, text

NAMES_SHOWN = 8  # submissions named for one failure in the class summary


def failure_text(what: Failure) -> str:
    """The failure as text: its label, message and detail."""
    found = text(what.label)
    if what.message is not None:
        found += f": {text(what.message)}"
    if what.detail is not None:
        found += f" ({text(what.detail)})"
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


def distribution_section(scores: list[float], full: float, digits: int) -> list[str]:
    """The scores' summary line and a table of ten bins, highest first."""
    found = distribution(scores, full)
    if found is None:
        return ["No submissions.", ""]
    lines = [f"{found.count} submissions; scores out of {full:g}: mean "
             f"{found.mean:.{digits}f}, median {found.median:.{digits}f}, lowest "
             f"{found.lowest:.{digits}f}, highest {found.highest:.{digits}f}.", "",
             "| score | submissions | |", "|---|---|---|"]
    lines += [f"| {low:g} to {high:g} | {count} | {'#' * count} |"
              for low, high, count in found.bins]
    return lines + [""]


def pass_rates(report: Results, graded: list[Scored]) -> list[str]:
    """Valid runs over runs, per problem and mode, over the class (repeats counted)."""
    modes = modes_used(report.items)
    counts = pass_counts(graded)
    lines = ["### Pass rate per problem and mode", "",
             "| problem | " + " | ".join(modes) + " |", "|---|" + "---|" * len(modes)]
    for problem in problems(report.items):
        cells = [f"{valid}/{runs} ({100 * valid / runs:.0f}%)" if runs else "-"
                 for valid, runs in (counts.get((problem, mode), (0, 0)) for mode in modes)]
        lines.append(f"| {text(problem)} | " + " | ".join(cells) + " |")
    return lines + [""]


def slowest(report: Results, graded: list[Scored]) -> list[str]:
    lines = ["### Slowest runs", "",
             "| submission | problem | mode | repeat | time | relative to ours | verdict |",
             "|---|---|---|---|---|---|---|"]
    for row in slowest_runs(graded):
        verdict = "valid" if row["valid"] else text(failure_label(row))
        lines.append(f"| {text(row['submission'])} | {text(row['problem'])} | {row['mode']} | "
                     f"{row['repeat'] + 1} | {seconds(row['wall_time'])} | "
                     f"{times(relative_time(row, report.calibration))} | {verdict} |")
    return lines + [""]


def table_section(intro: list[str], columns: list[str], rows: list[str]) -> list[str]:
    """``intro``, then a table of ``columns`` over ``rows`` (lines already in pipes), or
    "None." where there are no rows."""
    if not rows:
        return intro + ["None.", ""]
    return intro + ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)] + rows + [""]


def flaky_runs(graded: list[Scored]) -> list[str]:
    rows = [f"| {text(name)} | {text(problem)} | {mode} | "
            f"{sum(run['valid'] for run in runs)} of {len(runs)} |"
            for name, (problem, mode), runs in flaky_items(graded)]
    return table_section(["### Flaky: valid on some repeats only", ""],
                         ["submission", "problem", "mode", "valid repeats"], rows)


def class_failures_section(graded: list[Scored]) -> list[str]:
    """Each distinct failure over the class: how many runs, which submissions."""
    rows = []
    for what, count, names in class_failures(graded):
        shown = ", ".join(text(name) for name in names[:NAMES_SHOWN])
        more = len(names) - NAMES_SHOWN
        rows.append(f"| {failure_text(what)} | {count} | "
                    f"{shown}{f' and {more} more' if more > 0 else ''} |")
    return table_section(["### Failing runs", ""], ["failure", "runs", "submissions"], rows)


def similar_pairs(pairs: list) -> list[str]:
    intro = ["### Similar pairs to look at", "",
             "A flag for a person to look at, never a change of score: pairs whose valid "
             "answers are byte-identical on the same problem and mode (the same code with "
             "the same seeds), or whose sources are near-identical (shared token shingles).",
             ""]
    rows = [f"| {text(pair.first)}, {text(pair.second)} | {pair.kind} | "
            f"{text(pair.evidence)} |" for pair in pairs]
    return table_section(intro, ["submissions", "what", "evidence"], rows)


def cell(rows: list[dict], out: Path) -> str:
    """An item's verdict in a submission's table: a failing run links its PDF."""
    label, failing = item_verdict(rows)
    return link(text(label), failing["pdf"], out) if failing and failing.get("pdf") \
        else text(label)


def where_text(rows: list[dict], report: Results) -> str:
    """``simple-0.sw: point, grad; space-0.sw: left (2 of 4)``: the runs of one failure."""
    return "; ".join(f"{text(problem)}: {', '.join(modes)}"
                     for problem, modes in where(rows, report.items))


def submission_failures_section(report: Results, one: Scored) -> list[str]:
    """Each distinct failure of a submission once, with its count and where."""
    return [f"- {failure_text(what)}: {len(rows)} run{'s' if len(rows) > 1 else ''} "
            f"({where_text(rows, report)})" for what, rows in submission_failures(report, one)]


def submission_section(report: Results, one: Scored) -> list[str]:
    """A submission: score, build, sandbox, times, the problem x mode table, failures."""
    facts = standing(report, one)
    build = facts.build
    built = "ok" if build.get("ok") else f"failed: {text(build.get('reason'))}"
    if build.get("log"):
        built += f" ({link('log', build['log'], report.out)})"
    lines = [f"## {text(one.name)}", "",
             f"- Score: **{facts.score}** out of {facts.full} ({facts.counts})",
             f"- Build: {built}",
             f"- Sandbox: {text(build.get('sandbox') or 'unknown')}"]
    if facts.median:
        lines.append(f"- Time: median {times(facts.median[0])} of our planner's "
                     f"over its {facts.median[1]} valid runs")
    modes = modes_used(report.items)
    lines += ["", "| problem | " + " | ".join(modes) + " |", "|---|" + "---|" * len(modes)]
    graded = {key(item) for item in report.items}
    for problem in problems(report.items):
        cells = [cell(one.runs.get((problem, mode), []), report.out)
                 if (problem, mode) in graded else "-" for mode in modes]
        lines.append(f"| {text(problem)} | " + " | ".join(cells) + " |")
    failures = submission_failures_section(report, one)
    if failures:
        lines += ["", "Failures, each once with its count:", ""] + failures
    return lines + [""]


def report_text(report: Results, pairs: list) -> str:
    """The whole of report.md."""
    graded = report.graded
    lines = ["# Grading report", ""] + rubric_section(report)
    lines += ["## Class summary", ""]
    lines += distribution_section([one.score for one in graded],
                                  report.rubric.full_score(report.items), report.rubric.digits)
    lines += pass_rates(report, graded) + slowest(report, graded) + flaky_runs(graded)
    lines += class_failures_section(graded) + similar_pairs(pairs)
    for one in graded:
        lines += submission_section(report, one)
    return "\n".join(lines)
