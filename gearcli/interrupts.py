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
import os
import signal
import threading

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


def _after_fork_in_child() -> None:
    """A process forked during a command (a sweep's worker) is not the command: SIGTERM and
    SIGHUP end it at once, by the default action, instead of raising :class:`Terminated`
    wherever it is (in its pool's start-up that printed a traceback on the sweep's stderr)."""
    for name in ("SIGTERM", "SIGHUP"):
        signum = getattr(signal, name, None)
        if signum is not None and signal.getsignal(signum) is on_signal:
            with contextlib.suppress(ValueError):  # not the main thread: nothing to reset
                signal.signal(signum, signal.SIG_DFL)


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_after_fork_in_child)


@contextlib.contextmanager
def deferred():
    """Hold SIGINT, SIGTERM and SIGHUP back for a short section (a few renames): a signal that
    arrives meanwhile takes effect when the section ends, as it would have without the section
    (an exception from :func:`on_signal` or Python's Ctrl-C handler, another handler called, or
    the default action). In the main thread the handlers are replaced for the section by one
    that records (library use, where gearcli's handler is not installed and numpy's threads
    may receive the signal); everywhere the signals are also masked in the calling thread."""
    global _depth
    names = [n for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n)]
    held = {getattr(signal, n) for n in names}
    masked = hasattr(signal, "pthread_sigmask")
    previous_mask = signal.pthread_sigmask(signal.SIG_BLOCK, held) if masked else None
    replaced = {}
    if threading.current_thread() is threading.main_thread():
        for signum in held:
            handler = signal.getsignal(signum)
            if handler is not on_signal and handler is not None:
                replaced[signum] = signal.signal(signum, _record)
    _depth += 1
    try:
        yield
    finally:
        _depth -= 1
        for signum, handler in replaced.items():
            signal.signal(signum, handler)
        if masked:
            signal.pthread_sigmask(signal.SIG_SETMASK, previous_mask)
        if not _depth and _pending:
            signum = _pending[0]
            _pending.clear()
            _deliver(signum, replaced.get(signum, on_signal))


def _record(signum, frame) -> None:
    _pending.append(signum)


def _deliver(signum: int, handler) -> None:
    """What ``signum`` would have done under ``handler`` (the one in place before the
    section)."""
    if handler is on_signal:  # (it recorded the signal when it held it back)
        raise_for(signum)
    if handler is signal.SIG_IGN:
        return
    if handler is signal.SIG_DFL:
        os.kill(os.getpid(), signum)  # the default action, with the handler restored
        return
    handler(signum, None)  # Python's default_int_handler raises KeyboardInterrupt
