"""A reader that closes the pipe early (`gearcli ... | head -1`) ends the command quietly.

A real pipe in a child process: the reader takes the first line and closes its end, so the
command's next write fails with EPIPE. Python's own note on SIGPIPE: exit 1, no second error
from the interpreter's final flush; the reader got what it asked for, so no message either.
"""

from __future__ import annotations

import os
import subprocess
import sys

from tests.conftest import SEED


def test_closing_the_pipe_after_the_first_line_is_quiet(tmp_path):
    # the time series of the seed is megabytes: far more than a pipe's buffer, so the write
    # after the reader closed fails (a short output, `geometry`, may fit the buffer: exit 0)
    argv = ["simulate", str(SEED), "-o", "-"]
    env = {**os.environ, "GEARCLI_LOG_DIR": str(tmp_path)}
    proc = subprocess.Popen([sys.executable, "-m", "gearcli", *argv], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, env=env)
    first = proc.stdout.readline()
    proc.stdout.close()  # the reader is gone
    stderr = proc.stderr.read().decode()
    rc = proc.wait(timeout=300)
    assert first.strip(), "the first line reached the reader"
    assert rc == 1, (rc, stderr)
    assert "Traceback" not in stderr and "error" not in stderr.lower(), stderr
    assert not list(tmp_path.glob("gearcli-error-*.log")), "no internal-error log"
