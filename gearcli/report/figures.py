"""The report's figures: choose what to zoom on, draw with gearcli.plotting, save PNG (and SVG
on request)."""

from __future__ import annotations

import dataclasses
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gearcli.io.files import make_folder, write_atomic
from gearcli.model.gap import Modifications, Relief, modification_gaps
from gearcli.plotting import results as plots
from gearcli.plotting.campbell import plot_campbell_summary
from gearcli.plotting.geometry import drawable, plot_pair
from gearcli.plotting.orders import plot_order_map
from gearcli.plotting.spectra import plot_spectra
from gearcli.report.data import ReportData

#: Resolution of the PNG files (the HTML embeds them) [dots per inch].
PNG_DPI = 110
#: Mesh cycles shown by the zooms.
ZOOM_CYCLES = 3
#: Spectrum signals: key in analysis.json lines -> (panel title, spectrum.csv column, unit).
SPECTRA = {
    "gear_speed": ("gear speed ω2", "gear_speed_amplitude_rad_s", "rad/s"),
    "dte": ("DTE δ", "dte_amplitude_mm", "mm"),
    "force": ("total normal force", "force_amplitude_N", "N"),
}


@dataclass(frozen=True)
class FigureFile:
    """One saved figure: a short name, its caption and the files written (``svg`` None when
    no SVG was asked for)."""

    name: str
    caption: str
    png: Path
    svg: Path | None


