"""`gearcli mesh --method fe`: the tooth law (potential energy, PE; docs/theory.md §4b) beside
the finite-element model of the case's pair (docs/theory.md, "Finite-element check of the tooth
compliance"; gearcli/model/fe/).

Both sides are evaluated alike, so their ratio isolates the compliance models: the case's
materials, narrower face width and bores (default d_f/3 in both), the FE's plane state (plane
strain when b ≥ 5 m) in both, both contact terms secants at the line load. Two comparisons:
(1) rigid engagement without profile modifications, the pairs on the path in parallel
(k_mesh = Σ k_pair, STE = F/k_mesh; the FE shares the load between the pairs for its local
terms); (2) the loaded contact with the case's gap tables (extended contact at the tip corners,
profile modifications): the same LTCA (model.ltca) with k(x) of the law and of the FE
(model/fe/extended.py) on the same roll nodes. The influence coefficients are cached per
geometry hash on disk (gearcli/io/fe_store.py).
"""

from __future__ import annotations

import numpy as np

from gearcli.results.models import FeCheck, PeFe

_PATH_NODES = 15  # FE load positions on the path (ends included)
_SIDE_NODES = 8  # and on each side of it, up to where the tip gap reaches _GAP_REACH STEs
_GAP_REACH = 3.0  # the loaded contact never reaches a gap of three mean STEs (Harris ≤ 2×)


def _note(teeth: PeFe, contact: PeFe) -> str:
    """What differs, from this pair's numbers (docs/theory.md, "PE law against FE")."""
    return (f"FE vs PE at the pitch point: teeth + body {100 * teeth.fe_over_pe_minus_1:+.1f} %, "
            f"contact term {100 * contact.fe_over_pe_minus_1:+.1f} % (the law's beam is the "
            "centreline's and its contact term Weber's flattening to the centrelines; the FE "
            "reads 0.25 m below the surface and adds Weber's flattening above that depth, so "
            "the split differs by construction and the pair is the comparison). Pairs on the "
            "path: rigid engagement without profile modifications; with the tip corners: the "
            "case's gaps and the same LTCA on both sides (docs/theory.md, 'Finite-element "
            "check of the tooth compliance')")


def _pe_fe(pe: float, fe: float) -> PeFe:
    ratio = float(fe) / float(pe) - 1.0 if float(pe) != 0.0 else None  # JSON null: undefined
    return PeFe(pe=float(pe), fe=float(fe), fe_over_pe_minus_1=ratio)


def _roll_nodes(g, tables, reach_mm: float) -> np.ndarray:
    """FE load positions: on the path and outside it where the drive tip gap G1 + G2 is below
    ``reach_mm`` (the corner contact a load can close), with nodes at A and E (k has a kink
    there, where the tip corner takes over)."""
    from gearcli.core.layout import TABLE_G1, TABLE_G2, TABLE_GAP

    x = tables.x_mm
    gap = tables.tables[TABLE_G1, TABLE_GAP] + tables.tables[TABLE_G2, TABLE_GAP]
    near = x[gap <= reach_mm]
    lo, hi = min(float(near.min()), 0.0), max(float(near.max()), g.g_alpha_mm)
    return np.unique(np.concatenate([np.linspace(lo, 0.0, _SIDE_NODES),
                                     np.linspace(0.0, g.g_alpha_mm, _PATH_NODES),
                                     np.linspace(g.g_alpha_mm, hi, _SIDE_NODES)]))


def _table_law(nodes, k_nodes, tables, g):
    """The tooth law's table (k, dk/dx) on the gap grid from pair stiffness at ``nodes``: a
    monotone cubic (Fritsch & Carlson 1980) on each of [x_a, 0], [0, g_α], [g_α, x_b], constant
    beyond (no contact reaches there at this load)."""
    from scipy.interpolate import PchipInterpolator

    from gearcli.model.ltca import tooth_law

    x = np.clip(tables.x_mm, nodes[0], nodes[-1])
    k, dk = np.empty_like(x), np.zeros_like(x)
    for a, b in ((nodes[0], 0.0), (0.0, g.g_alpha_mm), (g.g_alpha_mm, nodes[-1])):
        sel = (nodes >= a) & (nodes <= b)
        if sel.sum() < 2:
            continue
        f = PchipInterpolator(nodes[sel], k_nodes[sel])
        at = (x >= a) & (x <= b)
        k[at] = f(x[at])
        inner = at & (tables.x_mm > nodes[0]) & (tables.x_mm < nodes[-1])
        dk[inner] = f.derivative()(x[inner])
    return tooth_law(np.stack([k, dk]), tables.x_lo, tables.x_hi)


