"""One place that turns library errors into messages and exit codes (see gearcli.errors)."""

from __future__ import annotations

import functools
import os
import sys
import tempfile
import traceback
from pathlib import Path

import typer

from gearcli.errors import ExitCode, GearcliError


def handle_errors(func):
    """Decorator for every command: GearcliError -> one message line + its exit code;
    Ctrl-C -> 130; anything else -> exit 3 with the traceback written to a log file."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except (typer.Exit, typer.Abort, SystemExit):
            raise
        except GearcliError as exc:
            typer.echo(f"error: {exc}", err=True)
            raise typer.Exit(int(exc.exit_code)) from None
        except KeyboardInterrupt:
            typer.echo("interrupted", err=True)
            raise typer.Exit(int(ExitCode.INTERRUPTED)) from None
        except Exception:  # a bug: keep the traceback for the report, not on the screen
            log = _write_log(traceback.format_exc())
            typer.echo(
                f"internal error: {sys.exc_info()[1]!r}; traceback written to {log} "
                "(please report it)",
                err=True,
            )
            raise typer.Exit(int(ExitCode.INTERNAL)) from None

    return wrapper


def _write_log(text: str) -> Path:
    folder = Path(os.environ.get("GEARCLI_LOG_DIR", tempfile.gettempdir()))
    folder.mkdir(parents=True, exist_ok=True)
    fd, name = tempfile.mkstemp(prefix="gearcli-error-", suffix=".log", dir=folder)
    with os.fdopen(fd, "w") as fh:
        fh.write(text)
    return Path(name)


def is_terminal() -> bool:
    return sys.stdout.isatty()


class _NoStatus:
    def __enter__(self):
        return None

    def __exit__(self, *exc):
        return False


def status_reporter(enabled: bool):
    """A spinner with elapsed time on a terminal (stderr); nothing in pipelines."""
    if not enabled or not sys.stderr.isatty():
        return _NoStatus()
    from contextlib import contextmanager

    from rich.console import Console

    @contextmanager
    def spinner():
        console = Console(stderr=True)
        with console.status("loading the case") as st:
            yield lambda text: st.update(text)

    return spinner()


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
    from rich.table import Table

    t = Table(title=title, title_justify="left")
    t.add_column("quantity")
    t.add_column("value", justify="right")
    t.add_column("unit")
    for label, value, unit in rows:
        t.add_row(label, format_value(value), unit)
    Console().print(t)


def print_checks_table(checks: list[dict]) -> None:
    """The Checks table (name, value, limit, pass/FAIL, note) of analyze and modal."""
    from rich.console import Console
    from rich.table import Table

    c = Table(title="Checks", title_justify="left")
    for col in ("check", "value", "limit", "result", "note"):
        c.add_column(col)
    for ck in checks:
        c.add_row(ck["name"], format_value(ck["value"]), ck["limit"],
                  "[green]pass[/green]" if ck["passed"] else "[red]FAIL[/red]", ck["note"])
    Console().print(c)
