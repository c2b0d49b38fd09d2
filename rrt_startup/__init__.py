"""What the launchers need before the planner or the validator runs: where bytecode
comes from (:mod:`rrt_startup.bytecode`), the compiled build of the hot modules
and its registry (:mod:`rrt_startup.compiled`), and the launchers' own start
(:mod:`rrt_startup.launch`).

Used by ``./run.sh``, ``./rrt-validator``, ``./make.sh``, ``./test.sh``,
``python -m rrt_cli`` and ``tools/build_compiled.py``; nothing in
``planning_core``, ``rrt_cli``'s planners or ``validator`` imports it.
"""
