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

__all__ = ["SCHEMA_VERSION", "Summary", "SummaryDocument", "EnergyBalance", "StoredMode",
           "AnalysisMetrics", "ResonanceMargin", "Check", "GearStress", "Mode", "MeshSummary",
           "PointLines", "PLACES", "shown", "shown_values", "sweep_metrics", "json_schema", "KINDS"]


#: Where a metric is shown (field metadata ``show``): the tables of `gearcli simulate`
#: ("simulate") and `gearcli analyze` ("analyze"), the report's results table ("report"), the
#: columns of a sweep's summary.csv ("sweep"), its trend table and figure ("trend") and the
#: further panels of its speed figure ("trend_plot"), the report's summary line ("headline").
PLACES = ("simulate", "analyze", "report", "sweep", "trend", "trend_plot", "headline")


def _field(key: str, default: Any = math.nan, show: str = "", *, required: bool = False,
           omit_none: bool = False, nested: type | None = None, metric: str | None = None,
           **extra):
    """A field of a document: ``key`` its name, with the label and stored unit of metric
    ``metric or key`` (gearcli/io/metrics.py); ``show`` the places it is shown
    (:data:`PLACES`, space-separated); ``required``: a stored document without it is refused
    (gearcli/io/results.py); ``omit_none``: left out of the JSON when None; ``nested``: the
    document class of its value (a tuple of them when the default is a tuple); ``extra``
    further metadata."""
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
    if isinstance(value, _Document):
        return value.to_dict()
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    return value


class _Document:
    """A result document: ``to_dict()`` is its JSON (fields in order, the keys of the files),
    ``from_document()`` reads it back (absent keys take the field's default)."""

    def to_dict(self) -> dict[str, Any]:
        out = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is None and f.metadata.get("omit_none"):
                continue
            out[f.name] = _plain(value)
        return out

    @classmethod
    def from_document(cls, doc: Mapping[str, Any]):
        values = {}
        for f in dataclasses.fields(cls):
            if f.name not in doc:
                continue
            value, nested = doc[f.name], f.metadata.get("nested")
            if nested is not None and value is not None:
                many = isinstance(value, list | tuple)
                value = (tuple(nested.from_document(v) for v in value) if many
                         else nested.from_document(value))
            elif isinstance(value, list):
                value = tuple(value)
            values[f.name] = value
        return cls(**values)


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


def shown_values(doc: _Document, place: str) -> dict[str, Any]:
    """{metric key: value} of the fields of ``doc`` shown at ``place``, in order."""
    out: dict[str, Any] = {}
    for f in dataclasses.fields(doc):
        nested = f.metadata.get("nested")
        value = getattr(doc, f.name)
        if nested is not None and isinstance(value, _Document):
            out.update(shown_values(value, place))
        elif place in f.metadata.get("show", ()):
            out[f.metadata["metric"]] = value
    return out


@dataclasses.dataclass(frozen=True)
class EnergyBalance(_Document):
    """ΔE_kin + ΔV against the net work in over the run [N·mm = mJ] (summary.json's
    ``scalars.energy_balance``; gearcli.pipeline.simulate.energy_balance)."""

    work_in_mJ: float = _field("work_in_mJ")
    work_load_mJ: float = _field("work_load_mJ")
    loss_bearing_mJ: float = _field("loss_bearing_mJ")
    loss_damping_mJ: float = _field("loss_damping_mJ")
    loss_friction_mJ: float = _field("loss_friction_mJ")
    delta_kinetic_mJ: float = _field("delta_kinetic_mJ")
    delta_contact_mJ: float = _field("delta_contact_mJ")
    delta_spring_mJ: float = _field("delta_spring_mJ")
    residual_mJ: float = _field("residual_mJ")
    relative_residual: float = _field("relative_residual", show="simulate", required=True,
                                      metric="energy_relative_residual")


@dataclasses.dataclass(frozen=True)
class StoredMode(_Document):
    """A mode as summary.json keeps it (``scalars.modes``; the full one: :class:`Mode`)."""

    mode: int = _field("mode", 0, required=True)
    natural_frequency_Hz: float | None = _field("natural_frequency_Hz", None, required=True)
    damping_ratio: float | None = _field("damping_ratio", None, required=True)
    description: str = _field("description", "")
    rigid_body: bool = _field("rigid_body", False, required=True)


