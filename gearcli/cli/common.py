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
from gearcli.cli.app import TABLE_FORMATS
from gearcli.errors import ExitCode, GearcliError
from gearcli.guards import clip, clip_message
from gearcli.interrupts import Terminated

#: errno values of a full or broken output stream or disk: the user's environment, not a bug.
_OUTPUT_ERRNOS = frozenset(getattr(errno, n) for n in (
    "ENOSPC", "EDQUOT", "EFBIG", "EPIPE", "EIO", "EROFS", "EACCES", "EPERM", "ENXIO")
    if hasattr(errno, n))


#: errno of a path the system refuses: a name above NAME_MAX or a path above PATH_MAX.
_PATH_ERRNOS = frozenset({errno.ENAMETOOLONG})


def handle_errors(func):
    """Decorator for every command: GearcliError -> one message line + its exit code;
    a full disk or a closed output stream -> exit 1 (a reader that closed the pipe:
    silently); Ctrl-C -> 130; anything else -> exit 3 with the traceback written to a log
    file."""

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
            if exc.errno in _PATH_ERRNOS:  # a path the user gave that the system cannot take
                _echo_err(f"error: {clip(str(exc.filename or ''), 200)}: {exc.strerror}; "
                          "expected a shorter path or name")
                raise typer.Exit(int(ExitCode.INPUT)) from None
            if exc.errno not in _OUTPUT_ERRNOS:
                return _internal()
            reader_gone = exc.errno == errno.EPIPE and not exc.filename and _stdout_widowed()
            _detach_stdout()
            if reader_gone:
                # the reader closed the pipe (`gearcli simulate -o - | head`): what it wanted
                # was read, so no message; exit 1 as Python's own SIGPIPE note prescribes
                raise typer.Exit(int(ExitCode.INPUT)) from None
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


def _stdout_widowed() -> bool:
    """Whether stdout is a pipe or socket whose reader has gone (poll reports an error or a
    hang-up on its write end): only then is a broken pipe the reader's choice, not a failure
    elsewhere (a pipe to another process, a FIFO the command opened) that must be reported."""
    import select
    import stat

    try:
        fd = sys.stdout.fileno()
        mode = os.fstat(fd).st_mode
        if not (stat.S_ISFIFO(mode) or stat.S_ISSOCK(mode)) or not hasattr(select, "poll"):
            return False
        poller = select.poll()
        poller.register(fd, select.POLLOUT)
        return any(ev & (select.POLLERR | select.POLLHUP) for _, ev in poller.poll(0))
    except (OSError, ValueError, AttributeError):
        return False


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
    from gearcli.io.files import check_new_file, check_suffix

    check_suffix(option, path, (".png", ".svg", ".pdf"))
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


#: How tables are printed (``gearcli --table-format`` / ``--table-format`` of a command /
#: GEARCLI_TABLE_FORMAT): "table" boxes (full width when piped: nothing is cut), "plain"
#: aligned columns without boxes or colour, "csv" a CSV block per table (its title as a
#: ``# title`` line), "json" one JSON object per table and line ({"table", "columns", "rows"}).


def table_format_option():
    """The ``--table-format`` option of a command with tables (None: the root's setting)."""
    return typer.Option(None, "--table-format", metavar="|".join(TABLE_FORMATS),
                        help="Tables as boxes ('table', full width when piped), 'plain' "
                             "columns, 'csv' or 'json' lines (default: gearcli "
                             "--table-format, GEARCLI_TABLE_FORMAT, else table).")


def table_options(func):
    """A command with tables: adds its ``--table-format`` option (:func:`table_format_option`)
    and sets it before the command runs (under :func:`handle_errors`)."""
    import inspect

    sig = inspect.signature(func)
    param = inspect.Parameter("table_fmt", inspect.Parameter.KEYWORD_ONLY,
                              default=table_format_option(), annotation=str | None)

    @functools.wraps(func)
    def wrapper(*args, table_fmt=None, **kwargs):
        set_table_format(table_fmt)
        return func(*args, **kwargs)

    wrapper.__signature__ = sig.replace(parameters=[*sig.parameters.values(), param])
    wrapper.__annotations__ = dict(func.__annotations__, table_fmt=str | None)
    return wrapper


def set_table_format(value: str | None) -> None:
    """A command's ``--table-format`` (None keeps the root's); an unknown one exits 1."""
    if value is None:
        return
    if value not in TABLE_FORMATS:
        from gearcli.errors import OutputError

        raise OutputError(f"--table-format {value}: expected one of {', '.join(TABLE_FORMATS)}")
    from gearcli.cli.app import settings

    settings["tables"] = value


def table_format() -> str:
    from gearcli.cli.app import settings

    return settings.get("tables", "table")


def _plain_cell(cell) -> str:
    """A rich cell (markup text, Text or None) as plain text."""
    from rich.text import Text

    if cell is None:
        return ""
    if isinstance(cell, Text):
        return cell.plain
    return Text.from_markup(str(cell)).plain


def table_data(table) -> tuple[str, list[str], list[list[str]]]:
    """(title, column headers, rows) of a rich Table, as plain text."""
    headers = [_plain_cell(c.header) for c in table.columns]
    cells = [[_plain_cell(x) for x in c._cells] for c in table.columns]
    rows = [list(r) for r in zip(*cells, strict=True)] if cells else []
    return _plain_cell(table.title or ""), headers, rows


