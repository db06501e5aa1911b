"""The machinery of the result documents (gearcli/results): a field's metadata (label and
stored unit from the metric registry gearcli/results/metrics.py, where it is shown, whether a stored
document must have it), the JSON of a document (``to_dict``, ``from_document``) and the
queries of what is shown where (:func:`shown`, :func:`shown_values`)."""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Mapping
from typing import Any

from gearcli.results.metrics import METRICS

#: Where a metric is shown (field metadata ``show``): the tables of `gearcli simulate`
#: ("simulate") and `gearcli analyze` ("analyze"), the report's results table ("report"), the
#: columns of a sweep's summary.csv ("sweep"), its trend table and figure ("trend") and the
#: further panels of its speed figure ("trend_plot"), the report's summary line ("headline").
PLACES = ("simulate", "analyze", "report", "sweep", "trend", "trend_plot", "headline",
          "speed_curve")


def metric_field(key: str, default: Any = math.nan, show: str = "", *, required: bool = False,
           omit_none: bool = False, nested: type | None = None, metric: str | None = None,
           **extra):
    """A field of a document: ``key`` its name, with the label and stored unit of metric
    ``metric or key`` (gearcli/results/metrics.py); ``show`` the places it is shown
    (:data:`PLACES`, space-separated); ``required``: a stored document without it is refused
    (gearcli/io/results.py); ``omit_none``: left out of the JSON when None; ``nested``: the
    document class of its value (a tuple of them when the default is a tuple); ``extra``
    further metadata (``json_key``: the JSON key where it is not a Python name, e.g.
    "2006")."""
    m = METRICS.get(metric or key)
    places = frozenset(show.split())
    assert places <= set(PLACES), places
    meta = {"label": m.label, "unit": m.unit} if m else {"label": key.replace("_", " ")}
    meta.update(show=places, required=required, omit_none=omit_none, nested=nested,
                metric=metric or key, **extra)
    if isinstance(default, list | dict):
        return dataclasses.field(default_factory=lambda: type(default)(default), metadata=meta)
    return dataclasses.field(default=default, metadata=meta)


def _plain(value):
    """A field's value as JSON data (documents as dicts, tuples as lists)."""
    if isinstance(value, Document):
        return value.to_dict()
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    return value


class Document:
    """A result document: ``to_dict()`` is its JSON (fields in order, the keys of the files:
    the field names, or their ``json_key``),
    ``from_document()`` reads it back (absent keys take the field's default)."""

    def to_dict(self) -> dict[str, Any]:
        out = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is None and f.metadata.get("omit_none"):
                continue
            out[f.metadata.get("json_key", f.name)] = _plain(value)
        return out

    def labelled(self, units: str = "engineering") -> list[str]:
        """"label: value unit" of each number of the document with a label and a unit (its
        metric, gearcli/results/metrics.py), in the display ``units``; a nested document's
        numbers follow."""
        from gearcli.results.metrics import METRICS, display

        out = []
        for f in dataclasses.fields(self):
            value, key = getattr(self, f.name), f.metadata.get("metric", f.name)
            if isinstance(value, Document) and not isinstance(value, tuple):
                out += value.labelled(units)
            elif (key in METRICS and isinstance(value, int | float)
                  and not isinstance(value, bool) and math.isfinite(value)):
                label, shown, unit = display(key, value, units)
                out.append(f"{label}: {shown:.4g}" + ("" if unit in ("", "–") else f" {unit}"))
        return out

    def __repr__(self) -> str:
        """One labelled line per number in engineering units (:meth:`labelled`): what a
        person reads; the keys are the attribute names and :meth:`to_dict`'s."""
        return f"<{type(self).__name__}\n  " + "\n  ".join(self.labelled()) + ">"

    @classmethod
    def from_document(cls, doc: Mapping[str, Any]):
        values = {}
        for f in dataclasses.fields(cls):
            key = f.metadata.get("json_key", f.name)
            if key not in doc:
                continue
            value, nested = doc[key], f.metadata.get("nested")
            if nested is not None and value is not None:
                value = _read_nested(nested, value, f.metadata.get("mapping_depth", 0))
            elif isinstance(value, list):
                value = tuple(value)
            else:
                _check_scalar(cls, f.name, value)
            values[f.name] = value
        return cls(**values)


@functools.cache
def _scalar_kinds(cls) -> dict[str, tuple[type, ...]]:
    """{field: accepted Python types} of ``cls``'s scalar fields (annotated float, int, str or
    bool, alone or with None): what a stored value of that field may be, None always
    included (NaN and missing values are stored as null)."""
    import types
    import typing

    plain = {float: (int, float), int: (int,), str: (str,), bool: (bool,)}
    kinds = {}
    for name, hint in typing.get_type_hints(cls).items():
        union = typing.get_origin(hint) in (typing.Union, types.UnionType)
        args = set(typing.get_args(hint)) - {type(None)} if union else {hint}
        if len(args) == 1 and (only := args.pop()) in plain:
            kinds[name] = plain[only]
    return kinds


def _check_scalar(cls, name: str, value) -> None:
    """TypeError when a stored scalar is not of its field's kind (a hand-edited file: "big"
    for a safety factor is not silently shown as a number)."""
    kinds = _scalar_kinds(cls).get(name)
    if kinds is None or value is None:
        return
    if isinstance(value, bool) and bool not in kinds or not isinstance(value, kinds):
        raise TypeError(f"{cls.__name__}.{name}: expected "
                        f"{' or '.join(k.__name__ for k in kinds)}, got {type(value).__name__}")


def _read_nested(cls, value, mapping_depth: int):
    """A nested document, a list of them, or (``mapping_depth`` levels of) mappings of them."""
    if mapping_depth:
        return {k: _read_nested(cls, v, mapping_depth - 1) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return tuple(_read_nested(cls, v, 0) for v in value)
    if not isinstance(value, Mapping):  # a hand-edited file: not silently a default document
        raise TypeError(f"{cls.__name__}: expected an object, got {type(value).__name__}")
    return cls.from_document(value)


def shown(cls, place: str) -> tuple[str, ...]:
    """The metric keys of ``cls``'s fields shown at ``place`` (:data:`PLACES`), in field order;
    nested documents (not lists of them) contribute theirs."""
    out: list[str] = []
    for f in dataclasses.fields(cls):
        nested = f.metadata.get("nested")
        if nested is not None and not isinstance(f.default, tuple):
            out.extend(shown(nested, place))
        elif place in f.metadata.get("show", ()):
            out.append(f.metadata["metric"])
    return tuple(out)


def shown_values(doc: Document, place: str) -> dict[str, Any]:
    """{metric key: value} of the fields of ``doc`` shown at ``place``, in order."""
    out: dict[str, Any] = {}
    for f in dataclasses.fields(doc):
        nested = f.metadata.get("nested")
        value = getattr(doc, f.name)
        if nested is not None and isinstance(value, Document):
            out.update(shown_values(value, place))
        elif place in f.metadata.get("show", ()):
            out[f.metadata["metric"]] = value
    return out
