"""Figures of a finished run: speeds, mesh force, load sharing, DTE, errors and relief (the
spectra: gearcli/plotting/spectra.py).

Every function takes plain arrays and dicts (internal units: s, rad, mm, N; spectra in the units
of analysis' spectrum.csv) and returns one matplotlib Figure (Agg canvas, never shown). The title
of each figure states what the reader should see; the numbers in it come from the arrays given.
matplotlib is imported inside the functions so that importing this module stays cheap.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from gearcli.plotting.decimate import minmax_decimate

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["plot_speeds", "plot_force", "plot_mesh_cycles", "plot_dte", "plot_modifications",
           "mesh_cycle_mean", "plot_lateral", "plot_drivetrain", "stacked_figure"]

PINION, GEAR, KIN, FORCE = "#1f5fa8", "#d9771e", "#222222", "#4a4a4a"
STATIC, PEAK = "#2e7d32", "#c62828"
HARMONIC, SIDEBAND, ALIAS = "#c62828", "#8c8c8c", "#7b2d8e"
_WINDOW_FILL = "#eef3ea"


def stacked_figure(rows: int, height: float = 3.1, ratios=None) -> tuple[Figure, list[Axes]]:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10.0, 0.9 + height * rows), layout="constrained")
    axes = fig.subplots(rows, 1, squeeze=False, height_ratios=ratios)[:, 0]
    for ax in axes:
        ax.grid(True, linewidth=0.4, alpha=0.5)
    return fig, list(axes)


def _shade_window(ax: Axes, window_s) -> None:
    if window_s is not None:
        ax.axvspan(window_s[0], window_s[1], color=_WINDOW_FILL, zorder=0, label="steady window")


def _line(ax: Axes, t, y, **style) -> None:
    """A time series over the whole run, decimated to the axes' pixel columns with every
    column's extrema kept (gearcli/plotting/decimate.py): the same picture, faster to draw."""
    ax.plot(*minmax_decimate(t, y), **style)


def _in(t: np.ndarray, span) -> np.ndarray:
    return (t >= span[0]) & (t <= span[1])


def _zoom_axis(ax: Axes, t0: float, what: str = "time") -> None:
    ax.set_xlabel(f"{what} − {t0:.4f} s [ms]")


def _mesh_cycles(zoom_s, f_z_Hz: float | None) -> float:
    """Mesh cycles in the zoom span (0 when the gear-mesh frequency is unknown)."""
    return (zoom_s[1] - zoom_s[0]) * f_z_Hz if f_z_Hz else 0.0


def _title_zoom(ax: Axes, n_samples: int, zoom_s, f_z_Hz: float | None) -> None:
    """Title a zoom axis with its mesh cycles and flag an output too coarse to resolve them."""
    cycles = _mesh_cycles(zoom_s, f_z_Hz)
    ax.set_title(f"zoom on {cycles:.0f} mesh cycles" if cycles else "zoom", fontsize=9)
    _note_coarse(ax, n_samples, cycles)


def _per_period(t, f_z_Hz: float | None) -> str:
    """Samples per mesh period of an evenly sampled stretch ``t`` [s], as text."""
    if not f_z_Hz or len(t) < 2:
        return "?"
    return f"{1.0 / (f_z_Hz * (t[1] - t[0])):.0f}"


def _note_coarse(ax: Axes, n_samples: int, cycles: float) -> None:
    """Say so on the plot when the output is too coarse to show a mesh cycle."""
    if cycles > 0 and n_samples / cycles < 8:
        ax.text(0.5, 0.5, f"only {n_samples} samples in {cycles:g} mesh cycles:\n"
                "the output rate cannot resolve the mesh (raise run.output_rate)",
                transform=ax.transAxes, ha="center", va="center", color=PEAK, fontsize=10,
                bbox={"facecolor": "white", "alpha": 0.85, "edgecolor": PEAK})


