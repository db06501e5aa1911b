"""Figure of a quasi-static loaded contact analysis (`gearcli mesh`): STE, load sharing, mesh
stiffness along the roll, and the Harris map when computed. Plain arrays in, one matplotlib
Figure out (Agg canvas, never shown); matplotlib is imported inside the function."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from gearcli.plotting.text import plain

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_mesh"]


def plot_mesh(roll_mm, ste, unloaded, pair_force_N, mesh_stiffness, *,
              force_N: float, iso_single: float, iso_mean: float, title: str,
              harris: tuple[np.ndarray, np.ndarray] | None = None, te_unit: str = "µm",
              stiffness_unit: str = "N/mm", single_pair_limit_N: float | None = None
              ) -> Figure:
    """Panels against the pinion roll [mm]: loaded STE and unloaded TE [``te_unit``]; force
    per pair slot [N] with the static force; mesh stiffness [``stiffness_unit``] with ISO
    6336-1 c′b and c_γα b; and the Harris map (STE peak-to-peak [``te_unit``] against load
    [N]) if given, with the single-pair limit F* [N] (model/ltca.single_pair_limit: above it
    no position has one pair alone) when it is inside the map's range."""
    from matplotlib.figure import Figure

    rows = 4 if harris is not None else 3
    fig = Figure(figsize=(8.0, 2.4 * rows), layout="constrained")
    axes = fig.subplots(rows, 1)
    ax = axes[0]
    ax.plot(roll_mm, ste, color="#1f5fa8", label="loaded STE")
    ax.plot(roll_mm, unloaded, color="#888888", ls="--", label="unloaded TE")
    ax.set_ylabel(f"TE [{te_unit}]")
    ax.legend(loc="upper right", fontsize=8)
    ax = axes[1]
    for j in range(pair_force_N.shape[1]):
        f = np.where(pair_force_N[:, j] > 0.0, pair_force_N[:, j], np.nan)
        if np.isfinite(f).any():
            ax.plot(roll_mm, f, lw=1.2, label=f"slot {j}")
    ax.axhline(force_N, color="#c62828", lw=0.8, ls=":", label="static force")
    ax.set_ylabel("pair force [N]")
    ax.legend(loc="upper right", fontsize=8, ncol=4)
    ax = axes[2]
    ax.plot(roll_mm, mesh_stiffness, color="#2e7d32", label="mesh stiffness")
    ax.axhline(iso_single, color="#7b2d8e", lw=0.8, ls=":", label="ISO 6336-1 c′b")
    ax.axhline(iso_mean, color="#8c564b", lw=0.8, ls="--", label="ISO 6336-1 c_γα b")
    ax.set_ylabel(f"stiffness [{stiffness_unit}]")
    ax.set_xlabel("pinion roll r_b1 θ1 [mm]")
    ax.legend(loc="upper right", fontsize=8)
    for a in axes[:3]:
        a.grid(alpha=0.3)
        a.set_xlim(roll_mm[0], roll_mm[-1])
    if harris is not None:
        ax = axes[3]
        loads, ptp = harris
        ax.plot(loads, ptp, "o-", color="#1f5fa8", ms=3)
        ax.axvline(force_N, color="#c62828", lw=0.8, ls=":", label="static force")
        if single_pair_limit_N is not None and loads[0] < single_pair_limit_N < loads[-1]:
            ax.axvline(single_pair_limit_N, color="#555555", lw=0.8, ls="--",
                       label="single-pair limit F*")
        ax.legend(loc="upper left", fontsize=8)
        ax.set_xlabel("static normal force [N]")
        ax.set_ylabel(f"STE peak-to-peak [{te_unit}]")
        ax.set_title("Harris map", fontsize=9, loc="left")
        ax.grid(alpha=0.3)
    fig.suptitle(plain(title), fontsize=10)
    return fig
