"""The rubric: which problems are graded in which modes, what each is worth, its time
limit and how many times it is run; read from a TOML file (``--rubric``) or made of
the command line's shortcuts (``--modes``, ``--weights``, ``--timeout``, ``--repeats``,
``--scale``), which set its top-level keys."""

from __future__ import annotations

import dataclasses
import fnmatch
import math
from dataclasses import dataclass
from pathlib import Path

from planning_core.vehicles import Vehicle

# The course's modes of a .sw map: how each reaches run.sh, and which vehicle the
# validator checks. A .kp problem names its own system: its one mode, KINOPLAN, has no flag.
MODE_FLAGS: dict[str, tuple[str, ...]] = {"point": (), "grad": ("-grad",),
                                          "left": ("-grad", "-left")}
MODE_VEHICLES: dict[str, Vehicle] = {"point": Vehicle.POINT, "grad": Vehicle.SPACESHIP,
                                     "left": Vehicle.LEFT_SPACESHIP}
KINOPLAN = "kinoplan"
MAX_RUBRIC_BYTES = 1 << 20
MAX_REPEATS = 100
MAX_TIMEOUT = 86400.0
VISIBILITIES = ("hidden", "after_due_date", "after_published", "visible")
PROBLEM_SUFFIXES = (".sw", ".kp")


class RubricError(ValueError):
    """A rubric that cannot be used: one line, naming the file and the key."""


@dataclass(frozen=True)
class Rule:
    """One ``[[problems]]`` entry: the keys it sets for the problems its glob matches
    (None: not set, the rubric's default or an earlier entry's stands)."""

    match: str                          # a file name or a glob among the problems
    modes: tuple[str, ...] | None = None  # .sw maps only; a .kp problem has one mode
    weight: float | None = None
    timeout: float | None = None
    repeats: int | None = None
    visibility: str | None = None
    skip: bool = False                  # leave the matched problems out


@dataclass(frozen=True)
class Item:
    """One problem in one mode as graded: each of its runs, and what they are worth."""

    problem: str         # the file's name in the problems folder
    mode: str            # point, grad, left; ``kinoplan`` for a .kp problem
    weight: float        # its weight (the rule's or default weight x the mode's weight)
    timeout: float       # seconds per run
    repeats: int         # runs of it; its part of the score is the share that is valid
    visibility: str = "visible"  # Gradescope's visibility of its test

    @property
    def label(self) -> str:
        return f"{self.problem} {self.mode}"


@dataclass(frozen=True)
class Rubric:
    """What is graded and how it is scored; ``items`` applies it to a problems folder."""

    modes: tuple[str, ...] = ("point", "grad", "left")  # the .sw problems' modes
    weight: float = 1.0        # a problem's weight when no rule sets one
    mode_weights: tuple[tuple[str, float], ...] = ()  # (mode, factor); a mode not named: 1
    timeout: float = 60.0      # seconds per run
    repeats: int = 1           # runs of each problem and mode
    scale: float | None = 100.0  # the full score; None: the score is the points earned
    digits: int = 1            # decimals of the scores in gradebook.csv
    visibility: str = "visible"  # Gradescope's tests' visibility
    rules: tuple[Rule, ...] = ()

    def items(self, problems: list[str]) -> list[Item]:
        """Each graded problem x mode, in the problems' then the modes' order; RubricError
        for a rule that matches no problem."""
        for number, rule in enumerate(self.rules, 1):
            if not any(fnmatch.fnmatchcase(name, rule.match) for name in problems):
                raise RubricError(f"problems entry {number} (match {rule.match!r}) matches "
                                  "no problem")
        found = []
        for name in problems:
            settings = self._settings(name)
            modes, weight = settings.pop("modes"), settings.pop("weight")
            if settings.pop("skip"):
                continue
            if name.endswith(".kp"):
                modes = (KINOPLAN,)
            found += [Item(name, mode, weight * self.mode_weight(mode), **settings)
                      for mode in modes]
        return found

    def _settings(self, name: str) -> dict:
        """The keys for one problem: the defaults, then each matching rule in order."""
        settings = {"modes": self.modes, "weight": self.weight, "timeout": self.timeout,
                    "repeats": self.repeats, "visibility": self.visibility, "skip": False}
        for rule in self.rules:
            if fnmatch.fnmatchcase(name, rule.match):
                settings.update({key: value for key, value in dataclasses.asdict(rule).items()
                                 if key != "match" and value is not None})
        return settings

    def mode_weight(self, mode: str) -> float:
        return dict(self.mode_weights).get(mode, 1.0)

    def points(self, items: list[Item]) -> dict[tuple[str, str], float]:
        """What each item is worth: its weight, scaled so they add up to ``scale``."""
        total = sum(item.weight for item in items)
        factor = self.scale / total if self.scale is not None and total > 0 else 1.0
        return {(item.problem, item.mode): item.weight * factor for item in items}

    def full_score(self, items: list[Item]) -> float:
        return round(sum(self.points(items).values()), self.digits)


def score(points: dict[tuple[str, str], float], shares: dict[tuple[str, str], float],
          digits: int) -> float:
    """The points earned: each item's points times the share of its runs that were valid."""
    return round(sum(worth * shares.get(key, 0.0) for key, worth in points.items()), digits)


# --- the TOML file ---------------------------------------------------------------------

