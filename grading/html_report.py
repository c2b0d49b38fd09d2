"""``report.html`` and a page per submission (``html/SUBMISSION/index.html``), for the
browser, offline: the class summary (the scores' histogram as inline SVG, the pass rate
per problem and mode as a heat-map, the slowest, flaky and failing runs, similar pairs),
a sortable table of the submissions linking their pages, and on each page the
submission's score, its problem x mode table, each distinct failure once, every run, and
each failing run's reason with its view (the validator's browser view, drawn by the
worker beside the page: ``html/SUBMISSION/STEM.html``) in a frame opened on demand.

The same facts as report.md (grading.summary computes them). Each file is whole: the
script and style (grading/page/) are inline, and a Content-Security-Policy allows only
them (by their hashes), frames of local files (the views) and no connection. Whatever a
submission or a planner wrote (names, messages, details, build reasons, evidence) is
escaped as text, in elements and attributes alike; paths are percent-encoded.
"""

from __future__ import annotations

import base64
import hashlib
import html
from pathlib import Path
from typing import Iterable

from grading.report import gradebook_rows
from grading.scores import Results, Scored, key, modes_used, relative_time
from grading.summary import (Distribution, Failure, class_failures, distribution,
                             failure, failure_label, flaky_items, item_verdict, median_time,
                             pass_counts, problems, slowest_runs, standing,
                             submission_failures, where)
from grading.text import relative_url
from validator.render_file import write_atomically

REPORT_HTML = "report.html"
PAGES = "html"          # the submissions' pages and their runs' views, in --out
PAGE = "index.html"     # a submission's page in its folder (a run's view is PROBLEM-MODE...)
_ASSETS = Path(__file__).resolve().parent / "page"


def esc(value) -> str:
    """Text as HTML: ``& < > " '`` as entities (in an element or a quoted attribute)."""
    return html.escape(str(value), quote=True)


def _source(text: str) -> str:
    return "'sha256-" + base64.b64encode(hashlib.sha256(text.encode()).digest()).decode() + "'"


def page_html(title: str, body: str, frames: bool = False) -> str:
    """A whole page: ``body`` (HTML), the inline style and script, the policy."""
    style = (_ASSETS / "report.css").read_text(encoding="utf-8")
    script = (_ASSETS / "report.js").read_text(encoding="utf-8")
    frame = "'self'" if frames else "'none'"  # the runs' views: files beside the page
    policy = (f"default-src 'none'; script-src {_source(script)}; style-src {_source(style)}; "
              f"img-src data:; frame-src {frame}")
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
            f"<meta http-equiv=\"Content-Security-Policy\" content=\"{policy}\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            f"<title>{esc(title)}</title>\n<style>{style}</style>\n</head>\n<body>\n{body}\n"
            f"<script>{script}</script>\n</body></html>\n")


def link(label: str, path: str | None, base: Path) -> str:
    """``<a>`` to ``path`` relative to the folder ``base`` (``label`` already HTML); the
    label alone without a path."""
    if not path:
        return label
    return f"<a href=\"{esc(relative_url(path, base))}\">{label}</a>"


def number(value: float | None, shown: str) -> str:
    """A numeric cell: its value for sorting (empty when missing), ``shown`` as text."""
    data = "" if value is None else f"{value:.6g}"
    return f"<td class=\"n\" data-v=\"{data}\">{esc(shown)}</td>"


def table(headers: Iterable[str], rows: Iterable[Iterable[str]], numeric: set[int] = frozenset(),
          sortable: bool = False) -> str:
    """A table: ``headers`` as text, each row's cells already HTML (``<td>``...); a sortable
    one's headers are buttons, ``numeric`` the columns sorted as numbers."""
    heads = []
    for index, name in enumerate(headers):
        kind = " data-kind=\"num\"" if index in numeric else ""
        label = f"<button type=\"button\">{esc(name)}</button>" if sortable else esc(name)
        heads.append(f"<th{kind}>{label}</th>")
    body = "\n".join("<tr>" + "".join(row) + "</tr>" for row in rows)
    opening = "<table class=\"sortable\">" if sortable else "<table>"
    return (f"{opening}<thead><tr>{''.join(heads)}</tr></thead>\n<tbody>\n{body}\n"
            "</tbody></table>")


