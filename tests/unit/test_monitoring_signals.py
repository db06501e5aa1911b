"""Angle resampling, time-synchronous average and order-domain signals (docs/theory.md,
"Condition-monitoring signals", §1–§4)."""

import math

import numpy as np
import pytest
from scipy import stats

from gearcli.model.monitoring import (
    resample_to_angle,
    samples_per_revolution,
    time_synchronous_average,
)
from gearcli.model.monitoring.orders import (
    difference_signal,
    keep_orders,
    order_amplitude,
    order_spectrum,
    regular_signal,
    residual_signal,
    sideband_table,
)

# A run-up: shaft frequency 10 → 20 Hz linearly over 2 s (30 revolutions, of which 29 whole ones
# lie within the samples, the last sample being 1/f_s before 2 s), sampled at 2800 Hz,
# 20 samples per period of order 7 at the top speed.
F0_HZ, F1_HZ, T_S, FS_HZ = 10.0, 20.0, 2.0, 2800.0


def _run_up():
    t = np.arange(0.0, T_S, 1.0 / FS_HZ)
    theta = 2 * np.pi * (F0_HZ * t + 0.5 * (F1_HZ - F0_HZ) / T_S * t**2)
    return t, theta


def test_samples_per_revolution_rule():
    """Power of two ≥ the most time samples in one revolution and ≥ 2 (order + 1)."""
    theta = 2 * np.pi * np.arange(5000) / 1000.0  # 1000 samples per revolution
    assert samples_per_revolution(theta) == 1024
    assert samples_per_revolution(theta, highest_order=700) == 2048
    _, run_up = _run_up()
    assert samples_per_revolution(run_up) == 512  # 280 per revolution at 10 Hz
    with pytest.raises(ValueError):
        samples_per_revolution(np.array([0.0, 1.0, 1.0, 2.0]))


def test_resampling_a_pure_order_under_varying_speed_gives_one_clean_line():
    """x(t) = cos 7θ(t) through a run-up: in time it smears over 70 … 140 Hz; on the shaft
    angle it is one line of amplitude 1 at order 7. Bound: the cubic spline's error for a
    sinusoid of φ rad per sample is ≤ (5/384) φ⁴ (Hall & Meyer 1976), φ ≤ 2π/20 here, so
    1.3e-4; a line of the spectrum of the error is at most twice its maximum: 2.5e-4. We allow
    5e-4 (the not-a-knot end conditions are not the clamped ones of the bound)."""
    t, theta = _run_up()
    x = np.cos(7 * theta)
    n = samples_per_revolution(theta, highest_order=7)
    sig = resample_to_angle(x, theta, n)
    assert sig.n_revolutions == 29 and sig.values.size == 29 * n
    tsa = time_synchronous_average(sig)
    orders, amp = order_spectrum(tsa)
    assert amp[7] == pytest.approx(1.0, abs=5e-4)
    assert np.max(np.delete(amp, 7)) < 5e-4
    time_amp = 2 * np.abs(np.fft.rfft(x)) / x.size
    assert time_amp.max() < 0.2  # the same signal's time spectrum has no clean line


def test_reference_angle_and_a_backward_shaft():
    """Index 0 of the grid is the reference angle: cos 3(θ − θ_ref) peaks at index 0. A shaft
    turning backwards (θ decreasing) is resampled on −θ: the same samples as the mirrored
    forward shaft with the mirrored reference."""
    _, theta = _run_up()
    ref = 1.0
    x = np.cos(3 * (theta - ref))
    fwd = resample_to_angle(x, theta, 512, reference_angle_rad=ref)
    assert fwd.values[0] == pytest.approx(1.0, abs=1e-6)
    assert fwd.start_angle_rad == pytest.approx(ref)  # the first θ_ref + 2πj ≥ θ(0) = 0
    back = resample_to_angle(x, -theta, 512, reference_angle_rad=-ref)
    np.testing.assert_allclose(back.values, fwd.values, rtol=0, atol=1e-15)
    with pytest.raises(ValueError):
        resample_to_angle(x[:10], theta[:10], 512)  # less than a revolution


def test_tsa_lowers_uncorrelated_noise_by_sqrt_n():
    """Noise σ per sample, independent between revolutions: each TSA sample is the mean of N,
    so N n rms²/σ² of the TSA's noise is χ² with n degrees of freedom, and √N rms/σ is
    χ_n/√n. With n = 4096 its 10⁻⁶ and 1 − 10⁻⁶ quantiles are 0.92 and 1.08; 1/N or no
    averaging falls far outside from N = 4 on. A periodic signal passes unchanged."""
    n, sigma = 4096, 0.7
    theta = 2 * np.pi * np.arange(n) / n
    s = np.cos(13 * theta) + 0.3 * np.cos(26 * theta + 0.4)
    lo = stats.chi.ppf(1e-6, n) / math.sqrt(n)
    hi = stats.chi.ppf(1 - 1e-6, n) / math.sqrt(n)
    rng = np.random.default_rng(11)
    for n_rev in (1, 4, 16, 64):
        x = np.tile(s, n_rev) + rng.normal(0.0, sigma, n * n_rev)
        tsa = time_synchronous_average(x, n)
        assert tsa.n_revolutions == n_rev
        ratio = math.sqrt(n_rev) * np.sqrt(np.mean((tsa.values - s) ** 2)) / sigma
        assert lo < ratio < hi, (n_rev, ratio)
    clean = time_synchronous_average(np.tile(s, 5), n)
    np.testing.assert_allclose(clean.values, s, atol=1e-14)


