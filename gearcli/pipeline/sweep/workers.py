"""Executors of a sweep's points: serially, in local worker processes, or on a Dask cluster.

Each yields one result per payload, in completion order, and no worker fault ends the study:

- A local worker process that dies (killed from outside, the kernel's out-of-memory killer)
  breaks its pool (``BrokenProcessPool``). The payloads in flight then are the suspects (at most
  two a worker: IN_FLIGHT_PER_WORKER); when there are several, each is run
  again alone in a new pool, so only the one that ends its worker again is given up. A given-up
  payload becomes ``lost(payload, reason)`` (a failed row, reason "worker killed"), the others
  go on in a new pool.
- A payload without a result within the per-point timeout (:class:`PointTimeout`; a hung local
  worker, a Dask cluster whose only worker died) becomes a failed row ("timed out"): local
  workers are stopped and the others rerun, on Dask the waiting ends.
- Every failure carries a ``cause``: ``environment`` (worker killed, timeout, out of disk space
  or quota, out of memory: a resume retries it) or ``case`` (the case itself: kept).
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import time
from collections import deque
from collections.abc import Callable, Iterator

from gearcli import guards
from gearcli.errors import OutputError

#: ``cause`` of a failed point: the machine (retried on resume) or the case (kept).
ENVIRONMENT = "environment"
CASE = "case"
#: errno values of a machine's fault, not the case's (full disk, quota, I/O, memory, a
#: read-only or inaccessible folder): the point can succeed once that is fixed.
ENVIRONMENT_ERRNOS = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EIO, errno.ENOMEM,
                                errno.EROFS, errno.EACCES, errno.EFBIG})
KILLED = ("worker killed (its process ended abruptly: out of memory, or killed from outside); "
          "a resume retries it")

#: The solver stops at 5e6 steps (core/layout.py, max_steps). A step costs ~1 us to ~10 us
#: measured on the seed case; the default per-point timeout allows 100 us a step (10x the
#: slowest) plus a minute to load the compiled solver and write the results: 560 s. A point
#: that ran longer is taken as lost (a hung or dead worker).
SOLVER_MAX_STEPS = 5e6
SECONDS_PER_STEP_BOUND = 100e-6
START_S = 60.0
DEFAULT_POINT_TIMEOUT_S = START_S + SOLVER_MAX_STEPS * SECONDS_PER_STEP_BOUND
#: With the default timeout, a point may also take this many times the slowest point so far.
SLOWEST_FACTOR = 20.0


class PointTimeout:
    """Seconds a point may run: the given limit, or the default that grows with the slowest
    point seen (``observe``)."""

    def __init__(self, seconds: float | None = None):
        self.fixed = seconds
        self.slowest_s = 0.0

    def observe(self, seconds: float) -> None:
        self.slowest_s = max(self.slowest_s, seconds)

    @property
    def seconds(self) -> float:
        if self.fixed is not None:
            return self.fixed
        return max(DEFAULT_POINT_TIMEOUT_S, SLOWEST_FACTOR * self.slowest_s)


def timed_out(seconds: float) -> str:
    return (f"timed out: no result within {seconds:g} s (a hung or lost worker); a resume "
            "retries it (--point-timeout sets the limit)")


def failure_cause(exc: BaseException) -> str:
    """``environment`` for out of memory and the errno values of ENVIRONMENT_ERRNOS anywhere in
    the exception's chain (an OutputError raised ``from None`` still has its context)."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        seen.add(id(exc))
        if isinstance(exc, MemoryError):
            return ENVIRONMENT
        if isinstance(exc, OSError) and exc.errno in ENVIRONMENT_ERRNOS:
            return ENVIRONMENT
        exc = exc.__cause__ or exc.__context__
    return CASE


def lost_point(payload: dict, reason: str, cause: str = ENVIRONMENT) -> dict:
    """The row of a point whose worker gave no result (``cause``: ENVIRONMENT or CASE)."""
    return {"point": payload["index"], "case_hash": payload["case_hash"], "status": "failed",
            "error": reason, "cause": cause}