def td(content: str, css: str = "") -> str:
    """A cell of HTML ``content``."""
    return f"<td class=\"{css}\">{content}</td>" if css else f"<td>{content}</td>"


def seconds(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f} s"


def times(value: float | None) -> str:
    return "-" if value is None else f"x{value:.2f}"


def failure_html(what: Failure) -> str:
    """A failure's label, message and detail as text."""
    found = f"<b>{esc(what.label)}</b>"
    if what.message is not None:
        found += f": {esc(what.message)}"
    if what.detail is not None:
        found += f" ({esc(what.detail)})"
    return found


def verdict_class(row: dict) -> str:
    return "valid" if row["valid"] else "failed"


# ----- the class's page ------------------------------------------------------------------

def histogram(found: Distribution, full: float) -> str:
    """The scores' ten bins as bars (inline SVG), the lowest bin on the left."""
    width, height, left, bottom, top = 640, 220, 30, 36, 18
    bins = list(reversed(found.bins))
    step = (width - left - 10) / len(bins)
    tallest = max(count for _, _, count in bins) or 1
    scale = (height - bottom - top) / tallest
    parts = [f"<svg class=\"histogram\" viewBox=\"0 0 {width} {height}\" role=\"img\" "
             f"aria-label=\"the scores' distribution, out of {full:g}\">",
             f"<line x1=\"{left}\" y1=\"{height - bottom}\" x2=\"{width - 10}\" "
             f"y2=\"{height - bottom}\"/>"]
    for index, (low, high, count) in enumerate(bins):
        x, tall = left + index * step, count * scale
        parts += [f"<rect x=\"{x + 3:.1f}\" y=\"{height - bottom - tall:.1f}\" "
                  f"width=\"{step - 6:.1f}\" height=\"{tall:.1f}\"><title>{low:g} to {high:g}: "
                  f"{count} submissions</title></rect>",
                  f"<text x=\"{x + step / 2:.1f}\" y=\"{height - bottom - tall - 4:.1f}\">"
                  f"{count}</text>",
                  f"<text x=\"{x + step / 2:.1f}\" y=\"{height - bottom + 16}\">{low:g}-{high:g}"
                  "</text>"]
    return "\n".join(parts) + "\n</svg>"


def distribution_section(report: Results) -> str:
    full = report.rubric.full_score(report.items)
    found = distribution([one.score for one in report.graded], full)
    if found is None:
        return "<p>No submissions.</p>"
    digits = report.rubric.digits
    return (f"<p>{found.count} submissions; scores out of {full:g}: mean "
            f"{found.mean:.{digits}f}, median {found.median:.{digits}f}, lowest "
            f"{found.lowest:.{digits}f}, highest {found.highest:.{digits}f}.</p>\n"
            + histogram(found, full))


def pass_rate_section(report: Results) -> str:
    """Valid runs over runs per problem and mode, each cell coloured by its rate."""
    modes = modes_used(report.items)
    counts = pass_counts(report.graded)
    rows = []
    for problem in problems(report.items):
        cells = [td(esc(problem))]
        for mode in modes:
            valid, runs = counts.get((problem, mode), (0, 0))
            cells.append(td(f"{valid}/{runs} ({100 * valid / runs:.0f}%)",
                            f"rate rate-{int(10 * valid / runs)}") if runs else td("-", "rate"))
        rows.append(cells)
    return "<h3>Pass rate per problem and mode</h3>\n" + table(["problem", *modes], rows)


