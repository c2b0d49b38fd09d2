"""The validator's picture as SVG: the browser view's drawing (render_scene), still,
every view one under the other, with the verdict, the first failure and the notes
above. Written directly (no drawing library). A tree of more than ``max_points``
vertices is thinned, one edge in k drawn, and the picture says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from html import escape

from validator.render_file import write_atomically
from validator.render_geometry import TAU, axis_ticks, cell_runs

LAYERS = ("grid", "obstacles", "tree", "footprints", "answer", "marks", "failure")
_FONT = "font-family='Helvetica, Arial, sans-serif'"


@dataclass(frozen=True)
class SvgOptions:
    width: float = 900.0
    """Pixels: the width of a plot."""
    max_points: int = 400_000
    """Tree vertices drawn at most (each some 14 bytes of path)."""
    strip_height: float = 110.0
    """Pixels: a plot of a variable against time."""


@dataclass
class _Plot:
    """Where a plot sits in the picture and how data maps to it."""

    left: float
    top: float
    width: float
    height: float
    box: tuple

    def x(self, value: float) -> float:
        return self.left + (value - self.box[0]) * self.width / (self.box[2] - self.box[0])

    def y(self, value: float) -> float:
        return self.top + (self.box[3] - value) * self.height / (self.box[3] - self.box[1])

    @property
    def sx(self) -> float:
        return self.width / (self.box[2] - self.box[0])

    @property
    def sy(self) -> float:
        return self.height / (self.box[3] - self.box[1])


def _n(value: float) -> str:
    return f"{value:.2f}".rstrip("0").rstrip(".") if math.isfinite(value) else "0"


def _text(x: float, y: float, text: str, size: float = 12, colour: str = "#111",
          anchor: str = "start", bold: bool = False) -> str:
    weight = " font-weight='bold'" if bold else ""
    return (f"<text x='{_n(x)}' y='{_n(y)}' font-size='{size}' fill='{colour}' "
            f"text-anchor='{anchor}'{weight} {_FONT}>{escape(text)}</text>")


# ----- items ------------------------------------------------------------------------------

def _lines(plot: _Plot, item: dict, every: int) -> list[str]:
    """Every ``every``-th polyline of a ``lines`` item, once per turn it lists."""
    points, per, starts = item["points"], item["per"], item["starts"]
    count = len(points) // (2 * per) if per else len(starts) - 1
    parts = []
    for i in range(0, count, every):
        a, b = (i * per, i * per + per) if per else (starts[i], starts[i + 1])
        if b - a < 2:
            continue
        xs = [plot.x(points[2 * j]) for j in range(a, b)]
        ys = [plot.y(points[2 * j + 1]) for j in range(a, b)]
        parts.append("M" + " ".join(f"{_n(x)} {_n(y)}" for x, y in zip(xs, ys)))
    dash = f" stroke-dasharray='{' '.join(map(_n, item['dash']))}'" if item["dash"] else ""
    out = []
    for kx, ky in item["turns"]:
        shift = f" transform='translate({_n(kx * TAU * plot.sx)} {_n(-ky * TAU * plot.sy)})'"
        for start in range(0, len(parts), 5000):
            out.append(f"<path{shift} d='{' '.join(parts[start:start + 5000])}' fill='none' "
                       f"stroke='{item['colour']}' stroke-width='{_n(item['width'])}' "
                       f"stroke-linecap='round' stroke-linejoin='round'{dash}/>")
    return out


def _cells(plot: _Plot, item: dict) -> list[str]:
    """Filled cells merged into runs along each row."""
    cols, rows, cells = item["cols"], item["rows"], item["cells"]
    x0, y0, x1, y1 = item["box"]
    cw, ch = (x1 - x0) / cols, (y1 - y0) / rows
    runs = [f"M{_n(plot.x(x0 + c * cw))} {_n(plot.y(y0 + (r + 1) * ch))}"
            f"h{_n((end - c) * cw * plot.sx)}v{_n(ch * plot.sy)}h{_n(-(end - c) * cw * plot.sx)}z"
            for r, c, end in cell_runs(cells, cols, rows)]
    return [f"<path d='{''.join(runs)}' fill='{item['colour']}' stroke='{item['colour']}' "
            "stroke-width='0.3'/>"] if runs else []


def _polygon(plot: _Plot, flat) -> str:
    return "M" + " ".join(f"{_n(plot.x(flat[k]))} {_n(plot.y(flat[k + 1]))}"
                          for k in range(0, len(flat), 2)) + "z"


def _shapes(plot: _Plot, item: dict) -> list[str]:
    fill = item["fill"]
    out = [f"<rect x='{_n(plot.x(x0))}' y='{_n(plot.y(y1))}' width='{_n((x1 - x0) * plot.sx)}' "
           f"height='{_n((y1 - y0) * plot.sy)}' fill='{fill}'/>"
           for x0, y0, x1, y1 in item["rects"]]
    out += [f"<ellipse cx='{_n(plot.x(cx))}' cy='{_n(plot.y(cy))}' rx='{_n(r * plot.sx)}' "
            f"ry='{_n(r * plot.sy)}' fill='{fill}'/>" for cx, cy, r in item["discs"]]
    out += [f"<path d='{_polygon(plot, flat)}' fill='{fill}'/>" for flat in item["polygons"]]
    return out


def _bodies(plot: _Plot, item: dict) -> list[str]:
    dash = f" stroke-dasharray='{' '.join(map(_n, item['dash']))}'" if item["dash"] else ""
    shapes = "".join(_polygon(plot, flat) for flat in item["polygons"])
    fronts = "".join(f"M{_n(plot.x(a))} {_n(plot.y(b))}L{_n(plot.x(c))} {_n(plot.y(d))}"
                     for a, b, c, d in item["fronts"])
    fill = f"fill='{item['fill']}' fill-opacity='0.6'" if item["fill"] else "fill='none'"
    return [f"<path d='{shapes}' {fill} "
            f"stroke='{item['colour']}' stroke-width='1.2'{dash}/>",
            f"<path d='{fronts}' stroke='{item['front']}' stroke-width='2.2' fill='none'/>"]


def _mark(plot: _Plot, item: dict) -> list[str]:
    kind, colour = item["kind"], item["colour"]
    if kind == "rings":
        return [f"<circle cx='{_n(plot.x(x))}' cy='{_n(plot.y(y))}' r='{_n(item['radius'])}' "
                f"fill='none' stroke='{colour}' stroke-width='1.8'/>" for x, y in item["points"]]
    x, y = plot.x(item["at"][0]), plot.y(item["at"][1])
    if kind == "dot":
        halo = (f"<circle cx='{_n(x)}' cy='{_n(y)}' r='{_n(item['radius'] + 2)}' fill='#fff'/>"
                if item["halo"] else "")
        return [halo + f"<circle cx='{_n(x)}' cy='{_n(y)}' r='{_n(item['radius'])}' "
                f"fill='{colour}'/>"]
    if kind == "circle":
        rx, ry, arm = item["radius"] * plot.sx, item["radius"] * plot.sy, item["cross"]
        d = (f"M{_n(x + rx)} {_n(y)}A{_n(rx)} {_n(ry)} 0 1 0 {_n(x - rx)} {_n(y)}"
             f"A{_n(rx)} {_n(ry)} 0 1 0 {_n(x + rx)} {_n(y)}" if item.get("outline", True)
             else "")
        if min(rx, ry) < 4 and arm:
            d += f"M{_n(x - arm)} {_n(y)}h{_n(2 * arm)}M{_n(x)} {_n(y - arm)}v{_n(2 * arm)}"
        width = 1.8
    else:  # the failure's cross
        s = item["size"]
        d = (f"M{_n(x - s)} {_n(y - s)}L{_n(x + s)} {_n(y + s)}M{_n(x - s)} {_n(y + s)}"
             f"L{_n(x + s)} {_n(y - s)}M{_n(x + 1.35 * s)} {_n(y)}A{_n(1.35 * s)} "
             f"{_n(1.35 * s)} 0 1 0 {_n(x - 1.35 * s)} {_n(y)}A{_n(1.35 * s)} {_n(1.35 * s)} "
             f"0 1 0 {_n(x + 1.35 * s)} {_n(y)}")
        width = 2.4
    return [f"<path d='{d}' fill='none' stroke='#fff' stroke-width='{_n(width + 3)}'/>",
            f"<path d='{d}' fill='none' stroke='{colour}' stroke-width='{_n(width)}'/>"]


def _item(plot: _Plot, item: dict, every: int) -> list[str]:
    kind = item["kind"]
    if kind == "lines":
        return _lines(plot, item, every if item["growth"] else 1)
    if kind == "cells":
        return _cells(plot, item)
    if kind == "gridlines":
        if plot.sx < 4 or plot.sy < 4:
            return []
        x0, y0, x1, y1 = plot.box
        d = "".join(f"M{_n(plot.x(i))} {_n(plot.y(y0))}V{_n(plot.y(y1))}"
                    for i in range(1, item["cols"]))
        d += "".join(f"M{_n(plot.x(x0))} {_n(plot.y(j))}H{_n(plot.x(x1))}"
                     for j in range(1, item["rows"]))
        return [f"<path d='{d}' stroke='#d1d1d1' stroke-width='1' fill='none'/>"]
    if kind == "shapes":
        return _shapes(plot, item)
    if kind == "outline":
        x0, y0, x1, y1 = item["box"]
        return [f"<rect x='{_n(plot.x(x0))}' y='{_n(plot.y(y1))}' width='{_n((x1 - x0) * plot.sx)}'"
                f" height='{_n((y1 - y0) * plot.sy)}' fill='none' stroke='{item['colour']}' "
                "stroke-width='1.2'/>"]
    if kind == "bodies":
        return _bodies(plot, item)
    return _mark(plot, item)


# ----- plots, views, the picture -----------------------------------------------------------

def _axes(plot: _Plot, spec: dict, labels_x: bool) -> list[str]:
    x0, y0, x1, y1 = plot.box
    out = [f"<rect x='{_n(plot.left)}' y='{_n(plot.top)}' width='{_n(plot.width)}' "
           f"height='{_n(plot.height)}' fill='none' stroke='#000'/>"]
    ticks = ""
    for value, label in axis_ticks(x0, x1, plot.sx, spec["x"]["angle"], 80.0):
        ticks += f"M{_n(plot.x(value))} {_n(plot.top + plot.height)}v5"
        if labels_x:
            out.append(_text(plot.x(value), plot.top + plot.height + 18, label, 11,
                             anchor="middle"))
    for value, label in axis_ticks(y0, y1, plot.sy, spec["y"]["angle"],
                                   min(50.0, plot.height / 3)):
        ticks += f"M{_n(plot.left)} {_n(plot.y(value))}h-5"
        out.append(_text(plot.left - 7, plot.y(value) + 4, label, 11, anchor="end"))
    out.append(f"<path d='{ticks}' stroke='#000'/>")
    out.append(_text(plot.left + 2, plot.top - 4, spec["y"]["name"], 12, bold=True))
    if labels_x:
        out.append(_text(plot.left + plot.width + 14, plot.top + plot.height + 18,
                         spec["x"]["name"], 12, bold=True))
    return out


def _plot_svg(plot: _Plot, spec: dict, number: int, every: int, labels_x: bool) -> list[str]:
    out = [f"<clipPath id='c{number}'><rect x='{_n(plot.left)}' y='{_n(plot.top)}' "
           f"width='{_n(plot.width)}' height='{_n(plot.height)}'/></clipPath>",
           f"<g clip-path='url(#c{number})'>"]
    for layer_id in LAYERS:
        for layer in spec["layers"]:
            if layer["id"] == layer_id:
                for item in layer["items"]:
                    out += _item(plot, item, every)
    out.append("</g>")
    return out + _axes(plot, spec, labels_x)


def _plot_size(spec: dict, count: int, options: SvgOptions) -> tuple[float, float]:
    x0, y0, x1, y1 = spec["box"]
    if count > 1:
        return options.width, options.strip_height
    if spec["equal"]:
        scale = min(options.width / (x1 - x0), options.width / (y1 - y0))
        return scale * (x1 - x0), scale * (y1 - y0)
    return options.width, options.width / 2


def _tree_points(scene: dict) -> int:
    return sum(len(item["points"]) // 2 for view in scene["views"] for spec in view["plots"]
               for layer in spec["layers"] for item in layer["items"]
               if item["kind"] == "lines" and item["growth"])


def _header(scene: dict, every: int) -> list[str]:
    lines = [(scene["verdict"], 16, "#008000" if scene["valid"] else "#d90d0d", True),
             (scene["heading"], 12, "#111", False)]
    if scene["counts"]:
        lines.append((scene["counts"] + (f" (the picture: one tree edge in {every})"
                                         if every > 1 else ""), 12, "#111", False))
    lines += [(caption, 12, "#8a008a", False) for caption in scene["captions"]]
    return [_text(14, 22 + 17 * k, text, size, colour, bold=bold)
            for k, (text, size, colour, bold) in enumerate(lines)]


def svg_text(scene: dict, options: SvgOptions = SvgOptions()) -> str:
    """The SVG of ``scene``."""
    every = max(1, math.ceil(_tree_points(scene) / options.max_points))
    out = _header(scene, every)
    top, right, number = 30 + 17 * len(out), 0.0, 0
    for view in scene["views"]:
        out.append(_text(14, top, view["what"], 12, "#444", bold=True))
        top += 30
        plots = view["plots"]
        for k, spec in enumerate(plots):
            width, height = _plot_size(spec, len(plots), options)
            plot = _Plot(70.0, top, width, height, tuple(spec["box"]))
            out += _plot_svg(plot, spec, number, every, k == len(plots) - 1)
            number += 1
            top += height + 26
            right = max(right, 70.0 + width + 60)
        top += 24
    width = max(right, 900.0)
    return (f"<svg xmlns='http://www.w3.org/2000/svg' width='{_n(width)}' height='{_n(top)}' "
            f"viewBox='0 0 {_n(width)} {_n(top)}'>\n<title>{escape(scene['title'])}</title>\n"
            f"<rect width='100%' height='100%' fill='#fff'/>\n" + "\n".join(out) + "\n</svg>\n")


def write_svg(path: str, scene: dict, options: SvgOptions = SvgOptions()) -> None:
    """Write the SVG of ``scene`` to ``path``, whole or not at all."""
    data = svg_text(scene, options).encode("utf-8")
    write_atomically(path, lambda out: out.write(data))