def _gear_signal(a, z=13, width=0.3, at=2.0):
    """Mesh tone cos zθ amplitude-modulated once per revolution by a Gaussian pulse (a local
    tooth fault): x = cos zθ (1 + a g(θ)), g = Σ_r exp(−(θ − at − 2πr)²/(2 width²))."""
    t, theta = _run_up()
    phase = np.mod(theta - at + np.pi, 2 * np.pi) - np.pi
    g = sum(np.exp(-((phase + 2 * np.pi * r) ** 2) / (2 * width**2)) for r in (-1, 0, 1))
    return theta, np.cos(z * theta) * (1.0 + a * g)


def test_a_once_per_revolution_fault_gives_sidebands_at_the_shaft_order_spacing():
    """g's Fourier series is c_0 + Σ 2 c_k cos k(θ − at), c_k = w/√(2π) exp(−k² w²/2), so the
    TSA's order spectrum has a c_k at z ± k (k = 1, 2, 3 …) and 1 + a c_0 at z; a healthy gear
    (a = 0) has no sidebands. Tolerance 1e-3: the resampling bound of the clean-line test
    (5e-4) for a signal whose peak is 1 + a."""
    z, w, a = 13, 0.3, 0.5
    c = [w / math.sqrt(2 * math.pi) * math.exp(-(k**2) * w**2 / 2) for k in range(4)]
    theta, x = _gear_signal(a, z, w)
    tsa = time_synchronous_average(resample_to_angle(x, theta, 512))
    table = sideband_table(tsa, z, n_sidebands=3, n_mesh_harmonics=1)[0]
    expect = [a * c[3], a * c[2], a * c[1], 1 + a * c[0], a * c[1], a * c[2], a * c[3]]
    np.testing.assert_allclose(table, expect, atol=1e-3)
    assert min(table[[0, 1, 2, 4, 5, 6]]) > 0.03  # the fault's sidebands are there ...
    theta, healthy = _gear_signal(0.0, z, w)
    clean = sideband_table(time_synchronous_average(resample_to_angle(healthy, theta, 512)),
                           z, n_sidebands=3, n_mesh_harmonics=1)[0]
    assert max(clean[[0, 1, 2, 4, 5, 6]]) < 5e-4  # ... and absent without it
    assert clean[3] == pytest.approx(1.0, abs=5e-4)


def test_the_pinion_fault_has_no_sidebands_on_the_mating_gear_shaft():
    """The same signal on the gear's angle (29 teeth, turning backwards: θ₂ = −13/29 θ₁): the
    mesh is gear order 29, but the pinion's once-per-revolution pattern sits at the gear orders
    29 k/13, not integers. The record holds 13 whole gear revolutions (= 29 pinion ones), so
    each such component makes a whole number of cycles over the 13 and the TSA's sum of its
    13 phases e^{2πi q r} is exactly zero: no sidebands at 29 ± 1 … 3 (the resampling bound
    5e-4), the mesh line 1 + a c_0 intact. The signature belongs to the faulty gear's shaft."""
    z1, z2, w, a = 13, 29, 0.3, 0.5
    c0 = w / math.sqrt(2 * math.pi)
    theta, x = _gear_signal(a, z1, w)
    gear = resample_to_angle(x, -theta * z1 / z2, 1024)
    assert gear.n_revolutions == 13
    table = sideband_table(time_synchronous_average(gear), z2, n_sidebands=3,
                           n_mesh_harmonics=1)[0]
    assert max(table[[0, 1, 2, 4, 5, 6]]) < 5e-4
    assert table[3] == pytest.approx(1 + a * c0, abs=1e-3)


def test_regular_residual_difference_decomposition():
    """x̄ = mean + regular + difference exactly; residual − difference = the sidebands;
    regular holds shaft orders 1..K, harmonics h z and h z ± 1..S."""
    n, z = 256, 16
    rng = np.random.default_rng(5)
    x = rng.normal(size=n) + 2.0
    reg = regular_signal(x, [z], n_shaft_orders=2, n_sidebands=1)
    diff = difference_signal(x, [z], n_shaft_orders=2, n_sidebands=1)
    res = residual_signal(x, [z], n_shaft_orders=2)
    np.testing.assert_allclose(x.mean() + reg + diff, x, atol=1e-12)
    sidebands = [o for h in range(1, n // (2 * z) + 1) for o in (h * z - 1, h * z + 1)
                 if o <= n // 2]
    np.testing.assert_allclose(res - diff, keep_orders(x, sidebands), atol=1e-12)
    _, amp_reg = order_spectrum(reg)
    kept = {1, 2} | {h * z for h in range(1, 9)} | set(sidebands)
    others = [o for o in range(n // 2 + 1) if o not in kept]
    assert np.max(amp_reg[others]) < 1e-12
    _, amp_x = order_spectrum(x)
    np.testing.assert_allclose(amp_reg[sorted(kept)], amp_x[sorted(kept)], rtol=1e-10)


def test_order_spectrum_amplitudes_and_sideband_table_edges():
    n = 128
    theta = 2 * np.pi * np.arange(n) / n
    x = 0.5 + 2.0 * np.cos(5 * theta + 1.0) + 0.25 * np.cos(64 * theta)
    assert order_amplitude(x, 0) == pytest.approx(0.5, rel=1e-12)
    assert order_amplitude(x, 5) == pytest.approx(2.0, rel=1e-12)
    assert order_amplitude(x, 64) == pytest.approx(0.25, rel=1e-12)  # the Nyquist order
    table = sideband_table(x, 30, n_sidebands=5)  # harmonics 30, 60; 60 + 5 > 64
    assert table.shape == (2, 11)
    assert np.isnan(table[1, -1]) and not np.isnan(table[1, 9])
    _, theta = _run_up()
    with pytest.raises(ValueError):  # many revolutions are not one: average first
        order_spectrum(resample_to_angle(np.cos(theta), theta, 512))
