"""What a sensor sees: bearing forces, a housing accelerometer, encoder signals, sampling and
measurement noise (docs/theory.md, "What a sensor sees"). Pure functions of arrays (numpy and
scipy), internal units (mm, N, s, t, rad); no I/O.

- :func:`quasi_static_bearing_forces`: the bearings' reaction to the mesh force when the gear
  centres are fixed (torsional model; docs/theory.md §11.1's force balance without the centres'
  inertia and bearing damping).
- :func:`housing_frf` / :func:`housing_acceleration`: the housing transfer from a bearing force
  to the acceleration at the accelerometer, a sum of single-degree-of-freedom resonances (the
  housing/transfer-path model of Sawalhi & Randall 2008, one resonance per mode).
- :func:`torsional_acceleration`: dω/dt from the encoder's speed (cubic-spline derivative).
- :func:`resample`: the recorder's anti-alias low-pass and sampling at its rate.
- :func:`noise_rms_for_snr`, :func:`add_noise`: seeded white Gaussian measurement noise.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

__all__ = ["HousingMode", "quasi_static_bearing_forces", "housing_frf", "housing_acceleration",
           "torsional_acceleration", "resample", "noise_rms_for_snr", "add_noise",
           "ANTI_ALIAS_ORDER", "ANTI_ALIAS_CUTOFF", "AUDIO_RATE_HZ", "AUDIO_PEAK", "audio_samples"]

#: The recorder's anti-alias filter: a Butterworth low-pass of this order ...
ANTI_ALIAS_ORDER = 8
#: ... at this share of the sample rate (0.45 f_s: 0.9 of the Nyquist frequency) [-].
ANTI_ALIAS_CUTOFF = 0.45


@dataclass(frozen=True)
class HousingMode:
    """One housing resonance: natural frequency [Hz], damping ratio [-], modal mass [t]."""

    frequency_Hz: float
    damping_ratio: float
    modal_mass_t: float


def quasi_static_bearing_forces(force_drive_N, force_coast_N, alpha_w_rad: float):
    """Forces of the pinion and the gear on their bearings [N] in the pair frame, (F_x1, F_y1,
    F_x2, F_y2), when the centres do not move: each bearing carries the mesh force on its gear,
    F_b1 = −F_d n_d − F_c n_c, F_b2 = −F_b1, n_d = (sin α_w, cos α_w), n_c = (sin α_w,
    −cos α_w) (docs/theory.md §11.1 with ü = u̇ = 0; friction, ~μ of it, left out)."""
    fd = np.asarray(force_drive_N, dtype=float)
    fc = np.asarray(force_coast_N, dtype=float)
    s, c = math.sin(alpha_w_rad), math.cos(alpha_w_rad)
    fx1 = -(fd + fc) * s
    fy1 = -(fd - fc) * c
    return fx1, fy1, -fx1, -fy1


def housing_frf(frequency_Hz, modes: Sequence[HousingMode]) -> np.ndarray:
    """Accelerance A(f) = a/F [mm/s² per N] of the housing at ``frequency_Hz``:

        A(ω) = Σ_r (−ω²/m_r) / (ω_r² − ω² + 2 i ζ_r ω_r ω)

    (a single-DOF oscillator m ẍ + c ẋ + k x = F per mode, a = ẍ; Ewins, Modal Testing, §2.2).
    It is 0 at ω = 0 (a steady force accelerates nothing) and 1/m_r above the resonance."""
    w = 2.0 * np.pi * np.asarray(frequency_Hz, dtype=float)
    out = np.zeros(w.shape, dtype=complex)
    for m in modes:
        wr = 2.0 * np.pi * m.frequency_Hz
        out += (-w**2 / m.modal_mass_t) / (wr**2 - w**2 + 2j * m.damping_ratio * wr * w)
    return out


def housing_acceleration(t_s, force_N, modes: Sequence[HousingMode]) -> np.ndarray:
    """The housing acceleration [mm/s²] under the bearing force component ``force_N`` [N]
    sampled at the uniform times ``t_s``: the sum over the modes of ẍ of
    ẍ + 2ζω_r ẋ + ω_r² x = F/m (:func:`housing_frf` in the time domain), each started at rest
    in the static deflection under F(t_0) (no start-up transient from the steady load), the
    force linear between samples (scipy.signal.lsim's first-order hold: exact for it)."""
    from scipy.signal import lsim

    t = np.asarray(t_s, dtype=float)
    f = np.asarray(force_N, dtype=float)
    a = np.zeros_like(f)
    for m in modes:
        wr = 2.0 * np.pi * m.frequency_Hz
        z = m.damping_ratio
        g = 1.0 / m.modal_mass_t
        sys = (np.array([[0.0, 1.0], [-wr**2, -2.0 * z * wr]]), np.array([[0.0], [g]]),
               np.array([[-wr**2, -2.0 * z * wr]]), np.array([[g]]))
        x0 = np.array([g * f[0] / wr**2, 0.0])
        _t, y, _x = lsim(sys, f, t, X0=x0)
        a += np.asarray(y, dtype=float).reshape(-1)
    return a


def torsional_acceleration(t_s, omega_rad_s) -> np.ndarray:
    """dω/dt [rad/s²] at ``t_s``: the derivative of the not-a-knot cubic spline through the
    encoder's speed samples (an encoder measures the angle; the simulated ω is its exact first
    derivative, so one spline derivative remains)."""
    from scipy.interpolate import CubicSpline

    return CubicSpline(np.asarray(t_s, float), np.asarray(omega_rad_s, float)).derivative()(t_s)


def resample(t_s, x, rate_Hz: float, t_new=None, anti_alias: bool = True):
    """(t', x') sampled at ``rate_Hz`` from t_0 (or at ``t_new``): when the rate is below the
    input's, the recorder's anti-alias low-pass first (Butterworth, :data:`ANTI_ALIAS_ORDER`,
    cut-off :data:`ANTI_ALIAS_CUTOFF` · rate, applied forward and backward: zero phase, so the
    signal stays aligned with the encoder angles), then the not-a-knot cubic spline through the
    samples at the new times. ``anti_alias=False`` interpolates only (angles: an encoder reads
    the angle at the sample instant)."""
    from scipy.interpolate import CubicSpline
    from scipy.signal import butter, sosfiltfilt

    t = np.asarray(t_s, dtype=float)
    y = np.asarray(x, dtype=float)
    if t_new is None:
        n = int(math.floor((t[-1] - t[0]) * rate_Hz * (1.0 + 1e-12))) + 1
        t_new = t[0] + np.arange(n) / rate_Hz
    rate_in = (t.size - 1) / (t[-1] - t[0])
    if anti_alias and rate_Hz < rate_in:
        sos = butter(ANTI_ALIAS_ORDER, ANTI_ALIAS_CUTOFF * rate_Hz, fs=rate_in, output="sos")
        y = sosfiltfilt(sos, y)
    return t_new, CubicSpline(t, y)(t_new)


def noise_rms_for_snr(x, snr_db: float) -> float:
    """The noise rms that gives ``x`` the signal-to-noise ratio ``snr_db`` [dB]:
    RMS(x − mean x) · 10^(−SNR/20) (a power ratio in decibels)."""
    y = np.asarray(x, dtype=float)
    return float(np.sqrt(np.mean((y - y.mean()) ** 2)) * 10.0 ** (-snr_db / 20.0))


def add_noise(x, rms: float, seed: int, channel: int) -> np.ndarray:
    """``x`` plus white Gaussian noise N(0, rms²), independent per sample, from the generator
    seeded by (``seed``, ``channel``) (numpy's PCG64 via default_rng: the same seed gives the
    same noise on every machine; channels get independent streams)."""
    y = np.asarray(x, dtype=float)
    if rms <= 0.0:
        return y.copy()
    rng = np.random.default_rng([int(seed), int(channel)])
    return y + rng.normal(0.0, rms, y.shape)


#: Audio: the CD rate [Hz] and the peak level as a share of 16-bit full scale (headroom).
AUDIO_RATE_HZ = 44_100
AUDIO_PEAK = 0.9


def audio_samples(t_s, x, rate_Hz: int = AUDIO_RATE_HZ) -> np.ndarray:
    """16-bit PCM samples of a signal in real time (one simulated second lasts one second):
    resampled to ``rate_Hz`` (:func:`resample`; anti-aliased when the signal's rate is
    higher), its mean removed and its peak scaled to :data:`AUDIO_PEAK` of full scale
    (32767); a constant signal is silence."""
    _t, y = resample(t_s, x, float(rate_Hz))
    y = y - y.mean()
    peak = float(np.max(np.abs(y))) if y.size else 0.0
    scale = AUDIO_PEAK * 32767.0 / peak if peak > 0.0 else 0.0
    return np.round(y * scale).astype(np.int16)
