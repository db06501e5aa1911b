"""The scalar metrics of one sweep point, straight from a SimulationResult (no folder on disk).

The scalars are the simulation summary's (gearcli.pipeline.simulate.summarize); the mesh-line
amplitudes use the same spectrum and line measurement as `gearcli analyze`
(gearcli.pipeline.spectrum: Hann-windowed amplitude spectrum over the steady window, line at the
measured gear-mesh frequency f_z = z1 n1).
"""

from __future__ import annotations

import dataclasses

from gearcli.model.frequencies import mesh_frequencies
from gearcli.pipeline.run_rating import simulated_safeties
from gearcli.pipeline.spectrum import amplitude_spectrum, measure_line
from gearcli.pipeline.validity import UNSTEADY
from gearcli.results import PointLines, shown_values, sweep_metrics
from gearcli.results.metrics import json_number

#: The metrics of a sweep point, in column order: those of the summary shown at "sweep", then
#: the mesh-line amplitudes and the energy residual (gearcli/results/: field metadata).
METRICS = sweep_metrics("sweep")


def point_metrics(res) -> dict[str, float | None]:
    """Every metric of :data:`METRICS` for one finished simulation."""
    s = res.summary
    out: dict[str, float | None] = {m: _num(v) for m, v in shown_values(s, "sweep").items()
                                    if m in METRICS}
    k = res.kernel
    t = k.column("t_s")
    sel = (t >= res.window.t0_s - 1e-12) & (t <= res.window.t1_s + 1e-12)
    rate = res.kernel_input.output_rate_Hz
    g = res.geometry.geometry
    f_z = mesh_frequencies(g.pinion.teeth, float(k.column("omega1_rad_s")[sel].mean()), g.ratio)[0]
    lines = {}
    for f in dataclasses.fields(PointLines):
        if "signal" in f.metadata:
            freq, amp = amplitude_spectrum(k.column(f.metadata["signal"])[sel], rate)
            line = measure_line(freq, amp, f_z)
            lines[f.name] = _num(line.amplitude) if line.resolvable else None
    # no safeties from a window off one operating point (pipeline/validity.operating_state)
    s_h, s_f = (simulated_safeties(res.loaded, s.dynamic_factor)
                if s.operating_state != UNSTEADY else (None, None))
    extra = PointLines(**lines, energy_balance_relative_residual=_num(
        s.energy_relative_residual), safety_pitting_min=_num(s_h), safety_bending_min=_num(s_f))
    out.update(extra.to_dict())
    return out


_num = json_number
