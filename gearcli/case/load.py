"""Load a case file: YAML -> validated :class:`~gearcli.case.schema.Case`, errors located.

Every failure is a :class:`~gearcli.errors.CaseError` formatted as
``FILE:LINE: key.path: got VALUE; PROBLEM; expected ALLOWED`` plus the offending YAML line;
all errors of a file are reported together (:class:`CaseErrors`, one line each).
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from pathlib import Path

from pydantic import ValidationError

from gearcli import units
from gearcli.case.bounds import magnitude_errors
from gearcli.case.keypaths import allowed_keys, field_at
from gearcli.case.overrides import apply_overrides, text_name
from gearcli.case.schema import Case
from gearcli.case.section import FieldError, FieldErrors, compose
from gearcli.case.types import info_dim
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

    def __repr__(self) -> str:  # engineering units (gearcli/display_units.py), labelled
        g = self.case.gears
        return (f"<LoadedCase {self.name} ({self.source.file}): {g.pinion.teeth}/"
                f"{g.gear.teeth} teeth, module {g.module:g} mm, face width {g.face_width:g} mm, "
                f"{self.case.model} model, {self.case.contact.law} contact law>")

    def written_bare(self, loc: Loc) -> bool:
        """Whether the value at ``loc`` was written without a unit, so that its numbers mean the
        case's bare unit (gearcli/case/types.py): a number, a number as text, an expression of
        time outside a mapping with ``unit``, such a mapping without ``unit`` (whose function
        is itself bare). False for a value with units and for one not written (its default)."""
        from gearcli.case.expr import is_expression

        node = self.source.data
        for part in loc:
            if not isinstance(node, dict) or part not in node:
                return False
            node = node[part]
        if isinstance(node, dict):  # a time function: bare unless it gives a unit, or its
            if "function" not in node or "unit" in node:  # constant carries one ("450 N*m")
                return False
            node = node["function"]
        if isinstance(node, bool) or not isinstance(node, int | float | str):
            return False
        if isinstance(node, str) and not is_expression(node):
            try:
                float(node)
            except ValueError:
                return False  # "450 N*m"
        return True

    def error_at(self, loc: Loc, message: str):
        """:meth:`error` quoting the value as written at ``loc`` (none for a section or a
        list): for checks of the validated case that point back at the YAML."""
        return self.error(loc, message, *_shown_value(self.source.data, loc))


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
    """Validate the parsed case; every error of the file is reported at once
    (:class:`CaseErrors`), each naming its line, key, value and what is allowed."""
    try:
        case = Case.model_validate(src.data)
    except ValidationError as exc:
        raise CaseErrors.of(_schema_errors(exc, src)) from None
    found = [src.error(loc, message, *_shown_value(src.data, loc))
             for loc, _, message in magnitude_errors(case, case.units)]
    if found:
        raise CaseErrors.of(found)
    return LoadedCase(case, src, case.name or text_name(stem))


class CaseErrors(CaseError):
    """Every error of one case file, in the order of their lines: one line each
    (``FILE:LINE: key: got VALUE; ... expected ...``), without the quoted YAML lines. Its
    ``file``, ``line``, ``path``, ... are the first error's; ``errors`` holds them all."""

    #: At most this many errors are listed; the rest are counted.
    MAX_SHOWN = 25

    def __init__(self, errors: list[CaseError]) -> None:
        self.errors = errors
        first = errors[0]
        super().__init__(first.message, file=first.file, line=first.line, path=first.path,
                         value=first.value, has_value=first.has_value,
                         source_line=first.source_line)

    @staticmethod
    def of(errors: list[CaseError]) -> CaseError:
        """One error as itself (with its YAML line), several as a :class:`CaseErrors`."""
        return errors[0] if len(errors) == 1 else CaseErrors(errors)

    def format(self) -> str:
        lines = [CaseError(e.message, file=e.file, line=e.line, path=e.path, value=e.value,
                           has_value=e.has_value).format() for e in self.errors[:self.MAX_SHOWN]]
        rest = len(self.errors) - self.MAX_SHOWN
        if rest > 0:
            lines.append(f"... and {rest} more error{'s' if rest > 1 else ''}")
        return "\n".join(lines)


def _schema_errors(exc: ValidationError, src: Source) -> list[CaseError]:
    """Every validation error, located, one per key, by line; a missing key that an unknown
    key of the same section (a typo, with its did-you-mean) explains is left out."""
    found: dict[Loc, tuple] = {}
    for err in exc.errors():
        loc = data_loc(tuple(err["loc"]), src.data)
        if err["type"] in _TAG_ERRORS:  # a fault's kind: the key the tag is read from
            loc = (*loc, str(err.get("ctx", {}).get("discriminator", "kind")).strip("'"))
        cause = err.get("ctx", {}).get("error")
        parts = cause.errors if isinstance(cause, FieldErrors) else [cause]
        for part in parts:
            where = (*loc, *part.loc) if isinstance(part, FieldError) else loc
            found.setdefault(where, (err, part))  # a union's branches: the first one's
    typos = {(loc[:-1], close) for loc, (err, _) in found.items()
             if err["type"] == "extra_forbidden" for close in _close_keys(loc)}
    errors = []
    for loc, (err, cause) in found.items():
        missing = err["type"] == "missing" or (isinstance(cause, FieldError)
                                                and cause.problem.startswith("missing"))
        if missing and (loc[:-1], loc[-1]) in typos:
            continue
        errors.append((missing, src.line_of(loc) or 0, loc, err, cause))
    errors.sort(key=lambda e: e[:2])
    declared = src.data.get("units") if isinstance(src.data, dict) else None
    system = declared if declared in units.UNIT_SYSTEMS else None
    return [src.error(loc, _message(err, cause, loc, system),
                      *(_shown_value(src.data, loc) if err["type"] != "missing" else (None,
                                                                                       False)))
            for _, _, loc, err, cause in errors]


