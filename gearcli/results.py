"""Typed result documents (issue 17): the summary of a run, the metrics of its analysis, the
stress peaks of a gear and the modes of the linearised model, as frozen dataclasses.

Each field's name is its key in the JSON document (summary.json ``scalars``, analysis.json
``metrics``, stress.json per gear, the modal JSON's ``modes``) and carries its unit in the name
or is dimensionless; ``metadata`` holds the label and stored unit from the one metric registry
(gearcli/io/metrics.py), the registry the command line's and the report's tables print from
(gearcli/io/metrics.rows, in the chosen display units). :func:`json_schema` derives the
documents' JSON Schemas (``gearcli schema --results``). The documents' version is
:data:`SCHEMA_VERSION` (raised when a key is renamed or removed).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

from gearcli.io.manifest import RESULTS_SCHEMA_VERSION as SCHEMA_VERSION
from gearcli.io.metrics import METRICS

__all__ = ["SCHEMA_VERSION", "Summary", "AnalysisMetrics", "GearStress", "Mode",
           "MeshSummary", "json_schema", "KINDS"]


def _field(key: str, default: Any = math.nan):
    """A field with the label and stored unit of metric ``key`` (gearcli/io/metrics.py)."""
    m = METRICS.get(key)
    meta = {"label": m.label, "unit": m.unit} if m else {"label": key.replace("_", " ")}
    return dataclasses.field(default=default, metadata=meta)


def _pick(cls, values: Mapping[str, Any]) -> dict[str, Any]:
    """The entries of ``values`` that are fields of ``cls`` (lists of pairs as tuples)."""
    names = {f.name for f in dataclasses.fields(cls)}
    out = {k: v for k, v in values.items() if k in names}
    if isinstance(out.get("window_s"), list):
        out["window_s"] = tuple(out["window_s"])
    return out


class _Document:
    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)


@dataclasses.dataclass(frozen=True)
class Summary(_Document):
    """The scalars of a run over its steady window (summary.json's ``scalars``)."""

    dynamic_factor: float | None = _field("dynamic_factor", None)
    force_max_N: float = _field("force_max_N")
    force_max_t_s: float = _field("force_max_t_s")
    force_min_N: float = _field("force_min_N")
    force_mean_N: float = _field("force_mean_N")
    force_rms_N: float = _field("force_rms_N")
    force_static_N: float = _field("force_static_N")
    dte_mean_mm: float = _field("dte_mean_mm")
    dte_peak_to_peak_mm: float = _field("dte_peak_to_peak_mm")
    dte_rms_mm: float = _field("dte_rms_mm")
    contact_loss_fraction: float = _field("contact_loss_fraction")
    coast_force_max_N: float = _field("coast_force_max_N")
    pairs_in_contact_mean: float = _field("pairs_in_contact_mean")
    speed_ratio_mean: float = _field("speed_ratio_mean")
    speed_ratio_theory: float = _field("speed_ratio_theory")
    pinion_speed_mean_deg_s: float = _field("pinion_speed_mean_deg_s")
    gear_speed_mean_deg_s: float = _field("gear_speed_mean_deg_s")
    gear_mesh_frequency_Hz: float | None = _field("gear_mesh_frequency_Hz", None)
    mesh_natural_frequency_Hz: float = _field("mesh_natural_frequency_Hz")
    mesh_damping_ratio: float = _field("mesh_damping_ratio")
    mesh_stiffness_N_mm: float = _field("mesh_stiffness_N_mm")
    static_deflection_mm: float = _field("static_deflection_mm")
    output_rate_Hz: float = _field("output_rate_Hz")
    window_s: tuple[float, float] = _field("window_s", (math.nan, math.nan))
    energy_relative_residual: float = _field("energy_relative_residual")
    status: str = _field("status", "ok")  # validity of the run: "ok" or "invalid"
    invalid_reason: str = _field("invalid_reason", "")

    @classmethod
    def from_scalars(cls, scalars: Mapping[str, Any], status: str = "ok",
                     invalid_reason: str = "") -> Summary:
        balance = scalars.get("energy_balance") or {}
        return cls(**_pick(cls, scalars),
                   energy_relative_residual=balance.get("relative_residual", math.nan),
                   status=status, invalid_reason=invalid_reason)


@dataclasses.dataclass(frozen=True)
class AnalysisMetrics(_Document):
    """The metrics of an analysis window (analysis.json's ``metrics``)."""

    window_s: tuple[float, float] = _field("window_s", (math.nan, math.nan))
    window_reason: str = _field("window_reason", "")
    samples: int = _field("samples", 0)
    pinion_speed_mean_deg_s: float = _field("pinion_speed_mean_deg_s")
    gear_speed_mean_deg_s: float = _field("gear_speed_mean_deg_s")
    speed_ratio: float = _field("speed_ratio")
    speed_ratio_theory: float = _field("speed_ratio_theory")
    speed_ratio_error_percent: float = _field("speed_ratio_error_percent")
    gear_speed_fluctuation_percent: float = _field("gear_speed_fluctuation_percent")
    force_mean_N: float = _field("force_mean_N")
    force_rms_N: float = _field("force_rms_N")
    force_max_N: float = _field("force_max_N")
    force_max_t_s: float = _field("force_max_t_s")
    force_max_source: str = _field("force_max_source", "")
    force_min_N: float = _field("force_min_N")
    force_static_N: float = _field("force_static_N")
    dynamic_factor: float | None = _field("dynamic_factor", None)
    dte_mean_mm: float = _field("dte_mean_mm")
    dte_peak_to_peak_mm: float = _field("dte_peak_to_peak_mm")
    dte_rms_mm: float = _field("dte_rms_mm")
    contact_loss_fraction: float = _field("contact_loss_fraction")
    coast_impacts: int = _field("coast_impacts", 0)
    friction_loss_W: float | None = _field("friction_loss_W", None)
    damping_loss_W: float | None = _field("damping_loss_W", None)
    input_power_W: float | None = _field("input_power_W", None)
    mesh_efficiency: float | None = _field("mesh_efficiency", None)
    drive_torque_mean_Nmm: float | None = _field("drive_torque_mean_Nmm", None)
    drive_torque_ripple_Nmm: float | None = _field("drive_torque_ripple_Nmm", None)
    mesh_natural_frequency_Hz: float | None = _field("mesh_natural_frequency_Hz", None)
    mesh_damping_ratio: float | None = _field("mesh_damping_ratio", None)
    gear_mesh_frequency_Hz: float | None = _field("gear_mesh_frequency_Hz", None)
    pinion_shaft_Hz: float | None = _field("pinion_shaft_Hz", None)
    gear_shaft_Hz: float | None = _field("gear_shaft_Hz", None)
    output_rate_Hz: float = _field("output_rate_Hz")
    frequency_resolution_Hz: float = _field("frequency_resolution_Hz")
    resonance_margins_percent: tuple[float, ...] = _field("resonance_margins_percent", ())

    @classmethod
    def from_metrics(cls, metrics: Mapping[str, Any]) -> AnalysisMetrics:
        values = _pick(cls, metrics)
        if "resonance_margins_percent" in values:
            values["resonance_margins_percent"] = tuple(values["resonance_margins_percent"])
        return cls(**values)


@dataclasses.dataclass(frozen=True)
class GearStress(_Document):
    """Peak dynamic stresses of one gear in the window against its ISO 6336 static values
    (stress.json's ``pinion`` / ``gear`` with the ``static`` values of that gear)."""

    teeth: int = _field("teeth", 0)
    sigma_H_peak_MPa: float | None = _field("sigma_H_peak_MPa", None)
    sigma_F_peak_MPa: float | None = _field("sigma_F_peak_MPa", None)
    sigma_H_iso_MPa: float | None = _field("sigma_H_iso_MPa", None)
    sigma_F0_MPa: float | None = _field("sigma_F0_MPa", None)
    ratio_sigma_H_to_static: float | None = _field("ratio_sigma_H_to_static", None)
    ratio_sigma_F_to_static: float | None = _field("ratio_sigma_F_to_static", None)
    S_H: float | None = _field("S_H", None)
    S_F: float | None = _field("S_F", None)

    @classmethod
    def from_document(cls, doc: Mapping[str, Any], which: str) -> GearStress:
        g, st = doc[which], doc["static"][which]
        safety = g.get("safety") or {}
        return cls(teeth=g["teeth"], sigma_H_peak_MPa=g["peak_sigma_H"].get("MPa"),
                   sigma_F_peak_MPa=g["peak_sigma_F"].get("MPa"),
                   sigma_H_iso_MPa=st.get("sigma_H_iso_MPa"), sigma_F0_MPa=st.get("sigma_F0_MPa"),
                   ratio_sigma_H_to_static=g.get("ratio_sigma_H_to_static"),
                   ratio_sigma_F_to_static=g.get("ratio_sigma_F_to_static"),
                   S_H=safety.get("S_H"), S_F=safety.get("S_F"))


@dataclasses.dataclass(frozen=True)
class Mode(_Document):
    """One mode of the linearised model (the modal JSON's ``modes``)."""

    mode: int = _field("mode", 0)
    rigid_body: bool = _field("rigid_body", False)
    natural_frequency_Hz: float | None = _field("natural_frequency_Hz", None)
    damping_ratio: float | None = _field("damping_ratio", None)
    resonant_peak: bool = _field("resonant_peak", False)
    description: str = _field("description", "")
    shape: Mapping[str, float] = _field("shape", None)

    @classmethod
    def from_document(cls, mode: Mapping[str, Any]) -> Mode:
        return cls(**_pick(cls, mode))


@dataclasses.dataclass(frozen=True)
class MeshSummary(_Document):
    """The scalars of a quasi-static loaded contact analysis (`gearcli mesh --json`: its
    ``ste`` entries prefixed ``ste_``, its ``stiffness`` and ``iso6336_method_b`` entries)."""

    force_N: float = _field("force_N")
    ste_mean_um: float = _field("ste_mean_um")
    ste_peak_to_peak_um: float = _field("ste_peak_to_peak_um")
    ste_peak_to_peak_arcsec: float = _field("ste_peak_to_peak_arcsec")
    unloaded_te_peak_to_peak_um: float = _field("unloaded_te_peak_to_peak_um")
    mesh_mean_N_mm: float = _field("mesh_mean_N_mm")
    single_pair_zone_N_mm: float | None = _field("single_pair_zone_N_mm", None)
    double_pair_zone_N_mm: float | None = _field("double_pair_zone_N_mm", None)
    iso6336_single_pair_c_prime_b_N_mm: float = _field("iso6336_single_pair_c_prime_b_N_mm")
    iso6336_mean_c_gamma_alpha_b_N_mm: float = _field("iso6336_mean_c_gamma_alpha_b_N_mm")
    resonance_speed_rpm: float = _field("resonance_speed_rpm")
    resonance_ratio: float | None = _field("resonance_ratio", None)
    k_v: float | None = _field("k_v", None)

    @classmethod
    def from_document(cls, doc: Mapping[str, Any]) -> MeshSummary:
        ste = {k if k.startswith("unloaded") else f"ste_{k}": v for k, v in doc["ste"].items()}
        flat = {"force_N": doc["force_N"], **ste, **doc["stiffness"],
                **doc.get("iso6336_method_b", {})}
        return cls(**_pick(cls, flat))


def _finite(value) -> bool:
    """False for a float NaN/inf or a list/tuple holding one."""
    if isinstance(value, list | tuple):
        return all(_finite(v) for v in value)
    return not isinstance(value, float) or math.isfinite(value)


#: The documents ``gearcli schema --results KIND`` describes.
KINDS = ("summary", "analysis", "stress", "modal", "mesh")


def json_schema(kind: str = "summary") -> dict:
    """JSON Schema (draft 2020-12) of a result document: ``summary`` (summary.json),
    ``analysis`` (analysis.json), ``stress`` (stress.json), ``modal`` (gearcli modal --json)
    or ``mesh`` (gearcli mesh --json): the typed fields as above, the rest as open objects."""
    from pydantic import TypeAdapter

    if kind not in KINDS:
        raise ValueError(f"results schema {kind!r}: expected one of {', '.join(KINDS)}")

    def typed(cls, drop=()) -> dict:
        schema = TypeAdapter(cls).json_schema()
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
    obj = {"type": "object"}
    if kind == "summary":
        scalars = typed(Summary, ("status", "invalid_reason", "energy_relative_residual"))
        scalars["properties"]["energy_balance"] = obj
        scalars["properties"]["modes"] = {"type": "array", "items": obj}
        props = {"schema_version": version, "case": {"type": "string"},
                 "status": {"enum": ["ok", "invalid"]}, "invalid_reason": {"type": "string"},
                 "solver": obj, "rows": {"type": "integer", "minimum": 1},
                 "slots": {"type": "integer"},
                 "warnings": {"type": "array", "items": {"type": "string"}},
                 "scalars": scalars}
        return {**base, "title": "gearcli summary.json", "properties": props,
                "required": ["schema_version", "case", "status", "rows", "scalars"]}
    check = {"type": "object", "required": ["name", "value", "limit", "passed"],
             "properties": {"name": {"type": "string"}, "limit": {"type": "string"},
                            "passed": {"type": "boolean"}, "checked": {"type": "boolean"},
                            "note": {"type": "string"}}}
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
    if kind == "mesh":
        flat = typed(MeshSummary)["properties"]
        groups = {"ste": [k for k in flat if k.startswith(("ste_", "unloaded_"))],
                  "stiffness": [k for k in flat if k.endswith("_N_mm")],
                  "iso6336_method_b": ["resonance_speed_rpm", "resonance_ratio", "k_v"]}
        props = {"schema_version": version, "case": {"type": "string"},
                 "force_N": flat["force_N"], "notes": {"type": "array"},
                 **{g: {"type": "object", "additionalProperties": True,
                        "properties": {k.removeprefix("ste_") if g == "ste" else k: flat[k]
                                       for k in keys}} for g, keys in groups.items()}}
        return {**base, "title": "gearcli mesh --json", "properties": props,
                "required": ["schema_version", "case", "force_N", "ste", "stiffness"]}
    props = {"schema_version": version, "case": {"type": "string"},
             "model": {"type": "string"}, "modes": {"type": "array", "items": typed(Mode)},
             "linearisation": obj, "crossings": {"type": "array"}, "checks": checks,
             "passed": {"type": "boolean"}}
    return {**base, "title": "gearcli modal --json", "properties": props,
            "required": ["schema_version", "case", "modes", "checks", "passed"]}