def loaded_pe_fe(case, geo, force_N: float, law_kw: dict, cache, nodes=None):
    """Loaded STE peak-to-peak [µm] and the share of roll positions with one pair in contact
    by the law and by FE (two PeFe), both with the case's gap tables (extended contact at the
    tip corners, profile modifications) and the same LTCA (model.ltca): only k(x) differs;
    and the roll nodes [mm] of k (given ``nodes``, or those this load reaches)."""
    from gearcli.model.fe.extended import fe_pair_stiffness
    from gearcli.model.gap import slot_layout
    from gearcli.model.ltca import loaded_mesh
    from gearcli.model.pair_stiffness import pair_stiffness
    from gearcli.pipeline.kernel_input import case_gap_tables
    from gearcli.pipeline.mesh_input import case_mesh

    g = geo.geometry
    tables, _ = case_gap_tables(case, geo, case_mesh(case, geo))
    slots = int(slot_layout(g, tables)["n_slots"])
    args = (tables.tables, tables.x_lo, tables.x_hi, g.p_b_mm, slots)
    ps = pair_stiffness(g, tables.x_mm, **law_kw)
    first = loaded_mesh(*args, _table_law(tables.x_mm, ps.k_N_mm, tables, g), force_N, cycles=1)
    if nodes is None:
        nodes = _roll_nodes(g, tables, _GAP_REACH * float(first.ste_mm.mean()))
    # both on the same nodes and interpolant, so only the compliance model differs
    pe = loaded_mesh(*args, _table_law(nodes, pair_stiffness(g, nodes, **law_kw).k_N_mm,
                                       tables, g), force_N, cycles=1)
    k_fe = fe_pair_stiffness(g, nodes, cache=cache, **law_kw)
    fe = loaded_mesh(*args, _table_law(nodes, k_fe, tables, g), force_N, cycles=1)
    return (_pe_fe(1e3 * pe.ste_peak_to_peak_mm, 1e3 * fe.ste_peak_to_peak_mm),
            _pe_fe(np.mean(pe.pairs_in_contact == 1), np.mean(fe.pairs_in_contact == 1)), nodes)


def fe_check(case, geo, force_N: float, store=None) -> FeCheck:
    """The PE/FE comparison of the case's pair at the normal force ``force_N`` [N]; ``store``
    the persistent cache (load/store callbacks, default gearcli.io.fe_store.FEStore)."""
    from gearcli.io.fe_store import FEStore
    from gearcli.model.fe import ComplianceCache, fe_mesh_stiffness
    from gearcli.model.pair_stiffness import mesh_stiffness, pair_stiffness

    g, gears = geo.geometry, case.gears
    m1, m2 = case.material_of("pinion"), case.material_of("gear")
    b = g.narrow_face_width_mm
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
    loaded_ste, single, _ = loaded_pe_fe(case, geo, force_N, law, cache)
    contact = _pe_fe(1.0 / pe.hertz_mm_N[0], 1.0 / fe_local)
    return FeCheck(
        line_load_N_mm=force_N / b, plane_strain=fe.plane_strain,
        pitch_pair_stiffness_N_mm=_pe_fe(pe.k_N_mm[0], fe.pitch_pair_N_mm),
        mesh_mean_stiffness_N_mm=_pe_fe(pe_mesh.mean_N_mm, fe.mean_N_mm),
        ste_peak_to_peak_um=_pe_fe(np.ptp(pe_ste_um), np.ptp(fe.ste_um)),
        teeth_at_pitch_N_mm=teeth, contact_at_pitch_N_mm=contact,
        loaded_ste_peak_to_peak_um=loaded_ste, single_pair_share=single,
        fe_dofs=tuple(int(n) for n in fe.n_dofs), cache_hits=cache.hits,
        cache_misses=cache.misses, seconds=fe.seconds, note=_note(teeth, contact))
