"""Benchmarks: a seeded problem suite, a harness that runs planners x vehicles x
problems x seeds in worker processes, and reports (CSV, Markdown, HTML with SVG plots,
PDF, OMPL logs, OMPL's database layout).

    python -m benchmarks --preset quick      # regenerate the suite, run, report

See docs/benchmarks.md. Kept import-free so that ``python -m benchmarks.ompl_planner``
starts as fast as a stand-alone script.
"""
