"""Labels and display units of the result metrics, defined once (issue 17): the CLI tables, the
report tables and the Python API's typed :class:`gearcli.api.Summary` read them from here, so a
metric is added or renamed in one place. Keys are the names of summary.json's ``scalars`` and
analysis.json's ``metrics`` (internal units, the unit in the name); ``scale`` converts the stored
value to the display ``unit``."""

from __future__ import annotations

from typing import NamedTuple


class Metric(NamedTuple):
    label: str
    unit: str  #: display unit ("–" for dimensionless)
    scale: float = 1.0  #: display value = stored value * scale


METRICS: dict[str, Metric] = {
    "pinion_speed_mean_deg_s": Metric("pinion speed, mean", "deg/s"),
    "gear_speed_mean_deg_s": Metric("gear speed, mean", "deg/s"),
    "speed_ratio": Metric("speed ratio ω1/ω2", "–"),
    "speed_ratio_mean": Metric("speed ratio ω1/ω2, mean", "–"),
    "speed_ratio_theory": Metric("speed ratio, theory z2/z1", "–"),
    "speed_ratio_error_percent": Metric("speed ratio error", "%"),
    "gear_speed_fluctuation_percent": Metric("gear speed fluctuation, peak to peak / mean",
                                             "%"),
    "force_static_N": Metric("static normal force T_load/r_b2", "N"),
    "force_mean_N": Metric("normal force, mean", "N"),
    "force_rms_N": Metric("normal force, RMS", "N"),
    "force_max_N": Metric("normal force, maximum", "N"),
    "force_max_t_s": Metric("time of the maximum force", "s"),
    "force_min_N": Metric("normal force, minimum", "N"),
    "dynamic_factor": Metric("dynamic factor F_max / F_static", "–"),
    "dte_mean_mm": Metric("DTE, mean", "µm", 1e3),
    "dte_peak_to_peak_mm": Metric("DTE, peak to peak", "µm", 1e3),
    "dte_rms_mm": Metric("DTE, standard deviation", "µm", 1e3),
    "contact_loss_fraction": Metric("time without drive-flank contact", "%", 100.0),
    "coast_impacts": Metric("coast-flank impacts", "–"),
    "coast_force_max_N": Metric("coast-flank force, maximum", "N"),
    "pairs_in_contact_mean": Metric("tooth pairs in contact, mean", "–"),
    "input_power_W": Metric("input power", "W"),
    "friction_loss_W": Metric("friction loss", "W"),
    "mesh_efficiency": Metric("mesh efficiency", "–"),
    "drive_torque_mean_Nmm": Metric("drive torque, mean", "N·m", 1e-3),
    "drive_torque_ripple_Nmm": Metric("drive torque, peak to peak", "N·m", 1e-3),
    "gear_mesh_frequency_Hz": Metric("gear-mesh frequency f_z", "Hz"),
    "pinion_shaft_Hz": Metric("pinion shaft frequency n1", "Hz"),
    "gear_shaft_Hz": Metric("gear shaft frequency n2", "Hz"),
    "mesh_natural_frequency_Hz": Metric("mesh mode natural frequency f_n", "Hz"),
    "mesh_damping_ratio": Metric("mesh mode damping ratio ζ", "–"),
    "mesh_stiffness_N_mm": Metric("mesh stiffness (linearised)", "N/mm"),
    "static_deflection_mm": Metric("static deflection", "µm", 1e3),
    "resonance_margins_percent": Metric("distance of k·f_z from the nearest mode (k = 1, 2, ..)",
                                        "%"),
    "output_rate_Hz": Metric("output sampling rate", "Hz"),
    "frequency_resolution_Hz": Metric("spectrum resolution", "Hz"),
    "samples": Metric("samples in the window", "–"),
    "energy_relative_residual": Metric("energy balance, relative residual", "–"),
    "window_s": Metric("steady window", "s"),
}


def display(key: str, value):
    """(label, value in the display unit, unit) of a stored metric (lists elementwise)."""
    m = METRICS[key]
    if m.scale != 1.0 and isinstance(value, int | float) and not isinstance(value, bool):
        value = value * m.scale
    elif m.scale != 1.0 and isinstance(value, list):
        value = [v * m.scale for v in value]
    return m.label, value, m.unit


def rows(values: dict, keys) -> list[tuple[str, object, str]]:
    """Display rows of the ``keys`` present in ``values``."""
    return [display(k, values[k]) for k in keys if k in values]
