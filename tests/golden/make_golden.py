"""Record golden.json: SHA-256 of stdout and the exit status of every pinned run.

Run only on purpose (a change of output that is meant): ``python tests/golden/make_golden.py``
re-records every case; ``... make_golden.py grad left`` only those vehicles' cases, keeping
the others' records. Each run says how many records changed, per vehicle.
"""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
from collections import Counter
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


def main(vehicles: list[str]) -> None:
    out = Path(__file__).resolve().parent / "golden.json"
    before = json.loads(out.read_text()) if out.exists() else {}
    chosen = [case for case in cases() if not vehicles or case[0] in vehicles]
    with ThreadPoolExecutor(os.cpu_count() or 2) as pool:
        golden = dict(before, **dict(pool.map(run_case, chosen)))
    out.write_text(json.dumps(golden, indent=1, sort_keys=True) + "\n")
    changed = Counter(ident.split("/")[0] for ident in golden if golden[ident] != before.get(ident))
    print(f"{len(chosen)} cases recorded in {out}; changed: {dict(changed) or 'none'}",
          file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1:])
