"""The scalar metrics of one sweep point, straight from a SimulationResult (no folder on disk).

The scalars are the simulation summary's (gearcli.pipeline.simulate.summarize); the mesh-line
amplitudes use the same spectrum and line measurement as `gearcli analyze`
(gearcli.pipeline.spectrum: Hann-windowed amplitude spectrum over the steady window, line at the
measured gear-mesh frequency f_z = z1 n1).
"""

from __future__ import annotations

from gearcli.io.metrics import json_number
from gearcli.model.geometry import mesh_frequencies
from gearcli.pipeline.spectrum import amplitude_spectrum, measure_line

#: Scalars copied from the simulation summary, in column order.
SUMMARY_METRICS = (
    "force_max_N", "force_min_N", "force_mean_N", "force_rms_N", "force_static_N",
    "dynamic_factor", "dte_mean_mm", "dte_peak_to_peak_mm", "dte_rms_mm",
    "contact_loss_fraction", "coast_force_max_N", "pairs_in_contact_mean",
    "pinion_speed_mean_deg_s", "gear_speed_mean_deg_s", "gear_mesh_frequency_Hz",
    "mesh_stiffness_N_mm", "single_pair_stiffness_N_mm", "mesh_natural_frequency_Hz",
    "mesh_damping_ratio",
)
#: Mesh-line amplitudes: (metric, kernel column).
LINE_METRICS = (("gear_speed_gmf_amplitude_rad_s", "omega2_rad_s"),
                ("dte_gmf_amplitude_mm", "delta_mm"),
                ("force_gmf_amplitude_N", "force_total_N"))
METRICS = (*SUMMARY_METRICS, *(m for m, _ in LINE_METRICS), "energy_balance_relative_residual")


def point_metrics(res) -> dict[str, float | None]:
    """Every metric of :data:`METRICS` for one finished simulation."""
    s = res.summary
    out: dict[str, float | None] = {m: _num(s.get(m)) for m in SUMMARY_METRICS}
    k = res.kernel
    t = k.column("t_s")
    sel = (t >= res.window.t0_s - 1e-12) & (t <= res.window.t1_s + 1e-12)
    rate = res.kernel_input.output_rate_Hz
    g = res.geometry.geometry
    f_z = mesh_frequencies(g.pinion.teeth, float(k.column("omega1_rad_s")[sel].mean()), g.ratio)[0]
    for name, column in LINE_METRICS:
        freq, amp = amplitude_spectrum(k.column(column)[sel], rate)
        line = measure_line(freq, amp, f_z)
        out[name] = _num(line.amplitude) if line.resolvable else None
    out["energy_balance_relative_residual"] = _num(s["energy_balance"]["relative_residual"])
    return out


_num = json_number
