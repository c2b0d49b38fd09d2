"""Read a ``kinoplan 1`` problem (SPEC 5.1) into a :class:`KinoplanProblem`.

Lenient in layout (``#`` comments, any whitespace, CRLF, blank lines, items in
any order after the first line), strict in content: every malformed or
contradictory problem is a :class:`ProblemFormatError` naming the line and
column (1-based; a tab is one column), which the CLIs print as ``bad problem:
line L, column C: ...`` with exit status 2.

Decisions where SPEC 5.1 is silent: decimals may carry a ``+`` sign; an item
other than ``param``, ``bound``, ``control`` and the obstacles may appear once;
``x`` and ``y`` are bounded by the world box unless a ``bound`` says otherwise;
metric weights and the goal tolerance are > 0; the start's angles (and the
goal target's) are wrapped to [-pi, pi]; the ``system`` line is found first,
so any item may come before it. A goal naming only some variables is not
checked for validity (a state near it may be valid). Linear time, and memory
bounded by the caps below (one line at a time, no copy of the whole text).
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass, field
from typing import Callable, NamedTuple, Optional

from planning_core.kinoplan import (MAX_MAGNITUDE, MIN_POSITIVE, KinoplanProblem,
                                   invalid_reason, make_goal)
from planning_core.problem_text import ProblemFormatError
from planning_core.systems import load as load_system
from planning_core.systems.family import MAX_SLICES, FamilySystem
from planning_core.worlds.continuous import ContinuousWorld
from planning_core.worlds.shapes import ConvexPolygon, Disc, Rect, body_polygon

SYSTEMS = ("pendulum", "car2", "unicycle", "car1", "arm2", "rigid2")
MAX_POLYGON_VERTICES = 10_000
MAX_LINE_TOKENS = 2 * MAX_POLYGON_VERTICES + 2   # "polygon" / "body polygon" + pairs
MAX_OBSTACLE_VERTICES = 100_000                 # a rect counts 4, a circle 1
MAX_MOTION_SAMPLES = 10_000_000                 # a strict check across the whole space
MAX_INTEGER_DIGITS = 18

_BAD_CHAR = re.compile(r"[^\t\n\v\f\r\x20-\x7e]")
_ITEM = re.compile(r"^[ \t\v\f\r]*([^\s#][^\n]*)", re.M)
_SYSTEM_LINE = re.compile(r"^[ \t\v\f\r]*system(?![^\s#])", re.M)
_TOKEN = re.compile(r"\S+")
_DECIMAL = r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"  # unambiguous: linear time
_NUMBER = re.compile(rf"[+-]?{_DECIMAL}")
_PI = re.compile(rf"(-?)(?:({_DECIMAL})\*)?pi(?:/({_DECIMAL}))?")
_INTEGER = re.compile(r"[+-]?([0-9]+)")
_NON_FINITE = re.compile(r"[+-]?(nan|inf|infinity)", re.IGNORECASE)


class Token(NamedTuple):
    text: str
    line: int
    column: int


class Item(NamedTuple):
    """One keyword line: the keyword, its arguments, where the line's text ends."""

    keyword: Token
    args: list[Token]
    end: int


def _fail(where: Token, message: str):
    raise ProblemFormatError(where.line, where.column, message)


def _show(text: str) -> str:
    return repr(text if len(text) <= 40 else text[:37] + "...")


def _at_end(item: Item) -> Token:
    return Token("", item.keyword.line, item.end)


# ----- numbers ----------------------------------------------------------------------


def number(token: Token, what: str) -> float:
    """A finite decimal (optional exponent) or a pi form ``[-][N*]pi[/D]``."""
    text = token.text
    if _NUMBER.fullmatch(text):
        value = float(text)
    elif (pi := _PI.fullmatch(text)) is not None:
        sign, n, d = pi.groups()
        if d is not None and float(d) == 0.0:
            _fail(token, f"{what}: {_show(text)} divides by zero")
        value = (float(n) * math.pi if n is not None else math.pi) / (float(d) if d else 1.0)
        value = -value if sign else value
    elif _NON_FINITE.fullmatch(text):
        _fail(token, f"{what}: {_show(text)} is not a finite number")
    else:
        _fail(token, f"{what}: {_show(text)} is not a number")
    if not math.isfinite(value):
        _fail(token, f"{what}: {_show(text)} is not a finite number")
    if abs(value) > MAX_MAGNITUDE:
        _fail(token, f"{what}: {_show(text)} is larger than {MAX_MAGNITUDE:g} in magnitude "
                     "(the limit of a problem's numbers)")
    return value


