"""The documents of `gearcli simulate`: summary.json (:class:`SummaryDocument`) and its
scalars (:class:`Summary`), and the metrics of a sweep point besides them."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

from gearcli.results.fields import Document, metric_field, shown
from gearcli.results.rating import RatingSummary
from gearcli.results.version import RESULTS_SCHEMA_VERSION as SCHEMA_VERSION


@dataclasses.dataclass(frozen=True)
class EnergyBalance(Document):
    """ΔE_kin + ΔV against the net work in over the run [N·mm = mJ] (summary.json's
    ``scalars.energy_balance``; gearcli.pipeline.simulate.energy_balance)."""

    work_in_mJ: float = metric_field("work_in_mJ")
    work_load_mJ: float = metric_field("work_load_mJ")
    loss_bearing_mJ: float = metric_field("loss_bearing_mJ")
    loss_damping_mJ: float = metric_field("loss_damping_mJ")
    loss_friction_mJ: float = metric_field("loss_friction_mJ")
    delta_kinetic_mJ: float = metric_field("delta_kinetic_mJ")
    delta_contact_mJ: float = metric_field("delta_contact_mJ")
    delta_spring_mJ: float = metric_field("delta_spring_mJ")
    residual_mJ: float = metric_field("residual_mJ")
    relative_residual: float = metric_field("relative_residual", show="simulate", required=True,
                                      metric="energy_relative_residual")


@dataclasses.dataclass(frozen=True)
class StoredMode(Document):
    """A mode as summary.json keeps it (``scalars.modes``; the full one: :class:`Mode`)."""

    mode: int = metric_field("mode", 0, required=True)
    natural_frequency_Hz: float | None = metric_field("natural_frequency_Hz", None, required=True)
    damping_ratio: float | None = metric_field("damping_ratio", None, required=True)
    description: str = metric_field("description", "")
    rigid_body: bool = metric_field("rigid_body", False, required=True)


@dataclasses.dataclass(frozen=True, repr=False)  # Document's labelled repr
class Summary(Document):
    """The scalars of a run over its steady window (summary.json's ``scalars``)."""

    window_s: tuple[float, float] = metric_field("window_s", (math.nan, math.nan), required=True)
    window_reason: str = metric_field("window_reason", "", required=True)
    samples_in_window: int = metric_field("samples_in_window", 0)
    output_rate_Hz: float = metric_field("output_rate_Hz", required=True)
    gear_mesh_frequency_Hz: float | None = metric_field("gear_mesh_frequency_Hz", None,
                                                  "simulate sweep", required=True)
    pinion_speed_mean_deg_s: float = metric_field("pinion_speed_mean_deg_s", show="simulate sweep",
                                            required=True)
    gear_speed_mean_deg_s: float = metric_field("gear_speed_mean_deg_s", show="simulate sweep",
                                          required=True)
    speed_ratio_mean: float = metric_field("speed_ratio_mean", show="simulate")
    speed_ratio_theory: float = metric_field("speed_ratio_theory", show="simulate")
    force_mean_N: float = metric_field("force_mean_N", show="simulate sweep")
    force_rms_N: float = metric_field("force_rms_N", show="sweep")
    force_max_N: float = metric_field("force_max_N", show="simulate sweep trend", required=True)
    force_max_t_s: float = metric_field("force_max_t_s", required=True)
    force_min_N: float = metric_field("force_min_N", show="simulate sweep")
    force_static_N: float = metric_field("force_static_N", show="simulate sweep", required=True)
    dynamic_factor: float | None = metric_field("dynamic_factor", None, "simulate sweep trend")
    dte_mean_mm: float = metric_field("dte_mean_mm", show="simulate sweep")
    dte_peak_to_peak_mm: float = metric_field("dte_peak_to_peak_mm", show="simulate sweep trend")
    dte_rms_mm: float = metric_field("dte_rms_mm", show="sweep trend_plot")
    pairs_in_contact_mean: float = metric_field("pairs_in_contact_mean", show="sweep")
    contact_loss_fraction: float = metric_field("contact_loss_fraction", show="simulate sweep")
    coast_force_max_N: float = metric_field("coast_force_max_N", show="sweep")
    mesh_stiffness_N_mm: float = metric_field("mesh_stiffness_N_mm", show="simulate sweep")
    single_pair_stiffness_N_mm: float | None = metric_field("single_pair_stiffness_N_mm", None,
                                                      "sweep")
    double_pair_stiffness_N_mm: float | None = metric_field("double_pair_stiffness_N_mm", None)
    static_deflection_mm: float = metric_field("static_deflection_mm", show="simulate")
    mesh_natural_frequency_Hz: float = metric_field("mesh_natural_frequency_Hz",
                                              show="simulate sweep trend_plot", required=True)
    mesh_damping_ratio: float = metric_field("mesh_damping_ratio", show="simulate sweep",
                                       required=True)
    #: "steady", or "unsteady" when a speed or the load changes by more than 1 % over the
    #: window (pipeline/validity.operating_state): its dynamic factor is not a steady one
    operating_state: str = metric_field("operating_state", "steady", "simulate")
    operating_change_fraction: float = metric_field("operating_change_fraction", 0.0, "sweep")
    energy_balance: EnergyBalance = metric_field("energy_balance", EnergyBalance(),
                                           nested=EnergyBalance)
    modes: tuple[StoredMode, ...] = metric_field("modes", (), nested=StoredMode)

    @property
    def energy_relative_residual(self) -> float:
        return self.energy_balance.relative_residual


@dataclasses.dataclass(frozen=True)
class PointLines(Document):
    """The metrics of a sweep point besides its :class:`Summary`'s (summary.csv's columns after
    them): the mesh-line amplitudes at f_z of the steady window's spectra (``signal``: the
    time-series column; gearcli/pipeline/sweep/metrics.py) and the energy residual."""

    gear_speed_gmf_amplitude_rad_s: float | None = metric_field(
        "gear_speed_gmf_amplitude_rad_s", None, "sweep trend", signal="omega2_rad_s")
    dte_gmf_amplitude_mm: float | None = metric_field("dte_gmf_amplitude_mm", None, "sweep",
                                                signal="delta_mm")
    force_gmf_amplitude_N: float | None = metric_field("force_gmf_amplitude_N", None, "sweep",
                                                 signal="force_total_N")
    energy_balance_relative_residual: float | None = metric_field(
        "energy_balance_relative_residual", None, "sweep", metric="energy_relative_residual")
    #: ISO 6336 safeties with K_v = the point's F_max/F_static, the smaller of pinion and gear
    #: (pipeline/run_rating.py); None when the case has no fatigue limits
    safety_pitting_min: float | None = metric_field("safety_pitting_min", None, "sweep")
    safety_bending_min: float | None = metric_field("safety_bending_min", None, "sweep")


def sweep_metrics(place: str = "sweep") -> tuple[str, ...]:
    """The metrics of a sweep point shown at ``place`` ("sweep": summary.csv's metric columns;
    "trend", "trend_plot"): the :class:`Summary`'s, then the :class:`PointLines`'."""
    return shown(Summary, place) + tuple(
        f.name for f in dataclasses.fields(PointLines) if place in f.metadata["show"])


@dataclasses.dataclass(frozen=True)
class InputDigest(Document):
    """What the case asks for, at its final speed and load, for a check at a glance
    (gearcli/pipeline/digest.py; σ_H0 per ISO 6336-2 with Z_ε): summary.json's
    ``input_digest``."""

    power_kW: float = metric_field("power_kW", unit="kW", label="power T1 ω1")
    pitch_line_velocity_m_s: float = metric_field("pitch_line_velocity_m_s", unit="m/s",
                                                   label="pitch-line velocity v")
    line_load_N_mm: float = metric_field("line_load_N_mm", unit="N/mm", label="F_t/b")
    sigma_H0_MPa: float = metric_field("sigma_H0_MPa", unit="MPa", label="nominal σ_H0")
    gear_mesh_frequency_Hz: float = metric_field("gear_mesh_frequency_Hz", unit="Hz",
                                                  label="mesh frequency f_z")
    resonance_ratio: float = metric_field("resonance_ratio", label="N = f_z/f_n")
    warnings: tuple[str, ...] = metric_field("warnings", ())  #: implausible magnitudes


@dataclasses.dataclass(frozen=True)
class SummaryDocument(Document):
    """summary.json: the run's status, solver counters, warnings and :class:`Summary`."""

    schema_version: int = metric_field("schema_version", SCHEMA_VERSION)
    case: str | None = metric_field("case", None)
    status: str = metric_field("status", "ok")  # validity of the run: "ok" or "invalid"
    invalid_reason: str | None = metric_field("invalid_reason", None, omit_none=True)
    solver: Mapping[str, Any] = metric_field("solver", {})
    rows: int = metric_field("rows", 0)
    slots: int = metric_field("slots", 0)
    warnings: tuple[str, ...] = metric_field("warnings", ())
    scalars: Summary = metric_field("scalars", Summary(), nested=Summary)
    input_digest: InputDigest | None = metric_field("input_digest", None, omit_none=True,
                                                    nested=InputDigest)
    #: S_H, S_F per gear, ISO and simulated (`gearcli run` of a case it can rate)
    rating: RatingSummary | None = metric_field("rating", None, omit_none=True,
                                                nested=RatingSummary)


@dataclasses.dataclass(frozen=True, repr=False)  # Document's labelled repr
class SpeedLevel(Document):
    """One speed of a speed curve (`design: speed_curve`; gearcli/pipeline/speed_curve.py):
    a row of its summary.csv, whose column is the field's ``column`` (or its name)."""

    point: int = metric_field("point", 0)
    direction: str = metric_field("direction", "")
    mesh_frequency_Hz: float = metric_field("mesh_frequency_Hz", column="mesh_frequency [Hz]")
    pinion_speed_rpm: float = metric_field("pinion_speed_rpm", column="pinion_speed [rpm]")
    resonance_ratio: float = metric_field("resonance_ratio")  #: f_z / f_n of the case's mesh mode
    iso_resonance_ratio: float = metric_field("iso_resonance_ratio")  #: n1 / n_E1 (ISO 6336-1)
    dynamic_factor: float = metric_field("dynamic_factor", show="speed_curve")
    force_max_N: float = metric_field("force_max_N", show="speed_curve")
    dte_peak_to_peak_mm: float = metric_field("dte_peak_to_peak_mm", show="speed_curve")
    contact_loss_fraction: float = metric_field("contact_loss_fraction", show="speed_curve")
    #: ISO 6336 S_H, S_F at this speed with its K_v = dynamic_factor, the smaller of the gears'
    #: (pipeline/run_rating.level_safeties); NaN when the case cannot be rated
    safety_pitting_min: float = metric_field("safety_pitting_min", show="speed_curve")
    safety_bending_min: float = metric_field("safety_bending_min", show="speed_curve")
    status: str = metric_field("status", "ok")  #: "ok", "invalid" or "failed"
    error: str = metric_field("error", "")

    def to_row(self) -> dict[str, Any]:
        """The summary.csv row: {column: value}."""
        return {f.metadata.get("column", f.name): getattr(self, f.name)
                for f in dataclasses.fields(self)}


#: The columns of a speed curve's summary.csv.
SPEED_CURVE_COLUMNS = tuple(f.metadata.get("column", f.name)
                            for f in dataclasses.fields(SpeedLevel))
