"""Labels and stored units of the result metrics, defined once: the CLI tables, the
report tables and the Python API's typed results (gearcli/results/) read them from here, so a
metric is added or renamed in one place. Keys are the names of summary.json's ``scalars`` and
analysis.json's ``metrics`` (internal units, the unit in the name); the display unit follows the
display-unit setting (gearcli/display_units.py: rpm or rad/s, µm or m, ...)."""

from __future__ import annotations

import math
from typing import NamedTuple

from gearcli.display_units import DEFAULT, convert


class Metric(NamedTuple):
    label: str
    unit: str  #: stored unit ("–" dimensionless, "fraction" a fraction shown in %)
    fine: bool = False  #: a deflection: µm in engineering units (display_units)


METRICS: dict[str, Metric] = {
    "pinion_speed_mean_deg_s": Metric("pinion speed, mean", "deg/s"),
    "gear_speed_mean_deg_s": Metric("gear speed, mean", "deg/s"),
    "speed_ratio": Metric("speed ratio ω1/ω2", "–"),
    "speed_ratio_mean": Metric("speed ratio ω1/ω2, mean", "–"),
    "speed_ratio_theory": Metric("speed ratio, theory z2/z1", "–"),
    "speed_ratio_error_percent": Metric("speed ratio error", "%"),
    "gear_speed_fluctuation_percent": Metric("gear speed fluctuation, peak to peak / mean",
                                             "%"),
    "force_static_N": Metric("static normal force T/r_b2", "N"),
    "force_mean_N": Metric("normal force, mean", "N"),
    "force_rms_N": Metric("normal force, RMS", "N"),
    "force_max_N": Metric("normal force, maximum", "N"),
    "force_max_t_s": Metric("time of the maximum force", "s"),
    "force_min_N": Metric("normal force, minimum", "N"),
    "dynamic_factor": Metric("dynamic factor F_max / F_static", "–"),
    "operating_state": Metric("operating state in the window (steady/unsteady)", "–"),
    "operating_change_fraction": Metric("largest speed or load change over the window",
                                        "fraction"),
    "safety_pitting_min": Metric("S_H ISO 6336 with the simulated K_v, min of the gears", "–"),
    "safety_bending_min": Metric("S_F ISO 6336 with the simulated K_v, min of the gears", "–"),
    "dte_mean_mm": Metric("DTE, mean", "mm", True),
    "dte_peak_to_peak_mm": Metric("DTE, peak to peak", "mm", True),
    "dte_rms_mm": Metric("DTE, standard deviation", "mm", True),
    "contact_loss_fraction": Metric("time without drive-flank contact", "fraction"),
    "coast_impacts": Metric("coast-flank impacts", "–"),
    "coast_force_max_N": Metric("coast-flank force, maximum", "N"),
    "pairs_in_contact_mean": Metric("tooth pairs in contact, mean", "–"),
    "input_power_W": Metric("input power", "W"),
    "friction_loss_W": Metric("friction loss", "W"),
    "damping_loss_W": Metric("mesh damping loss", "W"),
    "mesh_efficiency": Metric("mesh efficiency", "fraction"),
    "drive_torque_mean_Nmm": Metric("drive torque, mean", "N*mm"),
    "drive_torque_ripple_Nmm": Metric("drive torque, peak to peak", "N*mm"),
    "gear_mesh_frequency_Hz": Metric("gear-mesh frequency f_z", "Hz"),
    "pinion_shaft_Hz": Metric("pinion shaft frequency n1", "Hz"),
    "gear_shaft_Hz": Metric("gear shaft frequency n2", "Hz"),
    "mesh_natural_frequency_Hz": Metric("mesh mode natural frequency f_n", "Hz"),
    # the mesh-frequency lines of a sweep's points (summary.csv)
    "gear_speed_gmf_amplitude_rad_s": Metric("gear speed, amplitude at f_z", "rad/s"),
    "dte_gmf_amplitude_mm": Metric("DTE, amplitude at f_z", "mm", True),
    "force_gmf_amplitude_N": Metric("normal force, amplitude at f_z", "N"),
    "mesh_damping_ratio": Metric("mesh mode damping ratio ζ", "–"),
    "mesh_stiffness_N_mm": Metric("mesh stiffness (linearised)", "N/mm"),
    "single_pair_stiffness_N_mm": Metric("mesh stiffness, single pair (linearised)", "N/mm"),
    "double_pair_stiffness_N_mm": Metric("mesh stiffness, two pairs (linearised)", "N/mm"),
    "static_deflection_mm": Metric("static deflection", "mm", True),
    "resonance_margins_percent": Metric("distance of k·f_z from the nearest mode (k = 1, 2, ..)",
                                        "%"),
    "output_rate_Hz": Metric("output sampling rate", "Hz"),
    "frequency_resolution_Hz": Metric("spectrum resolution", "Hz"),
    "samples": Metric("samples in the window", "–"),
    "energy_relative_residual": Metric("energy balance, relative residual", "–"),
    "window_s": Metric("steady window", "s"),
    # stress.json, per gear (gearcli stress)
    "sigma_H_peak_MPa": Metric("contact stress σ_H, dynamic peak", "MPa"),
    "sigma_F_peak_MPa": Metric("root stress σ_F, dynamic peak", "MPa"),
    "sigma_H_iso_MPa": Metric("ISO static σ_H (Z_B or Z_D Z_ε σ_H0, single contact)", "MPa"),
    "sigma_F0_MPa": Metric("ISO static σ_F0 = F_t/(b m) Y_F Y_S", "MPa"),
    "ratio_sigma_H_to_static": Metric("dynamic / static σ_H", "–"),
    "ratio_sigma_F_to_static": Metric("dynamic / static σ_F", "–"),
    "S_H": Metric("safety S_H = σ_Hlim / σ_H,max", "–"),
    "S_F": Metric("safety S_F = σ_Flim Y_ST / σ_F,max", "–"),
    # gearcli mesh (quasi-static loaded contact)
    "force_N": Metric("static normal force", "N"),
    "ste_mean_um": Metric("loaded STE, mean", "µm"),
    "ste_peak_to_peak_um": Metric("loaded STE, peak to peak", "µm"),
    "ste_peak_to_peak_arcsec": Metric("loaded STE, peak to peak at the pinion", "arcsec"),
    "unloaded_te_peak_to_peak_um": Metric("unloaded TE, peak to peak", "µm"),
    "mesh_mean_N_mm": Metric("mesh stiffness, mean over the cycle", "N/mm"),
    "pairs_in_contact_min": Metric("pairs in contact, fewest over the cycle", "–"),
    "pairs_in_contact_max": Metric("pairs in contact, most over the cycle", "–"),
    "single_pair_share": Metric("share of the cycle with one pair alone in contact",
                                "fraction"),
    "single_pair_limit_N": Metric("largest static force with one pair alone somewhere in the "
                                  "cycle", "N"),
    "single_pair_limit_N_per_mm": Metric("the same per face width (normal line load)",
                                         "N/mm (line load)"),
    "single_pair_zone_N_mm": Metric("mesh stiffness, single-pair zone (mean)", "N/mm"),
    "double_pair_zone_N_mm": Metric("mesh stiffness, double-pair zone (mean)", "N/mm"),
    "iso6336_single_pair_c_prime_b_N_mm": Metric("ISO 6336-1 c′b (single pair)", "N/mm"),
    "iso6336_mean_c_gamma_alpha_b_N_mm": Metric("ISO 6336-1 c_γα b (mean)", "N/mm"),
    "resonance_speed_rpm": Metric("ISO 6336-1 resonance speed n_E1", "rpm"),
    "resonance_ratio": Metric("ISO resonance ratio N = n1/n_E1", "–"),
    "k_v": Metric("ISO 6336-1 Method B K_v", "–"),
    # modal (gearcli modal), per mode
    "natural_frequency_Hz": Metric("natural frequency", "Hz"),
    "damping_ratio": Metric("damping ratio ζ", "–"),
}


