"""Build rrt-validator's launcher (validator/launch.c) into
.build/launcher/rrt-validator-launch, with its source's content key compiled in.

Usage: ``python tools/build_launcher.py`` (``./make.sh`` runs it, both targets).
Exit 0 when built or already built from this source; 1 with one line when the C
compiler fails or is missing, the old launcher then removed (./rrt-validator then
starts the planner itself, as it does without one). The new file is written beside
the old and renamed over it: a validator starting meanwhile runs one or the other.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from rrt_startup.launch import launcher_key  # noqa: E402

SOURCE = ROOT / "validator" / "launch.c"
TARGET = ROOT / ".build" / "launcher" / "rrt-validator-launch"
KEY = TARGET.with_name("key")  # the content key of the source the launcher was built from


def main() -> int:
    key = launcher_key()
    if TARGET.exists() and KEY.exists() and KEY.read_text() == key:
        return 0
    TARGET.parent.mkdir(parents=True, exist_ok=True)
    compiler = os.environ.get("CC", "cc").split()
    work = TARGET.with_name(f".{TARGET.name}-{os.getpid()}")
    try:
        if shutil.which(compiler[0]) is None:
            raise OSError(f"no C compiler ({compiler[0]}) on PATH")
        subprocess.run([*compiler, "-O2", "-Wall", f'-DRRT_LAUNCH_KEY="{key}"', "-o",
                        str(work), str(SOURCE)], check=True, capture_output=True, text=True)
        os.replace(work, TARGET)
        KEY.write_text(key)
        return 0
    except (OSError, subprocess.CalledProcessError) as error:
        detail = getattr(error, "stderr", "") or str(error)
        print(f"build_launcher: {detail.strip().splitlines()[-1] if detail.strip() else error}",
              file=sys.stderr)
        TARGET.unlink(missing_ok=True)
        return 1
    finally:
        work.unlink(missing_ok=True)


if __name__ == "__main__":
    sys.exit(main())