#: (payload, reason, cause) -> the failed result of a payload whose worker gave none
Lost = Callable[..., object]


# --- local workers -----------------------------------------------------------------------------
def warm_up(parent_pid: int | None = None) -> None:
    """Worker initializer: import the pipeline (and load the compiled solver) once; with
    ``parent_pid``, end the worker when that process (the sweep) is gone."""
    if parent_pid is not None:
        watch_parent(parent_pid)
        _default_signals()
    import gearcli.pipeline.simulate  # noqa: F401


def _default_signals() -> None:
    """In a forked worker: SIGTERM/SIGHUP end it (not the CLI's handler inherited from the
    sweep, which would only fail the point in flight); Ctrl-C is the sweep's to handle."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return
    for name in ("SIGTERM", "SIGHUP"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)


#: How often a worker checks that the sweep that started it still runs [s].
PARENT_POLL_S = 0.5


def watch_parent(pid: int) -> None:
    """End this process soon after process ``pid`` ends, even by kill -9 (which runs no
    cleanup in the sweep): a daemon thread polls it. Idempotent per process; nothing to do
    in the process ``pid`` itself."""
    import threading

    if pid == os.getpid() or getattr(watch_parent, "watching", None) == pid:
        return
    watch_parent.watching = pid
    direct = os.getppid() == pid  # then re-parenting tells at once, whatever the pid reuse

    def watch() -> None:
        while True:
            time.sleep(PARENT_POLL_S)
            if (direct and os.getppid() != pid) or not _alive(pid):
                os._exit(1)

    threading.Thread(target=watch, name="gearcli-parent-watch", daemon=True).start()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def serial(payloads: list[dict], fn) -> Iterator[dict]:
    warm_up()
    for p in payloads:
        yield fn(p)


def processes(payloads: list[dict], jobs: int, fn, lost: Lost = lost_point,
              timeout: PointTimeout | None = None) -> Iterator:
    """``fn`` over ``payloads`` in pools of ``jobs`` worker processes (module notes)."""
    timeout = timeout or PointTimeout()
    queue = deque(payloads)
    while queue:
        suspects = yield from _pool_pass(queue, jobs, fn, lost, timeout)
        if len(suspects) == 1:
            yield lost(suspects[0], KILLED)
            continue
        for p in suspects:  # which of them ended its worker: each alone
            if (yield from _pool_pass(deque([p]), 1, fn, lost, timeout)):
                yield lost(p, KILLED)


def _new_pool(jobs: int):
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    ctx = mp.get_context("fork") if "fork" in mp.get_all_start_methods() else None
    return ProcessPoolExecutor(max_workers=jobs, mp_context=ctx, initializer=warm_up,
                               initargs=(os.getpid(),))


#: Payloads in flight per worker: one running, one queued, so that a worker that finishes
#: never waits for the sweep (writing its row) to hand it the next point.
IN_FLIGHT_PER_WORKER = 2


def _pool_pass(queue: deque, jobs: int, fn, lost: Lost, timeout: PointTimeout):
    """Run payloads taken from ``queue`` in one pool, at most IN_FLIGHT_PER_WORKER x ``jobs``
    in flight, until the queue is empty (returns []) or the pool breaks (returns the payloads
    in flight then). A payload's clock starts when it is among the ``jobs`` oldest in flight
    (a worker is free for it)."""
    from concurrent.futures import FIRST_COMPLETED, wait

    pool = _new_pool(jobs)
    flight: dict = {}  # future -> [payload, start [s] or None], in submission order
    try:
        while queue or flight:
            while queue and len(flight) < IN_FLIGHT_PER_WORKER * jobs:
                p = queue.popleft()
                flight[pool.submit(fn, p)] = [p, None]
            now = time.monotonic()
            for entry in list(flight.values())[:jobs]:
                entry[1] = now if entry[1] is None else entry[1]
            oldest = min(t for _, t in flight.values() if t is not None)
            wait_s = max(0.0, oldest + timeout.seconds - now)
            done, _ = wait(list(flight), timeout=wait_s, return_when=FIRST_COMPLETED)
            if not done:  # a point past its time: stop the pool, rerun the others
                yield from _expire(flight, queue, lost, timeout)
                _stop(pool)
                return []
            broken = yield from _collect(done, flight, timeout, lost)
            if broken:
                wait(list(flight), timeout=30.0)  # the pool fails them all at once
                broken += yield from _collect(list(flight), flight, timeout, lost)
                _stop(pool)
                return broken + [p for p, _ in flight.values()]
    except BaseException:  # Ctrl-C, SIGTERM, a closed generator: points in flight are lost
        _stop(pool)
        raise
    pool.shutdown(wait=True)
    return []


def _collect(done, flight: dict, timeout: PointTimeout, lost: Lost):
    """Yield the results of the finished futures ``done`` (removed from ``flight``); returns
    the payloads whose worker died (BrokenProcessPool)."""
    from concurrent.futures.process import BrokenProcessPool

    broken = []
    for fut in done:
        if not fut.done():
            continue
        p, t0 = flight.pop(fut)
        exc = fut.exception()
        if isinstance(exc, BrokenProcessPool):
            broken.append(p)
        elif exc is not None:  # fn catches the case's errors: this is the machinery's
            yield lost(p, f"internal error: {exc!r}", failure_cause(exc))
        else:
            if t0 is not None:
                timeout.observe(time.monotonic() - t0)
            yield fut.result()
    return broken


def _expire(flight: dict, queue: deque, lost: Lost, timeout: PointTimeout):
    """The points past their time fail; the others go back to the front of the queue."""
    now = time.monotonic()
    back = []
    for fut, (p, t0) in flight.items():
        if t0 is not None and now - t0 >= timeout.seconds:
            yield lost(p, timed_out(timeout.seconds))
        elif fut.done() and fut.exception() is None:
            yield fut.result()
        else:
            back.append(p)
    queue.extendleft(reversed(back))  # in their order, before the rest
    flight.clear()


def _stop(pool) -> None:
    """Stop the pool's worker processes now (its shutdown alone waits for running points)."""
    procs = list((getattr(pool, "_processes", None) or {}).values())  # shutdown drops them
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in procs:
        with contextlib.suppress(Exception):
            proc.terminate()
    for proc in procs:
        with contextlib.suppress(Exception):
            proc.join(5.0)


# --- Dask --------------------------------------------------------------------------------------
def dask(payloads: list[dict], jobs: int, scheduler: str, fn, lost: Lost = lost_point,
         timeout: PointTimeout | None = None) -> Iterator:
    """``fn`` over ``payloads`` on Dask: an embedded LocalCluster ("local") or the scheduler at
    an address. A point that errs on a lost worker, or when no point finishes within the
    timeout, becomes ``lost(payload, reason)``."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise OutputError("--scheduler needs Dask: pip install 'dask[distributed]'") from None
    timeout = timeout or PointTimeout()
    cluster = None
    net_s = guards.NETWORK_TIMEOUT_S
    if scheduler == "local":
        cluster = LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    else:
        security = tls_security(scheduler)
        probe_scheduler(scheduler, net_s)
        client = bounded(lambda: Client(scheduler, timeout=f"{net_s}s", security=security),
                         net_s * 2, f"--scheduler {scheduler}")
    try:
        try:
            client.wait_for_workers(1, timeout=net_s * 3)
        except (TimeoutError, OSError) as exc:
            raise OutputError(f"--scheduler {scheduler}: no worker joined within "
                              f"{3 * net_s:g} s ({exc.__class__.__name__})") from None
        # local workers end with the sweep (a LocalCluster's nannies run in this process:
        # they are not watched, they end with it)
        client.run(warm_up, os.getpid() if cluster is not None else None)
        yield from _dask_results(client, payloads, fn, lost, timeout)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _dask_results(client, payloads, fn, lost: Lost, timeout: PointTimeout) -> Iterator:
    """Results as they come; when none comes within the timeout, the rest are lost."""
    from distributed import wait

    futures = {client.submit(fn, p, pure=False): p for p in payloads}
    pending = set(futures)
    last = time.monotonic()
    while pending:
        try:
            done, pending = wait(pending, timeout=timeout.seconds, return_when="FIRST_COMPLETED")
        except TimeoutError:
            for fut in pending:
                fut.cancel()
                yield lost(futures[fut], timed_out(timeout.seconds))
            return
        now = time.monotonic()
        timeout.observe(now - last)
        last = now
        for fut in done:
            if fut.status == "finished":
                yield fut.result()
                continue
            exc = fut.exception()  # KilledWorker: the workers running it died
            reason = KILLED if type(exc).__name__ == "KilledWorker" else \
                f"internal error: {exc!r}"
            yield lost(futures[fut], reason,
                       ENVIRONMENT if reason == KILLED else failure_cause(exc))


_ADDRESS = re.compile(r"^(tcp|tls)://(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9.-]+):(\d{1,5})$")


def check_scheduler(value) -> str | None:
    """None, 'local' or PROTOCOL://HOST:PORT; anything else an OutputError (the command
    line's usage error, exit 2)."""
    if value is None or value == "local":
        return value
    m = _ADDRESS.match(value) if isinstance(value, str) else None
    if m is None or not 0 < int(m.group(3)) < 65536:
        raise OutputError(f"{value!r:.60}: expected 'local' or tcp://HOST:PORT (or tls://)")
    return value


def tls_security(address: str):
    """For tls:// the Dask configuration's TLS files (distributed.comm.tls.*); without them a
    clear error rather than the client's TypeError."""
    if not address.startswith("tls://"):
        return None
    from distributed.security import Security

    security = Security()
    if not security.tls_ca_file or not security.tls_client_cert:
        raise OutputError(f"--scheduler {address}: tls:// needs the Dask TLS configuration "
                          "(distributed.comm.tls.ca-file, .client.cert and .client.key, e.g. "
                          "DASK_DISTRIBUTED__COMM__TLS__CA_FILE=ca.pem and "
                          "DASK_DISTRIBUTED__COMM__TLS__CLIENT__CERT=client.pem)")
    return security


def probe_scheduler(address: str, timeout: float) -> None:
    """Connect to a ``tcp://host:port`` scheduler and wait for the first bytes of its Dask
    handshake (a scheduler writes it as soon as it accepts): a peer that accepts but never
    speaks Dask is refused after ``timeout`` instead of hanging the client forever."""
    import socket
    from urllib.parse import urlsplit

    if not address.startswith("tcp://"):
        return  # tls:// and others: the client's own timeouts
    parts = urlsplit(address)
    try:
        with socket.create_connection((parts.hostname, parts.port), timeout=timeout) as sock:
            sock.settimeout(timeout)
            if not sock.recv(1):
                raise OutputError(f"--scheduler {address}: the peer closed the connection; "
                                  "expected a Dask scheduler")
    except TimeoutError:
        raise OutputError(f"--scheduler {address}: accepts connections but sent no Dask "
                          f"handshake within {timeout:g} s; expected a Dask scheduler") from None
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise OutputError(f"--scheduler {address}: cannot connect ({reason})") from None


def bounded(make, timeout: float, what: str):
    """``make()`` in a daemon thread, given up after ``timeout`` s (an OutputError naming
    ``what``). A connection that hangs past its own timeouts then cannot hang the sweep."""
    import threading

    box: dict = {}

    def target() -> None:
        try:
            box["value"] = make()
        except BaseException as exc:  # re-raised in the caller
            box["error"] = exc

    thread = threading.Thread(target=target, name="gearcli-dask-connect", daemon=True)
    thread.start()
    thread.join(timeout)
    if thread.is_alive():
        raise OutputError(f"{what}: no Dask handshake within {timeout:g} s; expected a Dask "
                          "scheduler")
    if "error" in box:
        exc = box["error"]
        if isinstance(exc, OSError | TimeoutError | ValueError | TypeError):
            raise OutputError(f"{what}: cannot connect ({exc})") from None
        raise exc
    return box["value"]
