"""What a grading run leaves for people: ``gradebook.csv`` (one row per
submission), ``report.md`` (grading.markdown) and the summary table printed at the
end."""

from __future__ import annotations

import csv
from pathlib import Path

from grading.markdown import report_text
from grading.scores import Results, modes_used
from grading.text import spreadsheet_text, terminal_text

GRADEBOOK = "gradebook.csv"
REPORT = "report.md"


def gradebook_rows(results: Results) -> list[dict]:
    """One row per submission: ``submission, valid, runs, valid_<mode>..., score`` (a
    mode's column when the rubric has it; ``kinoplan``: the .kp problems)."""
    modes = modes_used(results.items)
    rows = []
    for one in results.graded:
        runs = one.all_runs()
        row = {"submission": one.name, "valid": sum(run["valid"] for run in runs),
               "runs": len(runs)}
        row.update({f"valid_{mode}": sum(run["valid"] for run in runs if run["mode"] == mode)
                    for mode in modes})
        row["score"] = one.score
        rows.append(row)
    return rows


def write_gradebook(out: Path, rows: list[dict]) -> Path:
    """``gradebook.csv`` in ``out``; names that would start a formula stay text."""
    path = out / GRADEBOOK
    columns = list(rows[0]) if rows else ["submission", "valid", "runs", "score"]
    with open(path, "w", newline="") as book:
        writer = csv.DictWriter(book, columns, lineterminator="\n")
        writer.writeheader()
        writer.writerows({**row, "submission": spreadsheet_text(row["submission"])}
                         for row in rows)
    return path


def write_report(results: Results, pairs: list) -> Path:
    """``report.md`` in the results' folder."""
    path = results.out / REPORT
    path.write_text(report_text(results, pairs))
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