class CheckInfo(NamedTuple):
    label: str
    #: where the case file sets its limit ("checks.<key>"; "--strict" for a command-line
    #: switch; "" when the limit is fixed)
    limit_key: str


#: The checks of `gearcli analyze` and `gearcli modal` (analysis.json's ``checks[].name``, which
#: stays the key of files and scripts): what a person reads, and where its limit is set.
CHECKS: dict[str, CheckInfo] = {
    "solver_status": CheckInfo("solver finished", ""),
    "speed_ratio_error_percent": CheckInfo(METRICS["speed_ratio_error_percent"].label,
                                           "checks.speed_ratio_error_percent"),
    "no_aliasing": CheckInfo("mesh harmonics below fs/2 (no aliasing)",
                             "checks.harmonics, run.output_rate"),
    "gmf_line_present": CheckInfo("mesh-frequency line in the gear speed spectrum", ""),
    "resonance_margin_percent": CheckInfo("resonance margin of k·f_z to the nearest mode",
                                          "checks.resonance_margin_percent"),
    "dynamic_factor": CheckInfo(METRICS["dynamic_factor"].label, "checks.dynamic_factor_max"),
    "contact_loss_fraction": CheckInfo(METRICS["contact_loss_fraction"].label,
                                       "checks.contact_loss_fraction_max"),
    "dte_peak_to_peak_mm": CheckInfo(METRICS["dte_peak_to_peak_mm"].label,
                                     "checks.dte_peak_to_peak_max"),
    "energy_balance": CheckInfo(METRICS["energy_relative_residual"].label,
                                "checks.energy_balance_tolerance"),
    "no_warnings": CheckInfo("no warnings", "--strict"),
}


def check_label(name: str) -> str:
    """The label of check ``name`` (:data:`CHECKS`; an unknown name with spaces for
    underscores)."""
    info = CHECKS.get(name)
    return info.label if info else name.replace("_", " ")


def check_limit_key(name: str) -> str:
    """Where the case sets the limit of check ``name`` ("" when fixed or unknown)."""
    info = CHECKS.get(name)
    return info.limit_key if info else ""


def display(key: str, value, system: str = DEFAULT):
    """(label, value in the display unit, display unit) of a stored metric (lists
    elementwise)."""
    m = METRICS[key]
    shown, unit = convert(value, m.unit, system, m.fine)
    return m.label, shown, unit


def rows(values: dict, keys, system: str = DEFAULT) -> list[tuple[str, object, str]]:
    """Display rows of the ``keys`` present in ``values``."""
    return [display(k, values[k], system) for k in keys if k in values]


def json_number(value) -> float | None:
    """A number for a JSON document: NaN and infinities (not defined, e.g. a single-pair zone
    of a pair whose contact ratio is above 2) become null, which JSON has, unlike NaN."""
    if value is None:
        return None
    value = float(value)
    return value if math.isfinite(value) else None
