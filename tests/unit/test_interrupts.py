"""Signals inside a deferred section (gearcli.interrupts): held back until it ends, whichever
thread the kernel hands them to (the handler itself runs in the main thread mid-section when
another thread received the signal, as with a progress display running)."""

from __future__ import annotations

import os
import signal
import time

import pytest

from gearcli import interrupts
from gearcli.interrupts import Terminated


@pytest.fixture
def handlers():
    previous = {s: signal.signal(s, interrupts.on_signal) for s in (signal.SIGTERM,
                                                                    signal.SIGINT)}
    interrupts.received.clear()
    yield
    for s, h in previous.items():
        signal.signal(s, h)


def test_the_handler_run_mid_section_only_records(handlers):
    done = []
    with pytest.raises(Terminated) as caught:
        with interrupts.deferred():
            interrupts.on_signal(signal.SIGTERM, None)  # what runs when a thread got it
            done.append("moves")
    assert done == ["moves"] and caught.value.signum == signal.SIGTERM
    assert interrupts.received == [signal.SIGTERM]


def test_a_real_signal_arrives_after_the_section(handlers):
    done = []
    with pytest.raises(KeyboardInterrupt):
        with interrupts.deferred():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)
            done.append("moves")
    assert done == ["moves"]


def test_outside_a_section_the_signal_raises_at_once(handlers):
    with pytest.raises(Terminated):
        interrupts.on_signal(signal.SIGTERM, None)


def test_library_use_keeps_pythons_ctrl_c_and_the_default_action():
    """Without gearcli's handler (library use) a deferred section still holds Ctrl-C back and
    then raises KeyboardInterrupt as Python's own handler does; an ignored signal stays
    ignored."""
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    done = []
    with pytest.raises(KeyboardInterrupt):
        with interrupts.deferred():
            signal.raise_signal(signal.SIGINT)
            done.append("moves")
    assert done == ["moves"]
    previous = signal.signal(signal.SIGHUP, signal.SIG_IGN)
    try:
        with interrupts.deferred():
            signal.raise_signal(signal.SIGHUP)
        assert signal.getsignal(signal.SIGHUP) is signal.SIG_IGN
    finally:
        signal.signal(signal.SIGHUP, previous)


def test_a_forked_child_of_a_command_ends_on_sigterm_without_a_traceback(handlers):
    """A sweep worker killed at its timeout while starting up (before its initializer reset the
    signals) raised Terminated there: "Exception in initializer: Traceback ..." on the sweep's
    stderr. A process forked by a command takes the default action at once."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: report its handlers, then wait to be terminated
        try:
            ok = all(signal.getsignal(s) == signal.SIG_DFL for s in (signal.SIGTERM,
                                                                    signal.SIGHUP))
            os.write(write, b"1" if ok else b"0")
            time.sleep(30)
        finally:
            os._exit(0)  # never back into pytest
    os.close(write)
    reported = os.read(read, 1)
    os.close(read)
    os.kill(pid, signal.SIGTERM)
    _, status = os.waitpid(pid, 0)
    assert reported == b"1"
    assert os.WIFSIGNALED(status) and os.WTERMSIG(status) == signal.SIGTERM
    assert signal.getsignal(signal.SIGTERM) is interrupts.on_signal  # the command's own stays
