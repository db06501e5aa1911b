"""Angle-domain resampling and the time-synchronous average.

docs/theory.md, "Condition-monitoring signals", §1–§2. Pure functions of arrays, no I/O.

A signal sampled in time, x(t_i), becomes a signal of the shaft angle, x(θ_k), on the uniform
grid θ_k = θ_s + k Δθ, Δθ = 2π/n (n samples per revolution), through the shaft's angle series
θ(t_i). In gearcli that series is the simulated shaft angle itself (exact), not a tachometer
estimate (McFadden 1987 and Bonnardot et al. 2005 interpolate between once-per-revolution
pulses; here nothing is estimated). The time-synchronous average (TSA) of N whole revolutions
is then the mean of the N revolution-long blocks, sample by sample (Braun 1975; McFadden 1987):

    x̄_k = (1/N) Σ_{r=0}^{N−1} x(θ_s + 2π r + k Δθ),   k = 0 … n−1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline

__all__ = ["AngleSignal", "SynchronousAverage", "samples_per_revolution", "resample_to_angle",
           "time_synchronous_average"]

TWO_PI = 2.0 * math.pi


def _monotone_angle(shaft_angle_rad) -> tuple[np.ndarray, float]:
    """(s θ, s): θ made strictly increasing by its direction s = ±1 (a shaft turning backwards
    is mirrored: −θ)."""
    theta = np.asarray(shaft_angle_rad, dtype=float)
    if theta.ndim != 1 or theta.size < 2:
        raise ValueError("shaft angle: a 1-D series of at least two samples is needed")
    step = np.diff(theta)
    if np.all(step > 0.0):
        return theta, 1.0
    if np.all(step < 0.0):
        return -theta, -1.0
    raise ValueError("shaft angle: the series must be strictly monotone (the shaft may not "
                     "stop or reverse within the record)")


def samples_per_revolution(shaft_angle_rad, highest_order: int = 0) -> int:
    """Samples per revolution n [-] for resampling a record onto the shaft angle.

    Rule (docs/theory.md, "Condition-monitoring signals", §1): n is the smallest power of two
    that is at least the largest number of time samples in one revolution of the record,
    2π / min_i |θ_{i+1} − θ_i|, and at least 2 (m_max + 1), so that the order m_max lies below
    the angle-domain Nyquist order n/2. The slowest part of the record has the most samples per
    revolution; matching it keeps every order the time sampling resolved there (the time
    Nyquist frequency f_s/2 is the order f_s/(2 f_shaft), highest at the lowest speed). A power
    of two keeps the order FFTs fast.

    Parameters
    ----------
    shaft_angle_rad : array [rad]
        The shaft's angle at the time samples, strictly monotone.
    highest_order : int [-]
        m_max, the highest shaft order that must be resolved (e.g. the highest mesh harmonic
        plus its sidebands).

    Returns
    -------
    int
        n, a power of two [-].
    """
    theta, _ = _monotone_angle(shaft_angle_rad)
    per_rev_in_time = TWO_PI / float(np.min(np.diff(theta)))
    need = max(per_rev_in_time, 2.0 * (int(highest_order) + 1))
    n = 2
    while n < need * (1.0 - 1e-12):
        n *= 2
    return n


@dataclass(frozen=True)
class AngleSignal:
    """A signal on a uniform shaft-angle grid covering whole revolutions."""

    values: np.ndarray  #: x(θ_k), k = 0 … N n − 1 [signal unit]
    samples_per_revolution: int  #: n [-]
    start_angle_rad: float  #: θ_s, the shaft angle of values[0] [rad] (−θ_s for a backward shaft)

    @property
    def n_revolutions(self) -> int:
        """N, the number of whole revolutions [-]."""
        return self.values.size // self.samples_per_revolution

    @property
    def angle_rad(self) -> np.ndarray:
        """θ_k = θ_s + 2π k/n [rad]."""
        n = self.samples_per_revolution
        return self.start_angle_rad + TWO_PI * np.arange(self.values.size) / n


def resample_to_angle(signal, shaft_angle_rad, samples_per_rev: int,
                      reference_angle_rad: float = 0.0) -> AngleSignal:
    """Resample a time-sampled signal onto a uniform grid of the shaft angle.

    The grid starts at the first angle θ_s = θ_ref + 2π j (j integer) at or after the record's
    first angle and holds the N whole revolutions that fit in the record, so sample k of every
    revolution is at the same shaft angle θ_ref + 2π k/n (mod 2π): the TSA's index is the
    shaft's angular position, and index 0 is the reference angle (tooth indexing:
    docs/theory.md, "Tooth faults").
    x(θ) is the not-a-knot cubic spline through (θ_i, x_i) (the abscissa θ_i is strictly
    monotone, so x is a function of θ); its error for a sinusoid of φ rad per time sample is
    about (5/384) φ⁴ of the amplitude (docs/theory.md, §1), e.g. 1.3·10⁻⁴ at 20 samples per
    period. A shaft turning backwards (θ decreasing) is resampled on −θ.

    Parameters
    ----------
    signal : array [signal unit]
        x(t_i), the samples of the signal.
    shaft_angle_rad : array [rad]
        θ(t_i), the shaft's angle at the same instants, strictly monotone.
    samples_per_rev : int [-]
        n, samples per revolution of the grid (see :func:`samples_per_revolution`).
    reference_angle_rad : float [rad]
        θ_ref, the shaft angle that becomes index 0 of every revolution.

    Returns
    -------
    AngleSignal
        N n samples, N ≥ 1 whole revolutions.
    """
    x = np.asarray(signal, dtype=float)
    theta, direction = _monotone_angle(shaft_angle_rad)
    if x.shape != theta.shape:
        raise ValueError("signal and shaft angle must have the same length")
    n = int(samples_per_rev)
    if n < 4:
        raise ValueError("samples per revolution must be at least 4")
    ref = direction * reference_angle_rad
    start = ref + TWO_PI * math.ceil((theta[0] - ref) / TWO_PI - 1e-12)
    n_rev = math.floor((theta[-1] - start) / TWO_PI + 1e-12)
    if n_rev < 1:
        raise ValueError("the record holds less than one whole revolution after the reference "
                         "angle")
    grid = start + TWO_PI * np.arange(n_rev * n) / n
    values = CubicSpline(theta, x)(grid)
    return AngleSignal(values=values, samples_per_revolution=n, start_angle_rad=float(start))


@dataclass(frozen=True)
class SynchronousAverage:
    """The time-synchronous average: one revolution, the mean of N."""

    values: np.ndarray  #: x̄_k, k = 0 … n−1 [signal unit]
    n_revolutions: int  #: N, the revolutions averaged [-]

    @property
    def samples_per_revolution(self) -> int:
        """n [-]."""
        return self.values.size


def time_synchronous_average(signal: AngleSignal | np.ndarray,
                             samples_per_rev: int | None = None) -> SynchronousAverage:
    """Time-synchronous average over whole revolutions: N revolutions → one.

    x̄_k = (1/N) Σ_{r=0}^{N−1} x_{r n + k}, k = 0 … n−1 (Braun 1975; McFadden 1987). A component
    periodic in the shaft angle passes unchanged; noise uncorrelated from revolution to
    revolution, of standard deviation σ per sample, leaves σ/√N (docs/theory.md, §2).

    Parameters
    ----------
    signal : AngleSignal, or array [signal unit]
        The angle-domain signal; a plain array needs ``samples_per_rev``. Samples after the last
        whole revolution are not used.
    samples_per_rev : int [-]
        n, only for a plain array.

    Returns
    -------
    SynchronousAverage
        n samples and the count N.
    """
    if isinstance(signal, AngleSignal):
        x, n = signal.values, signal.samples_per_revolution
    else:
        if samples_per_rev is None:
            raise ValueError("samples_per_rev is needed for a plain array")
        x, n = np.asarray(signal, dtype=float), int(samples_per_rev)
    n_rev = x.size // n
    if n_rev < 1:
        raise ValueError("the signal is shorter than one revolution")
    blocks = x[: n_rev * n].reshape(n_rev, n)
    return SynchronousAverage(values=blocks.mean(axis=0), n_revolutions=n_rev)