def integer(token: Token, what: str) -> int:
    """An integer token, at most ``MAX_INTEGER_DIGITS`` digits."""
    match = _INTEGER.fullmatch(token.text)
    if match is None:
        _fail(token, f"{what}: {_show(token.text)} is not an integer (a count of slices)")
    if len(match.group(1)) > MAX_INTEGER_DIGITS:
        _fail(token, f"{what}: {_show(token.text)} is too large")
    return int(token.text)


def _positive(token: Token, what: str) -> float:
    """A number > 0, and at least ``MIN_POSITIVE`` (a length, step, weight or tolerance)."""
    value = number(token, what)
    if not value > 0.0:
        _fail(token, f"{what} must be > 0, got {token.text}")
    if value < MIN_POSITIVE:
        _fail(token, f"{what} must be at least {MIN_POSITIVE:g}, got {token.text}")
    return value


# ----- the lines --------------------------------------------------------------------


def _check_characters(text: str) -> None:
    bad = _BAD_CHAR.search(text)
    if bad is not None:
        start = text.rfind("\n", 0, bad.start()) + 1
        _fail(Token("", text.count("\n", 0, start) + 1, bad.start() - start + 1),
              f"character {bad.group()!r} is not allowed (ASCII text only)")


def _split(body: str, line: int, offset: int) -> tuple[list[Token], int]:
    """The tokens of one line (its comment removed), and the column after its text."""
    body = body.split("#", 1)[0]
    found = list(itertools.islice(_TOKEN.finditer(body), MAX_LINE_TOKENS + 1))
    if len(found) > MAX_LINE_TOKENS:
        _fail(Token("", line, offset + 1), f"more than {MAX_LINE_TOKENS} words on one line")
    tokens = [Token(m.group(), line, offset + m.start() + 1) for m in found]
    return tokens, offset + len(body.rstrip()) + 1


def _first_line(text: str) -> int:
    """Checks ``kinoplan 1`` and returns where the second line starts."""
    newline = text.find("\n")
    tokens, end = _split(text if newline < 0 else text[:newline], 1, 0)
    if not tokens or tokens[0].text != "kinoplan":
        where = tokens[0] if tokens else Token("", 1, 1)
        _fail(where, "the first line must be 'kinoplan 1', with nothing before it")
    if len(tokens) < 2:
        _fail(Token("", 1, end), "kinoplan: missing the version (the first line is 'kinoplan 1')")
    if tokens[1].text != "1":
        _fail(tokens[1], f"kinoplan: unsupported version {_show(tokens[1].text)} "
                         "(this reader reads version 1)")
    if len(tokens) > 2:
        _fail(tokens[2], f"unexpected {_show(tokens[2].text)} after 'kinoplan 1'")
    return len(text) if newline < 0 else newline + 1


def _items(text: str, start: int):
    """Every keyword line from ``start`` on, as an :class:`Item` (blank and comment
    lines skipped by the regular expression, in C)."""
    line, position = 2, start
    for match in _ITEM.finditer(text, start):
        line += text.count("\n", position, match.start())
        position = match.start()
        tokens, end = _split(match.group(1), line, match.start(1) - position)
        if tokens:
            yield Item(tokens[0], tokens[1:], end)


def _system_item(text: str, start: int) -> Item:
    """The ``system`` line, wherever it is (the other items need to know the system)."""
    match = _SYSTEM_LINE.search(text, start)
    if match is None:
        _fail(_end_of(text), "missing 'system NAME' (pendulum | car2 | unicycle | car1 | "
                             "arm2 | rigid2)")
    return _item_at(text, match.start())


def _item_at(text: str, position: int) -> Item:
    line = text.count("\n", 0, position) + 1
    newline = text.find("\n", position)
    body = text[position:] if newline < 0 else text[position:newline]
    tokens, end = _split(body, line, 0)
    return Item(tokens[0], tokens[1:], end)


def _end_of(text: str) -> Token:
    """Just after the last non-blank text (where a missing item is reported)."""
    stripped = text.rstrip()
    start = stripped.rfind("\n") + 1
    return Token("", stripped.count("\n") + 1, len(stripped) - start + 1)


# ----- what the lines say -------------------------------------------------------------