@dataclasses.dataclass(frozen=True)
class Summary(_Document):
    """The scalars of a run over its steady window (summary.json's ``scalars``)."""

    window_s: tuple[float, float] = _field("window_s", (math.nan, math.nan), required=True)
    window_reason: str = _field("window_reason", "", required=True)
    samples_in_window: int = _field("samples_in_window", 0)
    output_rate_Hz: float = _field("output_rate_Hz", required=True)
    gear_mesh_frequency_Hz: float | None = _field("gear_mesh_frequency_Hz", None,
                                                  "simulate sweep", required=True)
    pinion_speed_mean_deg_s: float = _field("pinion_speed_mean_deg_s", show="simulate sweep",
                                            required=True)
    gear_speed_mean_deg_s: float = _field("gear_speed_mean_deg_s", show="simulate sweep",
                                          required=True)
    speed_ratio_mean: float = _field("speed_ratio_mean", show="simulate")
    speed_ratio_theory: float = _field("speed_ratio_theory", show="simulate")
    force_mean_N: float = _field("force_mean_N", show="simulate sweep")
    force_rms_N: float = _field("force_rms_N", show="sweep")
    force_max_N: float = _field("force_max_N", show="simulate sweep trend", required=True)
    force_max_t_s: float = _field("force_max_t_s", required=True)
    force_min_N: float = _field("force_min_N", show="simulate sweep")
    force_static_N: float = _field("force_static_N", show="simulate sweep", required=True)
    dynamic_factor: float | None = _field("dynamic_factor", None, "simulate sweep trend")
    dte_mean_mm: float = _field("dte_mean_mm", show="simulate sweep")
    dte_peak_to_peak_mm: float = _field("dte_peak_to_peak_mm", show="simulate sweep trend")
    dte_rms_mm: float = _field("dte_rms_mm", show="sweep trend_plot")
    pairs_in_contact_mean: float = _field("pairs_in_contact_mean", show="sweep")
    contact_loss_fraction: float = _field("contact_loss_fraction", show="simulate sweep")
    coast_force_max_N: float = _field("coast_force_max_N", show="sweep")
    mesh_stiffness_N_mm: float = _field("mesh_stiffness_N_mm", show="simulate sweep")
    single_pair_stiffness_N_mm: float | None = _field("single_pair_stiffness_N_mm", None,
                                                      "sweep")
    double_pair_stiffness_N_mm: float | None = _field("double_pair_stiffness_N_mm", None)
    static_deflection_mm: float = _field("static_deflection_mm", show="simulate")
    mesh_natural_frequency_Hz: float = _field("mesh_natural_frequency_Hz",
                                              show="simulate sweep trend_plot", required=True)
    mesh_damping_ratio: float = _field("mesh_damping_ratio", show="simulate sweep",
                                       required=True)
    energy_balance: EnergyBalance = _field("energy_balance", EnergyBalance(),
                                           nested=EnergyBalance)
    modes: tuple[StoredMode, ...] = _field("modes", (), nested=StoredMode)

    @property
    def energy_relative_residual(self) -> float:
        return self.energy_balance.relative_residual


@dataclasses.dataclass(frozen=True)
class PointLines(_Document):
    """The metrics of a sweep point besides its :class:`Summary`'s (summary.csv's columns after
    them): the mesh-line amplitudes at f_z of the steady window's spectra (``signal``: the
    time-series column; gearcli/pipeline/sweep/metrics.py) and the energy residual."""

    gear_speed_gmf_amplitude_rad_s: float | None = _field(
        "gear_speed_gmf_amplitude_rad_s", None, "sweep trend", signal="omega2_rad_s")
    dte_gmf_amplitude_mm: float | None = _field("dte_gmf_amplitude_mm", None, "sweep",
                                                signal="delta_mm")
    force_gmf_amplitude_N: float | None = _field("force_gmf_amplitude_N", None, "sweep",
                                                 signal="force_total_N")
    energy_balance_relative_residual: float | None = _field(
        "energy_balance_relative_residual", None, "sweep", metric="energy_relative_residual")


def sweep_metrics(place: str = "sweep") -> tuple[str, ...]:
    """The metrics of a sweep point shown at ``place`` ("sweep": summary.csv's metric columns;
    "trend", "trend_plot"): the :class:`Summary`'s, then the :class:`PointLines`'."""
    return shown(Summary, place) + tuple(
        f.name for f in dataclasses.fields(PointLines) if place in f.metadata["show"])


@dataclasses.dataclass(frozen=True)
class SummaryDocument(_Document):
    """summary.json: the run's status, solver counters, warnings and :class:`Summary`."""

    schema_version: int = _field("schema_version", SCHEMA_VERSION)
    case: str | None = _field("case", None)
    status: str = _field("status", "ok")  # validity of the run: "ok" or "invalid"
    invalid_reason: str | None = _field("invalid_reason", None, omit_none=True)
    solver: Mapping[str, Any] = _field("solver", {})
    rows: int = _field("rows", 0)
    slots: int = _field("slots", 0)
    warnings: tuple[str, ...] = _field("warnings", ())
    scalars: Summary = _field("scalars", Summary(), nested=Summary)


