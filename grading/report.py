"""What a grading run leaves for people: ``gradebook.csv`` (one row per
submission), ``report.md`` (the verdicts, links to failing runs' PDFs) and the
summary table printed at the end."""

from __future__ import annotations

import csv
import html
import os
from collections import defaultdict
from pathlib import Path
from urllib.parse import quote

from grading.config import GradeConfig

GRADEBOOK = "gradebook.csv"
REPORT = "report.md"


def gradebook_rows(config: GradeConfig, runs: list[dict]) -> list[dict]:
    """One row per submission: ``submission, valid, runs, valid_<mode>..., score``."""
    valid: dict[str, dict[str, int]] = defaultdict(lambda: defaultdict(int))
    total: dict[str, dict[str, int]] = defaultdict(lambda: defaultdict(int))
    for run in runs:
        total[run["submission"]][run["mode"]] += 1
        valid[run["submission"]][run["mode"]] += run["valid"]
    rows = []
    for name in sorted(total):
        row = {"submission": name, "valid": sum(valid[name].values()),
               "runs": sum(total[name].values())}
        row.update({f"valid_{mode}": valid[name][mode] for mode in config.modes})
        row["score"] = config.score.score(valid[name], total[name])
        rows.append(row)
    return rows


def write_gradebook(config: GradeConfig, rows: list[dict]) -> Path:
    path = config.out / GRADEBOOK
    columns = ["submission", "valid", "runs", *(f"valid_{m}" for m in config.modes), "score"]
    with open(path, "w", newline="") as out:
        writer = csv.DictWriter(out, columns, lineterminator="\n")
        writer.writeheader()
        writer.writerows({**row, "submission": spreadsheet_text(row["submission"])}
                         for row in rows)
    return path


def spreadsheet_text(value: str) -> str:
    """A submission's name as a spreadsheet cell that stays text: a leading ``=``,
    ``+``, ``-``, ``@``, tab or carriage return would start a formula, so it gets a
    ``'`` before it (as OWASP advises for CSV)."""
    return "'" + value if value[:1] in ("=", "+", "-", "@", "\t", "\r") else value


def terminal_text(value) -> str:
    """What a submission named, for a terminal: control characters (escape
    sequences among them) shown as ``\\xNN``, not sent."""
    return "".join(char if char.isprintable() else f"\\x{ord(char):02x}"
                   for char in str(value))


_MARKDOWN = str.maketrans({char: "\\" + char for char in "\\`*_[]|~"})


def text(value) -> str:
    """What a submission, a planner or a file name gave, shown as text in Markdown: one
    line, HTML's ``& < >`` as entities, Markdown's emphasis, code, link and table marks
    escaped."""
    return html.escape(" ".join(str(value).split()), quote=False).translate(_MARKDOWN)


def _link(label: str, path: str, out: Path) -> str:
    return f"[{label}]({quote(os.path.relpath(path, out))})"


def _cell(run: dict, out: Path) -> str:
    """A run's verdict in a table cell: a link to the PDF when it failed."""
    if run["valid"]:
        return "valid"
    label = text(run["verdict"])
    if run["verdict"] == "invalid":
        label += f" ({text(run['failed_check'])})"
    elif run.get("timed_out"):
        label = "timed out"
    return _link(label, run["pdf"], out) if run.get("pdf") else label


def write_report(config: GradeConfig, runs: list[dict], builds: dict[str, dict]) -> Path:
    """``report.md``: per submission, its build and a problem x mode table."""
    by_submission: dict[str, dict[tuple[str, str], dict]] = defaultdict(dict)
    for run in runs:
        by_submission[run["submission"]][run["problem"], run["mode"]] = run
    lines = ["# Grading report", "",
             f"Modes: {', '.join(config.modes)}; timeout {config.timeout:g} s per run.", ""]
    for name, table in sorted(by_submission.items()):
        build = builds.get(name, {})
        lines += [f"## {text(name)}", "",
                  "Build: " + ("ok" if build.get("ok") else f"failed: {text(build.get('reason'))}")
                  + (f" ({_link('log', build['log'], config.out)})" if build.get("log") else ""),
                  f"Sandbox: {text(build.get('sandbox') or 'unknown')}", "",
                  "| problem | " + " | ".join(config.modes) + " |",
                  "|---|" + "---|" * len(config.modes)]
        for problem in sorted({problem for problem, _ in table}):
            cells = [_cell(table[problem, mode], config.out) if (problem, mode) in table
                     else "not run" for mode in config.modes]
            lines.append(f"| {text(problem)} | " + " | ".join(cells) + " |")
        failures = [run for run in table.values() if not run["valid"] and run["message"]]
        lines += [""] + [f"- {text(run['problem'])} {run['mode']}: {text(run['message'])}"
                         + (f" ({text(run['detail'])})" if run.get("detail") else "")
                         for run in sorted(failures, key=lambda r: (r["problem"], r["mode"]))]
        lines.append("")
    path = config.out / REPORT
    path.write_text("\n".join(lines))
    return path


def summary_table(rows: list[dict]) -> str:
    """The gradebook as an aligned text table, for the terminal."""
    if not rows:
        return "no submissions\n"
    columns = list(rows[0])
    cells = [columns] + [[terminal_text(row[c]) for c in columns] for row in rows]
    widths = [max(len(line[i]) for line in cells) for i in range(len(columns))]
    return "".join("  ".join(cell.ljust(width) if i == 0 else cell.rjust(width)
                             for i, (cell, width) in enumerate(zip(line, widths))).rstrip()
                   + "\n" for line in cells)
