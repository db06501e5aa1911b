"""The Typer application of the `gearcli` command line: its name, help, root options.

The command modules (``gearcli.cli.geometry``, ...) import :data:`app` from here and register
their commands on it; :mod:`gearcli.cli` imports them all. Only typer is imported here, so
`gearcli --help` stays fast.
"""

from __future__ import annotations

import typer

from gearcli import __version__

app = typer.Typer(
    name="gearcli",
    help="Dynamics of spur gear pairs from a YAML case file: geometry, simulation, checks.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"gearcli {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
) -> None:
    """Dynamics of spur gear pairs from a YAML case file.

    Exit codes: 0 ok, 1 bad input, 2 usage, 3 internal error (log path printed),
    4 a check failed, 130 interrupted.
    """
