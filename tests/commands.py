"""Running a script as a command of its own (a subprocess with the repository first on its path) and waiting for
the marker files it writes once it has reached the point a test signals it at."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[1]


def start_and_wait(script: Path, folder: Path, pattern: str, count: int, what: str,
                   seconds: float = 60.0) -> subprocess.Popen:
    """``script`` run with ``folder`` as its argument, returned once ``folder`` holds ``count`` files matching
    ``pattern`` (an AssertionError naming ``what`` with the script's stderr if it ends or ``seconds`` pass first)."""
    environment = dict(os.environ, PYTHONPATH=os.pathsep.join([str(REPOSITORY), os.environ.get("PYTHONPATH", "")]))
    command = subprocess.Popen([sys.executable, str(script), str(folder)], env=environment,
                               stderr=subprocess.PIPE, stdout=subprocess.DEVNULL)
    deadline = time.monotonic() + seconds
    while len(list(folder.glob(pattern))) < count:
        if command.poll() is not None or time.monotonic() > deadline:
            command.kill()
            raise AssertionError(f"{what} did not start: {command.communicate()[1].decode()}")
        time.sleep(0.05)
    return command
