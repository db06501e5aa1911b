"""The `gearcli` command line (Typer). Thin: parse options, call the library, write outputs.

The application lives in :mod:`gearcli.cli.app`; importing this package registers every
command on it. Heavy modules (numba, pandas, matplotlib, pydantic, pint) are imported inside
the commands so that `gearcli --help` stays fast.
"""

from __future__ import annotations

# Registering the commands (each module imports only typer at import time); the order of
# registration is the order of `gearcli --help`: the workflow first.
# isort: off
from gearcli.cli import (  # noqa: F401
    geometry, simulate, analyze, report, stress, modal, mesh, sweep, casefile,
)
# isort: on
from gearcli.cli.app import app

__all__ = ["app", "main"]


def main() -> None:
    """Console-script entry point."""
    app()
