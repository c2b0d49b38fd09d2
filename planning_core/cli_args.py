"""What every command line of the project shares: an argument parser whose errors
are one usage line and one error line on stderr with exit status 2 (never a
traceback), and the number types its options take."""

from __future__ import annotations

import argparse
import math
import sys

EXIT_USAGE = 2


class OneLineErrorParser(argparse.ArgumentParser):
    """``argparse`` with errors as ``usage: ...`` and ``PROG: error: ...``, exit 2."""

    def error(self, message):
        self.print_usage(sys.stderr)
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        raise SystemExit(EXIT_USAGE)


def positive_float(text: str) -> float:
    """An option value that must be a positive finite number (a time limit)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not (value > 0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"{text!r} must be a positive finite number")
    return value
