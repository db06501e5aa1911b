"""Drawing of a spur gear pair in mesh: true tooth outlines, circles, line of action, zoom.

Layout: pinion centre O1 at the origin, gear centre O2 at (a_w, 0), the pinion turning
counter-clockwise and driving, so the drive line of action runs from T1 (below the line of
centres, on the pinion base circle) to T2 (above, on the gear base circle), inclined α_w to the
common tangent at the pitch point C (ISO 21771). The pinion tooth whose drive flank passes
through C and the gear tooth touching it are placed exactly in contact: a flank at polar angle
β + ψ(r) (ψ from :func:`gearcli.model.profile.flank_half_angle`) passes through C when
β = −ψ1(r_w1) for the pinion and β = π − ψ2(r_w2) for the gear; both flank normals at C are then
the line of action, so the involutes touch without overlap.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from gearcli.model import profile

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from gearcli.model.geometry import GearGeometry, PairGeometry

__all__ = ["plot_pair", "mesh_layout", "check_drawable", "drawable", "MAX_DRAWN_TEETH"]

#: Teeth a gear may have to be drawn: the outlines are drawn twice (pair and zoom) at 24 and 120
#: segments a flank, so the cost grows with the teeth (~5 s at 600/600 teeth, 180 s at 3000);
#: larger gears are refused before any drawing.
MAX_DRAWN_TEETH = 500

_PINION_FILL, _GEAR_FILL = "#b9cde5", "#f2d7a6"
_OUTLINE = "#1a1a1a"
_LOA = "#7b2d8e"
_CIRCLES = (  # (attribute, label, colour, line style)
    ("d_b_mm", "base circles", "#2e7d32", (0, (6, 3))),
    ("d_w_mm", "operating pitch circles", "#c62828", (0, (8, 2, 1.5, 2))),
    ("d_a_mm", "tip circles", "#555555", (0, (3, 2))),
    ("d_f_mm", "root circles", "#555555", (0, (1, 2))),
)


def mesh_layout(geom: PairGeometry) -> dict[str, object]:
    """Positions used by the drawing [mm, rad].

    Returns a dict with centres ``O1``, ``O2``, the line-of-action origin ``T1`` and unit
    direction ``n`` (so a point at distance s from T1 is T1 + s n), and the outline rotations
    ``rot1``, ``rot2`` for :func:`gearcli.model.profile.gear_outline` that put one tooth pair
    in contact at the pitch point C.
    """
    aw, alpha_w = geom.a_w_mm, geom.alpha_w_rad
    n = np.array([math.sin(alpha_w), math.cos(alpha_w)])
    t1 = geom.pinion.r_b_mm * np.array([math.cos(alpha_w), -math.sin(alpha_w)])
    beta1 = -float(profile.flank_half_angle(geom.pinion, geom.pinion.r_w_mm))
    beta2 = math.pi - float(profile.flank_half_angle(geom.gear, geom.gear.r_w_mm))
    return {
        "O1": np.zeros(2), "O2": np.array([aw, 0.0]), "T1": t1, "n": n,
        "rot1": beta1 - 0.5 * math.pi, "rot2": beta2 - 0.5 * math.pi,
    }


def _draw_gear(ax: Axes, gear: GearGeometry, rotation: float, centre, fill: str, label: str,
               n_seg: int) -> None:
    from matplotlib.patches import Polygon

    x, y = profile.gear_outline(gear, rotation, n_seg, (float(centre[0]), float(centre[1])))
    xy = np.column_stack((x, y))
    # as ax.fill, with the data limits from the vertices at once: ax.fill walks the outline's
    # thousands of segments one by one in Python to find them (~0.2 s a gear)
    ax.add_artist(Polygon(xy, closed=True, facecolor=fill, edgecolor=_OUTLINE, linewidth=0.9,
                          label=label, zorder=2))
    ax.update_datalim(xy)
    ax.plot(*centre, marker="+", color=_OUTLINE, markersize=12, mew=1.0, zorder=5)


def _draw_circles(ax: Axes, geom: PairGeometry, layout: dict) -> None:
    t = np.linspace(0.0, 2.0 * math.pi, 721)
    for attr, label, colour, style in _CIRCLES:
        for k, (gear, centre) in enumerate(((geom.pinion, layout["O1"]),
                                            (geom.gear, layout["O2"]))):
            r = 0.5 * getattr(gear, attr)
            ax.plot(centre[0] + r * np.cos(t), centre[1] + r * np.sin(t), color=colour,
                    linestyle=style, linewidth=0.6, zorder=3, label=None if k else label)


def _draw_line_of_action(ax: Axes, geom: PairGeometry, layout: dict, fontsize: float,
                         label_offset: float, labels: tuple[str, ...]) -> None:
    t1, n = layout["T1"], layout["n"]
    at = lambda s: t1 + s * n  # noqa: E731  (point at distance s from T1)
    pts = geom.line_of_action_points()
    seg = np.array([at(0.0), at(geom.T1T2_mm)])
    ax.plot(seg[:, 0], seg[:, 1], color=_LOA, linewidth=0.9, zorder=6,
            label="line of action T1-T2")
    act = np.array([at(geom.A_mm), at(geom.E_mm)])
    ax.plot(act[:, 0], act[:, 1], color=_LOA, linewidth=3.0, alpha=0.55, zorder=6,
            solid_capstyle="butt", label=f"path of contact AE ({geom.g_alpha_mm:.2f} mm)")
    side = np.array([n[1], -n[0]])  # unit normal to the line of action (to the lower right)
    for k, (name, s) in enumerate(pts.items()):
        p = at(s)
        ax.plot(*p, marker="o", markersize=3.2, color=_LOA, zorder=7)
        if name in labels:
            off = side * label_offset * (1.0 if k % 2 else -1.0)
            ax.annotate(name, p, p + off, fontsize=fontsize, ha="center", va="center",
                        color=_LOA, zorder=8, clip_on=True,
                        bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                              "alpha": 0.75})


def _draw_all(ax: Axes, geom: PairGeometry, layout: dict, n_seg: int, fontsize: float,
              label_offset: float, labels: tuple[str, ...]) -> None:
    _draw_gear(ax, geom.pinion, layout["rot1"], layout["O1"], _PINION_FILL,
               f"pinion z1 = {geom.pinion.teeth}", n_seg)
    _draw_gear(ax, geom.gear, layout["rot2"], layout["O2"], _GEAR_FILL,
               f"gear z2 = {geom.gear.teeth}", n_seg)
    _draw_circles(ax, geom, layout)
    ax.plot([layout["O1"][0], layout["O2"][0]], [0.0, 0.0], color=_OUTLINE, linewidth=0.5,
            linestyle=(0, (12, 3, 2, 3)), zorder=3)
    _draw_line_of_action(ax, geom, layout, fontsize, label_offset, labels)
    c = layout["T1"] + geom.C_mm * layout["n"]
    ax.plot(*c, marker="o", markersize=6, markerfacecolor="none", markeredgecolor="#c62828",
            zorder=8)


def _summary(geom: PairGeometry) -> str:
    j = "" if abs(geom.j_n_mm) < 5e-7 else f"\nj_n = {geom.j_n_mm:.3f} mm"
    return (f"m = {geom.module_mm:g} mm, α = {math.degrees(geom.pressure_angle_rad):.4g}°\n"
            f"x1 = {geom.pinion.profile_shift:g}, x2 = {geom.gear.profile_shift:g}\n"
            f"a_w = {geom.a_w_mm:.3f} mm, α_w = {math.degrees(geom.alpha_w_rad):.3f}°\n"
            f"ε_α = {geom.eps_alpha:.4f}" + j)


def drawable(geom: PairGeometry) -> bool:
    """Whether both gears have at most MAX_DRAWN_TEETH teeth (the report leaves the drawing
    of a larger pair out; ``--plot`` refuses it with :func:`check_drawable`)."""
    return max(geom.pinion.teeth, geom.gear.teeth) <= MAX_DRAWN_TEETH


def check_drawable(geom: PairGeometry) -> None:
    """Refuse a pair with a gear of more than MAX_DRAWN_TEETH teeth (before any drawing)."""
    from gearcli.errors import OutputError

    teeth = {"z1": geom.pinion.teeth, "z2": geom.gear.teeth}
    big = {k: z for k, z in teeth.items() if z > MAX_DRAWN_TEETH}
    if big:
        got = ", ".join(f"{k} = {z}" for k, z in big.items())
        raise OutputError(f"--plot: draws gears of at most {MAX_DRAWN_TEETH} teeth (got {got}); "
                          "the numbers need no drawing (--json)")


def plot_pair(geom: PairGeometry, title: str | None = None) -> Figure:
    """Draw the gear pair in mesh at its operating centre distance, with a zoom on the mesh.

    Parameters
    ----------
    geom : PairGeometry
        Result of :func:`gearcli.model.geometry.compute_pair_geometry` (its α_w must exist).
    title : str, optional
        Figure title; default names the pair.

    Returns
    -------
    matplotlib.figure.Figure
        Left: both gears (true involute flanks and trochoid fillets from
        :mod:`gearcli.model.profile`), base / operating pitch / tip / root circles, the line of
        action T1–T2 with A, B, C, D, E. Right: zoom on the tooth pair in contact at C.
    """
    from matplotlib.figure import Figure

    from gearcli.plotting.text import plain

    check_drawable(geom)
    if not math.isfinite(geom.alpha_w_rad):
        raise ValueError("cannot draw the pair: the operating pressure angle does not exist")
    layout = mesh_layout(geom)
    m = geom.module_mm
    fig = Figure(figsize=(14.0, 7.2), layout="constrained")
    ax, inset = fig.subplots(1, 2, width_ratios=(1.65, 1.0))
    _draw_all(ax, geom, layout, 24, fontsize=8.0, label_offset=1.2 * m, labels=("T1", "T2"))
    r1, r2 = geom.pinion.r_a_mm, geom.gear.r_a_mm
    pad = 0.6 * m
    ax.set_xlim(-r1 - pad, geom.a_w_mm + r2 + pad)
    ax.set_ylim(-max(r1, r2) - pad, max(r1, r2) + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.grid(True, linewidth=0.3, alpha=0.4)
    ax.text(0.01, 0.99, _summary(geom), transform=ax.transAxes, va="top", ha="left",
            fontsize=8, bbox={"boxstyle": "round", "facecolor": "white", "alpha": 0.85})

    # zoom on the mesh zone: the pitch point C and the path of contact A..E
    c = layout["T1"] + geom.C_mm * layout["n"]
    half = 0.5 * max(1.35 * geom.g_alpha_mm, 4.0 * m)
    _draw_all(inset, geom, layout, 120, fontsize=9.0, label_offset=0.09 * half,
              labels=("T1", "A", "B", "C", "D", "E", "T2"))
    inset.set_xlim(c[0] - half, c[0] + half)
    inset.set_ylim(c[1] - half, c[1] + half)
    inset.set_aspect("equal")
    inset.tick_params(labelsize=7)
    inset.set_xlabel("x [mm]", fontsize=8)
    inset.set_title("zoom: tooth pair in contact at the pitch point C", fontsize=9)
    ax.indicate_inset_zoom(inset, edgecolor="#444444", linewidth=0.8)

    handles, labels = ax.get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=4, fontsize=8, frameon=False)
    fig.suptitle(plain(title) if title else (
        f"Spur gear pair z1/z2 = {geom.pinion.teeth}/{geom.gear.teeth}, "
        f"m = {m:g} mm: mesh at a_w = {geom.a_w_mm:.3f} mm"))
    return fig
