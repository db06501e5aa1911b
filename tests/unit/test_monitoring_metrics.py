"""Condition-monitoring metrics against closed forms and independent implementations
(docs/theory.md, "Condition-monitoring signals", §5–§6)."""

import json
import math

import numpy as np
import pytest
from scipy import stats

from gearcli.model.monitoring import SynchronousAverage, gear_metrics
from gearcli.model.monitoring import metrics as m
from gearcli.model.monitoring.orders import narrowband_envelope, residual_signal

N_REV = 768  # samples per revolution: divisible by 3·16·16, so the extremes below are on grid
THETA = 2 * np.pi * np.arange(N_REV) / N_REV
Z = 16  # mesh order (teeth)


def test_sinusoid_moments_are_the_closed_forms():
    """cos over whole periods: μ_2k = C(2k, k)/4^k, so kurtosis = FM4 = (3/8)/(1/2)² = 1.5,
    M6A = (5/16)/(1/2)³ = 2.5, M8A = (35/128)/(1/2)⁴ = 4.375, RMS = a/√2, CF = √2 (a sample sits
    on the crest). Summation of cosines over whole periods is exact to round-off."""
    x = 3.0 * np.cos(Z * THETA + 0.0)
    assert m.kurtosis(x) == pytest.approx(1.5, abs=1e-12)
    assert m.fm4(x) == pytest.approx(1.5, abs=1e-12)
    assert m.m6a(x) == pytest.approx(2.5, abs=1e-12)
    assert m.m8a(x) == pytest.approx(35 / 8, abs=1e-12)
    assert m.rms(x) == pytest.approx(3.0 / math.sqrt(2.0), rel=1e-13)
    assert m.crest_factor(x) == pytest.approx(math.sqrt(2.0), rel=1e-13)
    assert m.peak_to_peak(x) == pytest.approx(6.0, rel=1e-13)


def test_gaussian_kurtosis_is_three_within_its_sampling_spread():
    """Sample kurtosis b2 of N iid normal values: E[b2] = 3(N − 1)/(N + 1),
    Var[b2] = 24 N (N − 2)(N − 3) / ((N + 1)² (N + 3)(N + 5)) (D'Agostino, Belanger &
    D'Agostino 1990; ≈ 24/N). Six standard deviations (≈ 0.11 at N = 2¹⁶) bound it; an excess
    kurtosis (0) or one of |x| (≈ 3.87) misses."""
    n = 2**16
    x = np.random.default_rng(20261127).normal(0.0, 2.5, n)
    mean = 3.0 * (n - 1) / (n + 1)
    sd = math.sqrt(24.0 * n * (n - 2) * (n - 3) / ((n + 1) ** 2 * (n + 3) * (n + 5)))
    assert abs(m.kurtosis(x) - mean) < 6.0 * sd


def test_moments_match_scipy():
    """Independent implementation: scipy.stats (population moments, bias=True)."""
    rng = np.random.default_rng(7)
    x = rng.gamma(2.0, 1.0, 5000) + 0.3 * rng.normal(size=5000)
    assert m.kurtosis(x) == pytest.approx(stats.kurtosis(x, fisher=True, bias=True) + 3.0,
                                          rel=1e-12)
    for k, f in ((6, m.m6a), (8, m.m8a)):
        expect = stats.moment(x, order=k) / stats.moment(x, order=2) ** (k / 2)
        assert f(x) == pytest.approx(expect, rel=1e-11)
    assert m.rms(x) == pytest.approx(math.sqrt(np.dot(x, x) / x.size), rel=1e-13)


def test_fm0_of_a_pure_mesh_harmonic_sum():
    """x = cos zθ + ½ cos 2zθ: max 1.5 at u = zθ = 0; min at cos u = −½: −½ − ¼ = −0.75, so
    PP = 2.25 and FM0 = 2.25/(1 + ½) = 1.5. One tone: PP = 2a, FM0 = 2."""
    x = np.cos(Z * THETA) + 0.5 * np.cos(2 * Z * THETA)
    assert m.fm0(x, [Z]) == pytest.approx(1.5, rel=1e-12)
    # crests between grid points: each is missed by at most half a step, π z/n in phase, so PP
    # falls short by at most 1 − cos(π z/n) = 2.1e-3 relative
    fm0 = m.fm0(4.0 * np.sin(Z * THETA + 0.3), [Z], n_mesh_harmonics=1)
    assert 2.0 * math.cos(math.pi * Z / N_REV) <= fm0 <= 2.0
    assert m.fm0(np.cos(Z * THETA), [Z]) == pytest.approx(2.0, rel=1e-13)


def test_energy_ratio_and_sidebands_closed_forms():
    """TSA = A cos zθ + B cos 5θ: order 5 is neither shaft order (K = 2), mesh harmonic nor
    sideband, so d = B cos 5θ, regular = A cos zθ, ER = B/A. AM x = cos zθ (1 + μ cos θ): the
    first sidebands are μ/2 each, SI = μ/2, σ² = (1 + μ²/2)/2, SLF = μ/σ."""
    from gearcli.model.monitoring.orders import difference_signal, regular_signal

    a, b = 2.0, 0.3
    x = a * np.cos(Z * THETA) + b * np.cos(5 * THETA)
    er = m.energy_ratio(difference_signal(x, [Z]), regular_signal(x, [Z]))
    assert er == pytest.approx(b / a, rel=1e-12)
    mu = 0.4
    am = np.cos(Z * THETA) * (1.0 + mu * np.cos(THETA))
    assert m.sideband_index(am, Z) == pytest.approx(mu / 2, rel=1e-12)
    sigma = math.sqrt((1.0 + mu**2 / 2) / 2)
    assert m.sideband_level_factor(am, Z) == pytest.approx(mu / sigma, rel=1e-12)


