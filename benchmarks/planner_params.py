"""Our planner with some ``Params`` fields set: ``python -m benchmarks.planner_params b=3
-planner blossom -seed 1 < problem.kp`` is ``python -m rrt_cli -planner blossom -seed 1``
planning with ``Params(b=3)``. The harness runs blossom's b = 1 and 3 this way
(``rrt_cli`` takes no option for a planner's parameters); everything else, the
output and the exit statuses, is ``rrt_cli``'s.
"""

from __future__ import annotations

import dataclasses
import functools
import sys

from cli_common import EXIT_USAGE, say


def _overrides(argv: list[str]) -> tuple[dict[str, str], list[str]]:
    """The leading ``NAME=VALUE`` words, and the rest of the command line."""
    given: dict[str, str] = {}
    while argv and "=" in argv[0] and not argv[0].startswith("-"):
        name, value = argv[0].split("=", 1)
        given[name] = value
        argv = argv[1:]
    return given, argv


def typed_overrides(params_class, given: dict[str, str]) -> dict:
    """Each value as its field's default's type; ValueError naming a bad one."""
    defaults = params_class()
    known = {f.name for f in dataclasses.fields(defaults)}
    typed = {}
    for name, text in given.items():
        if name not in known:
            raise ValueError(f"no parameter {name!r} (have {', '.join(sorted(known))})")
        kind = type(getattr(defaults, name))
        try:
            typed[name] = kind(text) if kind is not bool else text in ("1", "true", "True")
        except ValueError:
            raise ValueError(f"parameter {name}: {text!r} is not a {kind.__name__}") from None
    return typed


def main(argv: list[str]) -> None:
    from rrt_cli import cli
    from rrt_cli.planners import PLANNERS

    given, rest = _overrides(argv)
    name = rest[rest.index("-planner") + 1] if "-planner" in rest[:-1] else "rrt"
    if name not in PLANNERS:
        say(f"planner_params: error: no planner {name!r}")
        raise SystemExit(EXIT_USAGE)
    module = PLANNERS[name].load()
    try:
        typed = typed_overrides(module.Params, given)
    except ValueError as error:
        say(f"planner_params: error: {error}")
        raise SystemExit(EXIT_USAGE) from None
    module.Params = functools.partial(module.Params, **typed)  # what rrt_cli builds
    sys.argv = ["rrt_cli", *rest]
    cli.entry_point()


if __name__ == "__main__":
    main(sys.argv[1:])
