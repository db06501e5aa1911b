"""The spectra figure of an analysis: amplitude spectra of the steady window with the mesh
harmonics, their sidebands and the aliases of the harmonics above the Nyquist frequency marked.

Plain arrays and dicts in (spectra in the units of analysis' spectrum.csv), one matplotlib
Figure out (gearcli/plotting/results.py for the conventions).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from gearcli.plotting.results import ALIAS, FORCE, HARMONIC, SIDEBAND, stacked_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_spectra"]


def _decade(value: float, _pos=None) -> str:
    """Log-axis tick label: 1e-3, 0.01, 0.1, 1, 10, 100, 1e3."""
    if value <= 0.0:
        return ""
    e = round(math.log10(value))
    return f"{value:g}" if -2 <= e <= 2 else f"1e{e}"


def _alias(f: float, fs: float) -> float:
    return abs(f - fs * round(f / fs))


def _folds(f_z: float, fs: float, x_max: float, first: int) -> np.ndarray:
    """Where the mesh harmonics from ``first`` (and above f_s/2) up to 2 f_s land after
    sampling (aliases) [Hz]."""
    k = np.arange(max(math.floor(0.5 * fs / f_z) + 1, first), math.floor(2.0 * fs / f_z) + 1)
    f = k * f_z
    a = np.abs(f - fs * np.round(f / fs))
    return np.unique(np.round(a[(a > 0.0) & (a <= x_max)], 3))


def plot_spectra(freq_Hz, spectra: dict[str, tuple[str, str, np.ndarray]],
                 lines: dict[str, dict], f_z_Hz: float, harmonics: int,
                 sample_rate_Hz: float, *, order_Hz: float | None = None,
                 db: bool = False) -> Figure:
    """Amplitude spectra (log scale), one panel per signal, with the mesh harmonics k·f_z and
    their shaft-frequency sidebands marked.

    ``spectra`` maps a signal key to (title, unit, amplitudes); ``lines`` maps the same key to
    analysis.json's lines ({label: gearcli.results.SpectrumLine}, amplitudes in the panel's
    unit).
    Harmonics above the Nyquist frequency are drawn where they fold to (aliases).
    ``order_Hz``: draw against the order (frequency / ``order_Hz``, e.g. the pinion shaft
    frequency: the mesh harmonics at k·z1) instead of the frequency; ``db``: amplitudes in dB
    re each panel's largest line instead of a log axis.
    """
    from matplotlib.ticker import FuncFormatter, NullLocator

    sx = 1.0 / order_Hz if order_Hz else 1.0  # x axis: frequency [Hz] or order [-]

    def level(a, ref: float):
        """Amplitudes as plotted: dB re ``ref`` (the panel's largest) with ``db``, else as is."""
        return 20.0 * np.log10(np.maximum(np.asarray(a, float), 1e-300) / ref) if db else a

    freq = np.asarray(freq_Hz, float)
    nyq = 0.5 * sample_rate_Hz
    aliased = f_z_Hz >= nyq
    x_max = min((harmonics + 0.5) * f_z_Hz, nyq)
    fig, axes = stacked_figure(len(spectra), height=2.5)
    drawn: set[str] = set()
    sel = (freq > 0.0) & (freq <= x_max)
    for i, (key, (title, unit, amp)) in enumerate(spectra.items()):
        ax = axes[i]
        a = np.asarray(amp, float)[sel]
        top = float(a.max(initial=0.0)) or 1.0
        if db:
            ax.plot(sx * freq[sel], level(a, top), color=FORCE, lw=0.7)
            ax.set_ylim(-140.0, 10.0)
        else:
            ax.semilogy(sx * freq[sel], a, color=FORCE, lw=0.7)
            positive = a[a > 0]
            bottom = max(float(positive.min()) if positive.size else top * 1e-8, top * 1e-7)
            ax.set_ylim(bottom, top * 30.0)
        for label, ln in lines.get(key, {}).items():
            f = ln.expected_Hz
            if f is None:
                continue
            side = "+" in label or "-" in label
            if f > nyq:
                if not side:
                    ax.axvline(sx * _alias(f, sample_rate_Hz), color=ALIAS, ls="-.", lw=0.9)
                    drawn.add("alias")
                    if i == 0:
                        ax.text(sx * _alias(f, sample_rate_Hz), 1.01,
                                label.replace("fz", " f_z") + " alias", color=ALIAS,
                                fontsize=7, ha="center", va="bottom",
                                transform=ax.get_xaxis_transform())
                continue
            if f > x_max:
                continue
            if side:
                ax.axvline(sx * f, color=SIDEBAND, ls=":", lw=0.6, zorder=1)
                drawn.add("side")
                continue
            ax.axvline(sx * f, color=HARMONIC, ls="--", lw=0.8, alpha=0.7, zorder=1)
            drawn.add("harm")
            if i == 0:
                ax.text(sx * f, 1.01, label.replace("fz", " f_z"), color=HARMONIC, fontsize=8,
                        ha="center", va="bottom", transform=ax.get_xaxis_transform())
            if ln.resolvable and ln.amplitude:
                ax.plot(sx * ln.measured_Hz, level(ln.amplitude, top), "o", mfc="none",
                        color=HARMONIC, ms=6)
                drawn.add("meas")
        folds = _folds(f_z_Hz, sample_rate_Hz, x_max, harmonics + 1)
        if folds.size:
            drawn.add("fold")
            ax.plot(sx * folds, np.full(folds.size, 0.985), ls="", marker=7, ms=5, color=ALIAS,
                    alpha=0.8, transform=ax.get_xaxis_transform(), clip_on=False)
        ax.set_xlim(0.0, sx * x_max)
        if db:
            ax.set_ylabel("amplitude [dB re max]")
        else:
            ax.yaxis.set_minor_locator(NullLocator())  # log minor ticks: clutter, slow layout
            ax.yaxis.set_major_formatter(FuncFormatter(_decade))  # plain text, no mathtext
            ax.set_ylabel(f"amplitude [{unit}]")
        ax.text(0.995, 0.96, title, transform=ax.transAxes, ha="right", va="top", fontsize=9,
                bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none"})
    axes[-1].set_xlabel("order (per pinion revolution) [-]" if order_Hz else "frequency [Hz]")
    from matplotlib.lines import Line2D

    legend = {
        "harm": Line2D([], [], color=HARMONIC, ls="--", label="mesh harmonics k·f_z"),
        "side": Line2D([], [], color=SIDEBAND, ls=":", label="sidebands k·f_z ± n1, n2"),
        "meas": Line2D([], [], color=HARMONIC, marker="o", mfc="none", ls="",
                       label="measured line amplitude"),
        "alias": Line2D([], [], color=ALIAS, ls="-.", label="alias of k·f_z (k analysed)"),
        "fold": Line2D([], [], color=ALIAS, marker=7, ls="",
                       label="where higher harmonics above f_s/2 fold (aliases)"),
    }
    handles = [h for key, h in legend.items() if key in drawn]
    if aliased:
        fig.suptitle(f"f_z = {f_z_Hz:.1f} Hz is above the Nyquist frequency {nyq:.0f} Hz: "
                     "the output cannot show the mesh lines, only their aliases")
    else:
        fig.suptitle(f"Spectra of the steady window: lines at the mesh frequency "
                     f"f_z = {f_z_Hz:.2f} Hz and its harmonics")
    fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), fontsize=8,
               frameon=False)
    return fig