def plot_speeds(t_s, omega1_rad_s, omega2_rad_s, teeth: tuple[int, int], window_s=None,
                zoom_s=None, f_z_Hz: float | None = None, units: str = "engineering") -> Figure:
    """Pinion and gear speed over the run (in the display ``units``: rpm or rad/s,
    gearcli/display_units.py), and the gear speed against its kinematic value ω1·z1/z2 over
    a short stretch ``zoom_s`` = (t0, t1) [s] of the steady window."""
    from gearcli.display_units import speed_from_rad_s, speed_label

    t = np.asarray(t_s, float)
    unit = speed_label(units)
    w1 = speed_from_rad_s(np.asarray(omega1_rad_s, float), units)
    w2 = speed_from_rad_s(np.asarray(omega2_rad_s, float), units)
    kin = w1 * teeth[0] / teeth[1]
    fig, (ax, zx) = stacked_figure(2)
    _shade_window(ax, window_s)
    _line(ax, t, w1, color=PINION, lw=1.0, label=f"pinion ω1 (z1 = {teeth[0]})")
    _line(ax, t, w2, color=GEAR, lw=0.6, label=f"gear ω2 (z2 = {teeth[1]})")
    _line(ax, t, kin, color=KIN, lw=0.9, ls="--", label="kinematic gear speed ω1·z1/z2")
    ax.set(xlabel="time [s]", ylabel=f"speed [{unit}]", xlim=(t[0], t[-1]))
    ax.legend(loc="lower right", fontsize=8)
    sel = _in(t, window_s) if window_s is not None else np.ones(t.size, bool)
    k_mean = float(np.mean(kin[sel]))
    half = 0.5 * float(np.ptp(w2[sel] - kin[sel]))
    if zoom_s is not None:
        z = _in(t, zoom_s)
        ms = (t[z] - zoom_s[0]) * 1e3
        zx.plot(ms, w2[z], color=GEAR, lw=1.0, marker=".", ms=3, label="gear ω2 (output samples)")
        zx.plot(ms, kin[z], color=KIN, lw=0.9, ls="--", label="kinematic ω1·z1/z2")
        _zoom_axis(zx, zoom_s[0])
        zx.set_ylabel(f"gear speed [{unit}]")
        zx.legend(loc="best", fontsize=8)
        _title_zoom(zx, int(z.sum()), zoom_s, f_z_Hz)
    else:
        zx.set_visible(False)
    fig.suptitle(f"Gear speed fluctuates around the kinematic {k_mean:.4g} {unit} "
                 f"(±{half:.3g} {unit} in the steady window)")
    return fig