def submissions_table(report: Results) -> str:
    """One row per submission (gradebook.csv's numbers, flaky items, build, median time),
    its name linking its page; sortable."""
    modes = modes_used(report.items)
    headers = ["submission", "score", "valid runs", "runs", *(f"valid {m}" for m in modes),
               "flaky items", "build", "median time, ours = x1"]
    rows = []
    for one, book in zip(report.graded, gradebook_rows(report)):
        build = report.builds.get(one.name, {})
        median = median_time(report, one)
        flakes = len(flaky_items([one]))
        rows.append([f"<td data-v=\"{esc(one.name)}\">"
                     + link(esc(one.name), submission_page(report.out, one.name), report.out)
                     + "</td>", number(one.score, f"{one.score:.{report.rubric.digits}f}"),
                     number(book["valid"], str(book["valid"])), number(book["runs"],
                                                                        str(book["runs"])),
                     *(number(book[f"valid_{m}"], str(book[f"valid_{m}"])) for m in modes),
                     number(flakes, str(flakes)),
                     td("ok", "valid") if build.get("ok") else td("failed", "failed"),
                     number(median and median[0], times(median and median[0]))])
    numeric = set(range(1, len(headers))) - {len(headers) - 2}
    return table(headers, rows, numeric, sortable=True)


def slowest_section(report: Results) -> str:
    rows = [[td(esc(row["submission"])), td(esc(row["problem"])), td(esc(row["mode"])),
             number(row["repeat"] + 1, str(row["repeat"] + 1)),
             number(row["wall_time"], seconds(row["wall_time"])),
             number(relative_time(row, report.calibration),
                    times(relative_time(row, report.calibration))),
             td("valid" if row["valid"] else esc(failure_label(row)), verdict_class(row))]
            for row in slowest_runs(report.graded)]
    return "<h3>Slowest runs</h3>\n" + table(
        ["submission", "problem", "mode", "repeat", "time", "relative to ours", "verdict"], rows)


def flaky_section(report: Results) -> str:
    found = flaky_items(report.graded)
    if not found:
        return "<h3>Flaky: valid on some repeats only</h3>\n<p>None.</p>"
    rows = [[td(esc(name)), td(esc(problem)), td(esc(mode)),
             td(f"{sum(row['valid'] for row in rows)} of {len(rows)}")]
            for name, (problem, mode), rows in found]
    return "<h3>Flaky: valid on some repeats only</h3>\n" + table(
        ["submission", "problem", "mode", "valid repeats"], rows)


def failures_section(report: Results) -> str:
    """Each distinct failure over the class: its runs, the submissions (each linked)."""
    found = class_failures(report.graded)
    if not found:
        return "<h3>Failing runs</h3>\n<p>None.</p>"
    rows = [[td(failure_html(what)), number(count, str(count)),
             td(", ".join(link(esc(name), submission_page(report.out, name), report.out)
                          for name in names))] for what, count, names in found]
    return "<h3>Failing runs</h3>\n" + table(["failure", "runs", "submissions"], rows)


def pairs_section(pairs: list) -> str:
    text = ("<h3>Similar pairs to look at</h3>\n<p class=\"note\">A flag for a person to look "
            "at, never a change of score: pairs whose valid answers are byte-identical on the "
            "same problem and mode (the same code with the same seeds), or whose sources are "
            "near-identical (shared token shingles).</p>\n")
    if not pairs:
        return text + "<p>None.</p>"
    return text + table(["submissions", "what", "evidence"], [
        [td(f"{esc(pair.first)}, {esc(pair.second)}"), td(esc(pair.kind)), td(esc(pair.evidence))]
        for pair in pairs])


def rubric_section(report: Results) -> str:
    """The items: points, time limit, repeats, our planner's time on each."""
    points = report.rubric.points(report.items)
    rows = []
    for item in report.items:
        ours = report.calibration.get(key(item))
        shown = "-" if ours is None else (seconds(ours["wall_time"]) if ours["valid"]
                                          else failure_label(ours))
        rows.append([td(esc(item.problem)), td(esc(item.mode)),
                     number(points[key(item)], f"{points[key(item)]:.4g}"),
                     td(f"{item.timeout:g} s"), number(item.repeats, str(item.repeats)),
                     td(esc(shown))])
    return (f"<h2 id=\"rubric\">Rubric</h2>\n<p class=\"note\">Scores out of "
            f"{report.rubric.full_score(report.items):g}: each item's points times the share "
            "of its repeats that were valid. Our planner: this checkout's <code>run.sh -seed "
            "1</code>, outside the sandbox; a run's time relative to it (x2.00: twice as long "
            "as ours) compares across machines.</p>\n"
            + table(["problem", "mode", "points", "time limit", "repeats", "our planner"], rows))