def build_figures(data: ReportData, out_dir: Path, svg: bool = False) -> list[FigureFile]:
    """Draw every figure of the report into ``out_dir`` (created) as PNG, and as SVG too when
    ``svg`` (saving an SVG costs about as much as drawing the figure). A link on
    the way out of the results folder is refused (io.files.make_folder)."""
    make_folder(out_dir, out_dir.parent)
    c = data.run.columns
    t = c["t_s"]
    f_z = data.f_z_Hz
    period = 1.0 / f_z
    window = data.window_s
    start = _cycle_start(t, c["pairs_in_contact"], window, period)
    mesh_zoom = (start, start + ZOOM_CYCLES * period)
    # the solver's dense output (>= 100 points per mesh period) for the zooms, where stored
    zc = data.zoom or {}
    zt = zc.get("t_s")
    dense = c
    if zt is not None:
        last = zt[-1]
        end_zoom = (last - ZOOM_CYCLES * period, last)
        # the dense table holds the last mesh periods at the nominal f_z: where the measured
        # f_z is lower (a run that never settles) it does not cover them, and the samples do
        if _zoom_of(zc, end_zoom, None, column="delta_mm") is not None:
            mesh_zoom, dense = end_zoom, zc
    teeth = (data.case.gears.pinion.teeth, data.case.gears.gear.teeth)
    s, m = data.scalars, data.metrics
    analysed = math.isfinite(m.force_max_N)  # an analysis.json before these metrics: the run's
    f_max = m.force_max_N if analysed else s.force_max_N
    t_max = m.force_max_t_s if math.isfinite(m.force_max_t_s) else (
        s.force_max_t_s if f_max == s.force_max_N else None)
    force_zoom = None if t_max is None else (t_max - 1.5 * period, t_max + 1.5 * period)
    r_b2 = data.geometry.gear.r_b_mm if data.geometry else None
    static = (_static_force(c, r_b2, data.gear_side_damping) if r_b2
              else m.force_static_N if math.isfinite(m.force_static_N) else s.force_static_N)
    slots = {f"slot {k[len('force_slot'):-2]}": v for k, v in dense.items()
             if k.startswith("force_slot") and k.endswith("_N")}
    jobs = [
        ("speeds", "Pinion and gear speed over the run (shaded: the steady window analysed) and "
         "the gear speed against its kinematic value ω1·z1/z2 over 6 mesh cycles.",
         lambda: plots.plot_speeds(t, c["omega1_rad_s"], c["omega2_rad_s"], teeth, window,
                                   (start, start + 6 * period), f_z, data.units)),
        ("force", "Total normal mesh force with the static force (the gear side's resisting "
         "torque over r_b2: the load torque and its speed-dependent terms); the marker is the "
         "true maximum taken from the solver's own steps (the output samples may miss it).",
         lambda: plots.plot_force(t, c["force_total_N"], static, f_max, t_max, window,
                                  force_zoom, f_z, zoom_data=_zoom_of(
                                      zc, force_zoom, r_b2, data.gear_side_damping))),
        ("mesh_cycles", f"{ZOOM_CYCLES} mesh cycles in the steady window: the force carried in "
         "each pair slot (a slot is one base pitch of the line of action; a tooth pair moves "
         "through the slots as the gears turn), their sum, and the number of pairs in contact.",
         lambda: plots.plot_mesh_cycles(dense["t_s"], dense["force_total_N"], slots,
                                        dense["pairs_in_contact"], mesh_zoom, f_z)),
        ("dte", "Dynamic transmission error δ = r_b1·θ1 − r_b2·θ2 (deflection of the mesh "
         f"along the line of action) over the run and over {ZOOM_CYCLES} mesh cycles.",
         lambda: plots.plot_dte(t, c["delta_mm"], window, mesh_zoom, f_z, units=data.units,
                                zoom_data=_zoom_of(zc, mesh_zoom, None, column="delta_mm"))),
        ("spectra", "Hann-windowed amplitude spectra of the steady window (spectrum.csv): mesh "
         "harmonics k·f_z (dashed, measured amplitude circled) and shaft sidebands (dotted). "
         "Triangles on the top edge mark where harmonics above the Nyquist frequency f_s/2 "
         "fold to: peaks there can be sampling aliases of the impulsive force rather than "
         "physical lines.",
         lambda: _spectra(data)),
    ]
    if data.geometry is not None and drawable(data.geometry):  # a 600-tooth gear: no drawing
        jobs.insert(0, ("geometry", "The pair in mesh at its operating centre distance, drawn "
                        "from the generated tooth profiles (involute, trochoid fillet, tip), "
                        "with the line of action and the path of contact.",
                        lambda: plot_pair(data.geometry, title=f"{data.run.summary.case}: "
                                          "spur pair in mesh")))
    modes = data.scalars.modes
    if any(not m.rigid_body for m in modes):
        jobs.append(("campbell", "Campbell diagram from the modes of the linearised model "
                     "(summary.json): gear-mesh orders k·f_z against pinion speed, the modes "
                     "(dashed: overdamped, no resonant peak), crossings with peaked modes "
                     "circled and the case speed marked.",
                     lambda: plot_campbell_summary(
                         modes, teeth[0], abs(data.scalars.pinion_speed_mean_deg_s)
                         / 6.0, data.case.checks.harmonics,
                         units=data.units)))
    omega1 = c["omega1_rad_s"]
    # a run-up (the speed below 99 % of its final value for at least a tenth of the run, not
    # only a start-up transient): the order map
    if np.mean(np.abs(omega1) < 0.99 * abs(float(omega1[-1]))) >= 0.1:
        elastic_Hz = [m.natural_frequency_Hz for m in modes
                      if not m.rigid_body and m.natural_frequency_Hz]
        jobs.append(("orders", "Order map of the run-up: short-time spectra of the mesh force "
                     "against pinion speed (left) and time (right), with the mesh orders "
                     "k·z1·n/60 (white) and the modes (dashed); dB re the largest amplitude.",
                     lambda: plot_order_map(t, c["force_total_N"], omega1, teeth[0], elastic_Hz,
                                            label="mesh force", unit="N",
                                            units=data.units)))
    if data.stress and data.stress_series and data.geometry is not None:
        jobs.append(("stress", "Tooth stresses from the dynamic pair forces (gearcli stress): "
                     "Hertz contact stress σ_H and ISO 6336-3 root stress σ_F per pair slot "
                     "through the last mesh cycles of the window, and against the position on "
                     "the path of contact, with the ISO static values and the single-pair "
                     "quasi-static reference; stars mark the critical positions (the contact "
                     "and root stress peaks the simulated rating uses).", lambda: _stress(data)))
    lateral = [k for k in ("x1_mm", "y1_mm", "x2_mm", "y2_mm") if k in c]
    if lateral:
        jobs.append(("lateral", "Lateral-torsional model: centre displacements of the pinion "
                     "and the gear and their bearing forces over the run (shaded: the steady "
                     "window).", lambda: plots.plot_lateral(t, c, window, data.units)))
    if "omega_motor_rad_s" in c or "drive_shaft_torque_Nmm" in c:
        jobs.append(("drivetrain", "Drivetrain: motor and load speeds and the torques in the "
                     "drive and load shafts over the run.",
                     lambda: plots.plot_drivetrain(t, c, window, data.units)))
    if data.has_errors_or_relief():
        jobs.append(("modifications", "What the case's manufacturing errors and profile "
                     "modifications change: the once-per-revolution DTE they add (mean over each "
                     "mesh cycle) and the relief along the path of contact.",
                     lambda: _modifications(data, period)))
    from gearcli.report.parallel import render

    return render(jobs, _save, out_dir, svg)  # in two processes where that is safe