def plot_force(t_s, force_N, static_N, force_max_N=None, force_max_t_s=None, window_s=None,
               zoom_s=None, f_z_Hz: float | None = None, zoom_data=None) -> Figure:
    """Normal mesh force [N] with the static force (scalar or per sample) and the
    true maximum from the solver steps, over the run and zoomed (``zoom_s``) around it.
    ``zoom_data`` = (t [s], force [N], static [N] or None): the solver's dense output for the
    zoom (else the zoom shows the output samples)."""
    t, f = np.asarray(t_s, float), np.asarray(force_N, float)
    stat = np.broadcast_to(np.asarray(static_N, float), t.shape)
    fig, (ax, zx) = stacked_figure(2)
    _shade_window(ax, window_s)
    _line(ax, t, f / 1e3, color=FORCE, lw=0.35, label="total normal force (output samples)")
    _line(ax, t, stat / 1e3, color=STATIC, lw=1.2, ls="--",
          label="static force (resisted torque / r_b2)")
    has_max = force_max_N is not None and force_max_t_s is not None
    if has_max:
        ax.plot(force_max_t_s, force_max_N / 1e3, "*", color=PEAK, ms=11, mec="white", mew=0.6,
                label=f"true maximum {force_max_N / 1e3:.2f} kN at t = {force_max_t_s:.4f} s")
    top = max(float(f.max(initial=0.0)), force_max_N or 0.0) / 1e3
    ax.set(xlabel="time [s]", ylabel="normal force [kN]", xlim=(t[0], t[-1]),
           ylim=(min(0.0, float(f.min(initial=0.0)) / 1e3), 1.3 * top or 1.0))
    ax.legend(loc="upper left", fontsize=8, ncol=2, framealpha=0.95)
    if zoom_s is not None:
        if zoom_data is not None:
            zt, zf, zs = (np.asarray(a, float) if a is not None else None for a in zoom_data)
            ms = (zt - zoom_s[0]) * 1e3
            zx.plot(ms, zf / 1e3, color=FORCE, lw=1.0,
                    label=f"solver dense output ({_per_period(zt, f_z_Hz)} points per mesh "
                          "period)")
            zs = zs if zs is not None else np.interp(zt, t, stat)
            zx.plot(ms, zs / 1e3, color=STATIC, lw=1.2, ls="--", label="static force")
            z = np.ones(zt.size, bool)
        else:
            z = _in(t, zoom_s)
            ms = (t[z] - zoom_s[0]) * 1e3
            zx.plot(ms, f[z] / 1e3, color=FORCE, lw=0.9, marker=".", ms=4,
                    label="output samples")
            zx.plot(ms, stat[z] / 1e3, color=STATIC, lw=1.2, ls="--", label="static force")
        if has_max and zoom_s[0] <= force_max_t_s <= zoom_s[1]:
            zx.plot((force_max_t_s - zoom_s[0]) * 1e3, force_max_N / 1e3, "*", color=PEAK,
                    ms=12, mec="white", mew=0.6, label="true maximum (solver steps)")
        _zoom_axis(zx, zoom_s[0])
        zx.set_ylabel("normal force [kN]")
        zx.set_title("zoom around the maximum", fontsize=9)
        zx.legend(loc="upper left", fontsize=8)
        _note_coarse(zx, int(z.sum()), _mesh_cycles(zoom_s, f_z_Hz))
    else:
        zx.set_visible(False)
    if force_max_N is not None:
        t_ref = force_max_t_s if force_max_t_s is not None else t[-1]
        s_ref = float(np.interp(t_ref, t, stat))
        fig.suptitle(f"Mesh force peaks at {force_max_N / 1e3:.2f} kN, "
                     + (f"{force_max_N / s_ref:.2f} × the static {s_ref / 1e3:.2f} kN"
                        if s_ref > 0.0 else "without a static load (no dynamic factor)"))
    else:
        fig.suptitle("Mesh force against the static force")
    return fig


def plot_mesh_cycles(t_s, force_N, slot_forces: dict[str, np.ndarray], pairs, zoom_s,
                     f_z_Hz: float) -> Figure:
    """Total force and the force of each pair slot [N] over a few mesh cycles ``zoom_s``, with
    the number of tooth pairs in contact on a twin axis."""
    t = np.asarray(t_s, float)
    z = _in(t, zoom_s)
    ms = (t[z] - zoom_s[0]) * 1e3
    cycles = _mesh_cycles(zoom_s, f_z_Hz)
    fig, (ax,) = stacked_figure(1, height=4.6)
    nz = np.asarray(pairs, float)[z]
    tw = ax.twinx()
    tw.fill_between(ms, nz, step="mid", color="#9fb7d6", alpha=0.25, lw=0)
    tw.plot(ms, nz, drawstyle="steps-mid", color="#5b7fae", lw=1.0, label="pairs in contact")
    tw.set_ylim(0, max(3.0, float(nz.max(initial=0)) + 1.0))
    tw.set_yticks(range(int(tw.get_ylim()[1]) + 1))
    tw.set_ylabel("pairs in contact [-]", color="#5b7fae")
    ax.set_zorder(tw.get_zorder() + 1)
    ax.patch.set_visible(False)
    ax.plot(ms, np.asarray(force_N, float)[z] / 1e3, color=KIN, lw=2.2, alpha=0.6,
            label="total force")
    colours = ("#1f5fa8", "#d9771e", "#2e7d32", "#7b2d8e", "#8c564b", "#17becf")
    for k, (label, values) in enumerate(slot_forces.items()):
        v = np.asarray(values, float)[z]
        if np.any(v != 0.0):
            ax.plot(ms, v / 1e3, color=colours[k % len(colours)], lw=1.0, marker=".", ms=3,
                    label=label)
    _zoom_axis(ax, zoom_s[0])
    ax.set_ylabel("normal force [kN]")
    handles = ax.get_legend_handles_labels()
    th = tw.get_legend_handles_labels()
    ax.legend(handles[0] + th[0], handles[1] + th[1], loc="upper left", fontsize=8, ncol=3)
    ax.set_ylim(bottom=0.0, top=ax.get_ylim()[1] * 1.18)
    _note_coarse(ax, int(z.sum()), cycles)
    counts = sorted({int(round(v)) for v in nz} - {0})
    span = "-".join(str(n) for n in counts) if counts else "no"
    loss = ", with brief contact loss" if np.any(nz == 0) and counts else ""
    fig.suptitle(f"{cycles:.0f} mesh cycles of {1e3 / f_z_Hz:.2f} ms: {span} tooth pairs "
                 f"share the load in turn{loss}")
    return fig


