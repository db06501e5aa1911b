"""`--set key.path=value` overrides applied to a case's YAML data before validation."""

from __future__ import annotations

import copy
import difflib

import yaml

from gearcli.case.keypaths import model_in
from gearcli.errors import CaseError


def parse_override(text: str) -> tuple[tuple[str, ...], object]:
    """Split ``'gears.module=12'`` into (('gears', 'module'), 12); the value is YAML."""
    key, sep, raw = text.partition("=")
    path = tuple(p.strip() for p in key.strip().split("."))
    if not sep or not all(path):
        raise CaseError(f"--set {text!r}: expected key.path=value, e.g. --set gears.module=12")
    try:
        value = yaml.safe_load(raw) if raw.strip() else ""
    except yaml.YAMLError:
        value = raw
    return path, value


def apply_overrides(data: dict, overrides: list[str], schema) -> dict:
    """A copy of ``data`` with each override set; unknown paths are refused.

    ``schema`` is the pydantic model class of the whole case (to check key paths).
    """
    out = copy.deepcopy(data)
    for text in overrides:
        path, value = parse_override(text)
        check_path(path, schema, text)
        node = out
        for part in path[:-1]:
            child = node.get(part)
            if not isinstance(child, dict):
                child = {}
                node[part] = child
            node = child
        node[path[-1]] = value
    return out


def check_path(path: tuple[str, ...], schema, text: str) -> None:
    """Refuse a key path that ``schema`` (a pydantic model class) does not have.

    Raises
    ------
    CaseError
        ``--set TEXT: unknown key 'part' in where (did you mean ...); expected one of: ...``,
        naming the first unknown part of ``path``; ``text`` is the override as written.
    """
    model = schema
    for i, part in enumerate(path):
        fields = model.model_fields if model is not None else {}
        if part not in fields:
            where = ".".join(path[:i]) or "the case"
            close = difflib.get_close_matches(part, list(fields), n=1, cutoff=0.6)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            allowed = ", ".join(fields) or "no keys (a value)"
            raise CaseError(
                f"--set {text}: unknown key '{part}' in {where}{hint}; expected one of: {allowed}"
            )
        model = model_in(fields[part].annotation)
