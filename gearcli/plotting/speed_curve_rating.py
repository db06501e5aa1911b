"""Speed-curve rating figure: S_H and S_F (ISO 6336 with each speed's simulated K_v) against the
resonance ratio, run-up and run-down, with the minimum safeties."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_speed_curve_rating"]

_STYLE = {"up": ("#1565c0", "^", "run-up"), "down": ("#c62828", "v", "run-down")}


def plot_speed_curve_rating(panels, f_n_Hz: float, title: str = "") -> Figure:
    """One panel per safety against N = f_z/f_n [-]: ``panels`` = [(name, minimum, {direction:
    [(N, S), ...]})], name "S_H" or "S_F", its minimum [-] (dashed) and the points of the
    run-up ("up") and the run-down ("down") (gearcli/pipeline/run_rating.py: the smaller
    safety of the gears of each speed's rating)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.0, 3.2 * len(panels)), layout="constrained")
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    fig.suptitle(title)
    xs = [p[0] for _, _, by in panels for pts in by.values() for p in pts]
    for ax, (name, minimum, by) in zip(axes, panels, strict=True):
        for direction, (colour, marker, label) in _STYLE.items():
            pts = sorted(by.get(direction, []))
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker, color=colour,
                    lw=1.2, ms=4, label=label)
        ax.axhline(minimum, color="0.25", ls="--", lw=1.2, label=f"{name},min = {minimum:g}")
        for n in (0.5, 1.0, 2.0):  # f_n/2, f_n, 2 f_n where the speeds reach them
            if xs and min(xs) <= n <= max(xs):
                ax.axvline(n, color="0.6", ls=":", lw=1)
        ax.set_ylabel(f"{name} (smaller of the gears)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_title("ISO 6336 Method B with each speed's K_v = F_max/F_static", fontsize=9)
    axes[-1].set_xlabel("N = f_z / f_n" + (f"  (f_n = {f_n_Hz:.0f} Hz)"
                                           if math.isfinite(f_n_Hz) else ""))
    return fig
