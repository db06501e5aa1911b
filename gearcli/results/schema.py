"""JSON Schemas of the result documents (`gearcli schema --results --kind KIND`), derived from
the typed documents of gearcli/results."""

from __future__ import annotations

import dataclasses
import math

from gearcli.results.analysis import AnalysisMetrics, Remedy
from gearcli.results.models import (
    IsoResonance,
    Linearisation,
    MeshSharing,
    MeshSte,
    MeshStiffness,
    MeshSummary,
    Mode,
)
from gearcli.results.monitor import MonitorDocument
from gearcli.results.rating import SAFETY_CHECKS, GearSafeties, RatingColumn, RatingSummary
from gearcli.results.rating_document import RatingDocument
from gearcli.results.run import InputDigest, Summary
from gearcli.results.stress import GearStress
from gearcli.results.version import RESULTS_SCHEMA_VERSION as SCHEMA_VERSION


def _finite(value) -> bool:
    """False for a float NaN/inf or a list/tuple holding one."""
    if isinstance(value, list | tuple):
        return all(_finite(v) for v in value)
    return not isinstance(value, float) or math.isfinite(value)


#: The documents ``gearcli schema --results KIND`` describes.
KINDS = ("summary", "analysis", "stress", "modal", "mesh", "rating", "monitor")


def _rating_schema(typed) -> dict:
    """summary.json's ``rating`` (gearcli/results/rating.py): the ISO and the simulated column,
    each with both gears' safeties."""
    verdict = {"enum": ["pass", "fail"]}
    gear = typed(GearSafeties)
    gear["properties"].update(pitting=verdict, bending=verdict)
    gear["required"] = [name for check in SAFETY_CHECKS for name in check]
    column = typed(RatingColumn)
    column["properties"].update(pinion=gear, gear=gear, verdict=verdict)
    column["required"] = ["dynamic_factor", "pinion", "gear", "verdict"]
    rating = typed(RatingSummary)
    rating["properties"]["verdict"] = verdict
    rating["required"] = ["edition", "iso", "verdict"]
    rating["properties"].update(iso=column, simulated={"anyOf": [column, {"type": "null"}]})
    rating["description"] = RatingSummary.__doc__.split("\n")[0]
    return rating


def _deep(typed, cls) -> dict:
    """The schema of document ``cls`` with its nested documents described field by field too
    (recursively; a tuple of them as an array, an optional one as that or null) and each
    property under its JSON key (``json_key`` metadata, gearcli/results/fields.py). Every
    key ``to_dict`` always writes is required (all but the ``omit_none`` fields, left out when
    None), so a document missing one is refused; a None it writes is allowed where the field
    is optional."""
    schema = typed(cls)
    props = schema["properties"]
    required = []
    for f in dataclasses.fields(cls):
        key = f.metadata.get("json_key", f.name)
        if f.name not in props:
            continue
        if not f.metadata.get("omit_none"):
            required.append(key)
        prop = props.pop(f.name)
        nested = f.metadata.get("nested")
        if nested is not None:
            inner = _deep(typed, nested)
            inner["description"] = prop.get("description", "")
            if isinstance(f.default, tuple):
                inner = {"type": "array", "items": inner, "description": inner["description"]}
            prop = {"anyOf": [inner, {"type": "null"}]} if f.default is None else inner
        props[key] = prop
    schema["required"] = required
    return schema


def json_schema(kind: str = "summary") -> dict:
    """JSON Schema (draft 2020-12) of a result document: ``summary`` (summary.json),
    ``analysis`` (analysis.json), ``stress`` (stress.json), ``modal`` (gearcli modal --json),
    ``mesh`` (gearcli mesh --json), ``rating`` (rating.json of `gearcli rate -o` and `gearcli
    run`) or ``monitor`` (monitor.json): the typed fields as above, the rest as open
    objects."""
    from pydantic import TypeAdapter

    if kind not in KINDS:
        raise ValueError(f"results schema {kind!r}: expected one of {', '.join(KINDS)}")

    obj = {"type": "object"}

    def typed(cls, drop=()) -> dict:
        schema = TypeAdapter(cls).json_schema()
        schema.pop("$defs", None)  # nested documents: described as open objects below
        for f in dataclasses.fields(cls):
            nested = f.metadata.get("nested")
            if nested is not None and f.name in schema["properties"]:
                many = isinstance(f.default, tuple) or f.name == "resonance_margins"
                schema["properties"][f.name] = ({"type": "array", "items": obj} if many
                                                else dict(obj))
        for name in drop:
            schema["properties"].pop(name, None)
        for prop in schema["properties"].values():  # NaN is not JSON: no such defaults
            if not _finite(prop.get("default", 0.0)):
                del prop["default"]
        for f in dataclasses.fields(cls):
            if f.name in schema["properties"]:
                unit = f.metadata.get("unit")
                text = f.metadata.get("label", "")
                schema["properties"][f.name]["description"] = (
                    f"{text} [{unit}]" if unit and unit != "–" else text)
        schema["additionalProperties"] = True
        return schema

    base = {"$schema": "https://json-schema.org/draft/2020-12/schema", "type": "object"}
    version = {"const": SCHEMA_VERSION}
    if kind == "summary":
        scalars = typed(Summary)
        props = {"schema_version": version, "case": {"type": "string"},
                 "status": {"enum": ["ok", "invalid"]}, "invalid_reason": {"type": "string"},
                 "solver": obj, "rows": {"type": "integer", "minimum": 1},
                 "slots": {"type": "integer"},
                 "warnings": {"type": "array", "items": {"type": "string"}},
                 "scalars": scalars, "input_digest": typed(InputDigest),
                 "rating": _rating_schema(typed)}
        return {**base, "title": "gearcli summary.json", "properties": props,
                "required": ["schema_version", "case", "status", "rows", "scalars"]}
    check = {"type": "object", "required": ["name", "value", "limit", "passed"],
             "properties": {"name": {"type": "string"}, "limit": {"type": "string"},
                            "passed": {"type": ["boolean", "null"]},
                            "checked": {"type": "boolean"},
                            "note": {"type": "string"},
                            # what would make a failed check pass (gearcli/pipeline/remedy.py)
                            "remedy": typed(Remedy)}}
    checks = {"type": "array", "items": check}
    if kind == "analysis":
        props = {"schema_version": version, "case": {"type": "string"},
                 "passed": {"type": "boolean"}, "window_s": {"type": "array"},
                 "window_reason": {"type": "string"}, "metrics": typed(AnalysisMetrics),
                 "checks": checks, "warnings": {"type": "array"}, "lines": obj}
        return {**base, "title": "gearcli analysis.json", "properties": props,
                "required": ["schema_version", "case", "passed", "metrics", "checks"]}
    if kind == "stress":
        gear = {"type": "object", "description": "peaks, per-tooth maxima, ratios, safety; "
                "the typed view: " + ", ".join(f.name for f in dataclasses.fields(GearStress)),
                "required": ["teeth", "peak_sigma_H", "peak_sigma_F"]}
        props = {"schema_version": version, "case": {"type": "string"},
                 "window_s": {"type": "array"}, "static": obj, "pinion": gear, "gear": gear,
                 "warnings": {"type": "array"}}
        return {**base, "title": "gearcli stress.json", "properties": props,
                "required": ["schema_version", "case", "static", "pinion", "gear"]}
    if kind in ("rating", "monitor"):
        cls = RatingDocument if kind == "rating" else MonitorDocument
        doc = _deep(typed, cls)
        if "schema_version" in doc["properties"]:
            doc["properties"]["schema_version"] = version
        name = "rating.json" if kind == "rating" else "monitor.json"
        return {**base, **doc, "title": f"gearcli {name}",
                "description": cls.__doc__.split("\n")[0]}
    if kind == "mesh":
        props = typed(MeshSummary)["properties"]
        for group in (MeshSte, MeshStiffness, MeshSharing, IsoResonance):
            name = next(f.name for f in dataclasses.fields(MeshSummary)
                        if f.metadata.get("nested") is group)
            props[name] = typed(group)
        props["schema_version"] = version
        return {**base, "title": "gearcli mesh --json", "properties": props,
                "required": ["schema_version", "case", "force_N", "ste", "stiffness"]}
    props = {"schema_version": version, "case": {"type": "string"},
             "model": {"type": "string"}, "modes": {"type": "array", "items": typed(Mode)},
             "linearisation": typed(Linearisation), "crossings": {"type": "array"},
             "checks": checks, "passed": {"type": "boolean"}}
    return {**base, "title": "gearcli modal --json", "properties": props,
            "required": ["schema_version", "case", "modes", "checks", "passed"]}
