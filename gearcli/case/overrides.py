"""`--set key.path=value` overrides applied to a case's YAML data before validation."""

from __future__ import annotations

import copy
import difflib
import json
import math
import numbers
import os
from collections.abc import Mapping

import yaml

from gearcli.case.keypaths import model_in
from gearcli.errors import CaseError


def text_name(name: str) -> str:
    """A name as valid text: bytes of a file name that are not UTF-8 (Python keeps them as
    lone surrogates, e.g. a Latin-1 'é') become U+FFFD, so the name can be printed and
    written as UTF-8 (reports, JSON, figures)."""
    return _raw(name).decode("utf-8", "replace")


def _raw(text: str) -> bytes:
    try:
        return text.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:  # surrogates other than those of undecodable bytes
        return text.encode("utf-8", "surrogatepass")


def check_text(text: str, what: str) -> str:
    """Refuse text with bytes that are not UTF-8 (a command-line argument decoded by Python
    with surrogateescape): a one-line CaseError showing the bytes as \\xNN."""
    if text_name(text) != text:
        shown = _raw(text).decode("utf-8", "backslashreplace")
        raise CaseError(f"{what} {shown}: not UTF-8 text; expected names and values in UTF-8")
    return text


def parse_override(text: str) -> tuple[tuple[str, ...], object]:
    """Split ``'gears.module=12'`` into (('gears', 'module'), 12); the value is YAML."""
    check_text(text, "--set")
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

    ``schema`` is the pydantic model class of the whole case (to check key paths). A null
    value (``key=null`` or ``key=~``) removes the key, so its default applies, as ``null``
    does in a JSON Merge Patch (RFC 7396): e.g. ``--set contact.law=tooth --set
    contact.stiffness=null`` turns an IMPACT case to the tooth law without editing the file.
    """
    out = copy.deepcopy(data)
    for text in overrides:
        path, value = parse_override(text)
        check_path(path, schema, text)
        node = out
        for part in path[:-1]:
            child = node.get(part)
            if not isinstance(child, dict):
                if value is None:  # nothing there to remove
                    break
                child = {}
                node[part] = child
            node = child
        else:
            if value is None:
                node.pop(path[-1], None)
            else:
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


def overrides_from_set(set_) -> list[str]:
    """The Python API's ``set=`` (gearcli/api.py): ``{"key.path": value}`` as the command
    line's ``--set key.path=value`` texts (values as JSON, which the override parser reads as
    YAML: numbers, strings with units, lists); a sequence of such texts (the command line's)
    as it is."""
    if isinstance(set_, str):  # one "key.path=value" text, not a sequence of characters
        return [set_]
    if set_ is not None and not isinstance(set_, Mapping):
        if isinstance(set_, bytes) or not hasattr(set_, "__iter__"):
            raise CaseError(f"set={set_!r:.60}: expected a mapping {{'key.path': value}}, a "
                            "'key.path=value' text or a sequence of such texts")
        return [str(item) for item in set_]
    out = []
    for key, value in (set_ or {}).items():
        try:
            text = value if isinstance(value, str) else json.dumps(
                value, allow_nan=False, default=_plain)
        except (TypeError, ValueError):
            raise CaseError(f"set[{key!r}]: got {value!r:.60}; expected a number, a text "
                            "(with units) or a list of them") from None
        out.append(f"{key}={text}")
    return out


def _plain(value):
    """numpy scalars (np.int64(18), np.float32(2.0)) as the Python numbers they hold."""
    if hasattr(value, "item") and getattr(value, "shape", None) == ():
        return value.item()
    raise TypeError(type(value).__name__)


def quantity_arguments(values, dim, what: str, count: int) -> tuple[float, ...]:
    """The Python API's quantity arguments (gearcli/api.py): ``count`` values given as
    numbers (in ``dim``'s case-file unit) or texts with units, in internal units, as the
    command line's options take them; anything else a CaseError."""
    from gearcli import units

    items = (values,) if count == 1 else values
    if count > 1 and (isinstance(values, str | bytes) or not hasattr(values, "__len__")):
        items = None
    if items is None or len(items) != count or any(isinstance(v, bool) for v in items):
        shape = "a value" if count == 1 else f"{count} values"
        raise CaseError(f"{what}={values!r:.60}: expected {shape}, each a number in "
                        f"{dim.default} or a text with units")
    try:
        return units.parse_quantities(items, dim)
    except (units.UnitError, TypeError, ValueError) as exc:
        raise CaseError(f"{what} {exc}") from None


# --- the Python API's other arguments (gearcli/api.py) -----------------------------------
def callable_argument(value, what: str):
    if value is not None and not callable(value):
        raise CaseError(f"{what}={value!r:.60}: expected a callable or None")
    return value


def flag_argument(value, what: str) -> bool:
    """A yes/no argument: True or False only (a text "no" is truthy)."""
    if not isinstance(value, bool):
        raise CaseError(f"{what}={value!r:.60}: expected True or False")
    return value


def folder_argument(value, what: str):
    if value is not None and not isinstance(value, str | os.PathLike):
        raise CaseError(f"{what}={value!r:.60}: expected the path of a folder (str or Path)")
    return value


#: The Python API's bounds of `mesh`'s options (the command line uses the defaults 2 and
#: 200): at most 10 x 1000 = 10 000 roll positions, 25x the default's (~10 s).
MESH_OPTIONS = {"cycles": (1, 10), "points_per_cycle": (20, 1000)}


def mesh_options(options: dict) -> dict:
    for key, value in options.items():
        if key not in MESH_OPTIONS:
            raise CaseError(f"mesh({key}=...): unknown option; expected one of: "
                            + ", ".join(MESH_OPTIONS))
        lo, hi = MESH_OPTIONS[key]
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) \
                or not lo <= value <= hi:
            raise CaseError(f"{key}={value!r:.60}: expected a whole number from {lo} to {hi}")
    return {k: int(v) for k, v in options.items()}


def timeout_argument(value) -> None:
    if value is None:
        return
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value) \
            or value <= 0:
        raise CaseError(f"point_timeout {value!r:.60}: expected a number of seconds > 0 "
                        "(or None: the default)")

