"""Start one command, wait for it, and write its exit status, wall time and peak memory.

    python -S -I benchmarks/launch.py REPORT_FILE COMMAND [ARGS...]

The harness starts every planner through this small process. On Linux a
process's peak resident memory (``ru_maxrss``) includes the size of the
process it was forked from, so a planner forked straight from a harness worker
(tens of MB after validating large outputs) would report the worker's size.
This interpreter, started without site packages, is about 8 MB, less than any
planner's own peak, so the ``ru_maxrss`` it collects is the planner's. The
wall time is measured here too, from just before the fork to the reaping,
without this process's own start-up. stdin, stdout and stderr pass through.

REPORT_FILE gets one line: ``exit_status wall_seconds max_rss_kilobytes``
(the exit status negative when a signal ended the command). Standard library
only: run with -S -I, it must not import the project.
"""

import os
import sys
import time


def main() -> int:
    if len(sys.argv) < 3:
        sys.stderr.write("usage: launch.py REPORT_FILE COMMAND [ARGS...]\n")
        return 2
    report, command = sys.argv[1], sys.argv[2:]
    began = time.perf_counter()
    pid = os.fork()
    if pid == 0:
        try:
            os.execv(command[0], command)
        except OSError as error:
            os.write(2, f"launch.py: cannot run {command[0]}: {error}\n".encode())
        os._exit(127)
    _, status, usage = os.wait4(pid, 0)
    wall = time.perf_counter() - began
    exit_status = os.waitstatus_to_exitcode(status)
    with open(report, "w") as handle:
        handle.write(f"{exit_status} {wall!r} {usage.ru_maxrss}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
