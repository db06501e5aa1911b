"""Amplitude spectra and line (peak) measurement for mesh-frequency analysis (docs/theory.md §7).

Spectrum: the signal minus its mean, times a Hann window, one-sided |FFT| scaled by 2/Σw so a
sinusoid of amplitude A reads A at its bin (amplitude-correct; Harris, "On the use of windows
for harmonic analysis with the DFT", Proc. IEEE 66 (1978)).

Line measurement near an expected frequency: the largest bin within a search half-width, then
the true frequency and amplitude from the Hann kernel. For a line δ bins away from a bin centre
the Hann window's amplitude response is

    W(δ) = sinc(δ) / (1 − δ²)     (W(0) = 1, W(±1) = 1/2),

so two neighbouring bins determine δ exactly: with the larger bin a_k and its larger neighbour
a_{k±1}, r = a_{k±1}/a_k = (1 + δ)/(2 − δ) for the Hann kernel's main lobe, giving
δ = (2r − 1)/(1 + r) and A = a_k / W(δ) (Grandke, IEEE Trans. Instrum. Meas. 32 (1983)). Each
expected line is searched for on its own, so a harmonic larger than the fundamental, or leakage
from it, cannot be mistaken for the fundamental.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def amplitude_spectrum(signal: np.ndarray, rate_Hz: float) -> tuple[np.ndarray, np.ndarray]:
    """(frequencies [Hz], amplitudes [signal units]) of the zero-mean, Hann-windowed signal."""
    x = np.asarray(signal, float)
    x = x - x.mean()
    w = np.hanning(x.size)
    amp = np.abs(np.fft.rfft(x * w)) * 2.0 / w.sum()
    amp[0] *= 0.5  # the DC bin is not doubled (it is ~0 after removing the mean)
    return np.fft.rfftfreq(x.size, 1.0 / rate_Hz), amp


def hann_response(delta: float) -> float:
    """|W(δ)| of the Hann window for a line δ bins off a bin centre (Harris 1978)."""
    if abs(delta) < 1e-12:
        return 1.0
    return abs(np.sinc(delta) / (1.0 - delta * delta))


#: Spectra `gearcli analyze` takes: (name in the files, time-series column, unit).
SIGNALS = (("gear_speed", "omega2_rad_s", "rad/s"), ("dte", "delta_mm", "mm"),
           ("force", "force_total_N", "N"))

@dataclass(frozen=True)
class Line:
    expected_Hz: float
    measured_Hz: float
    amplitude: float
    bin_error: float  #: (measured - expected) / bin width
    #: below the Nyquist frequency, and the peak found within 1 bin of the expected
    #: frequency; else the search window caught a neighbour's lobe (a sideband closer than ~3
    #: bins to a far larger mesh line reads the mesh line) and the values are not this line's
    resolvable: bool


def measure_line(freq: np.ndarray, amp: np.ndarray, expected_Hz: float,
                 half_width_bins: float = 2.0) -> Line:
    """Measure the line nearest ``expected_Hz`` (see the module docstring)."""
    df = freq[1] - freq[0]
    if expected_Hz >= freq[-1] or expected_Hz <= 0.0:
        return Line(expected_Hz, float("nan"), float("nan"), float("nan"), False)
    centre = expected_Hz / df
    lo = max(int(np.floor(centre - half_width_bins)), 1)
    hi = min(int(np.ceil(centre + half_width_bins)), amp.size - 2)
    k = lo + int(np.argmax(amp[lo: hi + 1]))
    left, right = amp[k - 1], amp[k + 1]
    side = 1.0 if right >= left else -1.0
    r = max(right, left) / amp[k] if amp[k] > 0.0 else 0.0
    delta = side * (2.0 * r - 1.0) / (1.0 + r) if r > 0.5 else 0.0
    delta = float(np.clip(delta, -0.5, 0.5))
    f = (k + delta) * df
    bin_error = (f - expected_Hz) / df
    return Line(expected_Hz, f, float(amp[k] / hann_response(delta)), bin_error,
                abs(bin_error) <= 1.0)


def mesh_lines(f_z: float, shaft_Hz: dict[str, float], harmonics: int) -> list[tuple[str, float]]:
    """Named expected lines: k f_z for k = 1..N and the sidebands k f_z ± each shaft frequency."""
    out = []
    for k in range(1, harmonics + 1):
        out.append((f"{k}fz", k * f_z))
        for name, fs in shaft_Hz.items():
            out.append((f"{k}fz-{name}", k * f_z - fs))
            out.append((f"{k}fz+{name}", k * f_z + fs))
    return out


def alias_frequency(f_Hz: float, rate_Hz: float) -> float:
    """Where a line at f appears after sampling at ``rate`` (folding about multiples of it)."""
    return abs(f_Hz - round(f_Hz / rate_Hz) * rate_Hz)
