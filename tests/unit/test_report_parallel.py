"""The report's figures drawn in two forked processes (gearcli/report/parallel.py) are the same
files, byte for byte, as drawn one by one; where forking is not safe it is not used."""

from __future__ import annotations

import os
import subprocess
import sys
import threading

import pytest

from gearcli.report import parallel
from tests.conftest import ROOT
from tests.physics.simrun import write_run

SHORT = ["drive.speed=STEP(time, 0, 0, 0.2, 3000)", "load.torque=STEP(time, 0, 0, 0.2, 4.5e5)",
         "run.end_time=0.6"]


def _report(folder, jobs: str) -> dict[str, bytes]:
    """`gearcli report` in a fresh, single-threaded process with GEARCLI_REPORT_JOBS=jobs;
    the figures it wrote."""
    env = {**os.environ, "GEARCLI_REPORT_JOBS": jobs,  # this checkout's gearcli first
           "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT),
                                                       os.environ.get("PYTHONPATH")]))}
    probe = ("import sys; import gearcli.report.parallel as p; n = p.workers; "
             "p.workers = lambda k: print('workers', n(k), file=sys.stderr) or n(k); "
             "from gearcli.cli import main; sys.argv = ['gearcli', 'report', "
             f"{str(folder)!r}, '--force', '-q']; main()")
    done = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    workers = int(done.stderr.split("workers ")[1].split()[0])
    assert workers == (2 if jobs == "2" and (os.cpu_count() or 1) >= 2 else 1), done.stderr
    return {p.name: p.read_bytes() for p in sorted((folder / "figures").glob("*.png"))}


@pytest.mark.skipif(sys.platform != "linux", reason="forked workers are used on Linux only")
def test_forked_figures_equal_the_ones_drawn_in_process(tmp_path):
    folder = write_run(tmp_path / "run", SHORT, analysed=True)
    one = _report(folder, "1")
    two = _report(folder, "2")
    assert len(one) >= parallel.MIN_JOBS and one == two


def test_no_fork_beside_other_threads_or_for_few_figures(monkeypatch):
    monkeypatch.delenv("GEARCLI_REPORT_JOBS", raising=False)
    stop = threading.Event()
    t = threading.Thread(target=stop.wait)
    t.start()
    try:
        assert parallel.workers(8) == 1  # another thread: a fork could copy a held lock
    finally:
        stop.set()
        t.join()
    assert parallel.workers(parallel.MIN_JOBS - 1) == 1
    monkeypatch.setenv("GEARCLI_REPORT_JOBS", "1")
    assert parallel.workers(8) == 1


def test_no_fork_on_a_busy_machine(monkeypatch):
    """Measured: on a busy machine two workers were slower than one (parallel.py)."""
    monkeypatch.delenv("GEARCLI_REPORT_JOBS", raising=False)
    monkeypatch.setattr(os, "getloadavg", lambda: (64.0, 64.0, 64.0))
    assert parallel.workers(8) == 1
