"""``rrt-grade``: grade a class of submissions (or a sweep) through the validator.

Library first: :func:`grading.grade.grade` takes a :class:`grading.config.GradeConfig`
(its :class:`grading.rubric.Rubric` says what is graded and how it is scored) and returns
the finished rows; ``grading/cli.py`` is a thin command line over it.
"""

from grading.config import GradeConfig, Limits
from grading.rubric import Rubric

__all__ = ["GradeConfig", "Limits", "Rubric"]
