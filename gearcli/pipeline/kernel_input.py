"""Case -> the compiled kernel's plain inputs (parameter vector, tables, time functions).

Conventions (docs/theory.md §1, §3; core/rhs.py): θ1 = 0 is the instant a drive tooth pair touches
at the pitch point C; the pinion turns counter-clockwise, the gear clockwise; roll positions x
are measured from A along the line of action.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from gearcli.case.schema import Case, PitchDeviation, ProfileSlopeDeviation
from gearcli.case.schema import Relief as CaseRelief
from gearcli.case.schema_faults import fault_records
from gearcli.core import layout
from gearcli.model.accuracy import draw_deviations
from gearcli.model.errors import (
    cumulative_pitch_positions,
    profile_slope_gaps,
    runout_phases,
    tooth_offsets,
)
from gearcli.model.faults import tooth_index_offsets
from gearcli.model.frequencies import mesh_frequencies
from gearcli.model.gap import GapTables, Modifications, Relief, gap_tables, slot_layout
from gearcli.model.mesh import MeshMode
from gearcli.model.structure import Structure
from gearcli.pipeline.geometry import GeometryResult
from gearcli.pipeline.mesh_input import case_mesh, contact_stiffness, tooth_stiffness
from gearcli.pipeline.structure import build_structure

#: Output sampling: the analysed band reaches 10 mesh harmonics; 2.56 samples per
#: period of the highest one is the usual anti-aliasing margin of vibration analysers.
HARMONICS_RESOLVED = 10
SAMPLES_PER_PERIOD = 2.56


@dataclass(frozen=True)
class KernelInput:
    """Everything the kernel needs, plus the derived quantities the outputs report."""

    params: np.ndarray
    tables: GapTables
    #: Per-pair / per-tooth model arrays by their field name in gearcli.core.bundles.Model
    #: (keyword arguments of gearcli.core.integrate.simulate), e.g. ``tooth_offsets``.
    arrays: dict
    drive_pp: tuple
    drive_angle_pp: tuple | None
    load_pp: tuple
    t_out: np.ndarray
    mesh: MeshMode
    gear_mesh_frequency_Hz: float | None
    output_rate_Hz: float


def _relief(r: CaseRelief | None) -> Relief | None:
    if r is None:
        return None
    return Relief(r.amount, r.length, r.start_diameter, r.shape)


def modifications(case: Case) -> Modifications:
    m = case.modifications
    return Modifications(
        pinion_tip=_relief(m.tip_relief.pinion),
        gear_tip=_relief(m.tip_relief.gear),
        pinion_root=_relief(m.root_relief.pinion),
        gear_root=_relief(m.root_relief.gear),
    )


def _pitch_positions(dev: PitchDeviation | None, gear, m_mm: float) -> np.ndarray:
    """Flank positions [mm] of a gear's teeth from the case's pitch deviations (model.errors)."""
    if dev is None:
        return np.zeros(gear.teeth)
    return cumulative_pitch_positions(dev.values, dev.iso1328_grade, dev.seed, gear.teeth,
                                      gear.d_mm, m_mm)


def _profile_slopes_mm(dev: ProfileSlopeDeviation | None, gear, m_mm: float) -> np.ndarray:
    """f_Hα per tooth [mm] of a gear from the case (values, or the draws of an ISO 1328-1
    grade with its seed, model.accuracy); zeros without."""
    if dev is None:
        return np.zeros(gear.teeth)
    if dev.values is not None:
        return np.asarray(dev.values, float)
    return 1e-3 * draw_deviations(dev.iso1328_grade, gear.d_mm, m_mm, gear.teeth,
                                  dev.seed).profile_slope_um


def _profile_arrays(case: Case, g, tables: GapTables) -> dict[str, np.ndarray]:
    """The kernel's tooth_profile_gap (docs/theory.md §3.5) when any profile slope deviation
    is non-zero, else nothing (the kernel's path without profile deviations)."""
    pd = case.errors.profile_slope_deviation
    f1 = _profile_slopes_mm(pd.pinion, g.pinion, g.module_mm)
    f2 = _profile_slopes_mm(pd.gear, g.gear, g.module_mm)
    if not (np.any(f1 != 0.0) or np.any(f2 != 0.0)):
        return {}
    return {"tooth_profile_gap": profile_slope_gaps(f1, f2, tables.x_lo, tables.x_hi,
                                                    g.g_alpha_mm)}


def output_times(case: Case, f_z: float | None) -> tuple[np.ndarray, float]:
    """Sample times [s] and rate [Hz]: the case's steps/rate, or enough for 10 harmonics."""
    run = case.run
    t_end = run.end_time
    if run.output_steps is not None:
        n = run.output_steps
    else:
        if run.output_rate is not None:
            rate = run.output_rate
        elif f_z is not None and f_z > 0.0:
            rate = SAMPLES_PER_PERIOD * HARMONICS_RESOLVED * f_z
        else:
            rate = 10_000.0
        n = max(int(math.ceil(t_end * rate)), 10)
    t = np.linspace(0.0, t_end, n + 1)
    return t, n / t_end


@functools.lru_cache(maxsize=16)
def _gap_tables(geometry, mods, engagement: str, cap_mm: float) -> GapTables:
    """gap_tables, memoised per process: the points of a sweep that keep the geometry (speed,
    load, damping, ...) share their tables (~0.15 s each to build). The inputs are frozen
    dataclasses; the tables are only read."""
    return gap_tables(geometry, mods, engagement, cap_mm=cap_mm)


#: Default absolute tolerance on deflections: this fraction of the static deflection ...
ATOL_PER_STATIC_DEFLECTION = 1e-5
#: ... and at most this [mm] (also the value without load).
ATOL_MAX_MM = 1e-6


def deflection_atol(atol_mm: float | None, static_deflection_mm: float) -> float:
    """Absolute tolerance [mm] on the mesh deflection (and s1, the optional displacements).

    ``run.atol`` when the case gives it, else 1e-5 of the static deflection, at most 1e-6 mm
    (docs/theory.md §6.7: δ is a small difference of large rotations, so the step control
    rests on atol; 1e-6 mm was 1e-5 of the seed's IMPACT deflection but 4e-4 of a tooth-law
    deflection, where the dynamic factor above resonance moved by 3.6 % under refinement).
    """
    if atol_mm is not None:
        return atol_mm
    if static_deflection_mm > 0.0:
        return min(ATOL_MAX_MM, ATOL_PER_STATIC_DEFLECTION * static_deflection_mm)
    return ATOL_MAX_MM


def case_gap_tables(case: Case, geo: GeometryResult, mesh: MeshMode) -> tuple[GapTables, float]:
    """The case's gap tables (model.gap) and their cap [mm]: tip gaps are tabulated up to well
    beyond the deflections a run can reach, max(0.05 m, 20 static deflections)."""
    cap = max(0.05 * geo.geometry.module_mm, 20.0 * mesh.static_deflection_mm)
    return _gap_tables(geo.geometry, modifications(case), case.contact.engagement, cap), cap


def _structure_params(st: Structure) -> dict[str, float]:
    """Kernel parameters of the optional bodies: motor and load inertias, lateral supports."""
    out = {"motor_J": st.motor_inertia_t_mm2, "load_J": st.load_inertia_t_mm2,
           "load_k": st.load_shaft_stiffness_Nmm_rad, "load_c": st.load_shaft_damping_Nmms_rad,
           "sin_aw": math.sin(st.alpha_w_rad), "cos_aw": math.cos(st.alpha_w_rad)}
    if st.lateral:
        out.update(lateral=1.0, m1=st.m1_t, m2=st.m2_t)
        for i, sup in ((1, st.pinion_support), (2, st.gear_support)):
            out.update({f"kx{i}": sup.stiffness_x_N_mm, f"ky{i}": sup.stiffness_y_N_mm,
                        f"cx{i}": sup.damping_x_Ns_mm, f"cy{i}": sup.damping_y_Ns_mm})
    return out


def _contact_params(case: Case, geo: GeometryResult, mesh: MeshMode) -> dict[str, float]:
    """Kernel parameters of the contact law (docs/theory.md §4, §4b, §4c)."""
    ct = case.contact
    if ct.law == "tooth":  # k_contact: the mean pair stiffness, for reports; the table rules
        # reference force of the damping share: the static force, or without load the force
        # of a 1 um mesh deflection (docs/theory.md §4c)
        f_ref = mesh.static_force_N if mesh.static_force_N > 0.0 \
            else 1e-3 * mesh.mesh_stiffness_N_mm
        return {"contact_law": layout.LAW_TOOTH, "mesh_damping": mesh.mesh_damping_Ns_mm,
                "damping_force_ref": f_ref,
                "k_contact": mesh.pair_stiffness_N_mm, "exponent": 1.0, "c_max": 0.0}
    return {"contact_law": layout.LAW_IMPACT, "k_contact": contact_stiffness(case, geo),
            "exponent": ct.exponent, "c_max": ct.max_damping, "d_max": ct.penetration_depth}


def _contact_arrays(case: Case, geo: GeometryResult, tables: GapTables) -> dict:
    """The tooth law's pair stiffness table on the gap tables' grid (core.bundles.Model
    ``pair_stiffness``): k and dk/dx per flank family; the coast family of symmetric teeth
    has the drive family's values at its own roll position (model.pair_stiffness)."""
    if case.contact.law != "tooth":
        return {}
    ps = tooth_stiffness(case, geo, tables.x_mm)
    family = np.stack([ps.k_N_mm, ps.dk_dx_N_mm2])
    return {"pair_stiffness": np.stack([family] * layout.N_FAMILIES)}


#: Roll positions per mesh cycle of the loaded contact that linearises the tooth law.
LINEARISATION_POINTS = 100


def linearised_mesh(case: Case, geo: GeometryResult, geometric: MeshMode | None = None,
                    tables: GapTables | None = None) -> MeshMode:
    """The mesh linearised at the static load (the one `simulate`, `modal` and the checks use).

    IMPACT law: :func:`gearcli.pipeline.mesh_input.case_mesh` (closed form, docs/theory.md §4).
    Tooth law: the mean over a mesh cycle of the loaded contact's tangent stiffness, the single-
    and double-pair zone values from the same solution (model/ltca.py, what `gearcli mesh`
    reports), at LINEARISATION_POINTS positions: it has the case's profile modifications and
    the corner contact of extended engagement, which the sum of the pair stiffness over the
    geometric path of contact (``case_mesh``) leaves out (docs/theory.md §4b). Without a load,
    or when the teeth cannot carry it, the geometric value. ``geometric`` and ``tables``: the
    case's ``case_mesh`` and :func:`case_gap_tables` when the caller has them."""
    from gearcli.model.ltca import loaded_mesh, tooth_law
    from gearcli.model.mesh import with_mesh_stiffness

    mesh = geometric if geometric is not None else case_mesh(case, geo)
    if case.contact.law != "tooth" or not mesh.static_force_N > 0.0:
        return mesh
    g = geo.geometry
    if tables is None:
        tables, _ = case_gap_tables(case, geo, mesh)
    ps = tooth_stiffness(case, geo, tables.x_mm)
    law = tooth_law(np.stack([ps.k_N_mm, ps.dk_dx_N_mm2]), tables.x_lo, tables.x_hi)
    slots = int(slot_layout(g, tables)["n_slots"])
    try:
        lm = loaded_mesh(tables.tables, tables.x_lo, tables.x_hi, g.p_b_mm, slots, law,
                         mesh.static_force_N, cycles=1, points_per_cycle=LINEARISATION_POINTS)
    except ValueError:  # no static equilibrium: the run itself will say so
        return mesh
    return with_mesh_stiffness(mesh, float(lm.mesh_stiffness_N_mm.mean()),
                               lm.zone_stiffness_N_mm(1), lm.zone_stiffness_N_mm(2))


def factor_positions(tables: GapTables, n: int) -> np.ndarray:
    """The pinion roll positions x1 [mm] of a tooth stiffness factor table with ``n`` columns:
    ``n`` points evenly spaced over the gap tables' range [x_lo, x_hi] (docs/theory.md §4b.2)."""
    return np.linspace(tables.x_lo, tables.x_hi, n)


def stiffness_factor_array(factors, geo: GeometryResult) -> np.ndarray:
    """The kernel's ``tooth_stiffness_factor`` (core.bundles.Model) from a table given by
    the caller, checked: shape (rows, max(z1, z2), n >= 2) (columns at
    :func:`factor_positions`) or (rows, max(z1, z2)) (constant along the path), rows 2
    (pinion, gear; both flank families) or 4 (drive pinion, drive gear, coast pinion, coast
    gear, as the tooth offsets); finite and >= 0 (0: the tooth carries nothing). Entries
    beyond a gear's tooth count are not read."""
    a = np.asarray(factors, dtype=np.float64)
    z = max(geo.geometry.pinion.teeth, geo.geometry.gear.teeth)
    if a.ndim not in (2, 3) or a.shape[0] not in (layout.N_GEARS, layout.N_TABLES) \
            or a.shape[1] != z or (a.ndim == 3 and a.shape[2] < 2):
        raise ValueError(f"tooth stiffness factors need shape ({layout.N_GEARS} or "
                         f"{layout.N_TABLES}, {z}, n >= 2) or ({layout.N_GEARS} or "
                         f"{layout.N_TABLES}, {z}), got {a.shape}")
    if not np.all(np.isfinite(a)) or np.any(a < 0.0):
        raise ValueError("tooth stiffness factors must be finite and >= 0")
    return a


#: Factor-table columns per base pitch for tooth faults (a step of p_b/200: 0.15 mm at m = 10).
FAULT_POSITIONS_PER_PITCH = 200


def fault_factor_table(case: Case, geo: GeometryResult, tables: GapTables, mesh: MeshMode,
                       faults, columns: int | None = None) -> np.ndarray | None:
    """The factor table of tooth ``faults`` (model.faults records) at :func:`factor_positions`
    (``columns`` of them, default FAULT_POSITIONS_PER_PITCH per base pitch): the case's healthy
    pair stiffness there, spalls against the static deflection (docs/theory.md, "Tooth
    faults"). None when every fault has zero size (the run is the healthy one bit for bit)."""
    from gearcli.model.faults import is_void
    from gearcli.model.faults.factors import fault_factors

    g = geo.geometry
    if columns is None:
        columns = math.ceil((tables.x_hi - tables.x_lo) / g.p_b_mm * FAULT_POSITIONS_PER_PITCH) + 1
    x = factor_positions(tables, columns)
    table = fault_factors(g, tooth_stiffness(case, geo, x), faults,
                          deflection_mm=mesh.loaded_deflection_mm)
    return None if all(is_void(f) for f in faults) else table


def _factors(case, geo, tables, mesh, explicit, faults):
    """The run's factor table: the caller's (checked), the faults' (four rows), or their
    product (a two-row table serves both flank families, a 2-D one the whole path)."""
    table = None if explicit is None else stiffness_factor_array(explicit, geo)
    if faults:
        n = table.shape[2] if table is not None and table.ndim == 3 else None
        fault_table = fault_factor_table(case, geo, tables, mesh, faults, n)
        if fault_table is not None and table is not None:
            given = table if table.ndim == 3 else table[:, :, None]
            table = fault_table * np.tile(given, (layout.N_TABLES // given.shape[0], 1, 1))
        elif fault_table is not None:
            table = fault_table
    return {} if table is None else {"tooth_stiffness_factor": table}


def build_kernel_input(case: Case, geo: GeometryResult, tooth_stiffness_factor=None,
                       faults=None) -> KernelInput:
    """Assemble the kernel's inputs from a validated case and its checked geometry.

    ``tooth_stiffness_factor``: optional per-tooth, per-position stiffness factors
    (:func:`stiffness_factor_array`), carried to the kernel in ``arrays``; ``faults``: tooth
    faults (model.faults records; default the case's ``faults:``), turned into factors by
    :func:`fault_factor_table` (times the given factors when both are given). Absent, or
    faults of zero size only, the run is the one without factors bit for bit. Tooth
    indices: docs/theory.md, "Tooth faults".
    """
    g = geo.geometry
    faults = fault_records(case.faults) if faults is None else faults
    rb1, rb2 = g.pinion.r_b_mm, g.gear.r_b_mm
    J1, J2 = geo.mass[0].inertia_t_mm2, geo.mass[1].inertia_t_mm2
    fr, dr = case.friction, case.drive
    mode = {"speed": layout.DRIVE_SPEED, "shaft": layout.DRIVE_SHAFT,
            "torque": layout.DRIVE_TORQUE}[dr.type]
    geometric = case_mesh(case, geo)
    tables, cap = case_gap_tables(case, geo, geometric)
    mesh = linearised_mesh(case, geo, geometric, tables)

    speed = geo.pinion_speed_rad_s
    f_z = mesh_frequencies(g.pinion.teeth, speed, g.ratio)[0] if speed else None
    t_out, rate = output_times(case, f_z)

    ro = case.errors.runout
    ecc1, phi1 = (ro.pinion.eccentricity, ro.pinion.phase) if ro.pinion else (0.0, 0.0)
    ecc2, phi2 = (ro.gear.eccentricity, ro.gear.phase) if ro.gear else (0.0, 0.0)
    pd = case.errors.pitch_deviation
    offsets = tooth_offsets(_pitch_positions(pd.pinion, g.pinion, g.module_mm),
                            _pitch_positions(pd.gear, g.gear, g.module_mm))

    bearing = case.bearings
    params = layout.make_params(
        t_start=0.0,
        t_end=case.run.end_time,
        theta1_init=0.0,
        omega1_init=dr.initial_speed,
        r_b1=rb1, r_b2=rb2, J1=J1, J2=J2,
        z1=g.pinion.teeth, z2=g.gear.teeth,
        p_b=g.p_b_mm, T1A=g.A_mm, T1T2=g.T1T2_mm,
        x_lo=tables.x_lo, x_hi=tables.x_hi, **(slots := slot_layout(g, tables)),
        **tooth_index_offsets(g, tables.x_lo, slots), backlash_n=g.j_n_mm,
        ecc1=ecc1, ecc2=ecc2, **runout_phases(phi1, phi2, g.alpha_w_rad),
        **_contact_params(case, geo, mesh),
        mu_s=fr.static_coefficient if fr.enabled else 0.0,
        mu_d=fr.dynamic_coefficient if fr.enabled else 0.0,
        v_s=fr.stiction_velocity, v_d=fr.transition_velocity,
        drive_mode=mode,
        shaft_k=dr.shaft.stiffness if dr.shaft else 0.0,
        shaft_c=dr.shaft.damping if dr.shaft else 0.0,
        motor_omega0=dr.motor_curve.no_load_speed if dr.motor_curve else 0.0,
        c1=bearing.pinion.damping, c2=bearing.gear.damping,
        **_structure_params(build_structure(case, geo)),
        load_cv=case.load.viscous, load_cq=case.load.quadratic,
        rtol=case.run.rtol,
        atol_delta=(atol := deflection_atol(case.run.atol, mesh.static_deflection_mm)),
        atol_deltadot=atol * 2.0 * math.pi * max(mesh.natural_frequency_Hz, 1.0),
        max_step=case.run.max_step if case.run.max_step is not None else math.inf,
        # A penetration beyond the tabulated tip gaps means the model left its validity.
        penetration_limit=cap,
    )
    drive_fn = dr.torque if mode == layout.DRIVE_TORQUE else dr.speed
    angle = None if mode == layout.DRIVE_TORQUE else drive_fn.pp.antiderivative().to_arrays()
    return KernelInput(
        params=params,
        tables=tables,
        arrays={"tooth_offsets": offsets, **_contact_arrays(case, geo, tables),
                **_profile_arrays(case, g, tables),
                **_factors(case, geo, tables, mesh, tooth_stiffness_factor, faults)},
        drive_pp=drive_fn.pp.to_arrays(),
        drive_angle_pp=angle,
        load_pp=case.load.torque.pp.to_arrays(),
        t_out=t_out,
        mesh=mesh,
        gear_mesh_frequency_Hz=f_z,
        output_rate_Hz=rate,
    )
