"""A preset's results page, ``docs/results/<preset>.md``, from a results folder: when, at
which commit and on what machine the run was made (its ``meta.json``), then the tables of
its ``report.md``. Older runs are the page's git history.

    python -m benchmarks.results_page benchmarks/results/quick > docs/results/quick.md

A folder named otherwise than its preset (a narrowed run's ``--out``) is its own page,
``docs/results/<folder name>.md``. The page goes to stdout; a folder without ``report.md`` and ``meta.json`` is one line on
stderr and exit status 2.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from benchmarks.catalog import ROOT
from cli_common import OneLineErrorParser

RUN_KEYS = ("preset", "date", "commit", "host", "cpu", "workers",
            "load average (1, 5, 15 min) before", "load average after", "wall seconds",
            "runs", "python", "ompl", "command")
"""meta.json's keys the page's first table shows; any other key (a note, kept runs, an
interruption) follows them."""


def _shown(path: Path) -> str:
    """The folder as a command run from the checkout's root would name it."""
    try:
        return str(path.resolve().relative_to(ROOT))
    except ValueError:
        return str(path)


def run_table(meta: dict) -> list[str]:
    """When, where and how the run was made, as a two-column Markdown table."""
    def get(key: str) -> str:
        return str(meta.get(key, "unknown"))
    lines = ["| run | |", "|---|---|",
             f"| date | {get('date')} |",
             f"| commit | {get('commit')} |",
             f"| machine | {get('cpu')} (cores x CPU model), host {get('host')} |",
             f"| load average (1, 5, 15 min) | {get('load average (1, 5, 15 min) before')} "
             f"before, {get('load average after')} after |",
             f"| Python, OMPL | {get('python')}, {get('ompl')} |",
             f"| runs | {get('runs')} in {get('wall seconds')} s, {get('workers')} at a time |",
             f"| command | `{get('command')}` |"]
    lines += [f"| {key} | {value} |" for key, value in meta.items() if key not in RUN_KEYS]
    return lines


def report_body(markdown: str) -> list[str]:
    """report.md without its title and the list of run facts under it."""
    lines = markdown.rstrip("\n").splitlines()[1:]
    while lines and (not lines[0].strip() or lines[0].startswith("- ")):
        lines.pop(0)
    return lines


def results_page(folder: Path) -> str:
    meta = json.loads((folder / "meta.json").read_text())
    if not isinstance(meta, dict):
        raise ValueError("meta.json does not hold an object")
    preset = meta.get("preset", folder.name)
    shown = _shown(folder)
    # A run narrowed into its own folder (--out) has its own page, named as the folder.
    page = folder.name
    title, run = ((f"the `{preset}` preset", f"`python -m benchmarks --preset {preset}`")
                  if page == preset else
                  (f"`{page}`, a run of the `{preset}` preset", "the command below"))
    lines = [f"# Results: {title}", "",
             f"The tables of the last run of {run} "
             f"written here, by `python -m benchmarks.results_page {shown} > "
             f"docs/results/{page}.md`; earlier runs are this page's git history. "
             f"The plots are in `{shown}/report.html` after a run.", ""]
    lines += run_table(meta) + [""] + report_body((folder / "report.md").read_text())
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = OneLineErrorParser(prog="benchmarks.results_page",
                                description="Write a preset's results page (Markdown, on "
                                            "stdout) from a results folder.")
    parser.add_argument("folder", type=Path,
                        help="a results folder, e.g. benchmarks/results/quick")
    args = parser.parse_args(argv)
    for name in ("report.md", "meta.json"):
        if not (args.folder / name).is_file():
            parser.error(f"{args.folder / name} does not exist (run the preset first)")
    try:
        page = results_page(args.folder)
    except (OSError, ValueError) as error:  # unreadable, or meta.json is not JSON
        parser.error(f"{args.folder}: {error}")
    sys.stdout.write(page)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
