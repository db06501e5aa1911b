"""`gearcli analyze DIR`: steady-state metrics, spectra, mesh lines and checks of a finished run.

Physics references: docs/theory.md §6 (mesh mode), §7 (static force, dynamic factor, spectra,
aliasing). Deterministic: the same folder gives the same analysis.json byte for byte.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

import numpy as np

from gearcli.case.load import load_case_text
from gearcli.case.schema import Case
from gearcli.errors import ResultsError
from gearcli.io.results import StoredRun, read_run, window_mask
from gearcli.model.modal import has_resonant_peak
from gearcli.pipeline.geometry import run_geometry
from gearcli.pipeline.spectrum import (
    SIGNALS,
    Line,
    alias_frequency,
    amplitude_spectrum,
    measure_line,
    mesh_lines,
)
from gearcli.pipeline.validity import drift_phrase, window_state
from gearcli.pipeline.window import MIN_MESH_CYCLES, Window
from gearcli.results import AnalysisMetrics, Check, ResonanceMargin, StoredMode, Summary

#: A line counts as present when it stands this far above the spectrum's median floor.
LINE_PROMINENCE = 10.0


@dataclass
class Analysis:
    run: StoredRun
    window: Window
    metrics: AnalysisMetrics
    amplitude_spectra: dict[str, tuple[np.ndarray, np.ndarray]]  #: name -> (f [Hz], amplitude)
    lines: dict[str, list[tuple[str, Line]]]
    checks: list[Check] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    #: The run's resolved case (the manifest's, typed: gearcli.case.schema.Case)
    case: Case | None = None

    @property
    def passed(self) -> bool:
        return not any(c.failed for c in self.checks)

    @property
    def spectra(self):
        """One-sided amplitude spectra as a pandas DataFrame indexed by frequency [Hz]
        (spectrum.csv's columns)."""
        from gearcli.io.tables import columns_to_frame
        from gearcli.pipeline.analysis_io import spectrum_columns

        return columns_to_frame(spectrum_columns(self), "frequency_Hz")

    def document(self) -> dict:
        """analysis.json as a dict (what `gearcli analyze` writes)."""
        from gearcli.pipeline.analysis_io import analysis_document

        return analysis_document(self)

    def __repr__(self) -> str:
        failed = [c.label for c in self.checks if c.failed]
        return (f"<Analysis {self.run.summary.case or self.run.folder.name}: "
                f"{'passed' if self.passed else 'failed: ' + '; '.join(failed)}>")


def analyze(folder: str | Path, window: tuple[float, float] | None = None,
            strict: bool = False, remedies: bool = False) -> Analysis:
    """Analyse a results folder; bad input raises ResultsError (exit 1). ``remedies``: a
    failed check gets its remedy (gearcli/pipeline/remedy.py; a relief search and one short
    run for a failed dynamic factor or contact loss)."""
    run = read_run(folder)
    loaded = load_case_text(json.dumps(run.manifest["resolved_case"]),
                            str(Path(folder) / "manifest.json"))
    case = loaded.case
    geo = run_geometry(loaded).geometry
    s = run.summary.scalars
    t = run.column("t_s")
    rate = s.output_rate_Hz
    f_z = s.gear_mesh_frequency_Hz
    win = _window(t, s, window, f_z, geo)
    sel = window_mask(t, win.t0_s, win.t1_s)
    metrics = _metrics(run, sel, win, geo, s)
    n1 = metrics.pinion_speed_mean_deg_s / 360.0
    n2 = metrics.gear_speed_mean_deg_s / 360.0
    f_z_measured = geo.pinion.teeth * n1
    if not f_z_measured * (win.t1_s - win.t0_s) >= 1.0:  # also 0 and NaN
        raise ResultsError(
            f"the pinion turns less than one tooth pitch in the analysis window {win.t0_s:g} "
            f"... {win.t1_s:g} s (mean speed {metrics.pinion_speed_mean_deg_s:.3g} deg/s): "
            "there is no mesh frequency to analyse (a run at rest, such as a ring-down, is "
            "read from its time series and summary.json; use gearcli simulate for it)")
    spectra = {name: amplitude_spectrum(run.column(col)[sel], rate) for name, col, _ in SIGNALS}
    expected = mesh_lines(f_z_measured, {"n1": n1, "n2": n2}, case.checks.harmonics)
    lines = {name: [(label, measure_line(f, a, fe)) for label, fe in expected]
             for name, (f, a) in spectra.items()}
    metrics = dataclasses.replace(metrics, gear_mesh_frequency_Hz=f_z_measured,
                                  pinion_shaft_Hz=n1, gear_shaft_Hz=n2, output_rate_Hz=rate,
                                  frequency_resolution_Hz=float(spectra["force"][0][1]))
    n1_window = np.abs(run.column("omega1_rad_s")[sel]) / (2.0 * np.pi)  # [rev/s]
    band = (geo.pinion.teeth * float(n1_window.min()), geo.pinion.teeth * float(n1_window.max()))
    resonance = resonance_check(s.modes, (metrics.mesh_natural_frequency_Hz,
                                          metrics.mesh_damping_ratio),
                                metrics.gear_mesh_frequency_Hz, case.checks, band)
    metrics = dataclasses.replace(metrics, resonance_margins_percent=resonance.margins_percent,
                                  resonance_margins=resonance.margins)
    result = Analysis(run, win, metrics, spectra, lines, case=case)
    # the operating state of this window (a --window may differ from simulate's)
    unsteady = window_state(*(run.column(c)[sel] for c in (
        "t_s", "omega1_rad_s", "omega2_rad_s", "load_torque_Nmm")),
        (geo.pinion.teeth, geo.gear.teeth))[2]
    result.checks = _checks(result, case, s, resonance.check, unsteady)
    if remedies:
        from gearcli.pipeline.remedy import add_remedies

        add_remedies(result.checks, loaded, metrics)
    result.warnings = list(run.summary.warnings)
    if strict:
        result.checks.append(Check("no_warnings", len(result.warnings), "0 (--strict)",
                                   not result.warnings, "; ".join(result.warnings)))
    return result


def _window(t, s: Summary, given, f_z, geo) -> Window:
    t_end = float(t[-1])
    if given is None:
        t0, t1 = map(float, s.window_s)  # two numbers, T0 < T1 (io.results.check_summary)
        if not (t[0] - 1e-9 <= t0 and t1 <= t_end + 1e-9):
            raise ResultsError(f"summary.json: window_s = {list(s.window_s)!r} is not a "
                               f"window of the run ({t[0]:g} ... {t_end:g} s; edited?); "
                               "expected T0 < T1 inside the run, or give --window T0 T1")
        return Window(t0, t1, s.window_reason)
    t0, t1 = map(float, given)
    if not (t[0] <= t0 < t1 <= t_end + 1e-9):
        raise ResultsError(f"--window {t0:g} {t1:g}: outside the run or empty; expected "
                           f"{t[0]:g} <= T0 < T1 <= {t_end:g} s")
    # the sidebands k f_z +- n2 must fall in separate bins: resolution <= n2 / 2
    n2 = f_z / geo.ratio / geo.pinion.teeth if f_z else None
    need = max(2.0 / n2 if n2 else 0.0, MIN_MESH_CYCLES / f_z if f_z else 0.0)
    if t1 - t0 < need:
        raise ResultsError(f"--window {t0:g} {t1:g}: {t1 - t0:g} s is too short; the "
                           f"spectra need >= {need:.3g} s (bins <= half the gear shaft "
                           f"frequency, >= {MIN_MESH_CYCLES} mesh cycles)")
    return Window(t0, t1, "given (--window)")


def _true_extremum(stored: float, t_at: float, win: Window, sampled: float, larger: bool):
    """The solver's true extremum when it lies in the window, else the sampled one."""
    if stored is not None and win.t0_s <= t_at <= win.t1_s:
        return (max if larger else min)(stored, sampled), "solver steps"
    return sampled, "samples"


def _metrics(run: StoredRun, sel, win: Window, geo, s: Summary) -> AnalysisMetrics:
    c = run.column
    force = c("force_total_N")[sel]
    delta = c("delta_mm")[sel]
    w1, w2 = c("omega1_rad_s")[sel], c("omega2_rad_s")[sel]
    fmax, fmax_src = _true_extremum(s.force_max_N, s.force_max_t_s, win, force.max(), True)
    fmin = float(force.min())
    static = s.force_static_N
    ratio = float(w1.mean() / w2.mean())
    coast = c("force_coast_N")[sel] > 0.0
    # mean powers over the window from the solver's energy integrals (exact, unlike sample
    # means of the spiky instantaneous powers): mJ/s = mW
    t_w = c("t_s")[sel]
    span_s = float(t_w[-1] - t_w[0])

    def mean_power_W(column: str) -> float:
        e = c(column)[sel]
        return float(e[-1] - e[0]) / span_s * 1e-3 if span_s > 0 else math.nan

    p_fric_W = mean_power_W("loss_friction_mJ")
    p_damp_W = mean_power_W("loss_damping_mJ")
    p_in_W = mean_power_W("work_in_mJ")
    torque = c("drive_torque_Nmm")[sel]
    return AnalysisMetrics(
        window_s=(win.t0_s, win.t1_s),
        window_reason=win.reason,
        samples=int(sel.sum()),
        pinion_speed_mean_deg_s=math.degrees(float(w1.mean())),
        gear_speed_mean_deg_s=math.degrees(float(w2.mean())),
        speed_ratio=ratio,
        speed_ratio_theory=geo.ratio,
        speed_ratio_error_percent=100.0 * (ratio - geo.ratio) / geo.ratio,
        gear_speed_fluctuation_percent=100.0 * float(np.ptp(w2) / w2.mean()),
        force_mean_N=float(force.mean()),
        force_rms_N=float(np.sqrt(np.mean(force**2))),
        force_max_N=float(fmax),
        force_max_t_s=float(s.force_max_t_s) if fmax_src == "solver steps"
        else float(c("t_s")[sel][int(np.argmax(force))]),
        force_max_source=fmax_src,
        force_min_N=fmin,
        force_static_N=static,
        dynamic_factor=float(fmax / static) if static > 0 else None,
        dte_mean_mm=float(delta.mean()),
        dte_peak_to_peak_mm=float(np.ptp(delta)),
        dte_rms_mm=float(np.std(delta)),
        contact_loss_fraction=float(np.mean(force <= 0.0)),
        coast_impacts=int(np.count_nonzero(coast[1:] & ~coast[:-1]) + int(coast[0])),
        friction_loss_W=p_fric_W,
        damping_loss_W=p_damp_W,
        input_power_W=p_in_W,
        # the mesh's dissipation (friction and contact/mesh damping) against the input; without
        # a load there is no useful output to rate (docs/theory.md §7)
        mesh_efficiency=1.0 - (p_fric_W + p_damp_W) / p_in_W
        if p_in_W > 0 and mean_power_W("work_load_mJ") > 0 else None,
        drive_torque_mean_Nmm=float(torque.mean()),
        drive_torque_ripple_Nmm=float(np.ptp(torque)),
        mesh_natural_frequency_Hz=s.mesh_natural_frequency_Hz,
        mesh_damping_ratio=s.mesh_damping_ratio,
    )


#: Above this spread of the mesh frequency over the window, (max - min)/mean, the window is not
#: steady (a run-up): the resonance margins are taken over the swept band, not at the mean.
SWEPT_BAND = 0.05


class Resonance(NamedTuple):
    """The resonance-margin check with the margins it sets in the metrics."""

    check: Check
    margins_percent: tuple[float, ...]  #: per harmonic k = 1..N, to the nearest mode [%]
    margins: tuple[ResonanceMargin, ...] | None  #: every harmonic against every mode; None
    #: without a stored modal result


def resonance_check(modes: tuple[StoredMode, ...], mesh_mode: tuple[float, float], f_z: float,
                    ck, f_z_band: tuple[float, float] | None = None) -> Resonance:
    """Margin of the GMF harmonics k f_z (k = 1..N) to the modes (docs/theory.md §7).

    ``f_z_band`` = (lowest, highest) mesh frequency in the window [Hz]: when it spreads by more
    than :data:`SWEPT_BAND` of ``f_z`` (a run-up or run-down), each harmonic sweeps the band
    k f_lo .. k f_hi and its margin to a mode is 0 where the band contains the mode, else the
    distance of the nearer band end (a resonance crossed in the window fails the check).

    ``modes``: summary.json's modes (gearcli.pipeline.modal.modes_summary: every mode of the
    linearised model, the same as `gearcli modal`) when the run has them, else ``mesh_mode``
    = (f_n [Hz], ζ) of older results folders. Modes without a resonant peak (ζ >= 1/√2,
    gearcli.model.modal) are not checked. Returns the check, the margin of each harmonic to
    the nearest mode and, with modes, every harmonic against every mode, nearest first.
    """
    stored = bool(modes)  # an empty list (no modal result stored) counts as absent
    if stored:
        modes = [(md.mode, md.natural_frequency_Hz, md.damping_ratio)
                 for md in modes if not md.rigid_body and md.natural_frequency_Hz]
    else:
        modes = [(None, *mesh_mode)]
    limit = f">= {ck.resonance_margin_percent:g} %"
    if not modes:
        return Resonance(Check("resonance_margin_percent", None, limit, True, "no elastic mode"),
                         (), None)
    lo, hi = f_z_band if f_z_band is not None else (f_z, f_z)
    swept = f_z > 0.0 and (hi - lo) / f_z > SWEPT_BAND

    def margin(k: int, f_n: float) -> float:
        if not swept:
            return abs(k * f_z - f_n) / f_n * 100.0
        if k * lo <= f_n <= k * hi:
            return 0.0
        return min(abs(k * lo - f_n), abs(k * hi - f_n)) / f_n * 100.0

    rows = tuple(sorted((ResonanceMargin(k, num, k * f_z, f_n, margin(k, f_n),
                                         has_resonant_peak(zeta))
                         for num, f_n, zeta in modes for k in range(1, ck.harmonics + 1)),
                        key=lambda r: r.margin_percent))
    per_harmonic = tuple(min(r.margin_percent for r in rows if r.harmonic == k)
                         for k in range(1, ck.harmonics + 1))
    near = rows[0]
    name = "mesh mode" if near.mode is None else f"mode {near.mode}"
    note = (f"nearest: {near.harmonic} x f_z = {near.excitation_Hz:.1f} Hz vs {name} "
            f"{near.mode_Hz:.1f} Hz")
    if swept:
        note = (f"the window is not steady: f_z sweeps {lo:.1f}-{hi:.1f} Hz, so each k x f_z "
                f"sweeps a band and a mode inside it is crossed (margin 0); " + note)
    # A mode with zeta >= 1/sqrt(2) has no resonant peak (one rule: gearcli.model.modal).
    no_peak = [(num, zeta) for num, _, zeta in modes if not has_resonant_peak(zeta)]
    peaked = [r for r in rows if r.resonant_peak]
    if no_peak and near.mode is None:
        note += f"; the mode has no resonant peak (damping ratio {no_peak[0][1]:.2f} >= 0.707)"
    elif no_peak and peaked:  # without any, the "not checked" note below says it: once
        note += (f"; mode(s) {', '.join(str(n) for n, _ in no_peak)} have no resonant peak "
                 "(damping ratio >= 0.707) and are not checked")
    margins = rows if stored else None
    if not peaked:
        return Resonance(Check("resonance_margin_percent", None, limit, True,
                               "not checked: no mode has a resonant peak (every damping ratio "
                               ">= 0.707: overdamped); " + note, checked=False),
                         per_harmonic, margins)
    ok = peaked[0].margin_percent >= ck.resonance_margin_percent
    if not ok and near.mode is not None:
        p = peaked[0]
        note += (f"; violated by {p.harmonic} x f_z vs mode {p.mode} "
                 f"({p.margin_percent:.1f} %)")
    return Resonance(Check("resonance_margin_percent", peaked[0].margin_percent, limit, ok,
                           note), per_harmonic, margins)


def _checks(res: Analysis, case, s: Summary, resonance: Check, unsteady: str = ""
            ) -> list[Check]:
    """The checks of docs/theory.md §7.8; ``unsteady``: the reason the window is not one
    steady operating point (pipeline/validity.operating_state), empty when it is."""
    m, ck = res.metrics, case.checks
    f_z, rate = m.gear_mesh_frequency_Hz, m.output_rate_Hz
    out = [
        Check("solver_status", "ok", "ok", True),
        Check("speed_ratio_error_percent", m.speed_ratio_error_percent,
              f"|e| <= {ck.speed_ratio_error_percent:g} %",
              abs(m.speed_ratio_error_percent) <= ck.speed_ratio_error_percent),
    ]
    top = ck.harmonics * f_z
    ok = top < rate / 2.0
    note = "" if ok else (f"sampling at {rate:g} Hz: the {f_z:.2f} Hz mesh line folds to "
                          f"{alias_frequency(f_z, rate):.2f} Hz" if f_z >= rate / 2.0 else
                          f"sampling at {rate:g} Hz resolves only {int(rate / 2 // f_z)} of "
                          f"{ck.harmonics} harmonics")
    if ok:
        above = int(rate / 2 // f_z) + 1
        note = (f"the {ck.harmonics} analysed harmonics are below fs/2; harmonics from "
                f"{above} x f_z up fold into the spectra if the signals carry them (their alias "
                "positions are marked in the spectra figure)")
    out.append(Check("no_aliasing", top, f"{ck.harmonics} x f_z < fs/2 = {rate / 2:g} Hz", ok,
                     note))
    gmf = dict(res.lines["gear_speed"])["1fz"]
    freq, amp = res.amplitude_spectra["gear_speed"]
    floor = float(np.median(amp[1:])) if amp.size > 1 else 0.0
    present = gmf.resolvable and gmf.amplitude > LINE_PROMINENCE * floor  # resolvable: +-1 bin
    out.append(Check("gmf_line_present", gmf.measured_Hz if gmf.resolvable else None,
                     f"line at f_z = {f_z:.3f} Hz +- 1 bin, > {LINE_PROMINENCE:g} x floor",
                     bool(present), "" if gmf.resolvable else "f_z is above the Nyquist frequency"
                     if f_z >= rate / 2.0 else "no peak within 1 bin of f_z"))
    out.append(resonance)
    if m.dynamic_factor is not None and unsteady:
        # F_max/F_static of a window whose speed or load drifts (a run ending inside its
        # ramps, a run-up) is no operating point's dynamic factor (docs/theory.md §10.2)
        out.append(Check("dynamic_factor", None, f"<= {ck.dynamic_factor_max:g}", True,
                         "not checked: the window is not one steady operating point ("
                         f"{drift_phrase(unsteady)})",
                         checked=False))
    elif m.dynamic_factor is not None:
        out.append(Check("dynamic_factor", m.dynamic_factor, f"<= {ck.dynamic_factor_max:g}",
                         m.dynamic_factor <= ck.dynamic_factor_max,
                         "max normal force / static force over the window"))
    else:
        out.append(Check("dynamic_factor", None, f"<= {ck.dynamic_factor_max:g}", True,
                         "not checked: no load (static force 0)", checked=False))
    loss = m.contact_loss_fraction
    out.append(Check("contact_loss_fraction", loss,
                     f"<= {ck.contact_loss_fraction_max:g} "
                     f"({100.0 * ck.contact_loss_fraction_max:g} %)",
                     loss <= ck.contact_loss_fraction_max,
                     "share of the window without drive-flank contact (tooth separation); "
                     "analysis.json holds value and limit as fractions"))
    if ck.dte_peak_to_peak_max is not None:
        out.append(Check("dte_peak_to_peak_mm", m.dte_peak_to_peak_mm,
                         f"<= {ck.dte_peak_to_peak_max:g} mm",
                         m.dte_peak_to_peak_mm <= ck.dte_peak_to_peak_max))
    eb = s.energy_relative_residual
    out.append(Check("energy_balance", eb, f"<= {ck.energy_balance_tolerance:g}",
                     eb <= ck.energy_balance_tolerance))
    return out
