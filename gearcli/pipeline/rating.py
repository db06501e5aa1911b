"""`gearcli rate`: the ISO 6336 Method B rating of a case's pair (docs/theory.md, "ISO 6336
rating"), and the inspection dimensions of its gears.

typed case (+ its checked geometry, pipeline.geometry) → :class:`RatingInput` →
:func:`gearcli.model.iso6336.rate.rate` (the ISO column) and, with a ``rating.duty_cycle``,
:func:`gearcli.model.iso6336.spectrum.duty_cycle_damage` (ISO 6336-6).

The load is the case's: the load torque at the end of its ramps on the body ``load.applied_to``
(per mesh path: a planet's share) and the pinion speed of the drive (``drive.speed`` final
value or ``drive.reference_speed``), relative to the carrier where there is one. Their pinion
torque is T1 = F_n r_b1 with F_n = T_load / r_b(loaded body) (the normal force of the
quasi-static mesh, docs/theory.md §7.3), so F_t = 2000 T1/d1 = F_n cos α.

K_v: ``rating.dynamic_factor`` a number as given; ``iso`` ISO 6336-1 Method B as `gearcli
mesh` computes it (pipeline.mesh_input.iso_dynamic, gearcli/model/iso_kv.py) with the line load
F_t K_A/b; ``simulated`` needs a run's dynamic factor (:class:`SimulatedLoad`, passed by the
caller that has a run): without one it is an error, the ISO column then takes Method B.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

from gearcli.case.inspection import PairInspection, pair_inspection
from gearcli.case.load import LoadedCase, load_case, load_case_text
from gearcli.case.schema import Case
from gearcli.errors import CaseError
from gearcli.model.iso6336.common import Edition
from gearcli.model.iso6336.document import RatingResult
from gearcli.model.iso6336.editions import EditionRow, edition_rows
from gearcli.model.iso6336.inputs import GearInput, RatingInput
from gearcli.model.iso6336.material import MaterialKind, Quality
from gearcli.model.iso6336.rate import rate
from gearcli.model.iso6336.spectrum import DutyCycleDamage, LoadBin, duty_cycle_damage
from gearcli.pipeline.capabilities import not_included
from gearcli.pipeline.geometry import GeometryResult, run_geometry
from gearcli.pipeline.mesh_input import load_torque_Nmm
from gearcli.results.models import IsoResonance
from gearcli.results.rating_document import IsoDynamic, PeakSafety, RatingDocument

__all__ = ["SimulatedLoad", "CaseRating", "PairInspection", "rating_input", "rate_case",
           "case_inspection", "simulated_load", "simulated_load_of", "RPM_PER_RAD_S"]

RPM_PER_RAD_S = 30.0 / math.pi
_ROLES = ("pinion", "gear")


@dataclass(frozen=True)
class SimulatedLoad:
    """What a simulation run gives the rating (passed by the caller that has the run).

    ``dynamic_factor`` the run's max F / F_static [-] replaces K_v; ``load_sharing_factor``,
    when given, K_γ; ``sigma_H_peak_MPa``, ``sigma_F_peak_MPa`` (pinion, gear) the peak dynamic
    contact and root stresses of `gearcli stress` [N/mm²], each rated against the ISO strength
    σ_HG, σ_FG at the required life (S = σ_G/σ_peak)."""

    dynamic_factor: float
    load_sharing_factor: float | None = None
    sigma_H_peak_MPa: tuple[float, float] | None = None
    sigma_F_peak_MPa: tuple[float, float] | None = None

    def __post_init__(self):
        if not self.dynamic_factor > 0.0:
            raise ValueError(f"dynamic_factor must be > 0, got {self.dynamic_factor!r}")


@dataclass(frozen=True)
class CaseRating:
    """The rating of a case: the ISO column, the duty cycle's damage, the simulated column."""

    source: LoadedCase  #: the case rated
    rating_input: RatingInput  #: what was rated (engineering units)
    iso: RatingResult  #: K_v: a number or ISO 6336-1 Method B
    dynamic_factor_source: str  #: "given", "ISO 6336-1 Method B (...)"
    iso_dynamic: IsoDynamic | None  #: Method B data when K_v is 'iso' (resonance ratio, range)
    duty_cycle: DutyCycleDamage | None
    simulated: RatingResult | None  #: K_v (and K_γ) of the run
    simulated_peaks: dict[str, PeakSafety] | None  #: per gear name: the peak stresses' safeties
    notes: tuple[str, ...]
    #: the edition-dependent factors of the ISO column under ISO 6336:2006 and :2019
    editions: tuple[EditionRow, ...] = ()

    @property
    def name(self) -> str:
        return self.source.name

    @property
    def ok(self) -> bool:
        """Every safety at or above its minimum (both columns), every damage ≤ 1."""
        ok = self.iso.ok and (self.simulated is None or self.simulated.ok)
        if self.duty_cycle is not None:
            d = self.duty_cycle
            ok = ok and all(x <= 1.0 for g in (d.pinion, d.gear) for x in (g.pitting, g.bending))
        return ok

    def __repr__(self) -> str:  # labelled; safeties and K_v are dimensionless
        def column(r: RatingResult) -> str:
            return (f"S_H {r.pinion.S_H:.4g}/{r.gear.S_H:.4g} (min {r.pinion.S_H_min:g}), "
                    f"S_F {r.pinion.S_F:.4g}/{r.gear.S_F:.4g} (min {r.pinion.S_F_min:g})")

        sim = f"; simulated K_v: {column(self.simulated)}" if self.simulated else ""
        return (f"<CaseRating {self.name}, ISO 6336:{self.iso.edition} (pinion/gear): "
                f"{'pass' if self.ok else 'fail'}; {column(self.iso)} with K_v "
                f"{self.rating_input.dynamic_factor:.4g} ({self.dynamic_factor_source}){sim}>")

    def document(self) -> RatingDocument:
        """rating.json, typed (gearcli/results/rating_document.py)."""
        from gearcli.pipeline.rating_document import rating_document

        return rating_document(self)

    def to_dict(self) -> dict:
        """rating.json (what `gearcli rate --json` prints)."""
        return self.document().to_dict()


