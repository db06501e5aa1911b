"""Speed-curve figure: dynamic factor against the resonance ratio, run-up and run-down."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from gearcli.plotting.text import plain

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_speed_curve"]

_STYLE = {"up": ("#1565c0", "^", "run-up"), "down": ("#c62828", "v", "run-down")}


def plot_speed_curve(rows, f_n_Hz: float, title: str = "", iso=None,
                     iso_factors: tuple[float, float, float] = (0.0, 0.0, 1.0),
                     iso_without_low_load=None, grade: int | None = None) -> Figure:
    """Dynamic factor [-] against N = f_z / f_n [-] (f_n the case's mesh mode) for the run-up
    and the run-down of gearcli/pipeline/speed_curve.py (``rows``: its levels,
    gearcli.results.SpeedLevel); the lines break at the levels without a value, invalid ones
    (outside the model's validity) marked with a grey cross at the top of the axes, failed
    ones (the run did not finish) with a plus; levels that did not settle (status
    "unsettled") are ringed; dotted lines at f_n/2, f_n and 2 f_n. ``iso`` = (N, K_v, N_ISO)
    arrays: ISO 6336-1 Method B's K_v on the same axis (its own resonance ratio n1/n_E1 on a
    secondary axis), computed with ``iso_factors`` = (B_p, B_f, B_k) [-], which the legend
    states; ``iso_without_low_load``: K_v [-] on the same points without the standard's low-load
    factor (dotted); ``grade``: the ISO 1328-1 class the deviations and K_v are of."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.0, 4.8))
    ax = fig.add_subplot()
    valued = ("ok", "unsettled")  # levels with a value; unsettled ones ringed
    top = max((r.dynamic_factor for r in rows if r.status in valued), default=2.0)
    for direction, (colour, marker, label) in _STYLE.items():
        # every level of the direction, NaN where it has no value: the line breaks there
        levels = sorted((r for r in rows if r.direction == direction),
                        key=lambda r: r.resonance_ratio)
        ax.plot([r.resonance_ratio for r in levels],
                [r.dynamic_factor if r.status in valued else math.nan for r in levels],
                marker=marker, color=colour, lw=1.2, ms=4, label=f"gearcli {label}")
        loose = [r for r in levels if r.status == "unsettled"]
        if loose:
            ax.plot([r.resonance_ratio for r in loose], [r.dynamic_factor for r in loose], "o",
                    mfc="none", mec=colour, ms=10, mew=1.2,
                    label=f"{label}: not settled (status unsettled)")
        for status, what in (("invalid", "invalid (outside the model's validity)"),
                             ("failed", "failed (the run did not finish)")):
            bad = [r for r in levels if r.status == status]
            if bad:
                ax.plot([r.resonance_ratio for r in bad], [1.05 * top] * len(bad),
                        "x" if status == "invalid" else "+", color="0.5", ls="none",
                        label=f"{label}: {what}")
    if iso is not None:
        x_iso, k_v, n_iso = iso
        of_grade = f", ISO 1328-1 class {grade}" if grade is not None else ""
        ax.plot(x_iso, k_v, color="0.25", lw=1.6, ls="--",
                label="ISO 6336-1 Method B K_v (B_p = {:.3g}, B_f = {:.3g}, B_k = {:.3g}{})"
                .format(*iso_factors, of_grade))
        if iso_without_low_load is not None:
            ax.plot(x_iso, iso_without_low_load, color="0.45", lw=1.3, ls=":",
                    label="ISO K_v without the low-load factor (c' unreduced)")
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
    ax.set_title(plain(title))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig
