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
    geometry, simulate, analyze, report, stress, rate, modal, mesh, sweep, monitor, casefile,
)
# isort: on
from gearcli.cli.app import app

__all__ = ["app", "main"]


def main() -> None:
    """Console-script entry point."""
    limit_blas_threads()
    app()


def limit_blas_threads() -> None:
    """One BLAS/OpenMP thread in gearcli's own processes (set before numpy is imported; a value
    the user set wins). gearcli's linear algebra works on matrices of at most 16 x 16 (modal
    analysis): worker threads cannot help there, and on a 2-core machine their spin-waiting
    after each call took CPU from the compiled solver running next (bench/RESULTS.md). The
    library (``import gearcli``) leaves the calling process alone."""
    import os

    for name in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS"):
        os.environ.setdefault(name, "1")