def plot_dte(t_s, dte_mm, window_s=None, zoom_s=None, f_z_Hz: float | None = None,
             zoom_data=None, units: str = "engineering") -> Figure:
    """Dynamic transmission error δ (µm, or m with ``units="si"``) over the run (mean of the
    steady window marked) and zoomed on a few mesh cycles ``zoom_s``; ``zoom_data`` = (t [s],
    δ [mm], unused): the solver's dense output for the zoom (else the output samples)."""
    from gearcli.display_units import unit_and_factor

    u, k = unit_and_factor("mm", units, fine=True)
    t, d = np.asarray(t_s, float), np.asarray(dte_mm, float) * k
    fig, (ax, zx) = stacked_figure(2)
    _shade_window(ax, window_s)
    _line(ax, t, d, color=PINION, lw=0.4, label="DTE δ (output samples)")
    sel = _in(t, window_s) if window_s is not None else np.ones(t.size, bool)
    mean, pp = float(np.mean(d[sel])), float(np.ptp(d[sel]))
    if window_s is not None:
        ax.hlines(mean, window_s[0], window_s[1], color=KIN, ls="--", lw=1.0,
                  label=f"mean {mean:.3g} {u}")
    ax.set(xlabel="time [s]", ylabel=f"DTE δ [{u}]", xlim=(t[0], t[-1]))
    ax.legend(loc="lower right", fontsize=8)
    if zoom_s is not None:
        if zoom_data is not None:
            zt, zd = np.asarray(zoom_data[0], float), np.asarray(zoom_data[1], float) * k
            zx.plot((zt - zoom_s[0]) * 1e3, zd, color=PINION, lw=1.0,
                    label=f"solver dense output ({_per_period(zt, f_z_Hz)} points per mesh "
                          "period)")
            zx.legend(loc="upper left", fontsize=8)
            n_zoom = zt.size
        else:
            z = _in(t, zoom_s)
            zx.plot((t[z] - zoom_s[0]) * 1e3, d[z], color=PINION, lw=1.0, marker=".", ms=3)
            n_zoom = int(z.sum())
        zx.axhline(mean, color=KIN, ls="--", lw=1.0)
        _zoom_axis(zx, zoom_s[0])
        zx.set_ylabel(f"DTE δ [{u}]")
        _title_zoom(zx, n_zoom, zoom_s, f_z_Hz)
    else:
        zx.set_visible(False)
    fig.suptitle(f"DTE settles at a mean of {mean:.3g} {u} (mesh deflection) and swings "
                 f"{pp:.3g} {u} peak to peak in the steady window")
    return fig


