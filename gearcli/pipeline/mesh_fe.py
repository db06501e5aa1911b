"""`gearcli mesh --method fe`: the tooth law (potential energy, PE; docs/theory.md §4b) beside
the finite-element model of the case's pair (docs/theory.md, "Finite-element check of the tooth
compliance"; gearcli/model/fe/).

Both sides are evaluated alike, so their ratio isolates the compliance models: rigid engagement
without profile modifications, the pairs on the path in parallel (k_mesh = Σ k_pair, STE =
F/k_mesh), the case's materials, narrower face width and bores (default d_f/3 in both), at the
FE's plane state (plane strain when b ≥ 5 m) in both. The FE pair stiffness is a secant at the
load (Weber's local term depends on ln a), the law's is linear. The influence coefficients are
cached per geometry hash on disk (gearcli/io/fe_store.py).
"""

from __future__ import annotations

import numpy as np

from gearcli.results.models import FeCheck, PeFe


def _note(teeth: PeFe, contact: PeFe) -> str:
    """What differs, from this pair's numbers (docs/theory.md, "PE law against FE")."""
    return (f"FE vs PE at the pitch point: teeth + body {100 * teeth.fe_over_pe_minus_1:+.1f} %, "
            f"contact term {100 * contact.fe_over_pe_minus_1:+.1f} % (the law's linear Hertz "
            "term 2/(π b E*), Yang & Sun 1985, against Weber's flattening at the load in the FE "
            "model, which softens with less load); both columns rigid engagement without "
            "profile modifications (docs/theory.md, 'Finite-element check of the tooth "
            "compliance')")


def _pe_fe(pe: float, fe: float) -> PeFe:
    return PeFe(pe=float(pe), fe=float(fe), fe_over_pe_minus_1=float(fe) / float(pe) - 1.0)


def fe_check(case, geo, force_N: float, store=None) -> FeCheck:
    """The PE/FE comparison of the case's pair at the normal force ``force_N`` [N]; ``store``
    the persistent cache (load/store callbacks, default gearcli.io.fe_store.FEStore)."""
    from gearcli.io.fe_store import FEStore
    from gearcli.model.fe import ComplianceCache, fe_mesh_stiffness
    from gearcli.model.pair_stiffness import mesh_stiffness, pair_stiffness

    g, gears = geo.geometry, case.gears
    m1, m2 = case.material_of("pinion"), case.material_of("gear")
    b = min(g.pinion.face_width_mm, g.gear.face_width_mm)
    common = {"face_width_mm": b, "E1_MPa": m1.youngs_modulus, "nu1": m1.poisson_ratio,
              "E2_MPa": m2.youngs_modulus, "nu2": m2.poisson_ratio,
              "bore_diameter1_mm": gears.pinion.bore_diameter,
              "bore_diameter2_mm": gears.gear.bore_diameter}
    store = FEStore() if store is None else store
    cache = ComplianceCache(load=store.load, store=store.store)
    fe = fe_mesh_stiffness(g, load_N_mm=force_N / b, cache=cache, **common)
    x_c = g.C_mm - g.A_mm
    law = {"plane_strain": fe.plane_strain, "load_N_mm": force_N / b, **common}
    pe = pair_stiffness(g, [x_c], **law)
    pe_mesh = mesh_stiffness(g, **law)
    pe_ste_um = 1e3 * force_N / pe_mesh.k_mesh_N_mm
    fe_teeth = float(np.interp(x_c, fe.x_mm, fe.tooth1_mm_N + fe.tooth2_mm_N))
    fe_local = float(np.interp(x_c, fe.x_mm, fe.local_mm_N))
    teeth = _pe_fe(1.0 / (pe.pinion.total_mm_N[0] + pe.gear.total_mm_N[0]), 1.0 / fe_teeth)
    contact = _pe_fe(1.0 / pe.hertz_mm_N[0], 1.0 / fe_local)
    return FeCheck(
        line_load_N_mm=force_N / b, plane_strain=fe.plane_strain,
        pitch_pair_stiffness_N_mm=_pe_fe(pe.k_N_mm[0], fe.pitch_pair_N_mm),
        mesh_mean_stiffness_N_mm=_pe_fe(pe_mesh.mean_N_mm, fe.mean_N_mm),
        ste_peak_to_peak_um=_pe_fe(np.ptp(pe_ste_um), np.ptp(fe.ste_um)),
        teeth_at_pitch_N_mm=teeth, contact_at_pitch_N_mm=contact,
        fe_dofs=tuple(int(n) for n in fe.n_dofs), cache_hits=cache.hits,
        cache_misses=cache.misses, seconds=fe.seconds, note=_note(teeth, contact))
