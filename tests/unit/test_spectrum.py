"""Spectral line measurement on synthetic signals with known lines (issue 4)."""

import numpy as np
import pytest

from gearcli.pipeline.spectrum import (
    alias_frequency,
    amplitude_spectrum,
    hann_response,
    measure_line,
    mesh_lines,
)

RATE = 4000.0
T = 2.0  # s -> 0.5 Hz bins
t = np.arange(int(RATE * T)) / RATE


def test_hann_response():
    assert hann_response(0.0) == 1.0
    assert hann_response(1.0 - 1e-9) == pytest.approx(0.5, rel=1e-6)
    # scalloping loss of the Hann window at half a bin: 0.8488 (-1.42 dB, Harris 1978)
    assert hann_response(0.5) == pytest.approx(0.8488, abs=1e-4)


@pytest.mark.parametrize("f0", [141.5, 141.6667, 141.75, 141.9])  # on a bin and between bins
def test_line_between_bins(f0):
    x = 3.0 + 0.7 * np.sin(2 * np.pi * f0 * t + 0.3)
    f, a = amplitude_spectrum(x, RATE)
    line = measure_line(f, a, 141.6667)
    # Two-bin Hann interpolation is exact for a pure tone up to the far-lobe leakage of the
    # (negative-frequency) image: frequency within 1e-3 bins, amplitude within 0.5 %.
    assert line.measured_Hz == pytest.approx(f0, abs=1e-3 * (f[1] - f[0]))
    assert line.amplitude == pytest.approx(0.7, rel=5e-3)


def test_harmonic_stronger_than_fundamental_and_sidebands():
    fz, n2 = 141.6667, 5.6667
    x = (0.1 * np.sin(2 * np.pi * fz * t) + 1.0 * np.sin(2 * np.pi * 2 * fz * t)
         + 0.02 * np.sin(2 * np.pi * (fz - n2) * t) + 0.03 * np.sin(2 * np.pi * (fz + n2) * t))
    f, a = amplitude_spectrum(x, RATE)
    lines = {label: measure_line(f, a, fe) for label, fe in mesh_lines(fz, {"n2": n2}, 2)}
    assert lines["1fz"].amplitude == pytest.approx(0.1, rel=0.01)
    assert lines["2fz"].amplitude == pytest.approx(1.0, rel=0.01)
    assert lines["1fz-n2"].amplitude == pytest.approx(0.02, rel=0.05)
    assert lines["1fz+n2"].amplitude == pytest.approx(0.03, rel=0.05)
    for label in ("1fz", "2fz", "1fz-n2", "1fz+n2"):
        assert abs(lines[label].bin_error) < 0.05
    # an absent line reads only leakage, far below the present ones
    assert lines["2fz-n2"].amplitude < 0.01 * lines["2fz"].amplitude


def test_line_above_nyquist_is_not_resolvable():
    f, a = amplitude_spectrum(np.sin(2 * np.pi * 10 * t), RATE)
    assert not measure_line(f, a, 2500.0).resolvable


def test_alias_frequency_of_the_seed_at_1000_steps():
    # 1000 output steps over 5 s: 200 Hz; 141.67 Hz folds to 58.33 Hz (docs/theory.md §9, slip 4)
    assert alias_frequency(17 * 3000 / 360, 200.0) == pytest.approx(58.333, abs=1e-3)


def test_a_sideband_next_to_a_far_larger_line_is_not_read_from_that_line():
    """A sideband 2.8 bins from a 10x larger mesh line: the +-2-bin search finds the mesh
    line's lobe; it was reported as the sideband (resolvable). A sideband 20 bins away is
    measured, amplitude to 1 % (Hann amplitude correction, module docstring)."""
    rate, n = 1000.0, 2000  # bins of 0.5 Hz
    t = np.arange(n) / rate
    main, near, far = 100.25, 100.25 + 2.8 * 0.5, 100.25 + 20.3 * 0.5
    x = 1.0 * np.sin(2 * np.pi * main * t) + 0.1 * np.sin(2 * np.pi * far * t) \
        + 0.01 * np.sin(2 * np.pi * near * t)
    freq, amp = amplitude_spectrum(x, rate)
    assert measure_line(freq, amp, main).resolvable
    close = measure_line(freq, amp, near)
    assert not close.resolvable and abs(close.measured_Hz - main) < 0.1  # the main line's lobe
    apart = measure_line(freq, amp, far)
    assert apart.resolvable and apart.amplitude == pytest.approx(0.1, rel=0.01)