def plot_modifications(errors: dict | None = None, relief: dict | None = None) -> Figure:
    """What the case's manufacturing errors and profile reliefs do.

    errors : {"t_s", "dte_mm", "cycle_t_s", "cycle_mean_mm", "reference_mm" (expected half
        swing or None), "label"} — DTE over a few revolutions with its mean over each mesh
        cycle, which shows the once-per-revolution error apart from the mesh-frequency ripple.
    relief : {"x_mm", "curves" {label: relief [mm]}, "points" {A..E: x [mm]},
        "dte_mean_mm", "label"} — the relief along the path of contact (x from A), with the
        single-pair zone B–D and the mean mesh deflection for scale.
    """
    panels = [p for p in (errors, relief) if p is not None]
    if not panels:
        raise ValueError("nothing to draw: the case has no errors and no profile relief")
    fig, axes = stacked_figure(len(panels), height=3.4)
    if errors is not None:
        ax = axes[0]
        t = np.asarray(errors["t_s"], float)
        d = np.asarray(errors["dte_mm"], float) * 1e3
        m = np.asarray(errors["cycle_mean_mm"], float) * 1e3
        _line(ax, t, d, color=PINION, lw=0.3, alpha=0.5, label="DTE δ (output samples)")
        ax.plot(errors["cycle_t_s"], m, color=PEAK, lw=1.6,
                label=f"DTE mean over each mesh cycle: {np.ptp(m):.1f} µm peak to peak")
        ref = errors.get("reference_mm")
        if ref:
            c = 0.5 * (m.max() + m.min())
            ax.axhspan(c - ref * 1e3, c + ref * 1e3, color="#f4d9d9", alpha=0.6, zorder=0,
                       label=f"expected swing ±{ref * 1e3:.1f} µm (± the eccentricity)")
        ax.set(xlabel="time [s]", ylabel="DTE δ [µm]", xlim=(t[0], t[-1]))
        ax.set_title(errors["label"], fontsize=9)
        ax.legend(loc="lower right", fontsize=8, framealpha=0.95)
    if relief is not None:
        ax = axes[-1]
        pts = relief["points"]
        ax.axvspan(pts["B"], pts["D"], color=_WINDOW_FILL, zorder=0, label="single-pair zone B–D")
        for k, (label, values) in enumerate(relief["curves"].items()):
            ax.plot(relief["x_mm"], np.asarray(values, float) * 1e3, lw=1.6,
                    color=(PINION, GEAR, "#2e7d32", "#7b2d8e")[k % 4], label=label)
        if relief.get("dte_mean_mm"):
            ax.axhline(relief["dte_mean_mm"] * 1e3, color=KIN, ls="--", lw=0.9,
                       label="mean DTE (mesh deflection under load)")
        for name, x in pts.items():
            ax.axvline(x, color=SIDEBAND, lw=0.6)
            ax.text(x, 0.03, name, ha="center", va="bottom", fontsize=9,
                    transform=ax.get_xaxis_transform(),
                    bbox={"facecolor": "white", "edgecolor": "none", "pad": 1.0})
        ax.set(xlabel="position on the path of contact from A [mm]",
               ylabel="profile relief [µm]", xlim=(pts["A"] - 1.0, pts["E"] + 1.0))
        ax.set_ylim(bottom=0.0, top=ax.get_ylim()[1] * 1.15)
        x = np.asarray(relief["x_mm"], float)
        relieved = np.zeros(x.size, bool)
        for values in relief["curves"].values():
            relieved |= np.asarray(values, float) > 0.0
        inside = relieved & (x > pts["B"] + 1e-9) & (x < pts["D"] - 1e-9)
        where = ("it reaches into the single-pair zone B–D" if inside.any()
                 else "it acts only where two pairs share the load (A–B, D–E)")
        ax.set_title(f"{relief['label']}: {where}", fontsize=9)
        ax.legend(loc="upper left", fontsize=8, framealpha=0.95)
    what = " and ".join(w for w, p in (("errors", errors), ("profile relief", relief)) if p)
    fig.suptitle(f"What the case's {what} change")
    return fig


