"""One place that turns library errors into messages and exit codes (see gearcli.errors)."""

from __future__ import annotations

import errno
import functools
import os
import signal
import sys
import tempfile
import traceback
from contextlib import contextmanager
from pathlib import Path

import typer

from gearcli import interrupts
from gearcli.errors import ExitCode, GearcliError
from gearcli.guards import clip_message
from gearcli.interrupts import Terminated

#: errno values of a full or broken output stream or disk: the user's environment, not a bug.
_OUTPUT_ERRNOS = frozenset(getattr(errno, n) for n in (
    "ENOSPC", "EDQUOT", "EFBIG", "EPIPE", "EIO", "EROFS", "EACCES", "EPERM", "ENXIO")
    if hasattr(errno, n))


def handle_errors(func):
    """Decorator for every command: GearcliError -> one message line + its exit code;
    a full disk or a closed output stream -> exit 1; Ctrl-C -> 130; anything else -> exit 3
    with the traceback written to a log file."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        from gearcli.io import owner

        owner.command[0] = func.__name__  # the producer its results folders record
        try:
            with _signals_raise():
                result = func(*args, **kwargs)
                sys.stdout.flush()  # a full disk or a closed stdout shows up here, not at exit
            return result
        except (typer.Exit, typer.Abort, SystemExit):
            raise
        except Terminated as exc:  # temporary folders were removed on the way out
            _signal_exit(exc.signum)
        except GearcliError as exc:
            _echo_err(f"error: {clip_message(str(exc))}")
            raise typer.Exit(int(exc.exit_code)) from None
        except KeyboardInterrupt:
            _signal_exit(signal.SIGINT)
        except OSError as exc:
            if exc.errno not in _OUTPUT_ERRNOS:
                return _internal()
            _detach_stdout()
            where = f"{exc.filename}" if exc.filename else "writing the output"
            _echo_err(f"error: {where}: {exc.strerror or exc}")
            raise typer.Exit(int(ExitCode.INPUT)) from None
        except Exception:  # a bug: keep the traceback for the report, not on the screen
            if not interrupts.received:
                return _internal()
            # a signal's exception that a library wrapped in its own (pydantic's serializer
            # turns Terminated into a PydanticSerializationError): still the signal
            _signal_exit(interrupts.received[-1])

    return wrapper


def _signal_exit(signum: int):
    """The message and exit code of a command ended by a signal: 130 for Ctrl-C, 128 + n."""
    if signum == signal.SIGINT:
        _echo_err("interrupted")
        raise typer.Exit(int(ExitCode.INTERRUPTED)) from None
    _echo_err(f"terminated ({signal.Signals(signum).name})")
    raise typer.Exit(128 + signum) from None


@contextmanager
def _signals_raise():
    """During a command (main thread only) SIGTERM and SIGHUP raise Terminated and SIGINT
    KeyboardInterrupt, through :func:`gearcli.interrupts.on_signal`: held back inside
    :func:`gearcli.interrupts.deferred` sections, and recorded, so that an exception a library
    wraps around them (pydantic's serializer does) still ends as the signal."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    if hasattr(signal, "SIGXFSZ"):  # a file-size limit: the write raises EFBIG (exit 1)
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    names = [n for n in ("SIGTERM", "SIGHUP") if hasattr(signal, n)]
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        names.append("SIGINT")
    previous = {n: signal.signal(getattr(signal, n), interrupts.on_signal) for n in names}
    interrupts.received.clear()
    try:
        yield
    finally:
        for n, handler in previous.items():
            signal.signal(getattr(signal, n), handler)


def _internal():
    log = _write_log(traceback.format_exc())
    _echo_err(f"internal error: {clip_message(repr(sys.exc_info()[1]))}; traceback written "
              f"to {log} (please report it)")
    raise typer.Exit(int(ExitCode.INTERNAL)) from None


def _echo_err(text: str) -> None:
    """A message on stderr; a broken stderr is ignored (the exit code still tells)."""
    try:
        typer.echo(text, err=True)
    except OSError:
        pass


def _detach_stdout() -> None:
    """After stdout failed: point it at /dev/null so the interpreter's final flush does not
    fail again (and print a second, Python-level error)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):
        pass


def _write_log(text: str) -> Path:
    folder = Path(os.environ.get("GEARCLI_LOG_DIR", tempfile.gettempdir()))
    folder.mkdir(parents=True, exist_ok=True)
    fd, name = tempfile.mkstemp(prefix="gearcli-error-", suffix=".log", dir=folder)
    with os.fdopen(fd, "w") as fh:
        fh.write(text)
    return Path(name)


def display_units() -> str:
    """The display-unit system of this command line (``gearcli --units`` or GEARCLI_UNITS)."""
    from gearcli.cli.app import settings

    return settings["units"]


def option_quantities(texts, dim_name: str, option: str) -> tuple[float, ...] | None:
    """Values of an option that takes quantities (``--window 2 4``, ``--window '2 s' '4 s'``,
    ``--speed-range 0 '6000 rpm'``) in the internal unit of the gearcli.units dimension
    ``dim_name`` ("TIME", "ANGULAR_VELOCITY"); bare numbers are in its case-file default
    unit. None stays None; a bad value raises CaseError naming the option (exit 1)."""
    if texts is None:
        return None
    from gearcli import units
    from gearcli.errors import CaseError

    try:
        return units.parse_quantities(texts, getattr(units, dim_name))
    except units.UnitError as exc:
        raise CaseError(f"{option} {exc}") from None


def check_figure_path(option: str, path: Path | None, force: bool) -> None:
    """A figure file an option names (``--plot``, ``--orders``, ``--spectra``): a .png, .svg or
    .pdf name that is new (or ``force``), in an existing folder; checked before the work."""
    if path is None:
        return
    from gearcli.errors import OutputError
    from gearcli.io.files import check_new_file

    if path.suffix.lower() not in (".png", ".svg", ".pdf"):
        raise OutputError(f"{option} {path}: expected a file name ending in .png, .svg or .pdf")
    check_new_file(path, force, option)


def is_terminal() -> bool:
    return sys.stdout.isatty()


@contextmanager
def rich_progress(enabled: bool, columns, transient: bool = False):
    """A rich Progress on stderr when ``enabled`` and stderr is a terminal, else None.

    ``columns()`` returns the progress columns (called only when displayed, so rich stays
    unimported in pipelines)."""
    if not enabled or not sys.stderr.isatty():
        yield None
        return
    from rich.console import Console
    from rich.progress import Progress

    with Progress(*columns(), console=Console(stderr=True), transient=transient) as progress:
        yield progress


class _Reporter:
    """What a long command tells the terminal: ``reporter(text)`` names the current stage
    (a spinner with elapsed time), ``reporter.progress(t, t_start, t_end)`` turns it into a
    bar over the simulated time with the time remaining."""

    def __init__(self, progress, task):
        self._progress, self._task = progress, task

    def __call__(self, text: str) -> None:
        self._progress.update(self._task, description=text)

    def progress(self, t: float, t_start: float, t_end: float) -> None:
        self._progress.update(self._task, total=t_end - t_start, completed=t - t_start,
                              description=f"integrating: t = {t:.4g} of {t_end:.4g} s")


def _status_columns():
    from rich.progress import (
        BarColumn,
        SpinnerColumn,
        TaskProgressColumn,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    return (SpinnerColumn(), TextColumn("{task.description}"), BarColumn(),
            TaskProgressColumn(), TimeElapsedColumn(), TimeRemainingColumn())


@contextmanager
def status_reporter(enabled: bool):
    """A spinner and progress bar on a terminal (stderr, cleared when done); nothing in
    pipelines or with --quiet. Yields a :class:`_Reporter` (or None)."""
    with rich_progress(enabled, _status_columns, transient=True) as progress:
        yield None if progress is None else _Reporter(
            progress, progress.add_task("loading the case", total=None))


def format_value(value) -> str:
    """A table cell: strings as they are, None as a dash, numbers to 6 significant digits."""
    if isinstance(value, str):
        return value
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    return f"{value:.6g}"


def print_quantity_table(title: str, rows) -> None:
    """A (quantity, value, unit) table on the terminal (rich)."""
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    t = Table(title=escape(title), title_justify="left")
    t.add_column("quantity")
    t.add_column("value", justify="right")
    t.add_column("unit")
    for label, value, unit in rows:  # escaped: rich reads "[m]" or "[rpm]" as markup
        t.add_row(escape(label), escape(format_value(value)), escape(unit))
    Console().print(t)


def print_checks_table(checks) -> None:
    """The Checks table (name, value, limit, pass/FAIL, note) of analyze and modal
    (gearcli.results.Check)."""
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    c = Table(title="Checks", title_justify="left")
    for col in ("check", "value", "limit", "result", "note"):
        c.add_column(col)
    for ck in checks:
        verdict = ("[yellow]not checked[/yellow]" if ck.checked is False
                   else "[green]pass[/green]" if ck.passed else "[red]FAIL[/red]")
        c.add_row(escape(ck.name), escape(format_value(ck.value)), escape(ck.limit), verdict,
                  escape(ck.note))
    Console().print(c)