@dataclass
class _Reading:
    """What the lines said so far (filled in while reading, then assembled)."""

    cls: type
    system_item: Item
    seen: dict = field(default_factory=dict)           # "keyword [name]" -> line
    params: dict = field(default_factory=dict)
    bounds: dict = field(default_factory=dict)
    controls: dict = field(default_factory=dict)
    integrate: Optional[tuple[str, float]] = None
    duration: Optional[tuple[int, int]] = None
    check: Optional[float] = None
    check_at: Optional[Token] = None
    body: Optional[ConvexPolygon] = None
    box: Optional[Rect] = None
    world: Optional[Token] = None
    metric: Optional[tuple] = None
    start: Optional[dict] = None                      # name -> (value, var token, value token)
    start_at: Optional[Token] = None
    goal: Optional[dict] = None
    goal_at: Optional[Token] = None
    tolerance: float = 0.0
    obstacles: list = field(default_factory=list)
    obstacle_lines: list = field(default_factory=list)
    vertices: int = 0


def _once(r: _Reading, where: Token, key: str) -> None:
    if key in r.seen:
        _fail(where, f"{key} given twice (first on line {r.seen[key]})")
    r.seen[key] = where.line


def _arity(item: Item, usage: str) -> list[Token]:
    """Exactly the arguments ``usage`` names (e.g. ``"VAR LO HI"``)."""
    names, args, keyword = usage.split(), item.args, item.keyword.text
    if len(args) < len(names):
        _fail(_at_end(item), f"{keyword}: missing {' '.join(names[len(args):])} "
                             f"(usage: {keyword} {usage})")
    if len(args) > len(names):
        _fail(args[len(names)], f"{keyword}: unexpected {_show(args[len(names)].text)} "
                                f"(usage: {keyword} {usage})")
    return args


def _kinodynamic_only(r: _Reading, item: Item) -> None:
    if not r.cls.kinodynamic:
        _fail(item.keyword, f"{r.cls.name} is geometric: it takes no {item.keyword.text} "
                            "(only pendulum, car2, unicycle and car1 do)")


def _takes_world(r: _Reading, item: Item) -> None:
    if not r.cls.needs_world:
        _fail(item.keyword, f"{r.cls.name} has no workspace: it takes no {item.keyword.text}")


def _state_variable(r: _Reading, token: Token, what: str) -> str:
    if token.text not in r.cls.state_names:
        _fail(token, f"{what}: {r.cls.name} has no state variable {_show(token.text)} "
                     f"(its variables: {', '.join(r.cls.state_names)})")
    return token.text


def _interval(item: Item, what: str) -> tuple[float, float]:
    lo_t, hi_t = item.args[1], item.args[2]
    lo, hi = number(lo_t, f"{what} LO"), number(hi_t, f"{what} HI")
    if lo > hi:
        _fail(lo_t, f"{what}: LO {lo_t.text} is greater than HI {hi_t.text}")
    return lo, hi


# ----- one function per keyword ---------------------------------------------------------


def _kinoplan(r: _Reading, item: Item) -> None:
    _fail(item.keyword, "'kinoplan 1' belongs on the first line only")


def _system(r: _Reading, item: Item) -> None:
    if item.keyword.line != r.system_item.keyword.line:
        _fail(item.keyword, f"system given twice (first on line {r.system_item.keyword.line})")


def _param(r: _Reading, item: Item) -> None:
    name_t, value_t = _arity(item, "NAME VALUE")
    cls, name = r.cls, name_t.text
    if name not in cls.params:
        has = ", ".join(cls.params) if cls.params else "none"
        _fail(name_t, f"param: {cls.name} has no parameter {_show(name)} (its parameters: {has})")
    _once(r, item.keyword, f"param {name}")
    positive = name in cls.positive_params
    r.params[name] = (_positive if positive else number)(value_t, f"param {name}")


def _bound(r: _Reading, item: Item) -> None:
    name = _state_variable(r, _arity(item, "VAR LO HI")[0], "bound")
    if name in r.cls.angle_names:
        _fail(item.args[0], f"bound: {name} is an angle: angles wrap and take no bound")
    _once(r, item.keyword, f"bound {name}")
    r.bounds[name] = _interval(item, f"bound {name}")


