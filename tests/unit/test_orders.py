"""gearcli.plotting.orders.order_map: the numpy short-time spectra equal scipy.signal.stft's
(Hann, 50 % overlap, no boundary padding, "spectrum" scaling doubled) and read a sinusoid's
amplitude."""

from __future__ import annotations

import numpy as np
import pytest

from gearcli.plotting.orders import order_map


@pytest.mark.parametrize(("n_samples", "segment_s"), [(5001, 0.05), (4000, 0.0333), (64, 1.0)])
def test_order_map_equals_scipy_stft(n_samples, segment_s):
    from scipy.signal import stft

    rng = np.random.default_rng(1)
    t = np.linspace(0.0, 2.0, n_samples)
    x = 3.0 * np.sin(2 * np.pi * 160.0 * t * (1 + t)) + rng.normal(0.0, 0.5, t.size) + 7.0
    omega = 100.0 * t
    t_mid, rpm, f, amp = order_map(t, x, omega, segment_s)
    fs = (t.size - 1) / (t[-1] - t[0])
    n = max(min(int(round(segment_s * fs)), t.size // 4), min(16, t.size))
    f_ref, tau, z = stft(x - x.mean(), fs=fs, window="hann", nperseg=n, noverlap=n // 2,
                         boundary=None, padded=False, scaling="spectrum")
    # rounding only: both are the same sums in double precision
    assert np.allclose(f, f_ref, rtol=1e-12, atol=0)
    assert np.allclose(t_mid, t[0] + tau, rtol=1e-12, atol=0)
    assert amp.shape == z.shape
    assert np.allclose(amp, 2.0 * np.abs(z), rtol=1e-9, atol=1e-12 * np.abs(z).max())
    assert np.allclose(rpm, np.interp(t_mid, t, omega) * 30.0 / np.pi, rtol=1e-12)


def test_a_sinusoid_on_a_bin_reads_its_amplitude():
    fs, n = 1000.0, 200  # 5 Hz bins: 50 Hz is bin 10
    t = np.arange(2000) / fs
    _, _, f, amp = order_map(t, 2.5 * np.sin(2 * np.pi * 50.0 * t), np.ones_like(t), n / fs)
    k = int(np.argmin(np.abs(f - 50.0)))
    # Hann on a bin: the amplitude exactly (coherent gain divided out), to rounding
    assert np.allclose(amp[k], 2.5, rtol=1e-9)