def _stress(data: ReportData):
    """The figure of `gearcli stress --plot` from stress.csv, the slot columns of the time
    series and stress.json's static values."""
    from gearcli.plotting.stress import plot_stress_of_run

    st, ss, c = data.stress, data.stress_series, data.run.columns
    slots = sorted(int(k[len("sigma_H_slot"):-4]) for k in ss if k.startswith("sigma_H_slot"))

    def stack(fmt: str, cols):
        return np.column_stack([cols[fmt.format(j)] for j in slots])

    geo = data.geometry
    return plot_stress_of_run(
        ss["t_s"], stack("x_slot{}_mm", c), stack("force_slot{}_N", c),
        stack("sigma_H_slot{}_MPa", ss), stack("sigma_F_pinion_slot{}_MPa", ss),
        stack("sigma_F_gear_slot{}_MPa", ss), geometry=geo, static=st.static,
        window_s=tuple(st.window_s), peaks={"pinion": st.pinion, "gear": st.gear},
        f_z_Hz=data.scalars.gear_mesh_frequency_Hz or 0.0,  # as `gearcli stress --plot`
        title=f"{st.case}: tooth stresses (z1 = {geo.pinion.teeth}, "
              f"z2 = {geo.gear.teeth})")


def _static_force(columns: dict, r_b2: float, damping: tuple[float, float]):
    """The static force line [N] of the samples in ``columns``: the torque the gear's side
    resists at each sample's speed over r_b2 (model/mesh.static_reference_N)."""
    from gearcli.model.mesh import static_reference_N

    return static_reference_N(columns["load_torque_Nmm"], r_b2, columns["omega2_rad_s"], damping)


def _zoom_of(zoom: dict, span, r_b2, damping=(0.0, 0.0), column: str = "force_total_N"):
    """(t, values, static force or None) of the dense zoom table over ``span``, or None when
    the table does not cover it (the plots then zoom into the output samples)."""
    t = zoom.get("t_s")
    if t is None or span is None or t.size == 0:
        return None
    inside = (t >= span[0]) & (t <= span[1])
    ti = t[inside]
    if ti.size < 3:
        return None
    # covered: no gap wider than 1.5 dense steps inside, at either end included (the table
    # holds separate stretches, and its times are rounded: no sample need sit on the span's
    # ends, which the measured f_z places)
    gaps = np.diff(np.concatenate(([span[0]], ti, [span[1]])))
    if gaps.max() > 1.5 * float(np.median(np.diff(ti))):
        return None
    static = (_static_force({k: zoom[k][inside] for k in ("load_torque_Nmm", "omega2_rad_s")},
                            r_b2, damping) if r_b2 else None)
    return t[inside], zoom[column][inside], static