# The public NA4 example of oplib (github.com/Onepredict/onebone, oplib/feature/
# gear_condition_metrics.py at commit 337f9885, the docstring of `na4`; the signal of MathWorks'
# tsaresidual example: 180 rpm, 50 kHz, one revolution, mesh orders 17 and 51
# with two harmonics each, shaft orders 1 and 2, and a "fault" at order 10 growing k/6 · 2).
# NA4 per record k with the run's records 1 … k normalising, as printed there:
OPLIB_NA4 = [1.536982703280907, 3.857738227803903, 5.590250485891509, 6.835250547872656,
             7.755227746173137, 8.457654233606695, 9.009683995782796, 9.454160950683573,
             9.819352835339927, 10.12454304712786]


def test_na4_reproduces_the_published_oplib_values():
    """Their record has 16666 samples for 16666.7 per revolution, so each band of ±rps/2 they
    zero holds exactly the order bins 1, 2, 17, 34, 51, 102 that residual_signal removes here;
    the residual is then the same and NA4 agrees to round-off (the closed form for an exactly
    periodic record would be 1.5 (k/3)⁴ / mean_j (j/3)² ², e.g. 1.5 and 3.84: leakage gives
    their 1.537 and 3.858)."""
    fs, rps = 50e3, 3.0
    t = np.arange(0, (1 / 3) - 1 / fs, 1 / fs)
    records, na4 = [], []
    for k in range(1, 11):
        x = (np.sin(2 * np.pi * rps * t) + np.sin(2 * np.pi * 2 * rps * t)
             + 3 * np.sin(2 * np.pi * 51 * t) + 3 * np.sin(2 * np.pi * 102 * t)
             + 4 * np.sin(2 * np.pi * 153 * t) + 4 * np.sin(2 * np.pi * 306 * t)
             + 2 * (k / 6) * np.sin(2 * np.pi * 10 * rps * t))
        r = residual_signal(x, [17, 51], n_mesh_harmonics=2, n_shaft_orders=2)
        records.append(r)
        na4.append(m.na4(r, records))
    np.testing.assert_allclose(na4, OPLIB_NA4, rtol=1e-12)


def test_na4_closed_form_against_a_baseline():
    """Residual a sin(10θ) against baseline residuals b_j sin(10θ): μ_4 = 3a⁴/8,
    μ_2,j = b_j²/2, NA4 = 1.5 a⁴ / (mean_j b_j²)²."""
    a, bs = 0.9, [0.2, 0.3, 0.25]
    r = a * np.sin(10 * THETA)
    ref = [b * np.sin(10 * THETA) for b in bs]
    expect = 1.5 * a**4 / np.mean(np.square(bs)) ** 2
    assert m.na4(r, ref) == pytest.approx(expect, rel=1e-12)


def test_nb4_closed_form_of_an_amplitude_modulated_mesh_tone():
    """x = cos zθ (1 + μ cos θ): the band z ± w (w ≥ 1) holds all of it, its envelope is
    E = 1 + μ cos θ, μ_2(E) = μ²/2, μ_4(E) = 3μ⁴/8; against a baseline μ_b:
    NB4 = 1.5 (μ/μ_b)⁴."""
    mu, mu_b = 0.3, 0.1
    x = np.cos(Z * THETA) * (1.0 + mu * np.cos(THETA))
    xb = np.cos(Z * THETA) * (1.0 + mu_b * np.cos(THETA))
    e = narrowband_envelope(x, Z)
    np.testing.assert_allclose(e, 1.0 + mu * np.cos(THETA), atol=1e-12)
    assert m.nb4(e, [narrowband_envelope(xb, Z)]) == pytest.approx(1.5 * (mu / mu_b) ** 4,
                                                                   rel=1e-10)


def test_gear_metrics_document():
    """The document holds the single functions' values; no baseline: NA4/NB4 None; a baseline
    equal to the record: NA4 is the residual's kurtosis; to_dict is plain JSON."""
    rng = np.random.default_rng(3)
    x = (np.cos(Z * THETA) + 0.2 * np.cos(2 * Z * THETA) + 0.05 * np.cos((Z + 1) * THETA)
         + 0.02 * rng.normal(size=N_REV))
    tsa = SynchronousAverage(values=x, n_revolutions=10)
    doc = gear_metrics(tsa, Z, signal_unit="m/s^2")
    assert doc.na4 is None and doc.nb4 is None and doc.n_baseline_records == 0
    assert doc.fm0 == pytest.approx(m.fm0(x, [Z]), rel=1e-14)
    assert doc.rms == pytest.approx(m.rms(x - x.mean()), rel=1e-14)
    assert doc.sideband_index == pytest.approx(0.025, rel=0.2)  # 0.05/2 plus noise lines
    d = json.loads(json.dumps(doc.to_dict()))
    assert d["signal_unit"] == "m/s^2" and d["na4"] is None and d["samples_per_revolution"] == 768
    same = gear_metrics(tsa, Z, signal_unit="m/s^2", baseline=[tsa])
    assert same.na4 == pytest.approx(m.kurtosis(residual_signal(x, [Z])), rel=1e-12)
    assert same.n_baseline_records == 1
    with pytest.raises(ValueError):
        gear_metrics(tsa, Z, signal_unit="m/s^2",
                     baseline=[SynchronousAverage(values=x[:512], n_revolutions=1)])


def test_constant_signal_gives_nan_not_a_crash():
    x = np.full(64, 2.0)
    assert math.isnan(m.kurtosis(x)) and math.isnan(m.fm4(x))
    assert math.isnan(m.crest_factor(np.zeros(64)))
