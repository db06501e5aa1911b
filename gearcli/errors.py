"""Error types and process exit codes, defined once for the whole tool.

The library raises these; only the CLI layer turns them into exit codes and messages.
"""

from __future__ import annotations

from enum import IntEnum


class ExitCode(IntEnum):
    """Process exit codes of every gearcli command."""

    OK = 0  #: success
    INPUT = 1  #: bad input / user error (case file, output folder, options with bad values)
    USAGE = 2  #: command-line usage error (unknown option, missing argument) — Typer/Click's code
    INTERNAL = 3  #: internal error (a bug); the traceback is written to a log file
    CHECK_FAILED = 4  #: the run worked but a check (analyze / modal limits) failed
    INTERRUPTED = 130  #: Ctrl-C


class GearcliError(Exception):
    """Base of every error the user can act on. ``str(err)`` is the one-line message."""

    exit_code: ExitCode = ExitCode.INPUT


class CaseError(GearcliError):
    """A problem in a case file, located by file, line and key path.

    Formats as ``FILE:LINE: key.path: got VALUE; expected ...`` with the offending YAML line
    on a second line when it is known.
    """

    def __init__(
        self,
        message: str,
        *,
        file: str | None = None,
        line: int | None = None,
        path: str | None = None,
        value: object = None,
        has_value: bool = False,
        source_line: str | None = None,
    ) -> None:
        self.message = message
        self.file = file
        self.line = line
        self.path = path
        self.value = value
        self.has_value = has_value
        self.source_line = source_line
        super().__init__(self.format())

    def format(self) -> str:
        parts = []
        if self.file is not None:  # "--set key=VALUE" may be long: clipped like values
            parts.append(_clip(self.file, 160) + (f":{self.line}" if self.line is not None
                                                  else ""))
        if self.path:
            parts.append(_clip(self.path, 120))
        text = ": ".join(parts) + ": " if parts else ""
        if self.has_value:
            text += f"got {format_value(self.value)}; "
        text += self.message
        if self.source_line is not None and self.line is not None:
            text += f"\n    {self.line:>4} | {_clip(self.source_line.rstrip(), 120)}"
        return text


class GeometryError(GearcliError):
    """The gear pair cannot exist or cannot run (ε_α < 1, interference, impossible geometry)."""


class OutputError(GearcliError):
    """An output location is unusable (exists without --force, not writable, ...)."""


class InvalidResultError(GearcliError):
    """A run finished outside the model's range of validity (docs/theory.md §10.2): its
    numbers are not results. Exit code 4, like a failed check."""

    exit_code = ExitCode.CHECK_FAILED


class ResultsError(GearcliError):
    """A results folder is missing, foreign, truncated or inconsistent."""


class SolverError(GearcliError):
    """The solver failed (divergence, NaN, runaway penetration); nothing is written as results."""


class CheckFailed(GearcliError):
    """One or more checks failed; the results themselves are valid and written."""

    exit_code = ExitCode.CHECK_FAILED


def format_value(value: object) -> str:
    """Render a user value compactly for an error message (at most ~80 characters)."""
    if isinstance(value, str):
        return repr(_clip(value, 80)) if len(value) > 80 else repr(value)
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) > 10**30:
        return f"an integer of ~{int(abs(value).bit_length() * 0.30103) + 1} digits"
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _clip(text: str, limit: int) -> str:
    from gearcli.guards import clip

    return clip(text, limit)
