"""The validator: runs any planner on a problem, re-simulates its output with the
shared core and checks it (SPEC section 3). Never imports rrt_cli.

``validator.checks.validate_output`` is the library entry point; ``validator.cli``
is the ``rrt-validator`` command.
"""
