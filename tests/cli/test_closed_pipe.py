"""A reader that closes the pipe early (`gearcli ... | head -1`) ends the command quietly.

A real pipe in a child process: the reader takes the first line and closes its end, so the
command's next write fails with EPIPE. Python's own note on SIGPIPE: exit 1, no second error
from the interpreter's final flush; the reader got what it asked for, so no message either.
"""

from __future__ import annotations

import errno
import os
import subprocess
import sys

import pytest
import typer

from gearcli.cli.common import handle_errors
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


def _broken_pipe():
    raise BrokenPipeError(errno.EPIPE, "Broken pipe")  # a pipe that is not stdout's


@pytest.mark.parametrize("reader_gone", [True, False])
def test_only_a_closed_stdout_is_quiet(monkeypatch, capsys, reader_gone):
    """An EPIPE the command meets elsewhere while stdout's reader is still there (a pipe to
    another process, a FIFO it writes) is a failure: it is reported, exit 1. Quiet only when
    stdout itself is a pipe whose reader has gone."""
    r, w = os.pipe()
    stdout = os.fdopen(w, "w")
    reader = None if reader_gone else os.fdopen(r, "rb")
    if reader_gone:
        os.close(r)
    monkeypatch.setattr(sys, "stdout", stdout)
    try:
        with pytest.raises(typer.Exit) as exit_:
            handle_errors(_broken_pipe)()
    finally:
        monkeypatch.undo()
        stdout.close()
        if reader is not None:
            reader.close()
    assert exit_.value.exit_code == 1
    err = capsys.readouterr().err
    assert (err == "") if reader_gone else ("error: writing the output: Broken pipe" in err)