def load_rubric(path: Path) -> Rubric:
    """The rubric in ``path``; RubricError (one line) for anything it cannot be."""
    toml = _toml_reader()
    try:
        with open(path, "rb") as file:
            data = file.read(MAX_RUBRIC_BYTES + 1)
    except OSError as error:
        raise RubricError(f"{path}: cannot read it: {error.strerror or error}") from None
    if len(data) > MAX_RUBRIC_BYTES:
        raise RubricError(f"{path}: more than {MAX_RUBRIC_BYTES} bytes")
    try:
        table = toml.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, toml.TOMLDecodeError) as error:
        raise RubricError(f"{path}: not TOML: {error}") from None
    try:
        return rubric_from_table(table)
    except RubricError as error:
        raise RubricError(f"{path}: {error}") from None


def _toml_reader():
    """Python 3.11's tomllib, or the tomli backport; RubricError without either."""
    try:
        import tomllib
        return tomllib
    except ImportError:
        pass
    try:
        import tomli
        return tomli
    except ImportError:
        raise RubricError("reading a rubric needs Python 3.11 or newer, or the tomli "
                          "package (pip install tomli)") from None


_TOP = {"modes", "weight", "mode_weights", "timeout", "repeats", "scale", "visibility",
        "problems"}
_RULE = {"match", "modes", "weight", "timeout", "repeats", "visibility", "skip"}


def rubric_from_table(table: dict) -> Rubric:
    """A rubric from a parsed TOML table (keys checked, values bounded)."""
    _known(table, _TOP, "")
    given = _values(table, "")
    if "mode_weights" in table:
        given["mode_weights"] = _mode_weights(table["mode_weights"])
    # A rubric file without a scale scores in its own units: the points of its weights.
    given["scale"] = (_number(table["scale"], "scale", low=0.0, strict=True)
                      if "scale" in table else None)
    entries = table.get("problems", [])
    if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
        raise RubricError("problems: expected [[problems]] tables")
    rules = tuple(_rule(entry, f"problems entry {n}: ") for n, entry in enumerate(entries, 1))
    return Rubric(rules=rules, **given)


def _rule(entry: dict, where: str) -> Rule:
    _known(entry, _RULE, where)
    match = entry.get("match")
    if not isinstance(match, str) or not match:
        raise RubricError(f"{where}match: expected a file name or a glob")
    return Rule(match=match, **_values(entry, where))


def _known(table: dict, keys: set[str], where: str) -> None:
    unknown = sorted(set(table) - keys)
    if unknown:
        raise RubricError(f"{where}unknown key {unknown[0]!r} (known: {', '.join(sorted(keys))})")


def _values(table: dict, where: str) -> dict:
    """The keys a rule and the top level share, checked."""
    found = {}
    if "modes" in table:
        found["modes"] = _modes(table["modes"], f"{where}modes")
    if "weight" in table:
        found["weight"] = _number(table["weight"], f"{where}weight", low=0.0)
    if "timeout" in table:
        found["timeout"] = _number(table["timeout"], f"{where}timeout", low=0.0, strict=True,
                                   high=MAX_TIMEOUT)
    if "repeats" in table:
        found["repeats"] = _integer(table["repeats"], f"{where}repeats", 1, MAX_REPEATS)
    if "visibility" in table:
        if table["visibility"] not in VISIBILITIES:
            raise RubricError(f"{where}visibility: expected one of {', '.join(VISIBILITIES)}")
        found["visibility"] = table["visibility"]
    if "skip" in table:
        if not isinstance(table["skip"], bool):
            raise RubricError(f"{where}skip: expected true or false")
        found["skip"] = table["skip"]
    return found


def check_modes(modes) -> tuple[str, ...]:
    """Distinct modes among MODE_FLAGS, at least one; ValueError otherwise."""
    if isinstance(modes, str) or not isinstance(modes, (list, tuple)):
        raise ValueError("expected a list of modes")
    if (not modes or len(set(modes)) != len(modes)
            or any(mode not in MODE_FLAGS for mode in modes)):
        raise ValueError(f"expected distinct modes among {','.join(MODE_FLAGS)}")
    return tuple(modes)


def _modes(value, where: str) -> tuple[str, ...]:
    try:
        return check_modes(value)
    except ValueError as error:
        raise RubricError(f"{where}: {error}") from None


def _mode_weights(table) -> tuple[tuple[str, float], ...]:
    if not isinstance(table, dict):
        raise RubricError("mode_weights: expected a table, e.g. mode_weights = {grad = 2}")
    known = (*MODE_FLAGS, KINOPLAN)
    for mode in table:
        if mode not in known:
            raise RubricError(f"mode_weights: unknown mode {mode!r} (known: {', '.join(known)})")
    return tuple((mode, _number(weight, f"mode_weights.{mode}", low=0.0))
                 for mode, weight in table.items())


def _number(value, where: str, low: float, strict: bool = False,
            high: float = 1e9) -> float:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) \
        and math.isfinite(value) and (value > low if strict else value >= low) and value <= high
    if not ok:
        raise RubricError(f"{where}: expected a number {'above' if strict else 'at least'} "
                          f"{low:g} and at most {high:g}")
    return float(value)


def _integer(value, where: str, low: int, high: int) -> int:
    if not isinstance(value, int) or isinstance(value, bool) or not low <= value <= high:
        raise RubricError(f"{where}: expected an integer from {low} to {high}")
    return value
