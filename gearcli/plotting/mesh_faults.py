"""The faulted mesh over one pinion revolution (`gearcli mesh` with faults; docs/theory.md,
"Tooth faults"): mesh stiffness and loaded STE, faulted against healthy. Pure: arrays in, a
matplotlib Figure out."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_revolution"]


def plot_revolution(pitches, k_faulted, k_healthy, ste_faulted, ste_healthy,
                    stiffness_unit: str, te_unit: str, title: str) -> Figure:
    """Two panels against the pinion roll in base pitches from t = 0 (x = i: pinion tooth i's
    drive pair at the pitch point): mesh stiffness and loaded STE, faulted (red) over healthy
    (grey)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10.0, 5.5), layout="constrained")
    ax1, ax2 = fig.add_subplot(2, 1, 1), fig.add_subplot(2, 1, 2, sharex=fig.axes[0]
                                                         if fig.axes else None)
    x = np.asarray(pitches, float)
    ax1.plot(x, k_healthy, color="0.6", lw=1.0, label="healthy")
    ax1.plot(x, k_faulted, color="#c0392b", lw=1.0, label="faulted")
    ax1.set_ylabel(f"mesh stiffness [{stiffness_unit}]")
    ax1.legend(fontsize=8, loc="lower right")
    ax1.set_title(title, fontsize=10, loc="left")
    ax2.plot(x, ste_healthy, color="0.6", lw=1.0, label="healthy")
    ax2.plot(x, ste_faulted, color="#c0392b", lw=1.0, label="faulted (NaN: no pair carries)")
    ax2.set_ylabel(f"loaded STE [{te_unit}]")
    ax2.set_xlabel("pinion roll [base pitches from t = 0; x = i: pinion tooth i at the pitch "
                   "point]")
    ax2.legend(fontsize=8, loc="upper right")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        ax.set_xlim(x[0], x[-1])
    return fig
