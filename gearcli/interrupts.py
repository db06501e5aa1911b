"""Signals during a command: SIGTERM/SIGHUP as :class:`Terminated`, SIGINT as KeyboardInterrupt,
and short sections that must not be interrupted halfway (:func:`deferred`).

The command layer (:func:`gearcli.cli.common.handle_errors`) installs :func:`on_signal` for
the duration of a command. Python runs signal handlers in the main thread between bytecodes,
whichever thread the kernel delivered the signal to, so a thread mask alone cannot hold a
signal back while another thread (a progress display) runs; the handler therefore checks
whether a :func:`deferred` section is in progress and, if so, only records the signal, which is
raised when the section ends. Every signal seen is also recorded (:data:`received`), so that
an exception a library wraps around the handler's (pydantic's serializer does) can still be
told apart from a bug.
"""

from __future__ import annotations

import contextlib
import signal

#: Signals received during the command in progress (cleared when a command starts).
received: list[int] = []
_pending: list[int] = []
_depth = 0


class Terminated(BaseException):
    """SIGTERM or SIGHUP, raised in the main thread so that ``finally`` blocks and the
    cleanup of temporary folders (gearcli.io.outdir) run, as for Ctrl-C."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


def raise_for(signum: int) -> None:
    """Raise what ``signum`` means in a command: KeyboardInterrupt or :class:`Terminated`."""
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    raise Terminated(signum)


def on_signal(signum, frame) -> None:
    """The command's signal handler: raise now, or at the end of a :func:`deferred` section."""
    received.append(signum)
    if _depth:
        _pending.append(signum)
        return
    raise_for(signum)


@contextlib.contextmanager
def deferred():
    """Hold SIGINT, SIGTERM and SIGHUP back for a short section (a few renames): a signal that
    arrives meanwhile is raised when the section ends. Also masks them in the calling thread
    where the system allows it, which covers Python's default SIGINT handler (library use
    without :func:`on_signal`) when no other thread runs."""
    global _depth
    held = {getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n)}
    masked = hasattr(signal, "pthread_sigmask")
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, held) if masked else None
    _depth += 1
    try:
        yield
    finally:
        _depth -= 1
        if masked:
            signal.pthread_sigmask(signal.SIG_SETMASK, previous)
        if not _depth and _pending:
            signum = _pending[0]
            _pending.clear()
            raise_for(signum)