def _pinion_torque_Nm(case: Case, geo: GeometryResult, load_torque_Nmm: float) -> float:
    """T1 [N·m] of a load torque [N·mm] on the body load.applied_to (module notes)."""
    g = geo.geometry
    r_loaded = g.gear.r_b_mm if case.load.applied_to == "gear" else g.pinion.r_b_mm
    return load_torque_Nmm / r_loaded * g.pinion.r_b_mm / 1000.0


def _fatigue_limits(loaded: LoadedCase) -> list[tuple[float | None, float | None]]:
    """(σ_Hlim, σ_Flim) given per gear (its material, else the case's); a CaseError naming
    what is missing when neither they nor an ISO 6336-5 hardness are given."""
    case = loaded.case
    out, missing = [], []
    for role in _ROLES:
        mat = case.material_of(role)
        hard = getattr(case.rating, role).material.hardness
        limits = (mat.contact_fatigue_limit, mat.bending_fatigue_limit)
        for key, value in zip(("contact_fatigue_limit", "bending_fatigue_limit"), limits,
                              strict=True):
            if value is None and hard is None:
                missing.append(f"{role} {key}")
        out.append(limits)
    if missing:
        raise CaseError(f"the ISO 6336 rating needs each gear's fatigue limits, and these "
                        f"are missing: {', '.join(missing)}; expected "
                        "material.contact_fatigue_limit and material.bending_fatigue_limit "
                        "(shared, or per gear under gears.<gear>.material), or "
                        "rating.<gear>.material.kind/quality/hardness (ISO 6336-5)",
                        file=str(loaded.source.file), path="material")
    return out


def _check_proof_stress(loaded: LoadedCase) -> None:
    """St, V, GGG, GTS need σ_0.2 for the notch sensitivity (ISO 6336-3 Y_δrelT)."""
    from gearcli.model.iso6336.material import THROUGH_HARDENED

    for role in _ROLES:
        m = getattr(loaded.case.rating, role).material
        if MaterialKind(m.kind) in THROUGH_HARDENED and m.proof_stress is None:
            raise loaded.error(("rating", role, "material", "proof_stress"), f"missing: the "
                               f"notch sensitivity of {m.kind} needs it (ISO 6336-3 Y_δrelT); "
                               "expected the 0.2 % proof stress σ_0.2, e.g. 850 MPa")


def _gear_input(case: Case, geo: GeometryResult, role: str, limits, f_pb_um: float) -> GearInput:
    spec, rg = getattr(case.gears, role), getattr(case.rating, role)
    gg = getattr(geo.geometry, role)
    mat = case.material_of(role)
    allow = rg.thickness_allowances or (-spec.thickness_allowance, -spec.thickness_allowance)
    own_fpb = rg.base_pitch_deviation
    return GearInput(
        teeth=spec.teeth, face_width_mm=gg.face_width_mm, profile_shift=spec.profile_shift,
        tip_diameter_mm=gg.d_a_mm, material=MaterialKind(rg.material.kind),
        quality=Quality(rg.material.quality), surface_hardness=rg.material.hardness,
        sigma_h_lim_MPa=limits[0], sigma_f_lim_MPa=limits[1], youngs_MPa=mat.youngs_modulus,
        poisson=mat.poisson_ratio, proof_stress_MPa=rg.material.proof_stress,
        flank_roughness_rz_um=1e3 * rg.roughness.flank,
        root_roughness_rz_um=1e3 * rg.roughness.root,
        base_pitch_deviation_um=f_pb_um if own_fpb is None else 1e3 * own_fpb,
        accuracy_grade=rg.accuracy_grade, rim_thickness_mm=rg.rim_thickness, idler=rg.idler,
        contacts_per_revolution=rg.contacts_per_revolution,
        thickness_allowances_mm=(float(allow[0]), float(allow[1])),
        ball_diameter_mm=rg.ball_diameter)


def _check_inspection(loaded: LoadedCase, geo: GeometryResult, gears: list[GearInput]) -> None:
    """Refuse, at the key that sets it, a thickness allowance that leaves no tooth or a ball
    that cannot touch the flanks (model.iso6336.inspection.inspection_input_error): the
    inspection dimensions of the rating could not be computed."""
    from gearcli.model.iso6336.inspection import inspection_input_error

    g = geo.geometry
    for role, gear in zip(_ROLES, gears, strict=True):
        found = inspection_input_error(gear.teeth, gear.profile_shift, g.module_mm,
                                       g.pressure_angle_rad, gear.tip_diameter_mm,
                                       gear.thickness_allowances_mm, gear.ball_diameter_mm)
        if found is None:
            continue
        key, reason = found
        if key == "thickness_allowances" and getattr(loaded.case.rating, role).\
                thickness_allowances is None:  # the gear's own allowance (gears.<role>)
            raise loaded.error_at(("gears", role, "thickness_allowance"), reason)
        raise loaded.error_at(("rating", role, key), reason)


def _iso_kv(iso: IsoResonance, speed_rpm: float, k_a: float) -> tuple[float, IsoDynamic]:
    """K_v by ISO 6336-1 Method B at the pinion speed with the line load F_t K_A/b."""
    from gearcli.model.iso_kv import dynamic_factor
    from gearcli.pipeline.mesh_input import kv_arguments

    line_load_N_mm = iso.line_load_N_mm * k_a
    ratio = speed_rpm / iso.resonance_speed_rpm
    kv = dynamic_factor(ratio, **{**kv_arguments(iso), "line_load_N_mm": line_load_N_mm})
    info = IsoDynamic(resonance_speed_rpm=iso.resonance_speed_rpm, resonance_ratio=ratio,
                      speed_range=str(kv.range_name), line_load_N_mm=line_load_N_mm,
                      c_prime_N_mm_um=iso.c_prime_N_mm_um, f_pb_eff_um=iso.f_pb_eff_um,
                      tip_relief_um=iso.tip_relief_um, k_v=float(kv.k_v))
    return float(kv.k_v), info


def rating_input(loaded: LoadedCase, geo: GeometryResult | None = None
                 ) -> tuple[RatingInput, str, IsoDynamic | None]:
    """(the RatingInput of the case, the source of its K_v, the Method B data or None)."""
    from gearcli.pipeline.mesh_input import iso_dynamic

    case, r = loaded.case, loaded.case.rating
    geo = geo or run_geometry(loaded)
    limits = _fatigue_limits(loaded)
    _check_proof_stress(loaded)
    torque = load_torque_Nmm(case)
    if not torque > 0.0:
        raise loaded.error(("load", "torque"), "the rating needs the load: the load torque is "
                           "zero; expected a load torque > 0")
    if not geo.pinion_speed_rad_s:
        raise loaded.error(("drive",), "the rating needs the pinion speed; expected "
                           "drive.speed (or drive.reference_speed with a torque drive) > 0")
    speed_rpm = abs(geo.pinion_speed_rad_s) * RPM_PER_RAD_S
    iso = iso_dynamic(case, geo)
    if not isinstance(r.dynamic_factor, str):
        k_v, source, info = r.dynamic_factor, "given", None
    else:
        k_v, info = _iso_kv(iso, speed_rpm, r.application_factor)
        source = f"ISO 6336-1 Method B ({info.speed_range}, N = {info.resonance_ratio:.3g})"
    gears = [_gear_input(case, geo, role, lim, iso.f_pb_eff_um)
             for role, lim in zip(_ROLES, limits, strict=True)]
    _check_inspection(loaded, geo, gears)
    g, rack = geo.geometry, case.gears.rack
    try:
        inp = RatingInput(
            module_mm=g.module_mm, pinion=gears[0], gear=gears[1],
            pinion_torque_Nm=_pinion_torque_Nm(case, geo, torque), pinion_speed_rpm=speed_rpm,
            life_h=r.life / 3600.0, pressure_angle_deg=math.degrees(g.pressure_angle_rad),
            centre_distance_mm=g.a_w_mm, addendum_coefficient=rack.addendum,
            dedendum_coefficient=rack.dedendum, root_radius_coefficient=rack.root_radius,
            application_factor=r.application_factor, load_sharing_factor=r.load_sharing_factor,
            dynamic_factor=k_v, face_load_factor=r.face_load_factor,
            transverse_load_factor=r.transverse_load_factor,
            mesh_stiffness_N_mm_um=(r.mesh_stiffness if r.mesh_stiffness is not None
                                    else iso.c_gamma_alpha_N_mm_um),
            shaft_misalignment_um=1e3 * r.shaft_misalignment,
            manufacturing_misalignment_um=1e3 * r.manufacturing_misalignment,
            viscosity_40_mm2_s=r.lubricant.viscosity_40,
            minimum_safety_pitting=r.minimum_safety.pitting,
            minimum_safety_bending=r.minimum_safety.bending,
            pitting_permitted=r.pitting_permitted, optimum_long_life=r.optimum_long_life,
            edition=Edition(str(r.edition)))
    except ValueError as exc:
        raise loaded.error(("rating",), f"cannot rate this case: {exc}") from None
    return inp, source, info


def _duty_bins(loaded: LoadedCase, geo: GeometryResult) -> list[LoadBin] | None:
    bins = loaded.case.rating.duty_cycle
    if bins is None:
        return None
    return [LoadBin(_pinion_torque_Nm(loaded.case, geo, b.torque),
                    b.speed * RPM_PER_RAD_S, b.time_share) for b in bins]


def _peaks(result: RatingResult, sim: SimulatedLoad) -> dict[str, PeakSafety] | None:
    """Safeties of the run's peak stresses against the ISO strengths at the required life.

    The peaks of `gearcli stress` come from the converged dynamic pair forces at their actual
    contact positions: they carry what K_v, K_Hα/K_Fα, Z_B/Z_D and Z_ε stand for in ISO, but not
    the load the torsional model does not see: K_A, K_γ and the face load distribution K_Hβ,
    K_Fβ (and, in the root, Y_β Y_B Y_DT, taken 1 by the stress histories). So (ISO 6336-2
    σ_H = Z_B σ_H0 √ΠK, ISO 6336-3 σ_F = σ_F0 ΠK; docs/theory.md, "ISO 6336 rating" §9)
    σ_H,sim = σ_H,peak √(K_A K_γ K_Hβ), σ_F,sim = σ_F,peak K_A K_γ K_Fβ Y_β Y_B Y_DT, and
    S = σ_G/σ_sim."""
    if sim.sigma_H_peak_MPa is None and sim.sigma_F_peak_MPa is None:
        return None
    k = {f.symbol: f.value for f in result.pair_factors}
    k_h = k["K_A"] * k["K_γ"] * k["K_Hβ"]
    k_f = k["K_A"] * k["K_γ"] * k["K_Fβ"]
    out = {}
    for i, g in enumerate((result.pinion, result.gear)):
        row = {}
        if sim.sigma_H_peak_MPa is not None:
            s = sim.sigma_H_peak_MPa[i]
            s_h = s * math.sqrt(k_h)
            row.update(sigma_H_peak_MPa=s, sigma_H_MPa=s_h, S_H=g.sigma_HG_MPa / s_h,
                       S_H_min=g.S_H_min)
        if sim.sigma_F_peak_MPa is not None:
            s = sim.sigma_F_peak_MPa[i]
            y = math.prod(g.factor(sym).value for sym in ("Y_β", "Y_B", "Y_DT"))
            s_f = s * k_f * y
            row.update(sigma_F_peak_MPa=s, sigma_F_MPa=s_f, S_F=g.sigma_FG_MPa / s_f,
                       S_F_min=g.S_F_min)
        out[g.name] = PeakSafety(**row)
    return out