def _control(r: _Reading, item: Item) -> None:
    _kinodynamic_only(r, item)
    var, held = _arity(item, "VAR LO HI")[0], r.cls.control_names[:-1]
    if var.text == "K":
        _fail(var, "control: K, the number of slices, is bounded by 'duration KMIN KMAX'")
    if var.text not in held:
        _fail(var, f"control: {r.cls.name} has no control {_show(var.text)} "
                   f"(its controls: {', '.join(held)})")
    _once(r, item.keyword, f"control {var.text}")
    r.controls[var.text] = _interval(item, f"control {var.text}")


def _integrate(r: _Reading, item: Item) -> None:
    _kinodynamic_only(r, item)
    scheme, dt = _arity(item, "SCHEME DT")
    _once(r, item.keyword, "integrate")
    if scheme.text not in ("euler", "rk4"):
        _fail(scheme, f"integrate: unknown scheme {_show(scheme.text)} (euler | rk4)")
    r.integrate = (scheme.text, _positive(dt, "integrate DT"))


def _duration(r: _Reading, item: Item) -> None:
    _kinodynamic_only(r, item)
    kmin_t, kmax_t = _arity(item, "KMIN KMAX")
    _once(r, item.keyword, "duration")
    kmin, kmax = integer(kmin_t, "duration KMIN"), integer(kmax_t, "duration KMAX")
    if kmin < 1:
        _fail(kmin_t, f"duration: KMIN must be at least 1 slice, got {kmin}")
    if kmin > kmax:
        _fail(kmin_t, f"duration: KMIN {kmin} is greater than KMAX {kmax}")
    if kmax > MAX_SLICES:
        _fail(kmax_t, f"duration: KMAX {kmax} is more than {MAX_SLICES} slices")
    r.duration = (kmin, kmax)


def _check(r: _Reading, item: Item) -> None:
    if r.cls.kinodynamic:
        _fail(item.keyword, f"{r.cls.name} is kinodynamic: it takes no check "
                            "(every slice of its motions is checked)")
    (step,) = _arity(item, "STEP")
    _once(r, item.keyword, "check")
    r.check, r.check_at = _positive(step, "check STEP"), step


def _body(r: _Reading, item: Item) -> None:
    if r.cls.occupies != "body":
        _fail(item.keyword, f"{r.cls.name} has no body: it takes no body line")
    _once(r, item.keyword, "body")
    if not item.args:
        _fail(_at_end(item), "body: missing KIND (square SIDE | rect LENGTH WIDTH | "
                             "polygon X1 Y1 X2 Y2 ...)")
    kind = item.args[0]
    if kind.text not in ("square", "rect", "polygon"):
        _fail(kind, f"body: unknown kind {_show(kind.text)} (square | rect | polygon)")
    dims = [number(t, f"body {kind.text}") for t in item.args[1:]]
    try:
        r.body = body_polygon(kind.text, dims)
    except ValueError as exc:
        _fail(item.args[1] if dims else _at_end(item), str(exc))


def _world(r: _Reading, item: Item) -> None:
    _takes_world(r, item)
    corners = [number(t, "world") for t in _arity(item, "X0 Y0 X1 Y1")]
    _once(r, item.keyword, "world")
    if not (corners[0] < corners[2] and corners[1] < corners[3]):
        _fail(item.keyword, "world: needs X0 < X1 and Y0 < Y1 (min corner, max corner)")
    r.box, r.world = Rect(*corners), item.keyword


def _add_obstacle(r: _Reading, item: Item, shape, vertices: int) -> None:
    r.vertices += vertices
    if r.vertices > MAX_OBSTACLE_VERTICES:
        _fail(item.keyword, f"more than {MAX_OBSTACLE_VERTICES} obstacle vertices in all")
    r.obstacles.append(shape)
    r.obstacle_lines.append(item.keyword.line)


def _rect(r: _Reading, item: Item) -> None:
    _takes_world(r, item)
    corners = [number(t, "rect") for t in _arity(item, "X0 Y0 X1 Y1")]
    if not (corners[0] < corners[2] and corners[1] < corners[3]):
        _fail(item.keyword, "rect: needs X0 < X1 and Y0 < Y1 (min corner, max corner)")
    _add_obstacle(r, item, Rect(*corners), 4)


def _circle(r: _Reading, item: Item) -> None:
    _takes_world(r, item)
    cx, cy, radius = _arity(item, "CX CY R")
    centre = (number(cx, "circle CX"), number(cy, "circle CY"))
    _add_obstacle(r, item, Disc(*centre, _positive(radius, "circle R")), 1)


