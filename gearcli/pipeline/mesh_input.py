"""The case's mesh at its operating load: static force, contact stiffness (IMPACT k or the
tooth law's pair stiffness k(x)) and the one linearisation (model.mesh) that `simulate`
(tolerances, output rate, validity limit, mesh damping), `modal` (the linear model) and
`mesh` use."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from gearcli.case.schema import Case
from gearcli.model.mesh import MeshMode, mesh_mode, static_normal_force_N, tooth_mesh_mode
from gearcli.model.stiffness import derived_pair_stiffness
from gearcli.pipeline.geometry import GeometryResult
from gearcli.results.models import IsoResonance

if TYPE_CHECKING:
    from gearcli.model.pair_stiffness import PairStiffness

#: Roll positions on the path at which the tooth law's mesh mode integrates k(x).
_PATH_POINTS = 401


def load_torque_Nmm(case: Case) -> float:
    """The load torque at the end of its ramps [N·mm] (its final value, else its value at the
    run's end time)."""
    final = case.load.torque.pp.final_value()
    return float(final if final is not None else case.load.torque.pp(case.run.end_time))


def static_force_N(case: Case, geo: GeometryResult) -> float:
    """F_n [N] of the load torque at the end of its ramps, T_load/r_b2: the operating load of
    the contact model (linearisation, tolerances, validity; docs/theory.md §7.3). The dynamic
    factor's static force adds the speed-dependent terms measured in the run
    (model.mesh.static_reference_N)."""
    return static_normal_force_N(load_torque_Nmm(case), geo.geometry.gear.r_b_mm)


def iso_stiffness(case: Case, geo: GeometryResult, force_N: float | None = None):
    """ISO 6336-1 Method B stiffness of the case's pair (model.stiffness) at its static
    normal force (or ``force_N`` [N]) and material."""
    force = static_force_N(case, geo) if force_N is None else force_N
    return derived_pair_stiffness(geo.geometry, case.gears.rack.dedendum,
                                  force * geo.geometry.gear.r_b_mm,
                                  case.material.youngs_modulus)


def contact_stiffness(case: Case, geo: GeometryResult, force_N: float | None = None) -> float:
    """k of the IMPACT law [N/mm^e]: given, or 'derived' (e = 1): the constant pair stiffness
    whose mean over the mesh cycle, ε_α k, is ISO 6336-1's c_γα b (docs/theory.md §4) at the
    static normal force (or ``force_N`` [N])."""
    if case.contact.stiffness != "derived":
        return float(case.contact.stiffness)
    return iso_stiffness(case, geo, force_N).mesh_stiffness_N_mm / geo.geometry.eps_alpha


#: Line load [N/mm] of the tooth law's contact term when the case has no load: ISO 6336-1's
#: 100 N/mm, above which its single stiffness c′ has no low-load factor (§9.3).
REFERENCE_LINE_LOAD_N_MM = 100.0


def contact_line_load_N_mm(case: Case, geo: GeometryResult, force_N: float | None = None
                           ) -> float:
    """w = F/b [N/mm] at which the tooth law takes Weber's contact flattening (a secant,
    docs/theory.md §4b): the static normal force (or ``force_N``) over the narrower face
    width; without a load, REFERENCE_LINE_LOAD_N_MM."""
    g = geo.geometry
    force = static_force_N(case, geo) if force_N is None else float(force_N)
    w = force / g.narrow_face_width_mm
    return w if w > 0.0 else REFERENCE_LINE_LOAD_N_MM


def tooth_stiffness(case: Case, geo: GeometryResult, x_mm, force_N: float | None = None
                    ) -> PairStiffness:
    """The tooth law's pair stiffness k(x) [N/mm] and dk/dx on pinion roll positions ``x_mm``
    from A (model.pair_stiffness): each gear's material (or the case's), the narrower face
    width, the bores given or model.tooth_stiffness.default_bore_diameter, the contact term at
    the line load of the static force (or ``force_N`` [N]; :func:`contact_line_load_N_mm`)."""
    # imported here: the tooth-compliance model loads scipy.interpolate (~0.4 s), which a case
    # with the IMPACT law does not need
    from gearcli.model.pair_stiffness import pair_stiffness

    g, gears = geo.geometry, case.gears
    m1, m2 = case.material_of("pinion"), case.material_of("gear")
    try:
        return pair_stiffness(g, np.asarray(x_mm, float),
                              face_width_mm=g.narrow_face_width_mm,
                              E1_MPa=m1.youngs_modulus, nu1=m1.poisson_ratio,
                              E2_MPa=m2.youngs_modulus, nu2=m2.poisson_ratio,
                              bore_diameter1_mm=gears.pinion.bore_diameter,
                              bore_diameter2_mm=gears.gear.bore_diameter,
                              load_N_mm=contact_line_load_N_mm(case, geo, force_N))
    except ValueError as exc:
        from gearcli.errors import CaseError
        from gearcli.model.tooth_stiffness import ContactOutsideTooth

        if isinstance(exc, ContactOutsideTooth):
            # the gap tables reach 20 static deflections beyond first touch (kernel_input):
            # a deflection that large no longer touches the tooth's flank
            raise CaseError(
                f"load.torque: the static deflection at this load is too large for the teeth "
                f"(E = {m1.youngs_modulus:g} / {m2.youngs_modulus:g} MPa): the tooth law would "
                f"need contact beyond the tooth ({exc}); expected a smaller load or a stiffer "
                "material") from None
        raise CaseError(f"gears: tooth stiffness: {exc}") from None


def bore_notes(case: Case, geo: GeometryResult) -> list[str]:
    """The tooth law's validity notes on the given bores: h_fi = r_f / r_int outside the range
    of Sainsot et al.'s body-compliance fit (model.tooth_stiffness, docs/theory.md §4b), where
    the foundation term is extrapolated."""
    if case.contact.law != "tooth":
        return []
    # imported here, as in tooth_stiffness: the model loads scipy.interpolate
    from gearcli.model.tooth_stiffness import SAINSOT_H_MAX, SAINSOT_H_MIN

    out = []
    for role in ("pinion", "gear"):
        bore = getattr(case.gears, role).bore_diameter
        if bore is None:
            continue
        h_fi = getattr(geo.geometry, role).d_f_mm / bore
        if not SAINSOT_H_MIN <= h_fi <= SAINSOT_H_MAX:
            out.append(f"gears.{role}.bore_diameter = {bore:g} mm gives h_fi = r_f/r_int = "
                       f"{h_fi:.2f}, outside {SAINSOT_H_MIN:g} ... {SAINSOT_H_MAX:g}, the range "
                       "of Sainsot et al.'s gear-body compliance fit: the foundation term is "
                       "extrapolated" + (" and grows fast, so the tooth stiffness may be far "
                                         "too low" if h_fi > SAINSOT_H_MAX else ""))
    return out


def case_mesh(case: Case, geo: GeometryResult, force_N: float | None = None) -> MeshMode:
    """The mesh linearised at the static load (or at a normal force ``force_N`` [N]; docs/
    theory.md §4, §4b, §6): with a prescribed pinion speed only the gear vibrates, else both
    gears are free."""
    g, ct = geo.geometry, case.contact
    force = static_force_N(case, geo) if force_N is None else force_N
    if ct.law == "tooth":
        x = np.linspace(0.0, g.g_alpha_mm, _PATH_POINTS)
        k = tooth_stiffness(case, geo, x, force_N).k_N_mm
        return tooth_mesh_mode(force, x, k, g.g_alpha_mm, g.p_b_mm,
                               ct.damping_ratio, g.pinion.r_b_mm, g.gear.r_b_mm,
                               geo.mass[0].inertia_t_mm2, geo.mass[1].inertia_t_mm2,
                               pinion_free=case.drive.type != "speed")
    return mesh_mode(force, g.eps_alpha, contact_stiffness(case, geo, force_N),
                     ct.exponent, ct.max_damping, ct.penetration_depth, g.pinion.r_b_mm,
                     g.gear.r_b_mm, geo.mass[0].inertia_t_mm2, geo.mass[1].inertia_t_mm2,
                     pinion_free=case.drive.type != "speed")


def reference_deflection_mm(case: Case, geo: GeometryResult) -> float:
    """The static deflection [mm] of the case's contact law at the reference line load
    :data:`REFERENCE_LINE_LOAD_N_MM` (normal force over the narrower face width): the
    validity guard's floor of its penetration limit (pipeline/validity.py, item 1)."""
    force = REFERENCE_LINE_LOAD_N_MM * geo.geometry.narrow_face_width_mm
    return case_mesh(case, geo, force).static_deflection_mm


def iso_dynamic(case: Case, geo: GeometryResult) -> IsoResonance:
    """ISO 6336-1 Method B resonance data of the case's pair (gearcli/model/iso_kv.py): the
    reduced mass (solid gears, or the given bores), the line load F_t/b [N/mm] (K_A = 1), c′
    and c_γα [N/(mm·µm)] with the standard's low-load factor (the rating values: below
    100 N/mm ISO 6336-1 §9.3 reduces c′ by (F_t K_A/b/100)^0.25, and n_E1 and B_p, B_f, B_k
    are computed from that c′), n_E1 [min⁻¹], and the case's deviations as Method B takes them
    (:func:`iso_deviations`), as the mesh JSON's typed ``iso6336_method_b`` (internal units
    where not stated); :func:`kv_arguments` gives the keyword arguments of
    :func:`gearcli.model.iso_kv.dynamic_factor`."""
    from gearcli.model.iso_kv import reduced_mass_kg_mm, resonance_speed_rpm

    g, gears = geo.geometry, case.gears
    iso = iso_stiffness(case, geo)
    d_m1 = 0.5 * (g.pinion.d_a_mm + g.pinion.d_f_mm)
    d_m2 = 0.5 * (g.gear.d_a_mm + g.gear.d_f_mm)
    rho = case.material.density * 1e3  # t/mm³ -> kg/mm³
    q1 = (gears.pinion.bore_diameter or 0.0) / d_m1
    q2 = (gears.gear.bore_diameter or 0.0) / d_m2
    m_red = reduced_mass_kg_mm(d_m1, g.pinion.d_b_mm, rho, rho, g.ratio, q1, q2)
    width = g.narrow_face_width_mm
    line_load = static_force_N(case, geo) * math.cos(g.pressure_angle_rad) / width
    c_prime = iso.c_prime_rating
    c_gamma_alpha = iso.c_gamma_alpha * iso.load_factor
    return IsoResonance(
        reduced_mass_kg_mm=m_red, low_load_factor=iso.load_factor, c_prime_N_mm_um=c_prime,
        c_gamma_alpha_N_mm_um=c_gamma_alpha, line_load_N_mm=line_load, eps_gamma=g.eps_alpha,
        resonance_speed_rpm=resonance_speed_rpm(g.pinion.teeth, c_gamma_alpha, m_red),
        **iso_deviations(case, geo, c_prime, line_load))


def kv_arguments(iso: IsoResonance) -> dict[str, float]:
    """The keyword arguments of :func:`gearcli.model.iso_kv.dynamic_factor` from the ISO data
    of :func:`iso_dynamic`."""
    return {"eps_gamma": iso.eps_gamma, "c_prime_N_mm_um": iso.c_prime_N_mm_um,
            "line_load_N_mm": iso.line_load_N_mm, "f_pb_eff_um": iso.f_pb_eff_um,
            "f_f_eff_um": iso.f_f_eff_um, "tip_relief_um": iso.tip_relief_um}


def running_in_tip_relief_um(sigma_hlim_MPa: float) -> float:
    """ISO 6336-1 running-in amount C_ay [µm] of a gear without designed tip relief, from its
    contact fatigue limit σ_Hlim [MPa]: C_ay = (σ_Hlim/97 − 18.45)²/18 + 1.5."""
    return (sigma_hlim_MPa / 97.0 - 18.45) ** 2 / 18.0 + 1.5


def iso_deviations(case: Case, geo: GeometryResult, c_prime: float, line_load: float) -> dict:
    """The case's deviations in ISO 6336-1 Method B's terms (docs/theory.md §10.4), with c′
    [N/(mm·µm)] and the line load F_t K_A/b [N/mm] of B_p, B_f, B_k:

    * f_pb,eff [µm]: the larger of the two gears' base pitch deviations f_pb = f_pt cos α
      (ISO 1328-1:2013 tolerances f_pt only; the KISSsoft printouts of the K_v test list
      f_pbT = f_ptT cos α): f_pt the largest |f_pt,i| of given values after their mean is
      removed (as the simulation uses them, model/errors.py), or the tolerance f_pT of an ISO
      1328-1 grade; 0 without pitch deviations. No running-in allowance y_p is credited
      (y_p = 0: it needs the material class), which is conservative.
    * f_f,eff = 0: case files have no profile form deviation.
    * C_a [µm]: per gear, its designed tip relief; without one, the running-in amount C_ay
      (:func:`running_in_tip_relief_um`, the mean of both gears') when both materials give
      σ_Hlim (``contact_fatigue_limit``), else 0 (B_k = 1, the formula at C_a = 0). Of the two
      gears', the C_a with the larger B_k = |1 − c′ C_a / (F_t K_A / b)| (conservative).
    """
    from gearcli.model.errors import iso1328_single_pitch_tolerance_um

    g = geo.geometry
    f_pt = 0.0
    for dev, gear in ((case.errors.pitch_deviation.pinion, g.pinion),
                      (case.errors.pitch_deviation.gear, g.gear)):
        if dev is None:
            continue
        if dev.values is not None:
            values = np.asarray(dev.values, float)
            f_pt = max(f_pt, 1e3 * float(np.max(np.abs(values - values.mean()))))
        else:
            f_pt = max(f_pt, iso1328_single_pitch_tolerance_um(dev.iso1328_grade, gear.d_mm,
                                                               case.gears.module))
    f_pb = f_pt * math.cos(g.pressure_angle_rad)
    limits = [(m or case.material).contact_fatigue_limit
              for m in (case.gears.pinion.material, case.gears.gear.material)]
    c_ay = (0.5 * sum(running_in_tip_relief_um(s) for s in limits)
            if all(s is not None for s in limits) else None)
    candidates = []
    for relief in (case.modifications.tip_relief.pinion, case.modifications.tip_relief.gear):
        if relief is not None:
            candidates.append((1e3 * relief.amount, "designed tip relief"))
        elif c_ay is not None:
            candidates.append((c_ay, "running-in amount C_ay"))
        else:
            candidates.append((0.0, "none (no tip relief, no sigma_Hlim for C_ay)"))

    def b_k(c_a: float) -> float:
        return abs(1.0 - c_prime * c_a / line_load)

    c_a, source = max(candidates, key=lambda c: b_k(c[0]))
    return {"f_pb_eff_um": f_pb, "f_f_eff_um": 0.0, "tip_relief_um": c_a,
            "tip_relief_source": source, "B_p": c_prime * f_pb / line_load, "B_f": 0.0,
            "B_k": b_k(c_a)}
