"""What a sensor sees (docs/theory.md, "What a sensor sees"; model/sensors.py,
pipeline/sensors.py).

* the housing transfer of one resonance, run in the time domain, matches its closed-form FRF
  (amplitude and phase) below, at and above the resonance;
* the quasi-static bearing reaction carries the mesh force along the line of action;
* the recorder's anti-alias filter keeps a tone in band and removes one above Nyquist;
* seeded noise: reproducible, the requested rms and SNR, independent channels;
* the TSA over N revolutions lowers the seeded noise by √N;
* a run without ``sensors:`` writes what it wrote before; with sensors and no noise the time
  series is unchanged and the sensors table holds the encoder TE and the bearing reaction.

Units: mm, N, s, t (tonne), rad; accelerations mm/s² inside, m/s² in the table.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from gearcli.model import sensors as phys
from gearcli.model.monitoring import resample_to_angle, time_synchronous_average
from tests.conftest import ROOT

MODE = phys.HousingMode(frequency_Hz=3000.0, damping_ratio=0.05, modal_mass_t=2e-3)


def _closed_form(f_Hz: float, m: phys.HousingMode) -> complex:
    """Accelerance of m ẍ + c ẋ + k x = F written out (Ewins §2.2): a/F = −ω²/(k − mω² + icω)."""
    w, wr = 2 * math.pi * f_Hz, 2 * math.pi * m.frequency_Hz
    k, c = m.modal_mass_t * wr**2, 2 * m.damping_ratio * m.modal_mass_t * wr
    return -w**2 / complex(k - m.modal_mass_t * w**2, c * w)


@pytest.mark.parametrize("f_Hz", [600.0, 2900.0, 3000.0, 9000.0])
def test_housing_single_resonance_matches_its_frf(f_Hz):
    fs = 400.0 * 3000.0  # 133+ samples per period of the fastest tone: the hold error ~1e-5
    t = np.arange(int(0.1 * fs)) / fs  # 300 resonance periods: the start transient, decaying
    force = 100.0 * np.sin(2 * math.pi * f_Hz * t)  # with e^(-ζ ω_r t), is below 1e-40 at the end
    a = phys.housing_acceleration(t, force, [MODE])
    tail = t > 0.06  # e^(-0.05 · 2π 3000 · 0.06) = 3e-25 of the transient left
    basis = np.column_stack([np.sin(2 * math.pi * f_Hz * t[tail]),
                             np.cos(2 * math.pi * f_Hz * t[tail])])
    (s, c), *_ = np.linalg.lstsq(basis, a[tail], rcond=None)
    measured = complex(s, c) / 100.0  # a = Im[(s + i c) e^{iωt}] for F = Im[e^{iωt}]
    expected = _closed_form(f_Hz, MODE)
    assert phys.housing_frf(f_Hz, [MODE]) == pytest.approx(expected, rel=1e-12)
    # the first-order hold of a sampled sinusoid: error ~ (ω Δt)²/12 <= 2e-5 here
    assert abs(measured - expected) / abs(expected) < 1e-4


def test_housing_static_load_accelerates_nothing():
    t = np.arange(2000) / 1e5
    a = phys.housing_acceleration(t, np.full(t.size, 5000.0), [MODE, MODE])
    assert np.max(np.abs(a)) < 1e-9 * 5000.0 / MODE.modal_mass_t


def test_quasi_static_bearing_forces_carry_the_mesh_force():
    alpha = math.radians(21.5)
    fx1, fy1, fx2, fy2 = phys.quasi_static_bearing_forces(np.array([1000.0, 0.0]),
                                                          np.array([0.0, 400.0]), alpha)
    # drive force F_d on the pinion along −n_d, n_d = (sin α, cos α); coast along −n_c
    np.testing.assert_allclose([fx1[0], fy1[0]], [-1000 * math.sin(alpha),
                                                  -1000 * math.cos(alpha)], rtol=1e-15)
    np.testing.assert_allclose([fx1[1], fy1[1]], [-400 * math.sin(alpha),
                                                  400 * math.cos(alpha)], rtol=1e-15)
    np.testing.assert_array_equal(fx2, -fx1)
    np.testing.assert_array_equal(fy2, -fy1)


def test_resample_anti_alias_keeps_the_band_and_removes_aliases():
    fs_in, rate = 100_000.0, 10_000.0
    t = np.arange(int(0.2 * fs_in)) / fs_in
    keep = np.sin(2 * math.pi * 1000.0 * t)
    alias = np.sin(2 * math.pi * 8000.0 * t)  # would fold to 2 kHz at 10 kHz
    t2, k2 = phys.resample(t, keep, rate)
    _, a2 = phys.resample(t, alias, rate)
    assert np.allclose(np.diff(t2), 1.0 / rate)
    inner = slice(200, -200)  # the filtfilt's edges
    # 8th-order Butterworth at 4.5 kHz: |H(1 kHz)|² = 1/(1 + (1/4.5)^16), 1 − 3e-11
    np.testing.assert_allclose(k2[inner], np.sin(2 * math.pi * 1000.0 * t2[inner]), atol=1e-4)
    # at 8 kHz: |H|² = 1/(1 + (8/4.5)^16) -> |H| = 1e-2 per pass, 1e-4 forward and back
    assert np.max(np.abs(a2[inner])) < 3e-4


def test_noise_is_seeded_with_the_requested_rms():
    x = np.sin(np.linspace(0, 200, 100_000))
    a = phys.add_noise(x, 0.1, seed=3, channel=2)
    np.testing.assert_array_equal(a, phys.add_noise(x, 0.1, seed=3, channel=2))
    b = phys.add_noise(x, 0.1, seed=3, channel=3)
    # rms of 1e5 Gaussian samples: relative standard error 1/√(2·1e5) = 0.22 %; 5 of them
    assert np.std(a - x) == pytest.approx(0.1, rel=0.011)
    assert abs(np.corrcoef(a - x, b - x)[0, 1]) < 5 / math.sqrt(x.size)  # independent
    rms = phys.noise_rms_for_snr(x + 7.0, 20.0)
    assert rms == pytest.approx(np.sqrt(np.mean((x - x.mean()) ** 2)) / 10.0, rel=1e-12)
    np.testing.assert_array_equal(phys.add_noise(x, 0.0, 1, 1), x)


@pytest.mark.parametrize("revolutions", [1, 4, 16, 64])
def test_tsa_lowers_seeded_noise_by_sqrt_n(revolutions):
    n = 512  # samples per revolution; the time samples sit on the angle grid (exact resampling)
    theta = np.arange(revolutions * n + 1) * (2 * math.pi / n)
    clean = np.cos(21 * theta) + 0.3 * np.cos(theta)
    sigma = 0.5
    noisy = phys.add_noise(clean, sigma, seed=11, channel=2)
    tsa_noise = (time_synchronous_average(resample_to_angle(noisy, theta, n)).values
                 - time_synchronous_average(resample_to_angle(clean, theta, n)).values)
    # N n rms²/σ² is χ² with n degrees of freedom: rms/(σ/√N) has standard deviation
    # 1/√(2n) = 3.1 %; 4 of them
    assert np.sqrt(np.mean(tsa_noise**2)) == pytest.approx(sigma / math.sqrt(revolutions),
                                                           rel=0.125)


SENSORS = ("sensors={sample_rate: 6400 Hz, accelerometer: {bearing: gear, direction: 90 deg, "
           "housing: [{frequency: 2 kHz, damping_ratio: 0.05, modal_mass: 2 kg}]}}")
SHORT = ["run.end_time=0.03", "drive.speed={function: 'STEP(time, 0, 0, 0.01, 1500)', unit: rpm}",
         "load.torque={function: 'STEP(time, 0, 0, 0.01, 300)', unit: N*m}"]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from gearcli import api

    out = {}
    for name, extra in (("plain", []), ("sensors", [SENSORS]),
                        ("same_rate", ["sensors={accelerometer: {housing: [{frequency: 2 kHz, "
                                       "modal_mass: 2 kg}]}}"])):
        folder = tmp_path_factory.mktemp(name) / "run"
        api.simulate(ROOT / "cases" / "iso_pair.yaml", SHORT + extra).save(folder)
        out[name] = folder
    return out


def test_no_sensors_writes_what_it_wrote_before(runs):
    from gearcli.io.results import read_columns

    plain, sens = runs["plain"], runs["sensors"]
    assert sorted(p.name for p in plain.iterdir()) == ["manifest.json", "summary.json",
                                                       "timeseries.csv"]
    assert "sensors" not in json.loads((plain / "manifest.json").read_text())["resolved_case"]
    assert (plain / "timeseries.csv").read_text() == (sens / "timeseries.csv").read_text()
    s1 = json.loads((plain / "summary.json").read_text())["scalars"]
    s2 = json.loads((sens / "summary.json").read_text())["scalars"]
    assert s1 == s2
    table = read_columns(sens / "sensors.csv", "t_s")
    assert np.allclose(np.diff(table["t_s"]), 1 / 6400.0)
    doc = json.loads((sens / "sensors.json").read_text())
    assert doc["sample_rate_Hz"] == 6400.0 and "quasi-static" in doc["bearing_forces"]
    assert np.std(table["accel_m_s2"][table["t_s"] > 0.015]) > 0.0


def test_sensors_at_the_output_rate_are_the_encoders_and_the_reaction(runs):
    from gearcli.io.results import read_columns

    ts = read_columns(runs["same_rate"] / "timeseries.csv", "t_s")
    table = read_columns(runs["same_rate"] / "sensors.csv", "t_s")
    np.testing.assert_array_equal(table["t_s"], ts["t_s"])
    from gearcli import api

    g = api.geometry(ROOT / "cases" / "iso_pair.yaml").geometry
    te = g.pinion.r_b_mm * ts["theta1_rad"] - g.gear.r_b_mm * ts["theta2_rad"]
    # both from angles stored to 10 significant digits (CSV): 5e-10 of r_b θ per term, twice
    room = 1e-9 * (g.pinion.r_b_mm * np.abs(ts["theta1_rad"])
                   + g.gear.r_b_mm * np.abs(ts["theta2_rad"])) + 1e-12
    assert np.all(np.abs(table["te_mm"] - te) <= room)
    fy2 = (ts["force_total_N"] - ts["force_coast_N"]) * math.cos(g.alpha_w_rad)
    np.testing.assert_allclose(table["bearing_force_y2_N"], fy2, rtol=1e-8, atol=1e-6)


def test_lateral_model_bearing_forces_are_the_models(tmp_path):
    from gearcli import api
    from gearcli.io.results import read_columns

    folder = tmp_path / "lat"
    api.simulate(ROOT / "cases" / "drivetrain.yaml",
                 ["run.end_time=0.02", "sensors={noise: {seed: 0}}"]).save(folder)
    ts = read_columns(folder / "timeseries.csv", "t_s")
    table = read_columns(folder / "sensors.csv", "t_s")
    assert "lateral-torsional" in json.loads((folder / "sensors.json").read_text())[
        "bearing_forces"]
    for name in ("bearing_force_x1_N", "bearing_force_y1_N", "bearing_force_x2_N",
                 "bearing_force_y2_N"):
        np.testing.assert_array_equal(table[name], ts[name])  # same values, same 10 digits
    assert np.max(np.abs(table["bearing_force_y2_N"])) > 1.0


def test_simulation_sensors_frame():
    from gearcli import api

    sim = api.simulate(ROOT / "cases" / "iso_pair.yaml", [*SHORT, SENSORS])
    frame = sim.sensors()
    assert frame.index.name == "t_s" and "accel_m_s2" in frame.columns
    assert frame.attrs["sensors"].sample_rate_Hz == 6400.0
    with pytest.raises(ValueError, match="no 'sensors:'"):
        api.simulate(ROOT / "cases" / "iso_pair.yaml", SHORT).sensors()


def test_tsa_of_a_runs_seeded_te_noise_falls_as_sqrt_n(tmp_path):
    """End to end: the sensors' TE with seeded noise (σ = 0.1 µm per sample, at the output
    rate) against the noise-free TE of the same run, both on the pinion's angle grid (monitor
    §1): the TSA of the difference over N revolutions has σ_rev/√N, σ_rev the noise's RMS in
    one revolution's record (the spline keeps samples of different revolutions independent)."""
    from gearcli import api
    from gearcli.io.results import read_run
    from gearcli.pipeline.monitor import angle_record, steady_signal

    folder = tmp_path / "noisy"
    fast = ["run.end_time=0.4", "drive.speed={function: 'STEP(time, 0, 0, 0.05, 1500)', "
            "unit: rpm}", "load.torque={function: 'STEP(time, 0, 0, 0.05, 300)', unit: N*m}",
            "sensors={noise: {seed: 5, transmission_error: 0.1 um}}"]
    api.simulate(ROOT / "cases" / "iso_pair.yaml", fast).save(folder)
    run = read_run(folder)
    noisy, _ = steady_signal(run, "te_mm")
    clean, _ = steady_signal(run, "te")
    a_noisy, n = angle_record(noisy, "pinion")
    a_clean, _ = angle_record(clean, "pinion", n)
    revs = a_noisy.n_revolutions
    e = (a_noisy.values - a_clean.values)[: revs * n].reshape(revs, n)
    sigma_rev = float(np.sqrt(np.mean(e**2)))
    tsa = e.mean(axis=0)
    assert revs >= 6
    assert sigma_rev == pytest.approx(1e-4, rel=0.1)  # the spline smooths white noise a little
    # N n rms²/σ² ~ χ²_n: relative sd 1/√(2n) <= 3.1 % for n >= 512; 4 of them
    assert np.sqrt(np.mean(tsa**2)) == pytest.approx(sigma_rev / math.sqrt(revs), rel=0.125)
