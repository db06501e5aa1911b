"""Order map of a run-up: the spectrogram of a signal against pinion speed, with the gear-mesh
orders and the modes drawn."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["order_map", "plot_order_map"]


def order_map(t_s, signal, omega1_rad_s, segment_s: float):
    """Short-time amplitude spectra (periodic Hann window, 50 % overlap, scaled so that a
    sinusoid of amplitude A on a bin reads A: Harris, "On the use of windows for harmonic
    analysis with the discrete Fourier transform", Proc. IEEE 66(1), 1978) of ``signal`` [its
    unit] sampled at ``t_s`` [s] in segments of ``segment_s`` [s]; returns (segment times [s],
    pinion speed at each [rpm], frequencies [Hz], amplitudes (frequency x segment)).

    The same numbers as ``scipy.signal.stft(..., window="hann", boundary=None, padded=False,
    scaling="spectrum")`` doubled, in numpy alone: importing scipy.signal costs about a second,
    more than the transform (tests/unit/test_orders.py compares the two)."""
    t = np.asarray(t_s, float)
    fs = (t.size - 1) / (t[-1] - t[0])
    x = np.asarray(signal, float) - float(np.mean(signal))
    # at least 16 samples a segment, at most a quarter of the run (four segments or more)
    n = max(min(int(round(segment_s * fs)), x.size // 4), min(16, x.size))
    step = n - n // 2
    starts = np.arange(0, x.size - n + 1, step)
    window = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(n) / n)  # periodic Hann
    segments = x[starts[:, None] + np.arange(n)] * window
    # one-sided amplitude: 2 |X_k| / sum(w) (the "spectrum" scaling A/2, doubled)
    amp = 2.0 * np.abs(np.fft.rfft(segments, axis=1)).T / window.sum()
    f = np.fft.rfftfreq(n, 1.0 / fs)
    t_mid = t[0] + (starts + n / 2) / fs
    rpm = np.interp(t_mid, t, np.asarray(omega1_rad_s, float)) * 30.0 / np.pi
    return t_mid, rpm, f, amp


def plot_order_map(t_s, signal, omega1_rad_s, pinion_teeth: int, modes_Hz=(), *,
                   label: str = "signal", unit: str = "", harmonics: int = 5,
                   f_max_Hz: float | None = None, segment_s: float | None = None,
                   db: bool = True, units: str = "engineering") -> Figure:
    """Order map: amplitude (dB re the largest, or linear) against pinion speed [rpm] (left)
    and time (right), frequencies up to ``f_max_Hz`` [Hz]; order lines k z1 n/60 [Hz],
    k = 1 .. ``harmonics``; modes as horizontal lines. ``segment_s`` defaults to 8 mesh
    periods at the final speed (a resolution of f_z/8 there). The speed panel shows the
    segments of the run-up (speed below 99 % of its final value); its speed axis in the
    display ``units`` (rpm or rad/s, gearcli/display_units.py)."""
    from matplotlib.figure import Figure

    from gearcli.display_units import unit_and_factor

    speed_unit, k_n = unit_and_factor("rpm", units)

    t = np.asarray(t_s, float)
    omega = np.asarray(omega1_rad_s, float)
    n_end = abs(float(omega[-1])) * 30.0 / np.pi
    f_z_end = pinion_teeth * n_end / 60.0
    if segment_s is None:
        segment_s = 8.0 / f_z_end if f_z_end > 0 else (t[-1] - t[0]) / 20.0
    t_mid, rpm, f, amp = order_map(t, signal, omega, segment_s)
    f_top = f_max_Hz or min(f[-1], 1.2 * harmonics * f_z_end if f_z_end > 0 else f[-1])
    keep = f <= f_top
    values = amp[keep]
    if db:
        ref = float(values.max()) or 1.0
        values = 20.0 * np.log10(np.maximum(values / ref, 1e-6))
    fig = Figure(figsize=(11.0, 4.6), layout="constrained")
    ax_speed, ax_time = fig.subplots(1, 2)
    up = np.abs(rpm) < 0.99 * n_end if n_end > 0 else np.ones(rpm.size, bool)
    if up.sum() < 2:
        up = np.ones(rpm.size, bool)
    for ax, x, v, xlabel in ((ax_speed, k_n * rpm[up], values[:, up],
                              f"pinion speed [{speed_unit}] (run-up)"),
                             (ax_time, t_mid, values, "time [s]")):
        mesh = ax.pcolormesh(x, f[keep], v, shading="nearest", cmap="viridis",
                             vmin=-60.0 if db else None)
        ax.set(xlabel=xlabel, ylabel="frequency [Hz]", ylim=(0.0, f_top))
        for fm in modes_Hz:
            ax.axhline(fm, color="white", ls="--", lw=0.8)
    order_x = np.linspace(0.0, max(float(rpm[up].max()), 1.0), 50)
    for k in range(1, harmonics + 1):
        ax_speed.plot(k_n * order_x, k * pinion_teeth * order_x / 60.0, color="w", lw=0.6,
                      alpha=0.8)
        ax_speed.text(k_n * order_x[-1], min(k * pinion_teeth * order_x[-1] / 60.0, f_top * 0.97),
                      f"{k}×", color="w", fontsize=7, ha="right")
    if np.ptp(rpm[up]) > 0:
        ax_speed.set_xlim(k_n * float(rpm[up].min()), k_n * float(rpm[up].max()))
    fig.colorbar(mesh, ax=ax_time, label=f"{label} amplitude " + (
        "[dB re max]" if db else f"[{unit}]"))
    fig.suptitle(f"Order map of the {label}: mesh orders k·z1·n/60 (white lines), modes "
                 "(dashed)")
    return fig
