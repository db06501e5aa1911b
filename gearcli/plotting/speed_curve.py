"""Speed-curve figure: dynamic factor against the resonance ratio, run-up and run-down."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_speed_curve"]

_STYLE = {"up": ("#1565c0", "^", "run-up"), "down": ("#c62828", "v", "run-down")}


def plot_speed_curve(rows, f_n_Hz: float, title: str = "", iso=None,
                     iso_factors: tuple[float, float, float] = (0.0, 0.0, 1.0)) -> Figure:
    """Dynamic factor [-] against N = f_z / f_n [-] (f_n the case's mesh mode) for the run-up
    and the run-down of gearcli/pipeline/speed_curve.py (``rows``: its levels,
    gearcli.results.SpeedLevel); the lines break at the levels that are not ok, invalid ones
    (outside the model's validity) marked with a grey cross at the top of the axes, failed
    ones (the run did not finish) with a plus; dotted lines
    at f_n/2, f_n and 2 f_n. ``iso`` = (N, K_v, N_ISO) arrays: ISO 6336-1 Method B's K_v on the
    same axis (its own resonance ratio n1/n_E1 on a secondary axis), computed with
    ``iso_factors`` = (B_p, B_f, B_k) [-], which the legend states."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.0, 4.8))
    ax = fig.add_subplot()
    top = max((r.dynamic_factor for r in rows if r.status == "ok"), default=2.0)
    for direction, (colour, marker, label) in _STYLE.items():
        # every level of the direction, NaN where it is not ok: the line breaks there
        levels = sorted((r for r in rows if r.direction == direction),
                        key=lambda r: r.resonance_ratio)
        ax.plot([r.resonance_ratio for r in levels],
                [r.dynamic_factor if r.status == "ok" else math.nan for r in levels],
                marker=marker, color=colour, lw=1.2, ms=4, label=f"gearcli {label}")
        for status, what in (("invalid", "invalid (outside the model's validity)"),
                             ("failed", "failed (the run did not finish)")):
            bad = [r for r in levels if r.status == status]
            if bad:
                ax.plot([r.resonance_ratio for r in bad], [1.05 * top] * len(bad),
                        "x" if status == "invalid" else "+", color="0.5", ls="none",
                        label=f"{label}: {what}")
    if iso is not None:
        x_iso, k_v, n_iso = iso
        ax.plot(x_iso, k_v, color="0.25", lw=1.6, ls="--",
                label="ISO 6336-1 Method B K_v (B_p = {:.3g}, B_f = {:.3g}, B_k = {:.3g})"
                .format(*iso_factors))
        ratio = x_iso[-1] / n_iso[-1] if n_iso[-1] else 1.0
        top = ax.secondary_xaxis("top", functions=(lambda x: x / ratio, lambda x: x * ratio))
        top.set_xlabel("ISO resonance ratio N = n1 / n_E1", fontsize=8)
        fig.text(0.01, 0.005, "bottom axis: f_z over the case's mesh mode f_n (with a speed "
                 "drive the pinion is held); top axis: ISO's n_E1 has both gears free "
                 "(docs/theory.md §10.4)", fontsize=6.5, color="0.35", va="bottom")
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
