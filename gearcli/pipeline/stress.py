"""`gearcli stress DIR`: contact and root stress histories from a results folder.

Reads the per-pair forces and roll positions that `gearcli simulate` wrote (timeseries.csv:
``force_slot{j}_N``, ``x_slot{j}_mm``, ``mesh_cycle``), finds each loaded pair's contact point
(:mod:`gearcli.model.contact_point`) and turns its force into

* the Hertz contact stress σ_H (both flanks of the pair share it) and
* the ISO 6336-3 Method B root stress σ_F of the pinion tooth and of the gear tooth
  (:mod:`gearcli.model.rating`),

per slot and per sample; maxima per tooth over the analysis window (the pair in slot j at mesh
cycle n has pinion tooth (n − j) mod z1 and gear tooth (n − j) mod z2); the static ISO 6336-2/-3
nominal values for the static load F_n = T/r_b2 (docs/theory.md §7.3), dynamic-to-static
ratios, and safety factors S_H = σ_Hlim/σ_H,max, S_F = σ_Flim Y_ST/σ_F,max when the case gives
the material limits.

Outputs (atomic): ``DIR/stress.csv`` (time histories) and ``DIR/stress.json``.
Stresses in N/mm² = MPa.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from gearcli.case.load import load_case_text
from gearcli.errors import CaseError, ResultsError
from gearcli.io.results import StoredRun, read_run, window_mask
from gearcli.model.contact_point import contact_points
from gearcli.model.geometry import PairGeometry
from gearcli.model.rating import (
    StaticRating,
    bending_face_width,
    effective_modulus,
    hertz_line_contact_stress,
    root_stress,
    static_rating,
)
from gearcli.pipeline.geometry import run_geometry
from gearcli.pipeline.validity import drift_phrase, window_state
from gearcli.results.metrics import json_number
from gearcli.results.stress import (
    GearPeaks,
    GearStress,
    Safety,
    StaticGear,
    StaticRatingDoc,
    StressDocument,
    StressPeak,
)

#: Stress correction factor of the standard reference test gear (ISO 6336-3:2019, σ_FE =
#: σ_Flim Y_ST; ISO 6336-5 gives σ_Flim for it).
Y_ST = 2.0
#: Fewer output samples than this per mesh cycle: the sampled peaks can miss the true ones.
SAMPLES_PER_MESH_FOR_PEAKS = 50
STRESS_FILES = ("stress.csv", "stress.json")


@dataclass(repr=False)
class StressResult:
    """Stress histories of one run (`gearcli stress`, :func:`gearcli.stress`); arrays
    (samples, slots) in MPa unless named otherwise; :attr:`pinion`, :attr:`gear` the peak
    dynamic stresses against the ISO 6336 static values and the safety factors."""

    run: StoredRun
    name: str
    geometry: PairGeometry
    static: StaticRating
    window_s: tuple[float, float]
    window_reason: str
    t_s: np.ndarray
    mesh_cycle: np.ndarray
    x_mm: np.ndarray  #: pinion roll position of each slot from A
    force_N: np.ndarray
    sigma_H: np.ndarray
    sigma_F_pinion: np.ndarray
    sigma_F_gear: np.ndarray
    clamped: np.ndarray  #: loaded samples at a sharp tip corner, evaluated at A/E
    limits: dict  #: {"pinion": (σ_Hlim, σ_Flim), "gear": (...)}, entries None when absent
    warnings: list[str] = field(default_factory=list)

    @property
    def slots(self) -> int:
        return self.force_N.shape[1]

    @property
    def in_window(self) -> np.ndarray:
        t0, t1 = self.window_s
        return window_mask(self.t_s, t0, t1)

    def document(self) -> dict:
        """stress.json as a dict."""
        return stress_document(self).to_dict()

    @property
    def pinion(self) -> GearStress:
        return GearStress.of(stress_document(self), "pinion")

    @property
    def gear(self) -> GearStress:
        return GearStress.of(stress_document(self), "gear")

    def __repr__(self) -> str:
        p = self.pinion

        def mpa(value):
            return "–" if value is None else f"{value:.4g} MPa"

        return (f"<Stress {self.name}: σ_H peak {mpa(p.sigma_H_peak_MPa)}, σ_F peak pinion "
                f"{mpa(p.sigma_F_peak_MPa)}>")


def _column_set(run: StoredRun) -> int:
    """Number of pair slots; ResultsError when the per-pair columns are missing."""
    names = run.columns
    slots = int(run.summary.slots or 0)
    need = ["mesh_cycle"] + [f"{p}{j}_{u}" for j in range(max(slots, 1))
                             for p, u in (("force_slot", "N"), ("x_slot", "mm"))]
    missing = [n for n in need if n not in names]
    if slots < 1 or missing:
        what = ", ".join(missing[:3]) + (" ..." if len(missing) > 3 else "") or "slots"
        raise ResultsError(
            f"{run.folder / 'timeseries.csv'}: no per-pair forces and contact positions "
            f"(missing {what}); expected a folder from a gearcli simulate that writes "
            "force_slot{j}_N, x_slot{j}_mm and mesh_cycle; rerun gearcli simulate"
        )
    return slots


def _window(run: StoredRun, given) -> tuple[tuple[float, float], str]:
    t = run.column("t_s")
    s = run.summary.scalars
    if given is None:  # a stored run has a window (io.results.check_summary)
        t0, t1 = s.window_s
        return (float(t0), float(t1)), s.window_reason
    t0, t1 = map(float, given)
    if not (t[0] - 1e-12 <= t0 < t1 <= t[-1] + 1e-9):
        raise ResultsError(f"--window {t0:g} {t1:g}: outside the run or empty; expected "
                           f"{t[0]:g} <= T0 < T1 <= {t[-1]:g} s")
    f_z = s.gear_mesh_frequency_Hz
    if f_z and (t1 - t0) * f_z < 1.0:  # a peak over part of a mesh cycle misses pair zones
        raise ResultsError(f"--window {t0:g} {t1:g}: {t1 - t0:g} s is shorter than one mesh "
                           f"cycle (1/f_z = {1.0 / f_z:.3g} s); expected a window of at least "
                           "one mesh cycle")
    return (t0, t1), "given (--window)"


def _materials(case):
    """((E1, E2), (ν1, ν2), limits) with each gear's own material overriding the case's."""
    mats = [case.material_of("pinion"), case.material_of("gear")]
    limits = {name: (m.contact_fatigue_limit, m.bending_fatigue_limit)
              for name, m in zip(("pinion", "gear"), mats, strict=True)}
    return (mats[0].youngs_modulus, mats[1].youngs_modulus), \
        (mats[0].poisson_ratio, mats[1].poisson_ratio), limits


def _require_limits(run: StoredRun, case, limits: dict) -> None:
    for gear, (h_lim, f_lim) in limits.items():
        own = getattr(case.gears, gear).material is not None
        base = f"gears.{gear}.material" if own else "material"
        for value, key, sym, example in (
                (h_lim, "contact_fatigue_limit", "sigma_Hlim", "1500 MPa"),
                (f_lim, "bending_fatigue_limit", "sigma_Flim", "430 MPa")):
            if value is None:
                raise CaseError(
                    f"missing; safety factors need the {gear}'s {sym} (e.g. {key}: {example}); "
                    "add it to the case and rerun gearcli simulate, or drop --safety",
                    file=str(run.manifest.get("case_file") or run.folder / "manifest.json"),
                    path=f"{base}.{key}",
                )


def compute_stress(folder: str | Path, window: tuple[float, float] | None = None,
                   require_limits: bool = False) -> StressResult:
    """Stress histories, maxima and ISO references of a results folder.

    Bad input raises ResultsError (folder, missing per-pair columns, window) or CaseError
    (material limits missing while ``require_limits``).
    """
    run = read_run(folder)
    slots = _column_set(run)
    win, reason = _window(run, window)
    if "resolved_case" not in run.manifest:
        raise ResultsError(f"{run.folder / 'manifest.json'}: no resolved_case; expected a "
                           "manifest written by gearcli simulate")
    loaded = load_case_text(json.dumps(run.manifest["resolved_case"]),
                            str(run.folder / "manifest.json"))
    case = loaded.case
    geo = run_geometry(loaded).geometry
    youngs, poisson, limits = _materials(case)
    if require_limits:
        _require_limits(run, case, limits)
    # a stored run has its static force (io.results.check_summary)
    static = static_rating(geo, float(run.summary.scalars.force_static_N), youngs, poisson)

    c = run.column
    force = np.column_stack([c(f"force_slot{j}_N") for j in range(slots)])
    x = np.column_stack([c(f"x_slot{j}_mm") for j in range(slots)])
    loaded_mask = force > 0.0
    cp = contact_points(geo, x)
    shape = x.shape
    e_star = effective_modulus(youngs[0], poisson[0], youngs[1], poisson[1])
    sigma_h = hertz_line_contact_stress(force.ravel(), static.contact_face_width_mm,
                                        cp.rho1_mm, cp.rho2_mm, e_star).reshape(shape)
    sigma_f = []
    for which, y_l, a_fen in (("pinion", cp.y_load1_mm, cp.alpha_fen1_rad),
                              ("gear", cp.y_load2_mm, cp.alpha_fen2_rad)):
        gear_static = getattr(static, which)
        sigma_f.append(root_stress(force.ravel(), bending_face_width(geo, which),
                                   getattr(geo, which), gear_static.section, y_l,
                                   a_fen).reshape(shape))
    res = StressResult(
        run, loaded.name, geo, static, win, reason, c("t_s"), c("mesh_cycle"), x, force,
        np.where(loaded_mask, sigma_h, 0.0), np.where(loaded_mask, sigma_f[0], 0.0),
        np.where(loaded_mask, sigma_f[1], 0.0), cp.clamped.reshape(shape) & loaded_mask, limits,
    )
    res.warnings = _warnings(res)
    return res


def _warnings(res: StressResult) -> list[str]:
    out = []
    sel = res.in_window
    clamped = res.clamped[sel]
    if clamped.any():
        f_max = float(res.force_N[sel][clamped].max())
        out.append(
            f"extended contact at a sharp tip corner in {int(clamped.sum())} loaded samples "
            f"(up to {f_max:.4g} N): evaluated at A/E, since Hertz is unbounded at a sharp "
            "corner; give gears.*.tip_rounding for the rounding's real stress"
        )
    if "force_coast_N" in res.run.columns:
        coast = float(res.run.column("force_coast_N")[sel].max(initial=0.0))
        if coast > 0.0:
            out.append(f"coast-flank contact (up to {coast:.4g} N) is not in the stress "
                       "histories (per-pair coast forces are not written); it reverses the "
                       "root stress")
    # the dynamic/static ratios compare with the static load of the ramps' end: a window
    # whose speed or load drifts does not carry it (docs/theory.md §10.2, operating state)
    unsteady = window_state(*(res.run.column(c)[sel] for c in (
        "t_s", "omega1_rad_s", "omega2_rad_s", "load_torque_Nmm")),
        (res.geometry.pinion.teeth, res.geometry.gear.teeth))[2]
    if unsteady:
        out.append(f"the window is not one steady operating point ({drift_phrase(unsteady)}): "
                   "its stresses are not those of the static load's operating point")
    s = res.run.summary.scalars
    rate, f_z = s.output_rate_Hz, s.gear_mesh_frequency_Hz
    if rate and f_z and rate / f_z < SAMPLES_PER_MESH_FOR_PEAKS:
        out.append(f"peaks come from the output samples: {rate / f_z:.1f} samples per mesh "
                   f"cycle (< {SAMPLES_PER_MESH_FOR_PEAKS}); raise run.output_rate for "
                   "sharper maxima")
    return out


def tooth_maxima(values: np.ndarray, mesh_cycle: np.ndarray, sel: np.ndarray,
                 loaded: np.ndarray, teeth: int) -> np.ndarray:
    """Maximum of ``values`` (samples, slots) per tooth over the selected, loaded samples.

    Slot j at mesh cycle n holds tooth (n − j) mod z. Teeth never loaded there: NaN.
    """
    n_s = values.shape[1]
    tooth = (mesh_cycle[:, None].astype(np.int64) - np.arange(n_s)[None, :]) % teeth
    keep = sel[:, None] & loaded
    out = np.full(teeth, np.nan)
    np.fmax.at(out, tooth[keep], values[keep])
    return out


def _zone(geo: PairGeometry, x: float) -> str:
    """Where on the path a roll position x (from A) lies [mm]."""
    b, d = geo.B_mm - geo.A_mm, geo.D_mm - geo.A_mm
    if x < 0.0:
        return "before A (gear tip on the pinion flank)"
    if x > geo.g_alpha_mm:
        return "after E (pinion tip on the gear flank)"
    return "A-B (two pairs)" if x < b else "B-D (single pair)" if x <= d else "D-E (two pairs)"


def _peak(res: StressResult, values: np.ndarray, sel: np.ndarray, teeth: int) -> StressPeak:
    masked = np.where(sel[:, None] & (res.force_N > 0.0), values, -np.inf)
    i, j = np.unravel_index(int(np.argmax(masked)), masked.shape)
    if not np.isfinite(masked[i, j]):
        return StressPeak(None)
    x = float(res.x_mm[i, j])
    return StressPeak(MPa=float(values[i, j]), t_s=float(res.t_s[i]), slot=int(j),
                      tooth=int((int(res.mesh_cycle[i]) - j) % teeth), x_from_A_mm=x,
                      force_N=float(res.force_N[i, j]), zone=_zone(res.geometry, x))


_num = json_number


def _ratio(num, den):
    """num/den as a JSON-safe float; None when either is missing or den is 0 (no load)."""
    return _num(num / den) if num is not None and den else None


def _static_doc(st: StaticRating) -> StaticRatingDoc:
    def gear(g, **at_point) -> StaticGear:
        return StaticGear(
            **at_point, sigma_H_iso_MPa=g.sigma_H_iso_MPa,
            face_width_bending_mm=g.face_width_mm, s_Fn_mm=g.section.s_Fn_mm,
            rho_F_mm=g.section.rho_F_mm, h_Fe_mm=g.h_Fe_mm,
            alpha_Fen_deg=math.degrees(g.alpha_Fen_rad), Y_F=g.Y_F, Y_S=g.Y_S,
            sigma_F0_MPa=g.sigma_F0_MPa, Y_Fa=g.Y_Fa, Y_Sa=g.Y_Sa,
            sigma_F0_tip_MPa=g.sigma_F0_tip_MPa)

    p, w = st.pinion, st.gear
    return StaticRatingDoc(
        force_normal_N=st.force_normal_N, force_tangential_N=st.force_tangential_N,
        ratio_u=st.ratio_u, E_star_MPa=st.e_star_MPa, Z_H=st.Z_H, Z_E_sqrt_MPa=st.Z_E,
        Z_eps=st.Z_eps, Y_eps=st.Y_eps, contact_face_width_mm=st.contact_face_width_mm,
        sigma_H0_MPa=st.sigma_H0_MPa, sigma_H0_with_Z_eps_MPa=st.sigma_H0_iso_MPa,
        pinion=gear(p, M1=p.M_single, Z_B=p.Z_single, sigma_H_at_B_MPa=p.sigma_H_single_MPa),
        gear=gear(w, M2=w.M_single, Z_D=w.Z_single, sigma_H_at_D_MPa=w.sigma_H_single_MPa),
        factors_taken_as_1="K_A K_v K_Halpha K_Hbeta K_Falpha K_Fbeta Z_beta Y_beta Y_B Y_DT")


def _safety(limits, peak_h, peak_f, iso_h, iso_f) -> Safety | None:
    h_lim, f_lim = limits
    if h_lim is None and f_lim is None:
        return None

    f_g = f_lim * Y_ST if f_lim is not None else None
    return Safety(
        sigma_Hlim_MPa=h_lim, sigma_Flim_MPa=f_lim, Y_ST=Y_ST,
        S_H=_ratio(h_lim, peak_h), S_F=_ratio(f_g, peak_f),
        S_H_static=_ratio(h_lim, iso_h), S_F_static=_ratio(f_g, iso_f),
        note="S_H = sigma_Hlim/sigma_H,max, S_F = sigma_Flim Y_ST/sigma_F,max against the "
             "peak dynamic stresses (life and influence factors Z_NT ... Y_X = 1)")


def stress_document(res: StressResult) -> StressDocument:
    """stress.json (its JSON: ``.to_dict()``): static ISO values, maxima per tooth, peaks,
    ratios, safety factors."""
    sel = res.in_window
    loaded = res.force_N > 0.0
    st = res.static
    from gearcli.io.manifest import RESULTS_SCHEMA_VERSION

    gears = {}
    for which, sig_f in (("pinion", res.sigma_F_pinion), ("gear", res.sigma_F_gear)):
        g = getattr(res.geometry, which)
        gs = getattr(st, which)
        iso_h = gs.sigma_H_iso_MPa  # Z_B (Z_D) Z_ε σ_H0 (ISO 6336-2 eq. 2-4)
        peak_h = _peak(res, res.sigma_H, sel, g.teeth)
        peak_f = _peak(res, sig_f, sel, g.teeth)
        h_max, f_max = peak_h.MPa, peak_f.MPa
        gears[which] = GearPeaks(
            teeth=g.teeth,
            sigma_H_max_per_tooth_MPa=tuple(_num(v) for v in tooth_maxima(
                res.sigma_H, res.mesh_cycle, sel, loaded, g.teeth)),
            sigma_F_max_per_tooth_MPa=tuple(_num(v) for v in tooth_maxima(
                sig_f, res.mesh_cycle, sel, loaded, g.teeth)),
            peak_sigma_H=peak_h, peak_sigma_F=peak_f,
            ratio_sigma_H_to_static=_ratio(h_max, iso_h),
            ratio_sigma_F_to_static=_ratio(f_max, gs.sigma_F0_MPa),
            safety=_safety(res.limits[which], h_max, f_max, iso_h, gs.sigma_F0_MPa))
    return StressDocument(
        schema_version=RESULTS_SCHEMA_VERSION, case=res.name, window_s=tuple(res.window_s),
        window_reason=res.window_reason,
        units={"stress": "MPa", "force": "N", "length": "mm"}, static=_static_doc(st),
        **gears,
        ratio_definition=("peak dynamic stress in the window / ISO static value of that gear: "
                          "sigma_H vs Z_B Z_eps sigma_H0 (pinion), Z_D Z_eps sigma_H0 (gear), "
                          "ISO 6336-2; sigma_F vs "
                          "sigma_F0 (Method B, outer point of single contact)"),
        run_max_MPa={"sigma_H": float(res.sigma_H.max(initial=0.0)),
                     "sigma_F_pinion": float(res.sigma_F_pinion.max(initial=0.0)),
                     "sigma_F_gear": float(res.sigma_F_gear.max(initial=0.0))},
        samples={"in_window": int(sel.sum()),
                 "loaded_at_sharp_corner": int(res.clamped[sel].sum())},
        warnings=tuple(res.warnings))


def stress_columns(res: StressResult) -> dict[str, np.ndarray]:
    """stress.csv columns: t_s, mesh_cycle, σ_H, σ_F pinion, σ_F gear per slot [MPa]."""
    cols = {"t_s": res.t_s, "mesh_cycle": res.mesh_cycle}
    for label, arr in (("sigma_H", res.sigma_H), ("sigma_F_pinion", res.sigma_F_pinion),
                       ("sigma_F_gear", res.sigma_F_gear)):
        for j in range(res.slots):
            cols[f"{label}_slot{j}_MPa"] = arr[:, j]
    return cols


def write_stress(res: StressResult, doc: dict | None = None) -> dict:
    """Write stress.csv and stress.json (``doc``, the caller's :func:`stress_document` when it
    has it) into the results folder atomically; return the doc."""
    from gearcli.io.files import write_atomic
    from gearcli.io.tables import columns_to_csv

    doc = doc or stress_document(res).to_dict()
    folder = res.run.folder
    write_atomic(folder / "stress.csv", columns_to_csv(stress_columns(res)))
    write_atomic(folder / "stress.json", json.dumps(doc, indent=2) + "\n")
    return doc


def _peaks_of(res: StressResult) -> dict:
    """stress.json's per-gear peaks (their positions are marked on the figure)."""
    doc = stress_document(res)
    return {"pinion": doc.pinion, "gear": doc.gear}


def save_stress_plot(res: StressResult, path: str | Path, cycles: float = 3.0) -> None:
    """σ_H and σ_F through the last ``cycles`` mesh cycles of the window and along the path."""
    from gearcli.io.files import save_figure
    from gearcli.plotting.stress import plot_stress_of_run

    geo = res.geometry
    f_z = res.run.summary.scalars.gear_mesh_frequency_Hz or 0.0
    fig = plot_stress_of_run(
        res.t_s, res.x_mm, res.force_N, res.sigma_H, res.sigma_F_pinion, res.sigma_F_gear,
        geometry=geo, static=_static_doc(res.static), window_s=res.window_s,
        f_z_Hz=f_z, cycles=cycles, peaks=_peaks_of(res),
        title=f"{res.name}: tooth stresses (z1 = {geo.pinion.teeth}, z2 = {geo.gear.teeth})")
    save_figure(fig, path, 130)
