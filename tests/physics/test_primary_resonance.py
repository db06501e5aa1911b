"""Time-domain primary resonance (issue 5): a speed sweep with low mesh damping peaks where the
gear-mesh frequency meets the mesh mode that `gearcli modal` computes for the same case."""

import numpy as np

from gearcli.pipeline.modal import run_modal
from gearcli.pipeline.simulate import run_simulation
from tests.conftest import SEED

# c_max = 5 N*s/mm: zeta = 0.095 instead of the seed's overdamped 1.9; short ramps and runs
# (the mesh mode settles in 5 / (zeta omega_n) = 30 ms)
BASE = ["contact.max_damping=5", "friction.enabled=false", "run.end_time=0.4",
        "load.torque=STEP(time, 0, 0, 0.05, 4.5e5)"]
RATIOS = (0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3)  # f_z / f_n


def _speed(ratio, f_n):
    """Pinion speed [deg/s] with f_z = ratio f_n (f_z = z1 n1)."""
    return f"drive.speed=STEP(time, 0, 0, 0.05, {ratio * f_n / 17 * 360:.6g})"


def test_speed_sweep_peaks_at_the_mesh_mode():
    modal = run_modal(SEED, BASE)
    (mode,) = modal.result.elastic  # speed drive: the gear against the prescribed pinion
    f_n = mode.natural_frequency_Hz
    assert 0.05 < mode.damping_ratio < 0.2
    dte = [run_simulation(SEED, [*BASE, _speed(r, f_n)]).summary.dte_peak_to_peak_mm
           for r in RATIOS]
    peak = RATIOS[int(np.argmax(dte))]
    # measured: DTE p-p 0.093, 0.170, 0.546, 0.797, 0.111, 0.067, 0.048 mm. The peak sits at
    # f_z = f_n; the contact opens near resonance (a softening nonlinearity that bends the
    # peak towards lower frequencies), so 0.9 f_n is accepted too, not 1.1 f_n.
    assert peak in (0.9, 1.0), dte
    assert max(dte) > 4.0 * max(dte[0], dte[-1]), dte
