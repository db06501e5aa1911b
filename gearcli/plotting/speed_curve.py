"""Speed-curve figure: dynamic factor against the resonance ratio, run-up and run-down."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_speed_curve"]

_STYLE = {"up": ("#1565c0", "^", "run-up"), "down": ("#c62828", "v", "run-down")}


def plot_speed_curve(rows: list[dict], f_n_Hz: float, title: str = "") -> Figure:
    """Dynamic factor [-] against N = f_z / f_n [-] (f_n the case's mesh mode) for the run-up
    and the run-down of gearcli/pipeline/speed_curve.py; points outside the model's validity
    are marked with a grey cross at the top of the axes, not plotted as values; dotted lines
    at f_n/2, f_n and 2 f_n."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.0, 4.8))
    ax = fig.add_subplot()
    top = max((r["dynamic_factor"] for r in rows if r["status"] == "ok"), default=2.0)
    for direction, (colour, marker, label) in _STYLE.items():
        ok = [r for r in rows if r["direction"] == direction and r["status"] == "ok"]
        ok.sort(key=lambda r: r["resonance_ratio"])
        ax.plot([r["resonance_ratio"] for r in ok], [r["dynamic_factor"] for r in ok],
                marker=marker, color=colour, lw=1.2, ms=4, label=f"gearcli {label}")
        bad = [r for r in rows if r["direction"] == direction and r["status"] != "ok"]
        if bad:
            ax.plot([r["resonance_ratio"] for r in bad], [1.05 * top] * len(bad), "x",
                    color="0.5", label=f"{label}: outside the model's validity")
    for n, text in ((0.5, "f_n/2"), (1.0, "f_n"), (2.0, "2 f_n")):
        ax.axvline(n, color="0.6", ls=":", lw=1)
        ax.text(n, 1.0, f" {text}", transform=ax.get_xaxis_transform(), va="top", ha="left",
                fontsize=8, color="0.4")
    ax.set_xlabel("N = f_z / f_n  (gear-mesh frequency over the mesh natural frequency"
                  + (f", f_n = {f_n_Hz:.0f} Hz)" if math.isfinite(f_n_Hz) else ")"))
    ax.set_ylabel("dynamic factor  max F / F_static")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig
