"""The planner, ``./run.sh``: its command line and the planners (``rrt_cli.planners``),
for the course's grid vehicles and the ``kinoplan 1`` family alike."""