def class_html(report: Results, pairs: list) -> str:
    """The whole of report.html."""
    body = ["<h1>Grading report</h1>",
            "<nav><a href=\"#summary\">Class summary</a><a href=\"#submissions\">Submissions</a>"
            "<a href=\"#runs\">Slowest, flaky and failing runs</a><a href=\"#rubric\">Rubric</a>"
            "</nav>",
            "<h2 id=\"summary\">Class summary</h2>", distribution_section(report),
            pass_rate_section(report),
            "<h2 id=\"submissions\">Submissions</h2>",
            "<p class=\"note\">Click a column's name to sort by it (again: the other way); "
            "a name opens its page: every run, each failure's reason and view.</p>",
            submissions_table(report),
            "<h2 id=\"runs\">Runs</h2>", failures_section(report), flaky_section(report),
            slowest_section(report), pairs_section(pairs), rubric_section(report)]
    return page_html("rrt-grade: grading report", "\n".join(body))


# ----- a submission's page ---------------------------------------------------------------

def submission_page(out: Path, name: str) -> Path:
    """``html/NAME/index.html`` in ``out``: beside the submission's runs' views."""
    return out / PAGES / name / PAGE


def facts(report: Results, one: Scored, here: Path) -> str:
    """Score, build (its log), sandbox, median time."""
    found = standing(report, one)
    build = found.build
    built = "ok" if build.get("ok") else f"failed: {esc(build.get('reason'))}"
    if build.get("log"):
        built += f" ({link('log', build['log'], here)})"
    items = [f"Score: <b>{found.score}</b> out of {found.full} ({found.counts})",
             f"Build: {built}", f"Sandbox: {esc(build.get('sandbox') or 'unknown')}"]
    if found.median:
        items.append(f"Time: median {times(found.median[0])} of our planner's over its "
                     f"{found.median[1]} valid runs")
    return "<ul class=\"facts\">" + "".join(f"<li>{item}</li>" for item in items) + "</ul>"


def run_ids(report: Results, one: Scored) -> dict[int, str]:
    """Each failing run's anchor on the page (``run-1``, ...), by the row's id()."""
    failing = [row for item in report.items for row in one.runs.get(key(item), [])
               if not row["valid"]]
    return {id(row): f"run-{number}" for number, row in enumerate(failing, 1)}


def verdicts_table(report: Results, one: Scored, ids: dict[int, str]) -> str:
    """Problem x mode: each item's verdict, linking its first failing run's section."""
    modes = modes_used(report.items)
    graded = {key(item) for item in report.items}
    rows = []
    for problem in problems(report.items):
        cells = [td(esc(problem))]
        for mode in modes:
            if (problem, mode) not in graded:
                cells.append(td("-"))
                continue
            label, failing = item_verdict(one.runs.get((problem, mode), []))
            shown = esc(label) if failing is None else \
                f"<a href=\"#{ids[id(failing)]}\">{esc(label)}</a>"
            cells.append(td(shown, "failed" if failing else "valid"))
        rows.append(cells)
    return table(["problem", *modes], rows)


def failures_list(report: Results, one: Scored) -> str:
    found = submission_failures(report, one)
    if not found:
        return ""
    items = [f"<li>{failure_html(what)}: {len(rows)} run{'s' if len(rows) > 1 else ''} ("
             + "; ".join(f"{esc(problem)}: {esc(', '.join(modes))}"
                         for problem, modes in where(rows, report.items)) + ")</li>"
             for what, rows in found]
    return "<h2>Failures, each once with its count</h2>\n<ul>" + "".join(items) + "</ul>"


