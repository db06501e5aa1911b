"""Campbell diagram (frequency vs pinion speed) and a mode-shape panel.

Mode lines are horizontal: the linearised mesh stiffness does not depend on speed. Order lines
f = per_rev · n1 (n1 the pinion speed in rev/s); a circle marks where an order line meets a mode
with a resonant peak (a cross when the mode has none), a vertical line the case speed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from gearcli.plotting.text import plain

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from gearcli.model.modal import ModalResult, Order

__all__ = ["plot_campbell"]

_DOF_LABELS = {"theta_m_rad": "motor θm", "theta1_rad": "pinion θ1", "theta2_rad": "gear θ2",
               "theta_L_rad": "load θL", "x1_mm": "pinion x1", "y1_mm": "pinion y1",
               "x2_mm": "gear x2", "y2_mm": "gear y2"}
_MODE_COLOURS = ["#c62828", "#1565c0", "#2e7d32", "#6a1b9a", "#ef6c00", "#00838f", "#ad1457",
                 "#4e342e"]


def plot_campbell(result: ModalResult, orders: tuple[Order, ...],
                  speed_range_deg_s: tuple[float, float], case_speed_deg_s: float | None,
                  title: str = "", units: str = "engineering") -> Figure:
    """Campbell diagram (left) and mode shapes (right) of a modal result (any model).

    Parameters
    ----------
    result : ModalResult
        Modes from :func:`gearcli.model.modal.linear_modes`.
    orders : tuple of Order
        Excitation orders (events per pinion revolution).
    speed_range_deg_s : (float, float)
        Pinion speed axis [deg/s].
    case_speed_deg_s : float or None
        The case's pinion speed [deg/s], marked when given.
    units : str
        Display units of the speed axis (gearcli/display_units.py: rpm or rad/s).
    """
    from matplotlib.figure import Figure

    from gearcli.display_units import unit_and_factor

    speed_unit, k = unit_and_factor("deg/s", units)

    fig = Figure(figsize=(12.0, 7.0), layout="constrained")
    ax, axs = fig.subplots(1, 2, width_ratios=[2.3, 1.0])
    lo, hi = speed_range_deg_s
    speed = np.linspace(lo, hi, 200)
    elastic = result.elastic
    f_modes = [m.natural_frequency_Hz for m in elastic]
    f_top = 1.25 * max(f_modes) if f_modes else (max(o.per_rev for o in orders) * hi / 360.0)
    mode_colours = [_MODE_COLOURS[k % len(_MODE_COLOURS)] for k in range(len(elastic))]

    gmf = [o for o in orders if "GMF" in o.name]
    shafts = [o for o in orders if "GMF" not in o.name]
    greys = np.linspace(0.15, 0.65, max(len(gmf), 1))
    for o, grey in zip(gmf, greys, strict=False):
        f = o.per_rev * speed / 360.0
        ax.plot(k * speed, f, color=str(grey), lw=1.0)
        _label_line(ax, k * speed, f, o.name, f_top)
    for o, style in zip(shafts, ("--", ":"), strict=False):
        f = o.per_rev * speed / 360.0
        ax.plot(k * speed, f, color="#555555", lw=1.0, ls=style, label=f"{o.name} (shaft order)")
    for m, col in zip(elastic, mode_colours, strict=False):
        ax.axhline(m.natural_frequency_Hz, color=col, lw=2.0,
                   label=f"mode {m.number}: {m.natural_frequency_Hz:.0f} Hz, "
                         f"ζ = {m.damping_ratio:.3g}")
        for o in orders:
            n = m.natural_frequency_Hz / o.per_rev * 360.0
            if lo <= n <= hi:
                ax.plot(k * n, m.natural_frequency_Hz, "o" if m.has_peak else "x", ms=7,
                        mfc="none", mec=col, color=col, mew=1.6)
    if case_speed_deg_s is not None and lo <= case_speed_deg_s <= hi:
        ax.axvline(k * case_speed_deg_s, color="#ef6c00", lw=1.5, ls="-.",
                   label=f"case speed {k * case_speed_deg_s:.4g} {speed_unit}")
    ax.set_xlim(k * lo, k * hi)
    ax.set_ylim(0.0, f_top)
    ax.set_xlabel(f"pinion speed [{speed_unit}]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title("Campbell diagram (o crossing with a resonant mode, x mode without a peak)",
                 fontsize=9)
    ax.grid(alpha=0.3)
    # outside the axes: inside, it hid the order labels at the right-hand end of the lines
    ax.legend(loc="upper left", bbox_to_anchor=(0.0, -0.12), ncol=3, fontsize=8,
              framealpha=0.9)

    _plot_shapes(axs, result, _MODE_COLOURS)
    if title:
        fig.suptitle(plain(title))
    return fig


def _label_line(ax, speed, f, text, f_top) -> None:
    """Write the order's name where its line leaves the plot (top or right edge)."""
    inside = np.nonzero(f <= 0.97 * f_top)[0]
    if inside.size == 0 or inside[-1] == 0:
        return
    i = inside[-1]
    ax.annotate(text, (speed[i], f[i]), fontsize=7, color="#333333", ha="right", va="bottom",
                xytext=(-2, 2), textcoords="offset points",
                bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none", "alpha": 0.8})


def _plot_shapes(ax, result: ModalResult, colours) -> None:
    dofs = [_DOF_LABELS.get(d, d) for d in result.dofs]
    x = np.arange(len(dofs))
    modes = result.modes
    width = 0.8 / max(len(modes), 1)
    for k, m in enumerate(modes):
        col = "#777777" if m.rigid else colours[(k - sum(mm.rigid for mm in modes))
                                                % len(colours)]
        label = (f"mode {m.number}: rigid body" if m.rigid
                 else f"mode {m.number}: {m.natural_frequency_Hz:.0f} Hz")
        ax.bar(x + (k - (len(modes) - 1) / 2) * width, m.shape, width, color=col, label=label)
    ax.axhline(0.0, color="black", lw=0.8)
    ax.set_xticks(x, dofs, rotation=30 if len(dofs) > 3 else 0)
    ax.set_ylim(-1.15, 1.35)
    ax.set_ylabel("normalised amplitude (largest = 1)")
    ax.set_title("mode shapes as lengths (rotations: r_b θ)",
                 fontsize=9)
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(axis="y", alpha=0.3)


def plot_campbell_summary(modes, pinion_teeth: int, case_speed_rpm: float,
                          harmonics: int = 5, title: str = "",
                          units: str = "engineering") -> Figure:
    """Campbell diagram from a run's stored modes (summary.json ``scalars.modes``,
    gearcli.results.StoredMode): the mode
    frequencies [Hz] as horizontal lines (dashed: no resonant peak, ζ >= 1/√2), the gear-mesh
    orders k z1 n1/60 (k = 1 .. ``harmonics``) against the pinion speed [rpm] up to 1.5 times
    the case speed, their crossings with the peaked modes circled and the case speed marked;
    the speed axis in the display ``units`` (rpm or rad/s)."""
    from matplotlib.figure import Figure

    from gearcli.display_units import unit_and_factor
    from gearcli.model.modal import has_resonant_peak

    unit, k_n = unit_and_factor("rpm", units)

    fig = Figure(figsize=(8.0, 4.8))
    ax = fig.add_subplot()
    top_speed = 1.5 * case_speed_rpm if case_speed_rpm > 0 else 1000.0
    n = np.linspace(0.0, top_speed, 200)
    elastic = [m for m in modes if not m.rigid_body and m.natural_frequency_Hz]
    f_top = max([m.natural_frequency_Hz for m in elastic]
                + [harmonics * pinion_teeth * top_speed / 60.0]) * 1.1
    for k in range(1, harmonics + 1):
        ax.plot(k_n * n, k * pinion_teeth * n / 60.0, color="0.35", lw=0.9)
        x_end = min(top_speed, f_top * 60.0 / (k * pinion_teeth))
        ax.text(k_n * x_end, k * pinion_teeth * x_end / 60.0, f" {k}×f_z", fontsize=7,
                va="bottom")
    for i, m in enumerate(elastic):
        f = m.natural_frequency_Hz
        peaked = has_resonant_peak(m.damping_ratio or 0.0)
        colour = _MODE_COLOURS[i % len(_MODE_COLOURS)]
        ax.axhline(f, color=colour, ls="-" if peaked else "--", lw=1.2,
                   label=f"mode {m.mode}: {f:.0f} Hz, ζ {m.damping_ratio or 0:.3f}"
                         + ("" if peaked else " (no resonant peak)"))
        if peaked:
            for k in range(1, harmonics + 1):
                n_cross = 60.0 * f / (k * pinion_teeth)
                if n_cross <= top_speed:
                    ax.plot(k_n * n_cross, f, "o", mfc="none", mec=colour, ms=7)
    if case_speed_rpm > 0:
        ax.axvline(k_n * case_speed_rpm, color="#2e7d32", lw=1.2, ls=":",
                   label=f"case speed {k_n * case_speed_rpm:.4g} {unit}")
    ax.set(xlim=(0.0, k_n * top_speed), ylim=(0.0, f_top), xlabel=f"pinion speed [{unit}]",
           ylabel="frequency [Hz]", title=plain(title))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    return fig