def _polygon(r: _Reading, item: Item) -> None:
    _takes_world(r, item)
    values = [number(t, "polygon") for t in item.args]
    if len(values) < 6 or len(values) % 2:
        _fail(item.args[-1] if len(values) % 2 else _at_end(item),
              f"polygon: needs X Y pairs of at least 3 vertices, got {len(values)} numbers")
    try:
        polygon = ConvexPolygon(tuple(zip(values[0::2], values[1::2])))
    except ValueError as exc:
        _fail(item.args[0], str(exc))
    _add_obstacle(r, item, polygon, len(values) // 2)


def _metric(r: _Reading, item: Item) -> None:
    _once(r, item.keyword, "metric")
    args, groups, named = item.args, [], set()
    if not args or len(args) % 2:
        _fail(_at_end(item), "metric: needs GROUP W pairs (usage: metric x,y 1 theta 0.5)")
    for group, weight in zip(args[0::2], args[1::2]):
        names = group.text.split(",")
        for name in names:
            _state_variable(r, Token(name, group.line, group.column), "metric")
            if name in named:
                _fail(group, f"metric: {name} is named twice (each variable in one group)")
            named.add(name)
        groups.append((tuple(names), _positive(weight, f"metric weight of {group.text}")))
    r.metric = tuple(groups)


def _assignments(r: _Reading, tokens: list[Token], missing_at: Token, what: str) -> dict:
    """``VAR VALUE`` pairs, each a state variable named once: name -> (value,
    the name's token, the value's token)."""
    if len(tokens) % 2:
        _fail(missing_at, f"{what}: {tokens[-1].text} has no value")
    out: dict = {}
    for var, value in zip(tokens[0::2], tokens[1::2]):
        name = _state_variable(r, var, what)
        if name in out:
            _fail(var, f"{what}: {name} is named twice")
        out[name] = (number(value, f"{what} {name}"), var, value)
    return out


def _start(r: _Reading, item: Item) -> None:
    _once(r, item.keyword, "start")
    if not item.args:
        _fail(_at_end(item), "start: missing VAR VALUE pairs (every state variable)")
    r.start, r.start_at = _assignments(r, item.args, _at_end(item), "start"), item.keyword


def _goal(r: _Reading, item: Item) -> None:
    _once(r, item.keyword, "goal")
    texts = [t.text for t in item.args]
    if "within" not in texts:
        _fail(_at_end(item), "goal: missing 'within TOL' (usage: goal VAR VALUE ... within TOL)")
    at = texts.index("within")
    if at == 0:
        _fail(item.args[0], "goal: names no variable (usage: goal VAR VALUE ... within TOL)")
    rest = item.args[at + 1:]
    if not rest:
        _fail(_at_end(item), "goal: missing TOL after 'within'")
    if len(rest) > 1:
        _fail(rest[1], f"goal: unexpected {_show(rest[1].text)} after the tolerance")
    r.goal = _assignments(r, item.args[:at], item.args[at], "goal")
    r.goal_at, r.tolerance = item.keyword, _positive(rest[0], "goal TOL")


_HANDLERS: dict[str, Callable[[_Reading, Item], None]] = {
    "kinoplan": _kinoplan, "system": _system, "param": _param, "bound": _bound,
    "control": _control, "integrate": _integrate, "duration": _duration, "check": _check,
    "body": _body, "world": _world, "rect": _rect, "circle": _circle, "polygon": _polygon,
    "metric": _metric, "start": _start, "goal": _goal,
}
KEYWORDS = tuple(_HANDLERS)


# ----- the whole problem --------------------------------------------------------------


def _system_class(item: Item) -> type:
    (name,) = _arity(item, "NAME")
    if name.text not in SYSTEMS:
        _fail(name, f"system: unknown system {_show(name.text)} ({' | '.join(SYSTEMS)})")
    return type(load_system(name.text))


def _required(r: _Reading, end: Token) -> None:
    cls = r.cls
    if cls.needs_world and r.box is None:
        _fail(end, f"missing 'world X0 Y0 X1 Y1' ({cls.name} moves in a workspace)")
    if cls.occupies == "body" and r.body is None and cls.DEFAULTS.body is None:
        _fail(end, f"missing 'body KIND ...' ({cls.name} has no default body)")
    if r.start is None:
        _fail(end, "missing 'start VAR VALUE ...' (every state variable)")
    if r.goal is None:
        _fail(end, "missing 'goal VAR VALUE ... within TOL'")


def _configure(r: _Reading) -> FamilySystem:
    cls, at = r.cls, r.system_item.keyword
    more = (dict(controls=r.controls, integrate=r.integrate, duration=r.duration)
            if cls.kinodynamic else dict(check=r.check))
    try:
        system = cls.configure(params=r.params, bounds=r.bounds, metric=r.metric,
                               body=r.body, world_box=r.box, **more)
    except ValueError as exc:  # every item was checked on its line: a guard only
        _fail(at, f"{cls.name}: {exc}")
    for v in system.space.variables:
        if not v.angle and not (math.isfinite(v.low) and math.isfinite(v.high)):
            _fail(at, f"{cls.name}: state variable {v.name} has no bound "
                      f"(give 'bound {v.name} LO HI')")
    return system


def _start_state(r: _Reading, system: FamilySystem, world) -> tuple[float, ...]:
    missing = [n for n in system.state_names if n not in r.start]
    if missing:
        _fail(r.start_at, f"start: missing {', '.join(missing)} (the start names every "
                          "state variable)")
    for v in system.space.variables:
        value, _, token = r.start[v.name]
        if not v.angle and not v.low <= value <= v.high:
            _fail(token, f"start: {v.name} = {token.text} is outside its bound "
                         f"[{v.low:g}, {v.high:g}]")
    start = system.space.wrap([r.start[n][0] for n in system.state_names])
    reason = invalid_reason(system, world, start, r.obstacle_lines)
    if reason is not None:
        _fail(r.start_at, f"start is not valid: {reason}")
    return start


def _goal_region(r: _Reading, system: FamilySystem, world):
    grouped = {name for names, _ in system.metric for name in names}
    for name, (_, token, _) in r.goal.items():
        if name not in grouped:
            _fail(token, f"goal: {name} is in no metric group, so no distance measures it "
                         "(add it to 'metric', or leave it out of the goal)")
    goal = make_goal(system.space, {n: v[0] for n, v in r.goal.items()}, r.tolerance)
    if goal.full:
        reason = invalid_reason(system, world, goal.target, r.obstacle_lines)
        if reason is not None:
            _fail(r.goal_at, f"goal is not valid: {reason}")
    return goal


def _check_samples(r: _Reading, system: FamilySystem) -> None:
    """A motion across the whole space, strictly checked, stays within
    ``MAX_MOTION_SAMPLES`` samples (so no check step makes a motion endless)."""
    variables = system.space.variables
    extent = sum(weight * math.sqrt(sum((math.pi if variables[i].angle
                                         else variables[i].high - variables[i].low) ** 2
                                        for i in indices))
                 for indices, weight in system.space.groups)
    if 10.0 * extent / system.check > MAX_MOTION_SAMPLES:
        at = r.check_at or r.world or r.system_item.keyword
        _fail(at, f"check step {system.check:g} is too fine for this space: a motion across "
                  f"it (length {extent:g}) would take more than {MAX_MOTION_SAMPLES} samples")


def parse_kinoplan(text: str) -> KinoplanProblem:
    """Parse ``kinoplan 1`` text, or raise :class:`ProblemFormatError`."""
    _check_characters(text)
    start = _first_line(text)
    system_item = _system_item(text, start)
    r = _Reading(_system_class(system_item), system_item)
    for item in _items(text, start):
        handler = _HANDLERS.get(item.keyword.text)
        if handler is None:
            _fail(item.keyword, f"unknown keyword {_show(item.keyword.text)} "
                                f"(one of: {', '.join(KEYWORDS[1:])})")
        handler(r, item)
    _required(r, _end_of(text))
    system = _configure(r)
    world = None if r.box is None else ContinuousWorld(r.box, tuple(r.obstacles))
    start_state = _start_state(r, system, world)
    goal = _goal_region(r, system, world)
    if not system.kinodynamic:
        _check_samples(r, system)
    return KinoplanProblem(system, world, start_state, goal, tuple(r.obstacle_lines))


def looks_like_kinoplan(text: str) -> bool:
    """The first word starts with ``kinoplan`` or ``#`` (a ``.sw`` grid starts with
    its width): the CLIs send such a text to :func:`parse_kinoplan`, whose message
    then says what is wrong with its first line."""
    match = _TOKEN.search(text, 0, 4096)
    return match is not None and match.group().startswith(("kinoplan", "#"))