def runs_table(report: Results, one: Scored, ids: dict[int, str], here: Path) -> str:
    """Every run: verdict, times, answer's size, its stderr, PDF and view."""
    rows = []
    for item in report.items:
        for row in one.runs.get(key(item), []):
            verdict = "valid" if row["valid"] else \
                f"<a href=\"#{ids[id(row)]}\">{esc(failure_label(row))}</a>"
            ratio = relative_time(row, report.calibration)
            files = [link(name, row.get(column), here) for name, column in
                     (("stderr", "log"), ("PDF", "pdf"), ("view", "view")) if row.get(column)]
            rows.append([td(esc(row["problem"])), td(esc(row["mode"])),
                         number(row["repeat"] + 1, str(row["repeat"] + 1)),
                         td(verdict, verdict_class(row)),
                         number(row.get("wall_time"), seconds(row.get("wall_time"))),
                         number(ratio, times(ratio)),
                         number(row.get("path_length"), _maybe(row.get("path_length"), ".3f")),
                         number(row.get("tree_size"), _maybe(row.get("tree_size"), "d")),
                         td(" ".join(files))])
    return table(["problem", "mode", "repeat", "verdict", "time", "relative to ours",
                  "path length", "tree edges", "files"], rows, {2, 4, 5, 6, 7}, sortable=True)


def _maybe(value, spec: str) -> str:
    return "-" if value is None else format(value, spec)


def failing_runs(report: Results, one: Scored, ids: dict[int, str], here: Path) -> str:
    """Each failing run: its reason, its files, its view in a frame opened on demand."""
    parts = []
    for item in report.items:
        for row in (r for r in one.runs.get(key(item), []) if not r["valid"]):
            title = f"{row['problem']} {row['mode']}" + (
                f" (repeat {row['repeat'] + 1})" if item.repeats > 1 else "")
            parts.append(f"<section id=\"{ids[id(row)]}\">\n<h3>{esc(title)}</h3>\n"
                         f"<p class=\"reason\">{failure_html(failure(row))}</p>")
            files = [link(name, row.get(column), here) for name, column in
                     (("the view alone", "view"), ("PDF", "pdf"), ("stderr", "log"))
                     if row.get(column)]
            if files:
                parts.append("<p>" + " | ".join(files) + "</p>")
            if row.get("view"):
                parts.append(f"<details class=\"view\"><summary>Show the view</summary>"
                             f"<iframe data-src=\"{esc(relative_url(row['view'], here))}\" "
                             f"title=\"the view of {esc(title)}\"></iframe></details>")
            parts.append("</section>")
    return "<h2>Failing runs</h2>\n" + "\n".join(parts) if parts else ""


def submission_html(report: Results, one: Scored) -> str:
    """The whole of a submission's page."""
    here = submission_page(report.out, one.name).parent
    ids = run_ids(report, one)
    body = [f"<p>{link('the class report', str(report.out / REPORT_HTML), here)}</p>",
            f"<h1>{esc(one.name)}</h1>", facts(report, one, here),
            "<h2>Problem x mode</h2>", verdicts_table(report, one, ids),
            failures_list(report, one), "<h2>Runs</h2>",
            "<p class=\"note\">A failing run has its PDF and its view (the validator's, "
            "drawn when it ran); a valid run has neither.</p>",
            runs_table(report, one, ids, here), failing_runs(report, one, ids, here)]
    return page_html(f"rrt-grade: {one.name}", "\n".join(body), frames=True)


def write_html_report(report: Results, pairs: list) -> Path:
    """``report.html`` and each submission's page; the path of report.html."""
    for one in report.graded:
        page = submission_page(report.out, one.name)
        page.parent.mkdir(parents=True, exist_ok=True)
        _write(page, submission_html(report, one))
    path = report.out / REPORT_HTML
    _write(path, class_html(report, pairs))
    return path


def _write(path: Path, text: str) -> None:
    data = text.encode("utf-8", errors="replace")
    write_atomically(str(path), lambda out: out.write(data))