def _save(name: str, caption: str, fig, out_dir: Path, svg: bool = False) -> FigureFile:
    from matplotlib import rc_context

    paths: dict[str, Path | None] = {"svg": None}
    # SVG text stays text (smaller, faster); a fixed hash salt keeps the SVG ids reproducible.
    with rc_context({"svg.fonttype": "none", "svg.hashsalt": "gearcli"}):
        for fmt in ("png", "svg") if svg else ("png",):
            buf = io.BytesIO()
            fig.savefig(buf, format=fmt, dpi=PNG_DPI, metadata=_metadata(fmt))
            paths[fmt] = out_dir / f"{name}.{fmt}"
            write_atomic(paths[fmt], buf.getvalue(), out_dir.parent)
            if fmt == "png":  # the layout is done: keep it for the SVG instead of redoing it
                fig.set_layout_engine("none")
    if not svg:  # an SVG of an earlier report would no longer match its PNG
        (out_dir / f"{name}.svg").unlink(missing_ok=True)
    return FigureFile(name, caption, paths["png"], paths["svg"])


def saved_formats(figures) -> str:
    """"PNG and SVG" when any of ``figures`` (FigureFile) was saved as SVG too, else "PNG"."""
    return "PNG and SVG" if any(f.svg is not None for f in figures) else "PNG"


def _metadata(fmt: str) -> dict:
    """No creation dates, so that the same folder gives the same files."""
    return {"Software": None} if fmt == "png" else {"Date": None}


def _cycle_start(t, pairs, window, period: float) -> float:
    """Start of the zoom: just before a new pair engages, past the middle of the window."""
    mid = 0.5 * (window[0] + window[1])
    i0 = int(np.searchsorted(t, mid))
    p = pairs[i0:int(np.searchsorted(t, mid + 10.0 * period))]
    rises = np.nonzero((np.diff(p) > 0) & (p[1:] >= p.max(initial=0)))[0]
    start = t[i0 + rises[0]] if rises.size else mid  # the last sample before the rise
    return float(min(max(start, window[0]), window[1] - ZOOM_CYCLES * period))


def _spectra(data: ReportData):
    harmonics = data.case.checks.harmonics
    return spectra_figure(data.spectrum, data.analysis, harmonics, units=data.units)


def spectra_figure(spectrum: dict, analysis, harmonics: int, order_axis: bool = False,
                   db: bool = False, units: str = "engineering"):
    """The spectra figure from spectrum.csv's columns and analysis.json (its typed
    gearcli.results.AnalysisDocument): on a
    frequency or (``order_axis``) pinion-order axis, log amplitudes or dB (``db``), amplitudes
    in the display ``units`` (gear speed in rpm or rad/s, DTE in µm or m)."""
    from gearcli.display_units import unit_and_factor

    m = analysis.metrics
    panels, lines = {}, {}
    for key, (title, col, unit) in SPECTRA.items():
        if col not in spectrum:
            continue
        shown, k = unit_and_factor(unit, units, fine=key == "dte")
        panels[key] = (title, shown, spectrum[col] * k)
        lines[key] = {label: dataclasses.replace(ln, amplitude=None if ln.amplitude is None
                                                 else ln.amplitude * k)
                      for label, ln in analysis.lines.get(key, {}).items()}
    return plot_spectra(spectrum["frequency_Hz"], panels, lines,
                              float(m.gear_mesh_frequency_Hz), harmonics,
                              float(m.output_rate_Hz),
                              order_Hz=float(m.pinion_shaft_Hz) if order_axis else None,
                              db=db)


