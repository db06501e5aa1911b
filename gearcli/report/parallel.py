"""Draw the report's figures in two processes where that is safe (a fast report).

matplotlib draws on one core; the report's figures are independent, so on Linux a forked
worker per core (at most :data:`MAX_WORKERS`) draws and saves its share, the parent keeps the
order. Forking copies the parent, its imported modules and the figures' data included (nothing
is pickled on the way there; each worker returns only its FigureFile), so it is used only
where it is safe: a single-threaded process (a fork copies no other thread, and with other
threads running a lock they hold would stay locked in the child: pytest-xdist workers, a
notebook's kernel, Dask), on Linux (fork is the platform's way, not macOS's), with at least
:data:`MIN_JOBS` figures and two CPUs, and only on a machine with a CPU to spare (load
average below the CPU count minus one): on the busy 2-core development machine (load average
6-9) two workers were slower than one (wall 11.9-16.9 s against 9.6-12.9 s, CPU +10-30 %:
each worker warms matplotlib's text-layout caches again), while on a quiet one they share the
figures' ~60 % of the report's CPU time. Elsewhere the figures are drawn here, one by one: the
files are the same byte for byte (tests/unit/test_report_parallel.py). GEARCLI_REPORT_JOBS=1
forces one process. The workers ignore SIGINT and die on SIGTERM (the parent's handlers of
`gearcli/cli/common.py` stay the parent's): an interrupted report is the parent's to clean up.
"""

from __future__ import annotations

import os
import signal
import sys
import threading

#: Most worker processes (the report has 6-10 figures; two cores are the target machine).
MAX_WORKERS = 2
#: Fewer figures than this are drawn in the process itself (forking costs ~20 ms a worker).
MIN_JOBS = 4

_PENDING: tuple | None = None  #: (jobs, save, out_dir, svg) of the running render, for the workers


def workers(n_jobs: int) -> int:
    """How many processes draw ``n_jobs`` figures here (1: this process)."""
    env = os.environ.get("GEARCLI_REPORT_JOBS", "").strip()
    if env.isdigit() and int(env) >= 1:
        limit = int(env)
    else:
        limit = MAX_WORKERS
    if (sys.platform != "linux" or n_jobs < MIN_JOBS or limit < 2
            or threading.active_count() > 1):
        return 1
    try:
        cpus = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cpus = os.cpu_count() or 1
    if not env and os.getloadavg()[0] > cpus - 1.0:  # no CPU to spare
        return 1
    return max(1, min(limit, cpus, n_jobs))


def render(jobs, save, out_dir, svg: bool) -> list:
    """``save(name, caption, draw(), out_dir, svg)`` of every (name, caption, draw) job, in
    order; in :func:`workers` processes."""
    n = workers(len(jobs))
    if n < 2:
        return [save(name, caption, draw(), out_dir, svg) for name, caption, draw in jobs]
    import multiprocessing

    global _PENDING
    _PENDING = (jobs, save, out_dir, svg)
    try:
        with multiprocessing.get_context("fork").Pool(n, initializer=_worker_signals) as pool:
            return pool.map(_one, range(len(jobs)), chunksize=1)
    finally:
        _PENDING = None


def _worker_signals() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for name in ("SIGTERM", "SIGHUP"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), signal.SIG_DFL)


def _one(i: int):
    jobs, save, out_dir, svg = _PENDING
    name, caption, draw = jobs[i]
    return save(name, caption, draw(), out_dir, svg)
