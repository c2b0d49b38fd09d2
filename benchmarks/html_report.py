"""report.html: the Markdown report (its tables, targets and notes) and the run's plots as
inline SVG, in one self-contained page: the style is inline and nothing is fetched.

The Markdown read is the subset ``report.py`` and ``family_report.py`` write: ``#``
headings, ``-`` lists, pipe tables with an alignment rule, paragraphs, ``**bold**`` and
``code`` spans.
"""

from __future__ import annotations

import html
import re
from typing import Iterable, Sequence

from benchmarks.plots import Plot, vehicle_title

STYLE = """
body { font-family: system-ui, sans-serif; margin: 1.5em auto; max-width: 90em;
       padding: 0 1em; color: #222; line-height: 1.4; }
h1 { font-size: 1.5em; } h2 { font-size: 1.25em; margin-top: 2em; } h3 { font-size: 1.05em; }
nav { font-size: 0.9em; } nav a { margin-right: 1em; }
table { border-collapse: collapse; margin: 0.5em 0 1em; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.5em; }
td[style*="right"] { white-space: nowrap; }
th { background: #f0f0f0; } tr:nth-child(even) td { background: #fafafa; }
figure { margin: 1em 0; } figure svg { max-width: 100%; height: auto; }
code { background: #f4f4f4; padding: 0 0.2em; }
"""
_ALIGN = {(True, False): "left", (False, True): "right", (True, True): "center"}


def _inline(text: str) -> str:
    """Escaped text with its bold and code spans."""
    text = html.escape(text, quote=False)
    text = re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", text)
    return re.sub(r"`([^`]+)`", r"<code>\1</code>", text)


def _cells(line: str) -> list[str]:
    return [cell.strip() for cell in line.strip().strip("|").split("|")]


def _table(lines: Sequence[str]) -> list[str]:
    """A pipe table (header, alignment rule, body) as an HTML table."""
    header, rule, body = _cells(lines[0]), _cells(lines[1]), [_cells(x) for x in lines[2:]]
    align = [_ALIGN.get((cell.startswith(":"), cell.endswith(":")), "left") for cell in rule]

    def row(cells: Sequence[str], tag: str) -> str:
        return "<tr>" + "".join(f'<{tag} style="text-align:{a}">{_inline(c)}</{tag}>'
                                for c, a in zip(cells, align)) + "</tr>"
    return (["<table>", "<thead>", row(header, "th"), "</thead>", "<tbody>"]
            + [row(cells, "td") for cells in body] + ["</tbody>", "</table>"])


def slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")


def markdown_html(text: str) -> list[str]:
    """The report's Markdown as HTML lines."""
    out: list[str] = []
    blocks = re.split(r"\n\s*\n", text.strip())
    for block in blocks:
        lines = block.splitlines()
        heading = re.match(r"(#{1,4}) (.*)", lines[0])
        if heading and len(lines) == 1:
            level, title = len(heading.group(1)), heading.group(2)
            out.append(f'<h{level} id="{slug(title)}">{_inline(title)}</h{level}>')
        elif all(line.startswith("|") for line in lines) and len(lines) >= 2:
            out += _table(lines)
        elif all(line.startswith("- ") for line in lines):
            out += ["<ul>"] + [f"<li>{_inline(line[2:])}</li>" for line in lines] + ["</ul>"]
        else:
            out.append(f"<p>{_inline(' '.join(lines))}</p>")
    return out


def _plots_section(plotted: Sequence[tuple[Plot, str]], note: str) -> list[str]:
    out = ['<h2 id="plots">Plots</h2>']
    if not plotted:
        return out + [f"<p>{_inline(note)}</p>"]
    vehicle = None
    for plot, svg in plotted:
        if plot.vehicle != vehicle:
            vehicle = plot.vehicle
            out.append(f'<h3 id="plots-{slug(vehicle)}">{_inline(vehicle_title(vehicle))}</h3>')
        out.append(f'<figure id="{plot.name}" aria-label="{html.escape(plot.caption)}">'
                   f"{svg}</figure>")
    return out


def _navigation(headings: Iterable[str]) -> str:
    links = [f'<a href="#{slug(title)}">{_inline(title)}</a>' for title in headings]
    return "<nav>" + "".join(links) + '<a href="#plots">Plots</a></nav>'


def html_report(markdown: str, plotted: Sequence[tuple[Plot, str]],
                note: str = "No plots in this report.") -> str:
    """The whole page: the report's Markdown, then the plots (``note`` where there are
    none), with links to every section at the top."""
    title = markdown.splitlines()[0].lstrip("# ") if markdown else "Benchmark report"
    headings = re.findall(r"^## (.*)$", markdown, re.MULTILINE)
    body = markdown_html(markdown)
    body.insert(1, _navigation(headings))
    return "\n".join(["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
                      f"<title>{_inline(title)}</title>", f"<style>{STYLE}</style>", "</head>",
                      "<body>", *body, *_plots_section(plotted, note), "</body>", "</html>",
                      ""])
