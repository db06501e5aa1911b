"""Assemble the ISO 6336 Method B rating document of a spur pair from plain inputs.

docs/theory.md, "ISO 6336 rating" (equations and the 2006/2019 differences). Order of the
calculation: pair geometry (ISO 21771) → nominal load F_t = 2000 T1/d1 → ISO 6336-1 load
factors → ISO 6336-2 contact stress and pitting strength → ISO 6336-3 root stress and bending
strength → ISO 6336-5 material limits → life (load cycles, life factors, life at S_min,
damage) → inspection dimensions. Every value goes into the document as a
:class:`~gearcli.model.iso6336.common.Factor` row (symbol, value, unit, clause, name).

:func:`evaluate` returns the intermediate values with the strength curves σ_HG(N), σ_FG(N) of
each gear (used by :mod:`gearcli.model.iso6336.spectrum`); :func:`rate` the document.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

from gearcli.model.iso6336 import bending as b3
from gearcli.model.iso6336 import pitting as p2
from gearcli.model.iso6336.common import Edition, Factor, inverse_involute, involute
from gearcli.model.iso6336.document import GearRating, RatingResult
from gearcli.model.iso6336.factors import (
    bending_face_load_factor,
    face_load_factor_method_c,
    running_in_profile,
    transverse_load_factors,
)
from gearcli.model.iso6336.inputs import GearInput, RatingInput
from gearcli.model.iso6336.inspection import inspection_dimensions
from gearcli.model.iso6336.life import (
    bending_life_curve,
    cycles_at_strength,
    influence_at,
    load_cycles,
    pitting_life_curve,
)
from gearcli.model.iso6336.material import NITRIDED, SURFACE_HARDENED, allowable_stress

__all__ = ["PairGeometry", "pair_geometry", "GearEvaluation", "Evaluation", "evaluate", "rate"]


class PairGeometry(NamedTuple):
    """Geometry of the rated pair (index 0 pinion, 1 gear); lengths [mm], angles [rad]."""

    alpha: float  #: reference pressure angle α
    alpha_w: float  #: operating pressure angle α_wt
    centre_distance: float  #: a_w
    d: tuple[float, float]  #: reference diameters
    d_b: tuple[float, float]  #: base diameters
    d_a: tuple[float, float]  #: tip diameters
    tooth_height: tuple[float, float]  #: h = (d_a − d_f)/2
    eps_alpha: float  #: transverse contact ratio ε_α
    u: float  #: gear ratio z2/z1


def pair_geometry(inp: RatingInput) -> PairGeometry:
    """ISO 21771 geometry of the pair (docs/theory.md §2): d = m z, d_b = d cos α,
    inv α_w = inv α + 2 (x1 + x2) tan α/(z1 + z2) or cos α_w = a cos α/a_w for a given a_w,
    d_f = d − 2 m (h_fP* − x), ε_α = (√(r_a1² − r_b1²) + √(r_a2² − r_b2²) − a_w sin α_w)/p_b."""
    m, g = inp.module_mm, (inp.pinion, inp.gear)
    alpha = math.radians(inp.pressure_angle_deg)
    z = (g[0].teeth, g[1].teeth)
    d = (m * z[0], m * z[1])
    d_b = (d[0] * math.cos(alpha), d[1] * math.cos(alpha))
    a = 0.5 * (d[0] + d[1])
    if inp.centre_distance_mm is None:
        inv_w = involute(alpha) + 2.0 * (g[0].profile_shift + g[1].profile_shift) \
            * math.tan(alpha) / (z[0] + z[1])
        alpha_w = inverse_involute(inv_w)
        a_w = a * math.cos(alpha) / math.cos(alpha_w)
    else:
        a_w = inp.centre_distance_mm
        alpha_w = math.acos(a * math.cos(alpha) / a_w)
    d_a = tuple(gi.tip_diameter_mm if gi.tip_diameter_mm is not None
                else di + 2.0 * m * (inp.addendum_coefficient + gi.profile_shift)
                for gi, di in zip(g, d, strict=True))
    d_f = tuple(di - 2.0 * m * (inp.dedendum_coefficient - gi.profile_shift)
                for gi, di in zip(g, d, strict=True))
    height = (0.5 * (d_a[0] - d_f[0]), 0.5 * (d_a[1] - d_f[1]))
    g_alpha = (math.sqrt((0.5 * d_a[0]) ** 2 - (0.5 * d_b[0]) ** 2)
               + math.sqrt((0.5 * d_a[1]) ** 2 - (0.5 * d_b[1]) ** 2) - a_w * math.sin(alpha_w))
    eps = g_alpha / (math.pi * m * math.cos(alpha))
    return PairGeometry(alpha, alpha_w, a_w, d, d_b, d_a, height, eps, z[1] / z[0])


@dataclass(frozen=True)
class GearEvaluation:
    """Stresses, strength curves and factor rows of one gear."""

    name: str
    speed_rpm: float  #: relative to the carrier [min⁻¹]
    contacts_per_revolution: float
    load_cycles: float  #: N_L of the required life
    sigma_H_MPa: float
    sigma_F_MPa: float
    pitting_strength: Callable[[float], float]  #: σ_HG(N) [N/mm²]
    bending_strength: Callable[[float], float]  #: σ_FG(N) [N/mm²]
    n_static_H: float  #: static knee of the pitting curve [cycles]
    n_static_F: float
    factors: tuple[Factor, ...]


@dataclass(frozen=True)
class Evaluation:
    """Everything :func:`rate` documents, before the lives and the inspection dimensions."""

    geometry: PairGeometry
    pair_factors: tuple[Factor, ...]
    pinion: GearEvaluation
    gear: GearEvaluation


def _limits(g: GearInput) -> tuple[float, str, float, str]:
    """(σ_Hlim, its source, σ_Flim, its source) of a gear: given, else ISO 6336-5 Table 1."""
    out = []
    for given, stress in ((g.sigma_h_lim_MPa, "H"), (g.sigma_f_lim_MPa, "F")):
        if given is not None:
            out += [float(given), "given"]
            continue
        if g.surface_hardness is None:
            raise ValueError(f"σ_{stress}lim of the {g.teeth}-tooth gear: give it or the hardness")
        out += [allowable_stress(g.material, g.quality, g.surface_hardness, stress).value_MPa,
                "ISO 6336-5:2016 Table 1"]
    return out[0], out[1], out[2], out[3]


def _work_hardening(g: GearInput, mate: GearInput) -> float:
    """Z_W of ``g``: a through-hardened gear meshing with a surface-hardened mate, else 1."""
    hard = SURFACE_HARDENED | NITRIDED
    if g.material in hard or mate.material not in hard:
        return 1.0
    hb = g.brinell_hardness if g.brinell_hardness is not None else g.surface_hardness
    return 1.0 if hb is None else p2.work_hardening_factor(hb)


def _load_factors(inp: RatingInput, geo: PairGeometry, f_t: float, v: float, z_eps: float,
                  s_hlim: tuple[float, float], ed: str) -> tuple[dict, list[Factor]]:
    """K_A, K_γ, K_v, K_Hβ, K_Fβ, K_Hα, K_Fα (ISO 6336-1) and their rows."""
    p1 = f"ISO 6336-1:{ed}"
    b = min(inp.pinion.face_width_mm, inp.gear.face_width_mm)
    k_a, k_g, k_v = inp.application_factor, inp.load_sharing_factor, inp.dynamic_factor
    f_m = f_t * k_a * k_g * k_v / b
    kinds = (inp.pinion.material, inp.gear.material)
    if inp.face_load_factor is not None:
        k_hb, src_b = inp.face_load_factor, "given"
    else:
        k_hb, _, _ = face_load_factor_method_c(
            f_m, 0.85 * inp.mesh_stiffness_N_mm_um, inp.shaft_misalignment_um,
            inp.manufacturing_misalignment_um, kinds=kinds, sigma_h_lim_MPa=s_hlim, v_m_s=v)
        src_b = f"{p1} K_Hβ Method C"
    b_over_h = min(gi.face_width_mm / h for gi, h in zip((inp.pinion, inp.gear),
                                                          geo.tooth_height, strict=True))
    k_fb = bending_face_load_factor(k_hb, b_over_h, 1.0)  # only the ratio b/h enters
    if inp.transverse_load_factor is not None:
        k_ha = k_fa = inp.transverse_load_factor
        src_a = "given"
    else:
        f_pb = max(inp.pinion.base_pitch_deviation_um, inp.gear.base_pitch_deviation_um)
        y_a = 0.5 * sum(running_in_profile(k, s, f_pb, v) for k, s in zip(kinds, s_hlim,
                                                                          strict=True))
        k_ha, k_fa = transverse_load_factors(geo.eps_alpha, inp.mesh_stiffness_N_mm_um, f_pb,
                                             y_a, f_m * k_hb, z_eps)
        src_a = f"{p1} K_Hα Method B"
    k = {"K_A": k_a, "K_gamma": k_g, "K_v": k_v, "K_Hb": k_hb, "K_Fb": k_fb, "K_Ha": k_ha,
         "K_Fa": k_fa}
    rows = [Factor("K_A", k_a, "-", "given", "application factor"),
            Factor("K_γ", k_g, "-", "given", "mesh load factor (load sharing)"),
            Factor("K_v", k_v, "-", "given", "dynamic factor"),
            Factor("K_Hβ", k_hb, "-", src_b, "face load factor, flank"),
            Factor("K_Fβ", k_fb, "-", f"{p1} K_Fβ from K_Hβ", "face load factor, root"),
            Factor("K_Hα", k_ha, "-", src_a, "transverse load factor, flank"),
            Factor("K_Fα", k_fa, "-", src_a, "transverse load factor, root")]
    return k, rows


def _pitting(inp: RatingInput, i: int, n_l: float, sigma_h: float, s_hlim: tuple[float, float],
             v: float, rho_red: float, ed: str):
    """σ_HG(N) of gear ``i`` and its rows at N_L (ISO 6336-2; life: ISO 6336-2 Table 2)."""
    p2c = f"ISO 6336-2:{ed}"
    g, mate = (inp.pinion, inp.gear) if i == 0 else (inp.gear, inp.pinion)
    soft = min(s_hlim)
    z_l = p2.lubricant_factor(soft, inp.viscosity_40_mm2_s)
    z_v = p2.velocity_factor(soft, v)
    z_r = p2.roughness_factor(soft, inp.pinion.flank_roughness_rz_um,
                              inp.gear.flank_roughness_rz_um, rho_red)
    z_w = _work_hardening(g, mate)
    z_x = p2.SIZE_FACTOR
    curve = pitting_life_curve(g.material, inp.pitting_permitted, inp.optimum_long_life)
    lim = s_hlim[i]

    def strength(n: float) -> float:
        return lim * curve(n) * influence_at(n, curve, 1.0, z_l * z_v * z_r * z_x) * z_w

    at = [influence_at(n_l, curve, 1.0, f) for f in (z_l, z_v, z_r, z_x)]
    sigma_hg = strength(n_l)
    rows = [Factor("Z_NT", curve(n_l), "-", f"{p2c} Table 2", "life factor, pitting"),
            Factor("Z_L", at[0], "-", f"{p2c} Method B (at N_L)", "lubricant factor"),
            Factor("Z_v", at[1], "-", f"{p2c} Method B (at N_L)", "velocity factor"),
            Factor("Z_R", at[2], "-", f"{p2c} Method B (at N_L)", "roughness factor"),
            Factor("Z_W", z_w, "-", f"{p2c} work hardening", "work hardening factor"),
            Factor("Z_X", at[3], "-", f"{p2c} size factor", "size factor, flank"),
            Factor("σ_HG", sigma_hg, "N/mm²", f"{p2c} basic formula", "pitting stress limit"),
            Factor("σ_HP", sigma_hg / inp.minimum_safety_pitting, "N/mm²", f"{p2c} basic formula",
                   "permissible contact stress"),
            Factor("S_H", sigma_hg / sigma_h, "-", f"{p2c} basic formula",
                   "safety factor for pitting")]
    return strength, curve.n_static, rows


def _bending(inp: RatingInput, i: int, geo: PairGeometry, f_t: float, k: dict, n_l: float,
             s_flim: float, ed: str):
    """σ_F, σ_FG(N) of gear ``i`` and its rows (ISO 6336-3 Method B; life: Table 3)."""
    p3 = f"ISO 6336-3:{ed}"
    g = inp.pinion if i == 0 else inp.gear
    m, alpha = inp.module_mm, geo.alpha
    form = b3.form_geometry(g.teeth, g.profile_shift, m, alpha, inp.dedendum_coefficient * m,
                            inp.root_radius_coefficient * m, geo.d_a[i], geo.eps_alpha)
    y_f = b3.form_factor(form.h_Fe_mm, form.s_Fn_mm, form.alpha_Fen_rad, m, alpha)
    y_s = b3.stress_correction_factor(form.s_Fn_mm, form.h_Fe_mm, form.rho_F_mm)
    y_beta = b3.helix_factor(0.0, 0.0, ed)
    y_b = b3.rim_factor(g.rim_thickness_mm, geo.tooth_height[i])
    y_dt = b3.deep_tooth_factor(geo.eps_alpha, max(inp.pinion.accuracy_grade,
                                                   inp.gear.accuracy_grade))
    narrow = min(inp.pinion.face_width_mm, inp.gear.face_width_mm)
    b = min(g.face_width_mm, narrow + 2.0 * m)
    s_f0 = b3.nominal_root_stress(f_t, b, m, y_f, y_s, y_beta, y_b, y_dt)
    s_f = b3.root_stress(s_f0, k["K_A"], k["K_gamma"], k["K_v"], k["K_Fb"], k["K_Fa"])
    q_s = form.s_Fn_mm / (2.0 * form.rho_F_mm)
    rho_slip = b3.slip_layer_thickness(g.material, g.proof_stress_MPa)
    y_d = b3.notch_sensitivity_factor(q_s, rho_slip)
    y_d_stat = b3.notch_sensitivity_factor_static(g.material, y_s, g.proof_stress_MPa)
    y_r = b3.relative_surface_factor(g.material, g.root_roughness_rz_um)
    y_x = b3.size_factor(g.material, m)
    y_m = b3.mean_stress_factor(g.idler, ed, g.material, y_s, g.mean_stress_sensitivity,
                                g.root_stress_ratio)
    curve = bending_life_curve(g.material, inp.optimum_long_life)
    y_st = b3.STRESS_CORRECTION_TEST

    def strength(n: float) -> float:
        return (s_flim * y_st * curve(n) * influence_at(n, curve, y_d_stat, y_d)
                * influence_at(n, curve, 1.0, y_r * y_x) * y_m)

    s_fg = strength(n_l)
    rows = [Factor("s_Fn", form.s_Fn_mm, "mm", f"{p3} Y_F Method B", "root chord (30° tangents)"),
            Factor("ρ_F", form.rho_F_mm, "mm", f"{p3} Y_F Method B", "root fillet radius"),
            Factor("h_Fe", form.h_Fe_mm, "mm", f"{p3} Y_F Method B", "bending moment arm"),
            Factor("α_Fen", math.degrees(form.alpha_Fen_rad), "deg", f"{p3} Y_F Method B",
                   "load direction angle"),
            Factor("Y_F", y_f, "-", f"{p3} Y_F Method B", "form factor"),
            Factor("Y_S", y_s, "-", f"{p3} Y_S Method B", "stress correction factor"),
            Factor("Y_β", y_beta, "-", f"{p3} helix angle factor", "helix angle factor"),
            Factor("Y_B", y_b, "-", f"{p3} rim thickness factor", "rim thickness factor"),
            Factor("Y_DT", y_dt, "-", f"{p3} deep tooth factor", "deep tooth factor"),
            Factor("σ_F0", s_f0, "N/mm²", f"{p3} basic formula", "nominal root stress"),
            Factor("σ_F", s_f, "N/mm²", f"{p3} basic formula", "root stress"),
            Factor("Y_ST", y_st, "-", f"{p3} reference test gear", "stress correction, test gear"),
            Factor("Y_NT", curve(n_l), "-", f"{p3} Table 3", "life factor, bending"),
            Factor("Y_δrelT", influence_at(n_l, curve, y_d_stat, y_d), "-",
                   f"{p3} Method B (at N_L)", "relative notch sensitivity factor"),
            Factor("Y_RrelT", influence_at(n_l, curve, 1.0, y_r), "-", f"{p3} Method B (at N_L)",
                   "relative surface factor"),
            Factor("Y_X", influence_at(n_l, curve, 1.0, y_x), "-", f"{p3} size factor (at N_L)",
                   "size factor, root"),
            Factor("Y_M", y_m, "-", f"{p3} mean stress influence", "mean stress factor"),
            Factor("σ_FG", s_fg, "N/mm²", f"{p3} basic formula", "tooth root stress limit"),
            Factor("σ_FP", s_fg / inp.minimum_safety_bending, "N/mm²", f"{p3} basic formula",
                   "permissible root stress"),
            Factor("S_F", s_fg / s_f, "-", f"{p3} basic formula", "safety factor for bending")]
    return s_f, strength, curve.n_static, rows


def evaluate(inp: RatingInput) -> Evaluation:
    """Stresses, strength curves and factor rows of both gears (module notes)."""
    ed = Edition(inp.edition).value
    p1, p2c = f"ISO 6336-1:{ed}", f"ISO 6336-2:{ed}"
    geo = pair_geometry(inp)
    gears = (inp.pinion, inp.gear)
    f_t = 2000.0 * inp.pinion_torque_Nm / geo.d[0]
    v = math.pi * geo.d[0] * inp.pinion_speed_rpm / 60000.0
    lims = [_limits(g) for g in gears]
    s_hlim = (lims[0][0], lims[1][0])
    z_h = p2.zone_factor(geo.alpha, geo.alpha_w)
    z_e = p2.elasticity_factor(gears[0].youngs_MPa, gears[0].poisson, gears[1].youngs_MPa,
                               gears[1].poisson)
    z_eps = p2.contact_ratio_factor(geo.eps_alpha)
    z_beta = p2.helix_factor(0.0, ed)
    k, k_rows = _load_factors(inp, geo, f_t, v, z_eps, s_hlim, ed)
    b = min(g.face_width_mm for g in gears)
    s_h0 = p2.nominal_contact_stress(f_t, geo.d[0], b, geo.u, z_h, z_e, z_eps, z_beta)
    m1, m2, z_b, z_d = p2.single_pair_factors(gears[0].teeth, gears[1].teeth, *geo.d_a, *geo.d_b,
                                              geo.alpha_w, geo.eps_alpha)
    rho_red = p2.pitch_point_relative_radius(*geo.d_b, geo.alpha_w)
    pair = [Factor("F_t", f_t, "N", f"{p1} nominal tangential load", "F_t = 2000 T1/d1"),
            Factor("v", v, "m/s", f"{p1} pitch line velocity", "at the reference circle"),
            Factor("u", geo.u, "-", "ISO 21771", "gear ratio z2/z1"),
            Factor("α_wt", math.degrees(geo.alpha_w), "deg", "ISO 21771",
                   "operating pressure angle"),
            Factor("ε_α", geo.eps_alpha, "-", "ISO 21771", "transverse contact ratio"),
            *k_rows,
            Factor("Z_H", z_h, "-", f"{p2c} zone factor", "zone factor"),
            Factor("Z_E", z_e, "√(N/mm²)", f"{p2c} elasticity factor", "elasticity factor"),
            Factor("Z_ε", z_eps, "-", f"{p2c} contact ratio factor", "contact ratio factor"),
            Factor("Z_β", z_beta, "-", f"{p2c} helix angle factor", "helix angle factor"),
            Factor("σ_H0", s_h0, "N/mm²", f"{p2c} basic formula", "nominal contact stress"),
            Factor("ρ_red", rho_red, "mm", f"{p2c} roughness factor", "pitch-point ρ_red")]
    out = []
    for i, (g, z_single, m_i) in enumerate(zip(gears, (z_b, z_d), (m1, m2), strict=True)):
        speed = inp.pinion_speed_rpm * (1.0 if i == 0 else gears[0].teeth / gears[1].teeth)
        n_l = load_cycles(speed, inp.life_h, g.contacts_per_revolution)
        s_h = p2.contact_stress(s_h0, z_single, k["K_A"], k["K_gamma"], k["K_v"], k["K_Hb"],
                                k["K_Ha"])
        h_strength, h_static, h_rows = _pitting(inp, i, n_l, s_h, s_hlim, v, rho_red, ed)
        s_f, f_strength, f_static, f_rows = _bending(inp, i, geo, f_t, k, n_l, lims[i][2], ed)
        sym = "Z_B" if i == 0 else "Z_D"
        rows = [Factor("N_L", n_l, "-", "ISO 6336-2/-3 load cycles", "60 n L_h × contacts"),
                Factor("σ_Hlim", lims[i][0], "N/mm²", lims[i][1], "contact endurance limit"),
                Factor("σ_Flim", lims[i][2], "N/mm²", lims[i][3], "bending endurance limit"),
                Factor("M1" if i == 0 else "M2", m_i, "-", f"{p2c} single pair contact",
                       "ρ_red ratio to the inner point of single contact"),
                Factor(sym, z_single, "-", f"{p2c} single pair contact", "single pair factor"),
                Factor("σ_H", s_h, "N/mm²", f"{p2c} basic formula", "contact stress"),
                *h_rows, *f_rows]
        out.append(GearEvaluation("pinion" if i == 0 else "gear", speed,
                                  g.contacts_per_revolution, n_l, s_h, s_f, h_strength,
                                  f_strength, h_static, f_static, tuple(rows)))
    return Evaluation(geo, tuple(pair), out[0], out[1])


def _life_h(strength, n_static: float, stress: float, per_hour: float) -> float:
    """Hours until the strength curve falls to ``stress`` (cycles_at_strength / cycles per h)."""
    return cycles_at_strength(strength, stress, n_static) / per_hour


def _damage(required_h: float, life_h: float) -> float:
    """Miner damage of the required life on the curve scaled by S_min: L_h,req / L_h(S_min)."""
    return math.inf if life_h <= 0.0 else required_h / life_h


def _gear_rating(inp: RatingInput, ev: GearEvaluation, geo: PairGeometry, i: int) -> GearRating:
    g = inp.pinion if i == 0 else inp.gear
    per_hour = load_cycles(ev.speed_rpm, 1.0, ev.contacts_per_revolution)
    s_hmin, s_fmin = inp.minimum_safety_pitting, inp.minimum_safety_bending
    life_h = _life_h(ev.pitting_strength, ev.n_static_H, s_hmin * ev.sigma_H_MPa, per_hour)
    life_f = _life_h(ev.bending_strength, ev.n_static_F, s_fmin * ev.sigma_F_MPa, per_hour)
    s_hg = ev.pitting_strength(ev.load_cycles)
    s_fg = ev.bending_strength(ev.load_cycles)
    life_rows = (Factor("L_H", life_h, "h", "ISO 6336-2 life factor curve",
                        "life at which S_H = S_H,min"),
                 Factor("L_F", life_f, "h", "ISO 6336-3 life factor curve",
                        "life at which S_F = S_F,min"))
    insp = inspection_dimensions(g.teeth, g.profile_shift, inp.module_mm, geo.alpha, geo.d_a[i],
                                 g.thickness_allowances_mm, g.ball_diameter_mm)
    return GearRating(
        ev.name, ev.load_cycles, ev.sigma_H_MPa, s_hg, s_hg / s_hmin, s_hg / ev.sigma_H_MPa, s_hmin,
        ev.sigma_F_MPa, s_fg, s_fg / s_fmin, s_fg / ev.sigma_F_MPa, s_fmin, life_h, life_f,
        _damage(inp.life_h, life_h), _damage(inp.life_h, life_f), ev.factors + life_rows, insp)


def rate(inp: RatingInput) -> RatingResult:
    """The ISO 6336 Method B rating document of the pair (module notes; docs/theory.md)."""
    ev = evaluate(inp)
    return RatingResult(Edition(inp.edition).value, ev.pair_factors,
                        _gear_rating(inp, ev.pinion, ev.geometry, 0),
                        _gear_rating(inp, ev.gear, ev.geometry, 1))