def print_table(table) -> None:
    """Print a rich Table in the chosen :func:`table_format`."""
    fmt = table_format()
    if fmt == "table":
        from rich.console import Console
        from rich.measure import Measurement

        console = Console()
        if not console.is_terminal:  # piped: as wide as the table needs, nothing cut
            wide = console.options.update_width(100_000)
            width = Measurement.get(console, wide, table).maximum
            title = len(_plain_cell(table.title or ""))
            if title > width:  # rich wraps a title to the table's width
                table.min_width = width = title
            console = Console(width=max(width, 80))
        console.print(table)
        return
    title, headers, rows = table_data(table)
    typer.echo(format_rows(fmt, title, headers, rows))


def format_rows(fmt: str, title: str, headers: list[str], rows: list[list[str]]) -> str:
    """A table as text in the format ``fmt`` ("plain", "csv" or "json")."""
    if fmt == "json":
        import json

        return json.dumps({"table": title, "columns": headers,
                           "rows": [dict(zip(headers, r, strict=True)) for r in rows]},
                          ensure_ascii=False)
    if fmt == "csv":
        import csv
        import io

        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(headers)
        writer.writerows(rows)
        return (f"# {title}\n" if title else "") + buf.getvalue()
    widths = [max([len(h)] + [len(r[i]) for r in rows]) for i, h in enumerate(headers)]
    lines = [title] if title else []
    lines += ["  ".join(c.ljust(w) for c, w in zip(line, widths, strict=True)).rstrip()
              for line in [headers, *rows]]
    return "\n".join(lines) + "\n"


def emit(item) -> None:
    """A command's console output: a rich Table through :func:`print_table`, a line of text
    (rich markup) as plain text; in csv a ``# text`` comment, in json {"text": ...}."""
    from rich.table import Table

    if isinstance(item, Table):
        print_table(item)
        return
    text = _plain_cell(item)
    fmt = table_format()
    if fmt == "csv":
        text = "\n".join(f"# {line}" for line in text.splitlines())
    elif fmt == "json":
        import json

        text = json.dumps({"text": text}, ensure_ascii=False)
    typer.echo(text)


def print_lines(lines) -> None:
    """Lines below a table (notes, remedies): each once, in order; none in csv/json."""
    if table_format() in ("csv", "json"):
        return
    seen = set()
    for line in lines:
        if line and line not in seen:
            seen.add(line)
            typer.echo(line)


def print_quantity_table(title: str, rows) -> None:
    """A (quantity, value, unit) table (rich; :func:`print_table`)."""
    from rich.markup import escape
    from rich.table import Table

    t = Table(title=escape(title), title_justify="left")
    t.add_column("quantity")
    t.add_column("value", justify="right")
    t.add_column("unit")
    for label, value, unit in rows:  # escaped: rich reads "[m]" or "[rpm]" as markup
        t.add_row(escape(label), escape(format_value(value)), escape(unit))
    print_table(t)


def print_checks_table(checks, units: str = "engineering") -> None:
    """The Checks table of analyze and modal (gearcli.results.Check): each check by its label,
    value, unit, limit and result, and quieter in the last column its key (where the case
    sets its limit); in csv and json also its name in analysis.json, its note and remedy as
    columns (in the other formats the notes and remedies follow the table, each once)."""
    from rich.markup import escape
    from rich.table import Table

    from gearcli.report.tables import check_cells

    inline = table_format() in ("csv", "json")
    columns = ["check", "value", "unit", "limit", "result", "limit key"]
    c = Table(title="Checks", title_justify="left")
    for col in columns + (["name", "note", "remedy"] if inline else []):
        c.add_column(col, justify="right" if col == "value" else "left",
                     style="dim" if col == "limit key" else None)
    notes, remedies = [], {}
    for ck in checks:
        verdict = ("[yellow]not checked[/yellow]" if ck.checked is False
                   else "[green]pass[/green]" if ck.passed else "[red]FAIL[/red]")
        value, unit, limit = check_cells(ck, units)
        remedy = ck.remedy.text if getattr(ck, "remedy", None) is not None else ""
        extra = [escape(ck.name), escape(ck.note), escape(remedy)] if inline else []
        c.add_row(escape(ck.label), escape(value), escape(unit), escape(limit), verdict,
                  escape(ck.limit_key or "–"), *extra)
        if ck.note:
            notes.append(f"  {ck.label}: {ck.note}")
        if remedy:
            remedies.setdefault(remedy, []).append(ck.label)
    print_table(c)
    print_lines(notes)
    print_lines(f"remedy ({'; '.join(names)}): {text}" for text, names in remedies.items())


def _named(checks) -> str:
    """Checks by label, their analysis.json names after them: "dynamic factor F_max /
    F_static (dynamic_factor)"."""
    return "; ".join(f"{c.label} ({c.name})" if getattr(c, "label", c.name) != c.name
                     else c.name for c in checks)


def report_findings(checks, where: str | None = None, also=()) -> None:
    """The end of a command whose checks failed: one "findings" line naming them (the verdicts
    and remedies are above and in ``where``), exit 4 without an error line; all passed: nothing.
    ``also``: further failed verdicts by name (e.g. the ISO 6336 rating of `run`)."""
    made = [c for c in checks if c.failed]
    failed = ([_named(made)] if made else []) + list(also)
    if not failed:
        return
    with_remedy = [c for c in made if getattr(c, "remedy", None)]
    extra = ("" if not with_remedy else "; remedy above" if len(with_remedy) == len(made)
             else f"; a remedy for {_named(with_remedy)} above")
    where = f"; verdicts in {where}" if where else ""
    _echo_err(f"findings: {len(made) + len(also)} check(s) failed: {'; '.join(failed)}{extra} "
              f"(exit 4{where})")
    raise typer.Exit(int(ExitCode.CHECK_FAILED))
