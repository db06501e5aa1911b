"""Load a case file: YAML -> validated :class:`~gearcli.case.schema.Case`, errors located.

Every failure is a :class:`~gearcli.errors.CaseError` formatted as
``FILE:LINE: key.path: got VALUE; expected ...`` plus the offending YAML line.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from pathlib import Path

from pydantic import ValidationError

from gearcli.case.bounds import magnitude_errors
from gearcli.case.keypaths import allowed_keys, field_at
from gearcli.case.overrides import apply_overrides
from gearcli.case.schema import Case, FieldError
from gearcli.case.yamlsrc import Loc, Source, parse_source, read_source
from gearcli.errors import CaseError


@dataclass(frozen=True)
class LoadedCase:
    """A validated case with the source it came from (for located errors later on)."""

    case: Case
    source: Source
    name: str

    def error(self, loc: Loc, message: str, value: object = None, has_value: bool = False):
        return self.source.error(loc, message, value, has_value)

    def error_at(self, loc: Loc, message: str):
        """:meth:`error` quoting the value as written at ``loc`` (none for a section or a
        list): for checks of the validated case that point back at the YAML."""
        value, has_value = _raw_value(self.source.data, loc)
        return self.error(loc, message, value, has_value and not isinstance(value, dict | list))


def load_case(path: str | Path, overrides: list[str] | None = None) -> LoadedCase:
    """Read, parse and validate the case file at ``path``, with ``--set`` overrides applied.

    Errors about an overridden key name the override; others name the file and line.
    """
    src = read_source(path)
    if overrides:
        src.data = apply_overrides(src.data, overrides, Case)
        for text in overrides:  # point errors in overridden values at the command line
            key = tuple(text.partition("=")[0].strip().split("."))
            src.key_lines.pop(key, None)
            src.overridden[key] = text
    return validate_source(src, Path(path).stem)


def load_case_text(text: str, name: str = "<case>") -> LoadedCase:
    """Validate case text (used by tests and `gearcli new`)."""
    return validate_source(parse_source(text, name), Path(name).stem)


def validate_source(src: Source, stem: str) -> LoadedCase:
    try:
        case = Case.model_validate(src.data)
    except ValidationError as exc:
        raise _first_error(exc, src) from None
    for loc, _, message in magnitude_errors(case):
        value, has_value = _raw_value(src.data, loc)
        raise src.error(loc, message, value, has_value and not isinstance(value, dict | list))
    return LoadedCase(case, src, case.name or stem)


def _first_error(exc: ValidationError, src: Source) -> CaseError:
    """The first (by line) validation error as a located CaseError, with a count of the rest."""
    errors = []
    for err in exc.errors():
        loc = data_loc(tuple(err["loc"]), src.data)
        cause = err.get("ctx", {}).get("error")
        if isinstance(cause, FieldError):
            loc = (*loc, *cause.loc)
        missing = err["type"] == "missing"  # an unknown key (a typo) explains a missing one
        errors.append((missing, src.line_of(loc) or 0, loc, err, cause))
    errors.sort(key=lambda e: e[:2])
    _, line, loc, err, cause = errors[0]
    message = _message(err, cause, loc)
    if len(errors) > 1:
        message += f" (+{len(errors) - 1} more error{'s' if len(errors) > 2 else ''})"
    value, has_value = _raw_value(src.data, loc)
    if err["type"] == "missing" or isinstance(cause, FieldError) or isinstance(value, dict | list):
        has_value = False
    return src.error(loc, message, value, has_value)


def _raw_value(data: object, loc: Loc) -> tuple[object, bool]:
    """The value as written in the YAML (not the unit-converted one)."""
    for part in loc:
        if isinstance(data, dict) and part in data:
            data = data[part]
        elif isinstance(data, list) and isinstance(part, int) and part < len(data):
            data = data[part]
        else:
            return None, False
    return data, True


def data_loc(loc: tuple, data: object) -> Loc:
    """Drop pydantic's union/validator tags from ``loc`` so it follows the YAML keys."""
    out: list = []
    node = data
    for part in loc:
        if isinstance(node, dict) and part in node:
            out.append(part)
            node = node[part]
        elif isinstance(node, list) and isinstance(part, int) and part < len(node):
            out.append(part)
            node = node[part]
        elif isinstance(part, str) and not any(c in part for c in "[]()") and node is not None:
            out.append(part)  # a key that is missing or unknown
            node = None
    return tuple(out)


def _message(err: dict, cause: Exception | None, loc: Loc) -> str:
    kind = err["type"]
    if kind == "extra_forbidden":
        allowed = allowed_keys(Case, loc[:-1])
        msg = "unknown key"
        close = difflib.get_close_matches(str(loc[-1]), allowed, n=1, cutoff=0.6)
        if close:
            msg += f" (did you mean '{close[0]}'?)"
        return msg + "; expected one of: " + ", ".join(allowed)
    if kind == "missing":
        return "missing required key"
    if cause is not None:
        text = str(cause)
        return (
            text
            if text.startswith(
                (
                    "expected",
                    "missing",
                    "cannot",
                    "wrong",
                    "give",
                    "only",
                    "a load",
                    "malformed",
                    "'",
                )
            )
            else "expected: " + text
        )
    limit = _limit_message(err, loc)
    if limit:
        return limit
    msg = err["msg"]
    for prefix in ("Input should be ", "Value error, "):
        if msg.startswith(prefix):
            msg = msg[len(prefix) :]
    msg = msg.replace("greater than or equal to", ">=").replace("less than or equal to", "<=")
    msg = msg.replace("greater than", ">").replace("less than", "<")
    return "expected " + msg


_LIMITS = {
    "greater_than": (">", "gt"),
    "greater_than_equal": (">=", "ge"),
    "less_than": ("<", "lt"),
    "less_than_equal": ("<=", "le"),
}


def _limit_message(err: dict, loc: Loc) -> str | None:
    """'expected > 0 mm': a bound of a quantity field, in the field's default unit."""
    if err["type"] not in _LIMITS:
        return None
    op, key = _LIMITS[err["type"]]
    limit = err.get("ctx", {}).get(key)
    field = field_at(Case, loc)
    dim = None
    for meta in getattr(field, "metadata", ()):
        dim = getattr(getattr(meta, "func", None), "dim", None) or dim
    if limit is None:
        return None
    if isinstance(limit, int) and not isinstance(limit, bool):  # counts, seeds: exact
        return f"expected {op} {limit}"
    if dim is None:  # a plain number (a coefficient): the bound as written, not pydantic's
        return f"expected {op} {float(limit):g}"  # fixed-point 0.000000000000023
    return f"expected {op} {float(limit) / dim.factor:g} {dim.default}"

