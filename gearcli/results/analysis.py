"""The documents of `gearcli analyze`: the metrics of analysis.json and its checks (one
:class:`Check` type for analyze and modal)."""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Mapping

from gearcli.display_units import DEFAULT, unit_and_factor
from gearcli.results.fields import Document, metric_field
from gearcli.results.metrics import check_label, check_limit_key


@dataclasses.dataclass(frozen=True)
class ResonanceMargin(Document):
    """A mesh harmonic k f_z against a mode (analysis.json's ``metrics.resonance_margins``)."""

    harmonic: int = metric_field("harmonic", 0)
    mode: int | None = metric_field("mode", None)
    excitation_Hz: float = metric_field("excitation_Hz")
    mode_Hz: float = metric_field("mode_Hz")
    margin_percent: float = metric_field("margin_percent")
    resonant_peak: bool = metric_field("resonant_peak", False)


_TABLES = "analyze report"


@dataclasses.dataclass(frozen=True, repr=False)  # Document's labelled repr
class AnalysisMetrics(Document):
    """The metrics of an analysis window (analysis.json's ``metrics``)."""

    window_s: tuple[float, float] = metric_field("window_s", (math.nan, math.nan))
    window_reason: str = metric_field("window_reason", "")
    samples: int = metric_field("samples", 0, "report")
    pinion_speed_mean_deg_s: float = metric_field("pinion_speed_mean_deg_s", show="report")
    gear_speed_mean_deg_s: float = metric_field("gear_speed_mean_deg_s", show=_TABLES)
    speed_ratio: float = metric_field("speed_ratio", show="report")
    speed_ratio_theory: float = metric_field("speed_ratio_theory", show="report")
    speed_ratio_error_percent: float = metric_field("speed_ratio_error_percent", show=_TABLES)
    gear_speed_fluctuation_percent: float = metric_field("gear_speed_fluctuation_percent",
                                                   show=_TABLES)
    force_mean_N: float = metric_field("force_mean_N", show=_TABLES)
    force_rms_N: float = metric_field("force_rms_N", show=_TABLES)
    force_max_N: float = metric_field("force_max_N", show=_TABLES + " headline")
    force_max_t_s: float = metric_field("force_max_t_s", show="report")
    force_max_source: str = metric_field("force_max_source", "")
    force_min_N: float = metric_field("force_min_N", show="report")
    force_static_N: float = metric_field("force_static_N", show=_TABLES)
    #: remedy: what gearcli/pipeline/remedy.py offers when the check of this metric fails
    dynamic_factor: float | None = metric_field("dynamic_factor", None, _TABLES + " headline",
                                                remedy="tip_relief")
    dte_mean_mm: float = metric_field("dte_mean_mm", show="report")
    dte_peak_to_peak_mm: float = metric_field("dte_peak_to_peak_mm", show=_TABLES + " headline")
    dte_rms_mm: float = metric_field("dte_rms_mm", show=_TABLES)
    contact_loss_fraction: float = metric_field("contact_loss_fraction", show=_TABLES,
                                                remedy="tip_relief")
    coast_impacts: int = metric_field("coast_impacts", 0, _TABLES)
    friction_loss_W: float | None = metric_field("friction_loss_W", None, _TABLES)
    damping_loss_W: float | None = metric_field("damping_loss_W", None, _TABLES)
    input_power_W: float | None = metric_field("input_power_W", None, "report")
    mesh_efficiency: float | None = metric_field("mesh_efficiency", None, _TABLES + " headline")
    drive_torque_mean_Nmm: float | None = metric_field("drive_torque_mean_Nmm", None, "report")
    drive_torque_ripple_Nmm: float | None = metric_field("drive_torque_ripple_Nmm", None, "report")
    mesh_natural_frequency_Hz: float | None = metric_field("mesh_natural_frequency_Hz", None,
                                                     _TABLES)
    mesh_damping_ratio: float | None = metric_field("mesh_damping_ratio", None, _TABLES)
    gear_mesh_frequency_Hz: float | None = metric_field("gear_mesh_frequency_Hz", None,
                                                  _TABLES + " headline")
    pinion_shaft_Hz: float | None = metric_field("pinion_shaft_Hz", None, "report")
    gear_shaft_Hz: float | None = metric_field("gear_shaft_Hz", None, "report")
    output_rate_Hz: float = metric_field("output_rate_Hz", show="report")
    frequency_resolution_Hz: float = metric_field("frequency_resolution_Hz", show="report")
    resonance_margins_percent: tuple[float, ...] = metric_field("resonance_margins_percent", (),
                                                          "report")
    resonance_margins: tuple[ResonanceMargin, ...] | None = metric_field(
        "resonance_margins", None, omit_none=True, nested=ResonanceMargin)