def _shown_value(data: object, loc: Loc) -> tuple[object, bool]:
    """The value as written at ``loc`` and whether an error shows it (not for a section)."""
    value, has_value = _raw_value(data, loc)
    if isinstance(value, dict):  # a mapping value (a time function's) yes, a section no
        field = field_at(Case, loc)
        has_value = field is not None and not allowed_keys(Case, loc)
    return value, has_value


def _close_keys(loc: Loc) -> list[str]:
    """The schema keys an unknown key at ``loc`` may be a typo of."""
    return difflib.get_close_matches(str(loc[-1]), allowed_keys(Case, loc[:-1]), n=1,
                                     cutoff=0.6)


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
    for i, part in enumerate(loc):
        if isinstance(node, dict) and part in node:
            out.append(part)
            node = node[part]
        elif isinstance(node, list) and isinstance(part, int) and part < len(node):
            out.append(part)
            node = node[part]
        elif isinstance(node, dict) and isinstance(part, str) and not _is_tag(node, part,
                                                                               loc[i + 1:]):
            out.append(part)  # a key that is missing or unknown
            node = None
    return tuple(out)


def _is_tag(node: dict, part: str, rest: tuple) -> bool:
    """Whether ``part``, not a key of the mapping ``node``, is pydantic's name of a union
    member rather than a missing key: a validator or type ("function-after[...]", "list[any]"),
    a model class ("Range"), a discriminator's value ("root_crack" of ``kind: root_crack``), or
    a step followed by a key of ``node`` (schema keys are lower case)."""
    return (any(c in part for c in "[]()") or part[:1].isupper() or node.get("kind") == part
            or (bool(rest) and rest[0] in node))


def _message(err: dict, cause: Exception | None, loc: Loc, system: str | None) -> str:
    """What is wrong and what is allowed (:func:`~gearcli.case.section.compose`); the loader
    adds file, line, key and value. A validator's own error says both itself."""
    kind = err["type"]
    raw = tuple(err["loc"])  # with pydantic's union member names: the schema's own path
    if kind == "extra_forbidden":
        close = _close_keys(raw)
        return compose("unknown key" + (f" (did you mean '{close[0]}'?)" if close else ""),
                       "one of: " + ", ".join(allowed_keys(Case, raw[:-1])))
    if kind == "missing":
        return compose("missing required key", _what(raw))
    if cause is not None:
        return str(cause)
    ctx = err.get("ctx", {})
    if kind == "union_tag_invalid":
        return compose("", "one of " + str(ctx.get("expected_tags", "")))
    if kind == "union_tag_not_found":
        from gearcli.case.schema_faults import FAULT_KINDS  # the only tagged union

        return compose("missing", "one of " + ", ".join(FAULT_KINDS))
    if kind == "too_short":
        n = ctx.get("min_length", 1)
        return compose("", f"at least {n} entr{'y' if n == 1 else 'ies'}")
    if kind in ("model_type", "dict_type"):
        return compose("", f"a mapping: {_what(raw)}")
    limit = _limit_message(err, raw, system)
    if limit:
        return limit
    msg = err["msg"]
    for prefix in ("Input should be ", "Value error, "):
        msg = msg.removeprefix(prefix)
    msg = msg.replace("greater than or equal to", ">=").replace("less than or equal to", "<=")
    msg = msg.replace("greater than", ">").replace("less than", "<")
    return compose("", msg)


#: pydantic's errors of a tagged union (``faults:``): located at the tag's key.
_TAG_ERRORS = ("union_tag_invalid", "union_tag_not_found")


def _what(loc: Loc) -> str:
    """What a required key holds: its schema description, or a section's keys."""
    field = field_at(Case, loc)
    keys = allowed_keys(Case, loc)
    if keys:
        return f"a '{loc[-1]}' section (keys: {', '.join(keys)})"
    text = (field.description or "") if field is not None else ""
    return text.removesuffix(" (required)") or f"a value for '{loc[-1]}'"


_LIMITS = {
    "greater_than": (">", "gt"),
    "greater_than_equal": (">=", "ge"),
    "less_than": ("<", "lt"),
    "less_than_equal": ("<=", "le"),
}


def _limit_message(err: dict, loc: Loc, system: str | None) -> str | None:
    """'expected > 0 mm': a bound of a quantity field, in the unit of its bare numbers (the
    field's default unit, or the declared ``units:`` system's)."""
    if err["type"] not in _LIMITS:
        return None
    op, key = _LIMITS[err["type"]]
    limit = err.get("ctx", {}).get(key)
    field = field_at(Case, loc)
    dim = info_dim(field) if field is not None else None  # Length | None too
    if limit is None:
        return None
    if dim is None and isinstance(limit, int) and not isinstance(limit, bool):  # counts, seeds
        return compose("", f"{op} {limit}")
    if dim is None:  # a plain number (a coefficient): the bound as written, not pydantic's
        return compose("", f"{op} {float(limit):g}")  # fixed-point 0.000000000000023
    dim = units.in_system(dim, system)
    return compose("", f"{op} {float(limit) / dim.factor:g} {dim.default}")

