"""``python -m rrt_cli``: the planner with the compiled modules when their build is
fresh, as ``./run.sh`` runs it (the benchmark harness starts it this way). Silent
about it: ``./run.sh -stats`` names the build that ran."""

from rrt_startup.compiled import activate

activate()  # before the planner's modules are imported

from rrt_cli.cli import entry_point  # noqa: E402

entry_point()