@dataclasses.dataclass(frozen=True)
class Remedy(Document):
    """What would make a failed check pass (gearcli/pipeline/remedy.py; analysis.json's
    ``checks[].remedy``): ``kind`` "tip_relief" (the relief that minimises the loaded STE at
    the case load, with the dynamic factor of a short run with it) or "speed_band" (the
    pinion speeds to avoid); ``text`` says it in one sentence."""

    kind: str = metric_field("kind", "")
    text: str = metric_field("text", "")
    tip_relief_amount_mm: float | None = metric_field("tip_relief_amount_mm", None,
                                                      omit_none=True)
    tip_relief_length_mm: float | None = metric_field("tip_relief_length_mm", None,
                                                      omit_none=True)
    ste_peak_to_peak_um: float | None = metric_field("ste_peak_to_peak_um", None, omit_none=True)
    ste_peak_to_peak_before_um: float | None = metric_field("ste_peak_to_peak_before_um", None,
                                                            omit_none=True)
    dynamic_factor: float | None = metric_field("dynamic_factor", None, omit_none=True)
    contact_loss_fraction: float | None = metric_field("contact_loss_fraction", None,
                                                       omit_none=True)
    run_end_time_s: float | None = metric_field("run_end_time_s", None, omit_none=True)
    #: the case overrides (``--set``) that apply the relief
    set: tuple[str, ...] = metric_field("set", ())
    #: (lowest, highest) pinion speed [rpm] of each band to avoid
    avoid_pinion_speed_rpm: tuple[tuple[float, float], ...] = metric_field(
        "avoid_pinion_speed_rpm", ())


@dataclasses.dataclass
class Check(Document):
    """A check of `gearcli analyze` or `gearcli modal` (analysis.json's and the modal JSON's
    ``checks``): its value against the limit (a text), passed or not."""

    name: str
    value: float | str | None
    limit: str
    #: True / False for a check that was made; None (JSON null) for one that was not
    passed: bool | None
    note: str = ""
    #: False when the check could not apply (the note says why); ``passed`` is then None,
    #: ``verdict`` "not checked", and the overall pass/fail ignores it
    checked: bool = True
    #: what would make a failed check pass (gearcli/pipeline/remedy.py); None: none offered
    remedy: Remedy | None = metric_field("remedy", None, omit_none=True, nested=Remedy)

    def __post_init__(self) -> None:
        if self.checked is False:
            self.passed = None

    @property
    def failed(self) -> bool:
        """Made and failed (what the overall pass/fail counts)."""
        return self.checked is not False and self.passed is False

    @property
    def verdict(self) -> str:
        """"passed", "failed" or "not checked"."""
        return ("not checked" if self.checked is False
                else "passed" if self.passed else "failed")

    @property
    def label(self) -> str:
        """What a person reads for this check (gearcli/results/metrics.py CHECKS)."""
        return check_label(self.name)

    @property
    def limit_key(self) -> str:
        """Where the case file sets its limit ("checks.dynamic_factor_max"; "" when fixed)."""
        return check_limit_key(self.name)

    def display(self, units: str = DEFAULT) -> tuple[float | str | None, str, str]:
        """(value, unit, limit) in the display ``units``: one unit, a fraction in % (its limit
        too), a length (stored in mm) as a deflection (µm in engineering units)."""
        value, unit, limit = self.value, "", self.limit
        name = self.name
        if name.endswith("_fraction") and isinstance(value, float):
            value, unit = 100.0 * value, "%"
            m = re.search(r"\(([^()]*%)\)", limit)
            if m:
                limit = limit[:limit.index("(")].split()[0] + " " + m.group(1)
        elif name.endswith("_percent"):
            unit = "%"
        elif name.endswith("_mm") and isinstance(value, float):
            unit, k = unit_and_factor("mm", units, fine=True)
            value = k * value
            limit = re.sub(r"([-+\d.eE]+) mm\b",
                           lambda g: f"{k * float(g.group(1)):.4g} {unit}", limit)
        elif name in ("no_aliasing", "gmf_line_present"):
            unit = "Hz"
        elif isinstance(value, float):
            unit = "–"
        return value, unit, limit

    def __repr__(self) -> str:
        value, unit, limit = self.display()
        shown = f"{value:.4g}" if isinstance(value, float) else "–" if value is None else value
        unit = f" {unit}" if unit not in ("", "–") and value is not None else ""
        return (f"<Check {self.label} ({self.name}): {self.verdict}, {shown}{unit}, "
                f"limit {limit}>")


@dataclasses.dataclass(frozen=True)
class SpectrumLine(Document):
    """An expected line of a spectrum, measured (gearcli/pipeline/spectrum.measure_line)."""

    expected_Hz: float = metric_field("expected_Hz")
    measured_Hz: float | None = metric_field("measured_Hz", None)
    amplitude: float | None = metric_field("amplitude", None)
    bin_error: float | None = metric_field("bin_error", None)  #: (measured - expected) / bin
    resolvable: bool = metric_field("resolvable", False)


@dataclasses.dataclass(frozen=True)
class AnalysisDocument(Document):
    """analysis.json (`gearcli analyze`): the metrics, the checks, the warnings and the
    measured lines of each spectrum ({signal: {line label: SpectrumLine}})."""

    schema_version: int = metric_field("schema_version", 0)
    case: str | None = metric_field("case", None)
    passed: bool = metric_field("passed", True)
    window_s: tuple[float, float] = metric_field("window_s", (math.nan, math.nan))
    window_reason: str = metric_field("window_reason", "")
    metrics: AnalysisMetrics = metric_field("metrics", AnalysisMetrics(), nested=AnalysisMetrics)
    checks: tuple[Check, ...] = metric_field("checks", (), nested=Check)
    warnings: tuple[str, ...] = metric_field("warnings", ())
    lines: Mapping[str, Mapping[str, SpectrumLine]] = metric_field(
        "lines", {}, nested=SpectrumLine, mapping_depth=2)