def simulated_load_of(res) -> SimulatedLoad:
    """The SimulatedLoad of a run's stress evaluation ``res`` (pipeline.stress.StressResult):
    K_v = the run's summary F_max/F_static, the peak σ_H, σ_F per gear of `gearcli stress` in
    the steady window (None where a gear has no loaded sample)."""
    scalars = res.run.summary.scalars
    f_max, f_static = float(scalars.force_max_N), float(scalars.force_static_N)
    if not (f_static > 0.0 and f_max > 0.0):
        raise CaseError(f"rate: the run's F_max {f_max:g} N / F_static {f_static:g} N is no "
                        "dynamic factor; expected a loaded run (both > 0)")
    gears = (res.pinion, res.gear)
    h = tuple(g.sigma_H_peak_MPa for g in gears)
    f = tuple(g.sigma_F_peak_MPa for g in gears)
    return SimulatedLoad(dynamic_factor=f_max / f_static,
                         sigma_H_peak_MPa=None if None in h else h,
                         sigma_F_peak_MPa=None if None in f else f)


def simulated_load(folder: str | Path) -> tuple[SimulatedLoad, LoadedCase]:
    """(SimulatedLoad, the run's case) of a results folder of `gearcli simulate`
    (:func:`simulated_load_of` its stress evaluation, pipeline.stress.compute_stress)."""
    import json

    from gearcli.pipeline.stress import compute_stress

    res = compute_stress(folder, None)
    loaded = load_case_text(json.dumps(res.run.manifest["resolved_case"]),
                            str(Path(folder) / "manifest.json"))
    return simulated_load_of(res), loaded


def _with_kv_clause(result: RatingResult, source: str) -> RatingResult:
    """The document with the K_v row's clause saying where K_v came from (the model writes
    "given" for every K it is handed)."""
    rows = tuple(dataclasses.replace(f, clause=source) if f.symbol == "K_v" else f
                 for f in result.pair_factors)
    return dataclasses.replace(result, pair_factors=rows)


def rate_case(source: str | Path | LoadedCase, overrides: list[str] | None = None,
              simulated: SimulatedLoad | None = None) -> CaseRating:
    """The ISO 6336 rating of a case (module notes); ``simulated``: a run's dynamic factor
    (and stress peaks) for the simulated column."""
    loaded = source if isinstance(source, LoadedCase) else load_case(source, overrides)
    r = loaded.case.rating
    if r.dynamic_factor == "simulated" and simulated is None:
        raise loaded.error(("rating", "dynamic_factor"), "'simulated' takes K_v from a "
                           "simulation run, and `gearcli rate` rates the case alone; expected "
                           "'iso' or a number here (the simulated rating comes with a run)",
                           "simulated", True)
    geo = run_geometry(loaded)
    inp, source_kv, info = rating_input(loaded, geo)
    notes = not_included("rate", loaded.case)
    if r.duty_cycle is not None and isinstance(r.dynamic_factor, str):
        notes.append("duty cycle: every bin is rated with the K_v of the case's load")
    bins = _duty_bins(loaded, geo)
    try:
        iso = _with_kv_clause(rate(inp), source_kv)
        editions = edition_rows(inp, iso)
        damage = duty_cycle_damage(inp, bins) if bins is not None else None
    except ValueError as exc:
        raise loaded.error(("rating",), f"cannot rate this case: {exc}") from None
    sim = peaks = None
    if simulated is not None:
        changes = {"dynamic_factor": simulated.dynamic_factor}
        if simulated.load_sharing_factor is not None:
            changes["load_sharing_factor"] = simulated.load_sharing_factor
        sim = _with_kv_clause(rate(dataclasses.replace(inp, **changes)),
                              "simulated: the run's F_max/F_static")
        peaks = _peaks(sim, simulated)
    return CaseRating(loaded, inp, iso, source_kv, info, damage, sim, peaks, tuple(notes),
                      editions)


def case_inspection(source: str | Path | LoadedCase, geo: GeometryResult | None = None,
                    overrides: list[str] | None = None) -> PairInspection:
    """The inspection dimensions of both gears (pipeline.geometry.pair_inspection: span W_k,
    balls, M_dK, chordal tooth thickness/height at the nominal thickness and the allowances);
    docs/theory.md, "ISO 6336 rating" §6."""
    loaded = source if isinstance(source, LoadedCase) else load_case(source, overrides)
    geo = geo or run_geometry(loaded)
    return pair_inspection(loaded.case, geo.geometry)