def mesh_cycle_mean(t_s, values, samples_per_cycle: float) -> tuple[np.ndarray, np.ndarray]:
    """Mean over each run of one mesh cycle of samples: (centre times [s], means).

    Only complete cycles are averaged, so the ends carry no partial-cycle bias.
    """
    t, v = np.asarray(t_s, float), np.asarray(values, float)
    n = max(int(math.floor(samples_per_cycle + 0.5)), 1)
    if n <= 1 or v.size < n:
        return t.copy(), v.copy()
    kernel = np.ones(n) / n
    return np.convolve(t, kernel, mode="valid"), np.convolve(v, kernel, mode="valid")


def _time_panels(t_s, window_s, panels, title: str, ncol: int) -> Figure:
    """One panel per (y label, curves) of ``panels`` against time [s], the steady window
    shaded; curves are (values, label, colour, line style)."""
    t = np.asarray(t_s, float)
    fig, axes = stacked_figure(len(panels))
    for ax, (ylabel, curves) in zip(axes, panels, strict=True):
        _shade_window(ax, window_s)
        for values, label, colour, style in curves:
            _line(ax, t, values, color=colour, ls=style, lw=0.8, label=label)
        ax.set(xlabel="time [s]", ylabel=ylabel, xlim=(t[0], t[-1]))
        ax.legend(fontsize=8, ncol=ncol, loc="best")
    fig.suptitle(title)
    return fig


def plot_lateral(t_s, columns: dict, window_s=None, units: str = "engineering") -> Figure:
    """Lateral-torsional model: centre displacements x, y of pinion and gear (µm, or m with
    ``units="si"``) and their bearing forces [kN] against time (columns ``x1_mm`` …
    ``bearing_force_y2_N``)."""
    from gearcli.display_units import unit_and_factor

    u, k = unit_and_factor("mm", units, fine=True)
    moves, forces = [], []
    for body, colour in (("1", PINION), ("2", GEAR)):
        name = "pinion" if body == "1" else "gear"
        for axis, style in (("x", "-"), ("y", "--")):
            d = columns.get(f"{axis}{body}_mm")
            if d is not None:
                moves.append((k * np.asarray(d, float), f"{name} {axis}{body}", colour, style))
            f = columns.get(f"bearing_force_{axis}{body}_N")
            if f is not None:
                forces.append((1e-3 * np.asarray(f, float), f"{name} bearing F_{axis}", colour,
                               style))
    return _time_panels(t_s, window_s, [(f"centre displacement [{u}]", moves),
                                        ("bearing force [kN]", forces)],
                        "Shaft centres on their bearings (x along the line of centres)", 3)


def plot_drivetrain(t_s, columns: dict, window_s=None, units: str = "engineering") -> Figure:
    """Drivetrain: motor, pinion, gear and load speeds (display ``units``) and the drive- and
    load-shaft torques [N·m] against time."""
    from gearcli.display_units import speed_from_rad_s, speed_label

    speeds = [(speed_from_rad_s(np.asarray(columns[key], float), units), label, colour, style)
              for key, label, colour, style in (("omega_motor_rad_s", "motor", STATIC, "-"),
                                                ("omega1_rad_s", "pinion ω1", PINION, "-"),
                                                ("omega2_rad_s", "gear ω2", GEAR, "-"),
                                                ("omega_load_rad_s", "load", KIN, "--"))
              if key in columns]
    torques = [(1e-3 * np.asarray(columns[key], float), label, colour, "-")
               for key, label, colour in (("drive_shaft_torque_Nmm", "drive shaft", PINION),
                                          ("load_shaft_torque_Nmm", "load shaft", GEAR),
                                          ("drive_torque_Nmm", "drive torque on the pinion",
                                           STATIC),
                                          ("load_torque_Nmm", "load torque", KIN))
               if key in columns]
    return _time_panels(t_s, window_s, [(f"speed [{speed_label(units)}]", speeds),
                                        ("torque [N·m]", torques)],
                        "Drivetrain speeds and shaft torques", 2)
