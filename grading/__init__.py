"""``rrt-grade``: grade a class of submissions (or a sweep) through the validator.

Library first: :func:`grading.grade.grade` takes a :class:`grading.config.GradeConfig`
and returns the finished rows; ``grading/cli.py`` is a thin command line over it.
"""

from grading.config import GradeConfig, Limits, ScoreRule

__all__ = ["GradeConfig", "Limits", "ScoreRule"]