@dataclasses.dataclass(frozen=True)
class ResonanceMargin(_Document):
    """A mesh harmonic k f_z against a mode (analysis.json's ``metrics.resonance_margins``)."""

    harmonic: int = _field("harmonic", 0)
    mode: int | None = _field("mode", None)
    excitation_Hz: float = _field("excitation_Hz")
    mode_Hz: float = _field("mode_Hz")
    margin_percent: float = _field("margin_percent")
    resonant_peak: bool = _field("resonant_peak", False)


_TABLES = "analyze report"


@dataclasses.dataclass(frozen=True)
class AnalysisMetrics(_Document):
    """The metrics of an analysis window (analysis.json's ``metrics``)."""

    window_s: tuple[float, float] = _field("window_s", (math.nan, math.nan))
    window_reason: str = _field("window_reason", "")
    samples: int = _field("samples", 0, "report")
    pinion_speed_mean_deg_s: float = _field("pinion_speed_mean_deg_s", show="report")
    gear_speed_mean_deg_s: float = _field("gear_speed_mean_deg_s", show=_TABLES)
    speed_ratio: float = _field("speed_ratio", show="report")
    speed_ratio_theory: float = _field("speed_ratio_theory", show="report")
    speed_ratio_error_percent: float = _field("speed_ratio_error_percent", show=_TABLES)
    gear_speed_fluctuation_percent: float = _field("gear_speed_fluctuation_percent",
                                                   show=_TABLES)
    force_mean_N: float = _field("force_mean_N", show=_TABLES)
    force_rms_N: float = _field("force_rms_N", show=_TABLES)
    force_max_N: float = _field("force_max_N", show=_TABLES + " headline")
    force_max_t_s: float = _field("force_max_t_s", show="report")
    force_max_source: str = _field("force_max_source", "")
    force_min_N: float = _field("force_min_N", show="report")
    force_static_N: float = _field("force_static_N", show=_TABLES)
    dynamic_factor: float | None = _field("dynamic_factor", None, _TABLES + " headline")
    dte_mean_mm: float = _field("dte_mean_mm", show="report")
    dte_peak_to_peak_mm: float = _field("dte_peak_to_peak_mm", show=_TABLES + " headline")
    dte_rms_mm: float = _field("dte_rms_mm", show=_TABLES)
    contact_loss_fraction: float = _field("contact_loss_fraction", show=_TABLES)
    coast_impacts: int = _field("coast_impacts", 0, _TABLES)
    friction_loss_W: float | None = _field("friction_loss_W", None, _TABLES)
    damping_loss_W: float | None = _field("damping_loss_W", None, _TABLES)
    input_power_W: float | None = _field("input_power_W", None, "report")
    mesh_efficiency: float | None = _field("mesh_efficiency", None, _TABLES + " headline")
    drive_torque_mean_Nmm: float | None = _field("drive_torque_mean_Nmm", None, "report")
    drive_torque_ripple_Nmm: float | None = _field("drive_torque_ripple_Nmm", None, "report")
    mesh_natural_frequency_Hz: float | None = _field("mesh_natural_frequency_Hz", None,
                                                     _TABLES)
    mesh_damping_ratio: float | None = _field("mesh_damping_ratio", None, _TABLES)
    gear_mesh_frequency_Hz: float | None = _field("gear_mesh_frequency_Hz", None,
                                                  _TABLES + " headline")
    pinion_shaft_Hz: float | None = _field("pinion_shaft_Hz", None, "report")
    gear_shaft_Hz: float | None = _field("gear_shaft_Hz", None, "report")
    output_rate_Hz: float = _field("output_rate_Hz", show="report")
    frequency_resolution_Hz: float = _field("frequency_resolution_Hz", show="report")
    resonance_margins_percent: tuple[float, ...] = _field("resonance_margins_percent", (),
                                                          "report")
    resonance_margins: tuple[ResonanceMargin, ...] | None = _field(
        "resonance_margins", None, omit_none=True, nested=ResonanceMargin)


@dataclasses.dataclass
class Check(_Document):
    """A check of `gearcli analyze` or `gearcli modal` (analysis.json's and the modal JSON's
    ``checks``): its value against the limit (a text), passed or not."""

    name: str
    value: float | str | None
    limit: str
    passed: bool
    note: str = ""
    #: False when the check could not apply (the note says why); it then passes, and the
    #: tables print "not checked" instead of "pass"
    checked: bool = True


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
        return super().from_document(flat)


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