def _modifications(data: ReportData, period: float):
    e, m = data.case.errors, data.case.modifications
    errors = _errors_panel(data, period) if any(
        x is not None for x in (e.runout.pinion, e.runout.gear, e.pitch_deviation.pinion,
                                e.pitch_deviation.gear)) else None
    relief = _relief_panel(data) if any(
        x is not None for x in (m.tip_relief.pinion, m.tip_relief.gear, m.root_relief.pinion,
                                m.root_relief.gear)) else None
    if errors is None and relief is None:
        raise ValueError("no errors and no relief in the case")
    return plots.plot_modifications(errors, relief)


def _errors_panel(data: ReportData, period: float) -> dict:
    errs, m = data.case.errors, data.metrics
    shaft = {"pinion": float(m.pinion_shaft_Hz or 0.0), "gear": float(m.gear_shaft_Hz or 0.0)}
    parts, rev_s, ecc = [], 0.0, 0.0
    for gear in ("pinion", "gear"):
        run_out = getattr(errs.runout, gear)
        pitch = getattr(errs.pitch_deviation, gear)
        if run_out is None and pitch is None:
            continue
        if shaft[gear] > 0:
            rev_s = max(rev_s, 1.0 / shaft[gear])
        if run_out is not None:
            ecc += run_out.eccentricity  # [mm]
            parts.append(f"{gear} runout e = {run_out.eccentricity * 1e3:.1f} µm")
        if pitch is not None:
            grade = pitch.iso1328_grade
            parts.append(f"{gear} pitch deviations"
                         + (f" (ISO 1328 grade {grade})" if grade else ""))
    t, d = data.run.columns["t_s"], data.run.columns["delta_mm"]
    w0, w1 = data.window_s
    span = 3.0 * rev_s if rev_s > 0 else w1 - w0
    sel = (t >= max(w0, w1 - span)) & (t <= w1)
    rate = float(data.metrics.output_rate_Hz if math.isfinite(data.metrics.output_rate_Hz)
                 else data.scalars.output_rate_Hz)
    t_mean, d_mean = plots.mesh_cycle_mean(t[sel], d[sel], rate * period)
    return {
        "t_s": t[sel], "dte_mm": d[sel], "cycle_t_s": t_mean, "cycle_mean_mm": d_mean,
        "reference_mm": ecc or None,
        "label": ", ".join(parts) + ": DTE over the last revolutions of the steady window",
    }


def _relief(spec) -> Relief | None:
    """The model's relief of a case's (gearcli.case.schema.Relief, internal units) or None."""
    if spec is None:
        return None
    return Relief(spec.amount, spec.length, spec.start_diameter, spec.shape)


def _relief_panel(data: ReportData) -> dict | None:
    geo = data.geometry
    if geo is None:
        return None
    mods_in = data.case.modifications
    tip, root = mods_in.tip_relief, mods_in.root_relief
    mods = Modifications(_relief(tip.pinion), _relief(tip.gear), _relief(root.pinion),
                         _relief(root.gear))
    x = np.linspace(-0.5, geo.g_alpha_mm + 0.5, 801)
    (g1, _), (g2, _) = modification_gaps(geo, mods, x)
    curves, parts = {}, []
    for gear, values in (("pinion", g1), ("gear", g2)):
        kinds = [k for k, src in (("tip", tip), ("root", root))
                 if getattr(src, gear) is not None]
        if kinds:
            curves[f"{gear} {' + '.join(kinds)} relief"] = values
        for kind, src in (("tip", tip), ("root", root)):
            r = getattr(src, gear)
            if r is not None:
                extent = (f"over {r.length:g} mm" if r.length is not None
                          else f"from d = {r.start_diameter:g} mm")
                parts.append(f"{gear} {kind} relief C = {r.amount * 1e3:g} µm "
                             f"{extent} ({r.shape})")
    points = {k: v - geo.A_mm for k, v in geo.line_of_action_points().items()
              if k in ("A", "B", "C", "D", "E")}
    mean = data.metrics.dte_mean_mm if math.isfinite(data.metrics.dte_mean_mm) else None
    return {"x_mm": x, "curves": curves, "points": points, "dte_mean_mm": mean,
            "label": "; ".join(parts)}
