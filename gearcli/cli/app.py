"""The Typer application of the `gearcli` command line: its name, help, root options.

The command modules (``gearcli.cli.geometry``, ...) import :data:`app` from here and register
their commands on it; :mod:`gearcli.cli` imports them all. Only typer is imported here, so
`gearcli --help` stays fast. Help and usage errors are click's plain text: typer's rich
formatting imports rich and markdown-it (~0.15 s, half of `gearcli --help`).
"""

from __future__ import annotations

import typer
from typer.core import TyperCommand, TyperGroup

from gearcli import __version__


class _HelpFlagDefault:
    """The help flag with the default an absent flag has, False.

    typer (0.29) gives its help option no default and coerces the resulting None through a
    pydantic TypeAdapter built on the spot: importing pydantic's machinery for it took ~0.25 s
    of every command, most of `gearcli schema`.
    """

    def get_help_option(self, ctx):
        option = super().get_help_option(ctx)
        if option is not None and option.default is None:
            option.default = False
        return option


class _Command(_HelpFlagDefault, TyperCommand):
    pass


class _Group(_HelpFlagDefault, TyperGroup):
    pass


class _App(typer.Typer):
    """Registers every command with :class:`_Command`."""

    def command(self, *args, cls=None, **kwargs):
        return super().command(*args, cls=cls or _Command, **kwargs)


app = _App(
    cls=_Group,
    name="gearcli",
    help="Dynamics of spur gear pairs from a YAML case file: geometry, simulation, checks.",
    no_args_is_help=True,
    add_completion=True,  # --install-completion / --show-completion (typer; ~4 ms of imports)
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
    context_settings={"help_option_names": ["-h", "--help"]},
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"gearcli {__version__}")
        raise typer.Exit()


#: The display-unit systems (gearcli/display_units.py; listed here so that `--help` does
#: not import it).
UNIT_SYSTEMS = ("engineering", "si")


#: Settings of the root options for the command that runs (set by the root callback on every
#: invocation, so one process running several commands, as tests do, starts each afresh).
settings = {"units": "engineering", "tables": "table"}

#: How tables are printed (gearcli/cli/common.py TABLE_FORMATS; listed here for `--help`).
TABLE_FORMATS = ("table", "plain", "csv", "json")


@app.callback()
def _root(
    ctx: typer.Context,
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
    units: str = typer.Option(
        "engineering", "--units", envvar="GEARCLI_UNITS", metavar="engineering|si",
        help="Display units of the tables, figures and reports: engineering (rpm, mm, µm, "
             "N·m, N/µm, MPa) or si (rad/s, m, N·m, N/m). Files keep their unit-suffixed "
             "columns. Also GEARCLI_UNITS."),
    tables: str = typer.Option(
        "table", "--table-format", envvar="GEARCLI_TABLE_FORMAT", metavar="|".join(TABLE_FORMATS),
        help="Terminal tables as boxes ('table': full width when piped, nothing cut), 'plain' "
             "aligned columns, 'csv' blocks or 'json' lines (one object per table); also each "
             "command's --table-format, GEARCLI_TABLE_FORMAT."),
) -> None:
    """Dynamics of spur gear pairs from a YAML case file.

    Exit codes: 0 ok, 1 bad input, 2 usage, 3 internal error (log path printed),
    4 a check failed or a result is outside the model's validity, 130 interrupted.

    Example: gearcli --units si run cases/seed.yaml -o out/seed
    """
    if units not in UNIT_SYSTEMS:
        source = getattr(ctx.get_parameter_source("units"), "name", "")
        given = "GEARCLI_UNITS=" if source == "ENVIRONMENT" else "--units "
        typer.echo(f"error: {given}{units}: expected one of {', '.join(UNIT_SYSTEMS)}",
                   err=True)
        raise typer.Exit(1)
    if tables not in TABLE_FORMATS:
        typer.echo(f"error: --table-format {tables}: expected one of {', '.join(TABLE_FORMATS)}",
                   err=True)
        raise typer.Exit(1)
    settings["units"] = units
    settings["tables"] = tables
