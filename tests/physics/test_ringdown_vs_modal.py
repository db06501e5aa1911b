"""Second method for `gearcli modal` (issue 5): free oscillation of the simulated model.

The drivetrain (motor inertia, drive shaft, pinion, mesh, gear, load shaft, load inertia; and
in the lateral-torsional model the four centre coordinates on their bearings) is put at rest
in static equilibrium under balanced constant torques, every coordinate is displaced by a
fraction of its static value, and the compiled solver integrates the free, undamped motion
(friction off, c_max = 0, linear contact law e = 1). The contact never opens and the pinion
stays in the single-pair zone around C, so the simulated model is exactly linear with the
mesh stiffness k of one pair: its spectrum must show the natural frequencies that
`gearcli.model.modal` computes for the same Structure with k_mesh = k.

Tolerance 2 % (issue 5). The spectral peaks are located to ~0.1 bin (Hann window, parabolic
interpolation of the log amplitude); 0.4 s of motion gives 2.5 Hz bins, 0.2 % of the lowest
mode compared.
"""


import numpy as np
import pytest

from gearcli.case.load import load_case
from gearcli.core.integrate import simulate
from gearcli.core.layout import P
from gearcli.model.modal import LinearSystem, linear_modes
from gearcli.model.structure import line_of_action
from gearcli.pipeline.geometry import run_geometry
from gearcli.pipeline.kernel_input import build_kernel_input
from gearcli.pipeline.structure import build_structure

K_MESH = 5.0e5  # N/mm, one pair, e = 1
T_LOAD = 4.5e5  # N*mm on the load inertia
CASE = """
name: ringdown
model: {model}
gears:
  module: 10
  pressure_angle: 20
  face_width: 100
  pinion: {{teeth: 17}}
  gear: {{teeth: 25}}
contact: {{law: impact, stiffness: {k}, exponent: 1, max_damping: 0}}
friction: {{enabled: false}}
drive:
  type: torque
  torque: {t_drive}          # N*mm: T_load r_b1/r_b2, no net torque on the rigid-body mode
  motor_inertia: 0.1 kg*m^2
  shaft: {{stiffness: 3e5 N*m/rad}}
  reference_speed: 3000
load:
  torque: {t_load}
  shaft: {{stiffness: 2e5 N*m/rad}}
  inertia: 0.5 kg*m^2
{bearings}
run: {{end_time: 0.4, output_rate: 40 kHz, rtol: 1e-9, atol: 1e-10}}
"""
BEARINGS = """bearings:
  pinion: {stiffness_x: 4e6, stiffness_y: 3e6}
  gear: {stiffness_x: 5e6, stiffness_y: 4e6}
"""
SIGNALS = ("force_total_N", "drive_shaft_torque_Nmm", "load_shaft_torque_Nmm",
           "bearing_force_x1_N", "bearing_force_y1_N", "bearing_force_x2_N",
           "bearing_force_y2_N")


def _ringdown(tmp_path, model):
    bearings = BEARINGS if model == "lateral-torsional" else ""
    text = CASE.format(model=model, k=K_MESH, t_drive=T_LOAD * 17 / 25, t_load=T_LOAD,
                       bearings=bearings)
    path = tmp_path / "ringdown.yaml"
    path.write_text(text)
    loaded = load_case(path)
    geo = run_geometry(loaded)
    ki = build_kernel_input(loaded.case, geo)
    st = build_structure(loaded.case, geo)
    # static equilibrium: F = T_load / r_b2 on one pair, shafts twisted by their torques,
    # centres pushed apart along n_d by their bearings (model/structure.py)
    f = T_LOAD / st.r_b2_mm
    nx, ny = line_of_action(st.alpha_w_rad)
    prm = ki.params.copy()
    p_eq = f / K_MESH
    lat_eq = 0.0
    if st.lateral:
        u1 = (-f * nx / st.pinion_support.stiffness_x_N_mm,
              -f * ny / st.pinion_support.stiffness_y_N_mm)
        u2 = (f * nx / st.gear_support.stiffness_x_N_mm, f * ny / st.gear_support.stiffness_y_N_mm)
        lat_eq = (u1[0] - u2[0]) * nx + (u1[1] - u2[1]) * ny
        # displaced from equilibrium by +-20..40 % so that every mode moves
        prm[P.x1_init], prm[P.y1_init] = 1.3 * u1[0], 0.8 * u1[1]
        prm[P.x2_init], prm[P.y2_init] = 0.7 * u2[0], 1.2 * u2[1]
    prm[P.delta_init] = p_eq - lat_eq + 0.25 * p_eq
    prm[P.tw_m_init] = 1.4 * f * st.r_b1_mm / st.drive_shaft_stiffness_Nmm_rad
    prm[P.tw_l_init] = 0.6 * T_LOAD / st.load_shaft_stiffness_Nmm_rad
    kr = simulate(prm, ki.tables.tables, t_out=ki.t_out, drive_pp=ki.drive_pp,
                  load_pp=ki.load_pp, drive_angle_pp=ki.drive_angle_pp, **ki.arrays)
    assert kr.ok, kr.message
    modes = linear_modes(LinearSystem(st, K_MESH)).elastic
    return kr, ki.output_rate_Hz, modes


def _spectrum(kr, rate):
    """Sum of the Hann amplitude spectra of the signals, each scaled to its own peak."""
    total = 0.0
    for name in SIGNALS:
        x = kr.column(name)
        x = x - x.mean()
        if np.ptp(x) == 0.0:  # torsional model: no bearing forces
            continue
        spec = np.abs(np.fft.rfft(x * np.hanning(x.size)))
        total = total + spec / spec.max()
    return np.fft.rfftfreq(kr.series.shape[0], 1.0 / rate), total


def _peak(freq, spec, lo, hi):
    """Frequency of the largest bin in [lo, hi] refined by a parabola through log amplitudes."""
    band = np.flatnonzero((freq >= lo) & (freq <= hi))
    i = band[np.argmax(spec[band])]
    a, b, c = np.log(spec[i - 1 : i + 2])
    return freq[i] + 0.5 * (a - c) / (a - 2 * b + c) * (freq[1] - freq[0]), spec[i]


@pytest.mark.parametrize("model", ["torsional", "lateral-torsional"])
def test_free_oscillation_matches_the_modal_frequencies(tmp_path, model):
    kr, rate, modes = _ringdown(tmp_path, model)
    assert np.nanmin(kr.column("force_total_N")) > 0.0  # contact never opened: linear
    assert np.all(kr.column("pairs_in_contact") == 1)  # single-pair zone: mesh stiffness k
    assert len(modes) == (3 if model == "torsional" else 7)
    freq, spec = _spectrum(kr, rate)
    found = []
    for m in modes:
        f_n = m.natural_frequency_Hz
        f_peak, height = _peak(freq, spec, 0.95 * f_n, 1.05 * f_n)
        assert height > 1e-3 * spec.max(), f"mode {m.number} ({f_n:.1f} Hz) not excited"
        assert f_peak == pytest.approx(f_n, rel=0.02), f"mode {m.number}: {m.description}"
        found.append(f_peak)
    # and no other resonance: every strong peak of the simulation is a modal frequency
    strong = [i for i in range(1, spec.size - 1) if spec[i] > 0.05 * spec.max()
              and spec[i] >= spec[i - 1] and spec[i] >= spec[i + 1] and freq[i] > 5.0]
    for i in strong:
        assert min(abs(freq[i] / m.natural_frequency_Hz - 1) for m in modes) < 0.02, freq[i]
