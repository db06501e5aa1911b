"""Figure of the tooth stresses of a run: σ_H and σ_F through a few mesh cycles and along the path.

Takes plain arrays (samples × pair slots; stresses in MPa, roll positions in mm from A, time in
s) and returns one matplotlib Figure (Agg canvas, never shown). matplotlib is imported inside
the function so that importing this module stays cheap.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from gearcli.plotting.text import plain

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_stress", "plot_stress_of_run", "critical_points"]

_SLOT_COLOURS = ("#1f5fa8", "#d9771e", "#2e7d32", "#7b2d8e", "#8c564b", "#e377c2")
_PINION, _GEAR, _STATIC, _MARK = "#1f5fa8", "#d9771e", "#c62828", "#555555"


def _marks(ax, marks_mm: dict[str, float]) -> None:
    for label, x in marks_mm.items():
        ax.axvline(x, color=_MARK, lw=0.6, ls=":")
        ax.text(x, 1.0, f" {label}", transform=ax.get_xaxis_transform(), va="bottom",
                ha="center", fontsize=8, color=_MARK)


def critical_points(peaks: dict | None) -> dict[str, list[tuple[str, float, float]]]:
    """The critical positions of stress.json's per-gear peaks ``peaks`` = {"pinion":
    GearPeaks, "gear": GearPeaks} (gearcli.results; their ``peak_sigma_H``, ``peak_sigma_F``:
    ``MPa``, ``x_from_A_mm``), the peaks the simulated rating divides σ_HG, σ_FG by
    (docs/theory.md, "ISO 6336 rating" §9): {"H": [(label, x [mm from A], σ [MPa])],
    "F": [...]}, a contact peak shared by both gears listed once."""
    out: dict[str, list[tuple[str, float, float]]] = {"H": [], "F": []}
    for role, gear in (peaks or {}).items():
        for kind, p in (("H", gear.peak_sigma_H), ("F", gear.peak_sigma_F)):
            if p.MPa is None or p.x_from_A_mm is None:
                continue
            point = (float(p.x_from_A_mm), float(p.MPa))
            if kind == "H" and any(q[1:] == point for q in out["H"]):
                continue
            label = f"σ_H peak ({role})" if kind == "H" else f"σ_F peak {role}"
            out[kind].append((label, *point))
    return out


def _critical(ax, points: list[tuple[str, float, float]]) -> None:
    """A marker and an annotation at each critical position (label, x [mm], σ [MPa])."""
    for k, (label, x, value) in enumerate(points):
        ax.plot([x], [value], marker="*", ms=13, color="#000000", mfc="#ffd600", ls="none",
                zorder=5, label="critical position (simulated rating)" if k == 0 else None)
        ax.annotate(f"{label}: {value:.4g} MPa at x = {x:.3g} mm", (x, value),
                    xytext=(0.99, 0.62 - 0.13 * k), textcoords="axes fraction", fontsize=7,
                    ha="right", va="top", arrowprops={"arrowstyle": "-", "lw": 0.5},
                    bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "#999999",
                          "alpha": 0.85})


def plot_stress(t_s, x_mm, force_N, sigma_H, sigma_F_pinion, sigma_F_gear, *, window_s,
                zoom_s, marks_mm: dict[str, float], single_pair_x_mm, single_pair_sigma_H,
                static_MPa: dict[str, float], title: str,
                critical: dict[str, list[tuple[str, float, float]]] | None = None) -> Figure:
    """Four panels: σ_H per slot and σ_F (pinion, gear) per slot over ``zoom_s`` = (t0, t1) [s];
    σ_H and σ_F against the roll position x from A [mm] for every loaded sample of the window.

    ``single_pair_sigma_H`` (on ``single_pair_x_mm``) is the Hertz stress of one pair carrying
    the whole static load, drawn as the quasi-static reference; ``static_MPa`` holds the ISO
    values ``sigma_H_B``, ``sigma_H_D``, ``sigma_F0_pinion``, ``sigma_F0_gear`` [MPa];
    ``marks_mm`` the points A…E [mm from A]; ``critical`` (:func:`critical_points`) the
    positions of the peaks the simulated rating uses, marked on the position panels.
    """
    from matplotlib.figure import Figure

    t = np.asarray(t_s, float)
    x = np.asarray(x_mm, float)
    loaded = np.asarray(force_N, float) > 0.0
    fig = Figure(figsize=(10.0, 12.0), layout="constrained")
    ax_h, ax_f, px_h, px_f = fig.subplots(4, 1)
    fig.suptitle(plain(title))
    zoom = (t >= zoom_s[0]) & (t <= zoom_s[1])
    ms = (t[zoom] - zoom_s[0]) * 1e3
    for j in range(x.shape[1]):
        colour = _SLOT_COLOURS[j % len(_SLOT_COLOURS)]
        ax_h.plot(ms, np.asarray(sigma_H)[zoom, j], color=colour, lw=1.0, label=f"slot {j}")
        ax_f.plot(ms, np.asarray(sigma_F_pinion)[zoom, j], color=colour, lw=1.0,
                  label=f"pinion, slot {j}")
        ax_f.plot(ms, np.asarray(sigma_F_gear)[zoom, j], color=colour, lw=1.0, ls="--",
                  label=f"gear, slot {j}")
    ax_h.axhline(static_MPa["sigma_H_B"], color=_STATIC, lw=0.9, ls="-.",
                 label="ISO static (Z_B Z_ε σ_H0)")
    ax_f.axhline(static_MPa["sigma_F0_pinion"], color=_PINION, lw=0.9, ls="-.",
                 label="ISO σ_F0 pinion")
    ax_f.axhline(static_MPa["sigma_F0_gear"], color=_GEAR, lw=0.9, ls=":",
                 label="ISO σ_F0 gear")
    for ax, what in ((ax_h, "contact stress σ_H [MPa]"), (ax_f, "root stress σ_F [MPa]")):
        ax.set(xlabel=f"time − {zoom_s[0]:.4f} s [ms]", ylabel=what)
        ax.grid(True, lw=0.4, alpha=0.5)
        ax.legend(fontsize=7, ncol=3, loc="upper right")
    ax_h.set_title("through the last mesh cycles of the window", fontsize=9)

    win = (t >= window_s[0]) & (t <= window_s[1])
    sel = win[:, None] & loaded
    px_h.plot(x[sel], np.asarray(sigma_H)[sel], ".", ms=1.5, color=_PINION,
              label="dynamic σ_H (samples in the window)")
    px_h.plot(single_pair_x_mm, single_pair_sigma_H, color=_STATIC, lw=1.0,
              label="one pair, full static load")
    px_f.plot(x[sel], np.asarray(sigma_F_pinion)[sel], ".", ms=1.5, color=_PINION,
              label="pinion σ_F")
    px_f.plot(x[sel], np.asarray(sigma_F_gear)[sel], ".", ms=1.5, color=_GEAR, label="gear σ_F")
    px_f.axhline(static_MPa["sigma_F0_pinion"], color=_PINION, lw=0.9, ls="-.",
                 label="ISO σ_F0 pinion (load at D)")
    px_f.axhline(static_MPa["sigma_F0_gear"], color=_GEAR, lw=0.9, ls=":",
                 label="ISO σ_F0 gear (load at B)")
    for ax, kind in ((px_h, "H"), (px_f, "F")):
        _critical(ax, (critical or {}).get(kind, []))
    for ax, what in ((px_h, "σ_H [MPa]"), (px_f, "σ_F [MPa]")):
        ax.set(xlabel="pinion roll position from A along the line of action [mm]", ylabel=what)
        ax.grid(True, lw=0.4, alpha=0.5)
        ax.legend(fontsize=7, loc="upper right")
        _marks(ax, marks_mm)
    return fig


def plot_stress_of_run(t_s, x_mm, force_N, sigma_H, sigma_F_pinion, sigma_F_gear, *, geometry,
                       static, window_s, f_z_Hz: float, title: str,
                       cycles: float = 3.0, peaks: dict | None = None) -> Figure:
    """:func:`plot_stress` of a run: the last ``cycles`` mesh cycles of the window (mesh
    frequency ``f_z_Hz`` [Hz]), the points A…E of ``geometry`` (a PairGeometry) and the
    single-pair Hertz reference from stress.json's ``static`` values (``static``: a
    gearcli.results.StaticRatingDoc; its ``force_normal_N``, ``contact_face_width_mm``,
    ``E_star_MPa``, and per gear ``sigma_H_iso_MPa``, ``sigma_F0_MPa``), so that `gearcli
    stress --plot` and the report draw the same figure; ``peaks``: stress.json's
    {"pinion": ..., "gear": ...}, whose peak positions are marked (:func:`critical_points`)."""
    from gearcli.model.rating import hertz_line_contact_stress

    geo = geometry
    t0, t1 = window_s
    zoom = (max(t0, t1 - cycles / f_z_Hz), t1) if f_z_Hz > 0 else (t0, t1)
    x_ref = np.linspace(0.0, geo.g_alpha_mm, 200)
    rho1 = geo.A_mm + x_ref
    ref_h = hertz_line_contact_stress(static.force_normal_N, static.contact_face_width_mm,
                                      rho1, geo.T1T2_mm - rho1, static.E_star_MPa)
    marks = {k: v - geo.A_mm for k, v in geo.line_of_action_points().items()
             if k in ("A", "B", "C", "D", "E")}
    return plot_stress(
        t_s, x_mm, force_N, sigma_H, sigma_F_pinion, sigma_F_gear, window_s=window_s,
        zoom_s=zoom, marks_mm=marks, single_pair_x_mm=x_ref, single_pair_sigma_H=ref_h,
        static_MPa={"sigma_H_B": static.pinion.sigma_H_iso_MPa,
                    "sigma_H_D": static.gear.sigma_H_iso_MPa,
                    "sigma_F0_pinion": static.pinion.sigma_F0_MPa,
                    "sigma_F0_gear": static.gear.sigma_F0_MPa},
        title=title, critical=critical_points(peaks))
