"""Record golden.json: SHA-256 of stdout and the exit status of every pinned run.

Run only on purpose (a change of output that is meant): ``python tests/golden/make_golden.py``.
"""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from golden_cases import PROBLEM_DIR, ROOT, argv, case_id, cases  # noqa: E402


def run_case(case) -> tuple[str, dict]:
    vehicle, planner, problem, seed = case
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "rrt_cli", *argv(vehicle, planner, seed)],
                          stdin=open(PROBLEM_DIR / problem, "rb"), capture_output=True,
                          cwd=ROOT, env=env)
    return case_id(*case), {"sha256": hashlib.sha256(done.stdout).hexdigest(),
                            "exit": done.returncode, "bytes": len(done.stdout)}


def main() -> None:
    with ThreadPoolExecutor(os.cpu_count() or 2) as pool:
        golden = dict(pool.map(run_case, cases()))
    out = Path(__file__).resolve().parent / "golden.json"
    out.write_text(json.dumps(golden, indent=1, sort_keys=True) + "\n")
    print(f"{len(golden)} cases written to {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
