"""The case's mesh at its operating load: static force, contact stiffness and the one
linearisation (model.mesh.mesh_mode) that both `simulate` (tolerances, output rate,
validity limit) and `modal` (the linear model) use."""

from __future__ import annotations

from gearcli.case.schema import Case
from gearcli.model.mesh import MeshMode, mesh_mode, static_normal_force_N
from gearcli.model.stiffness import derived_pair_stiffness
from gearcli.pipeline.geometry import GeometryResult


def static_force_N(case: Case, geo: GeometryResult) -> float:
    """F_n,static [N] of the load torque at the end of its ramps (docs/theory.md §7)."""
    final = case.load.torque.pp.final_value()
    torque = final if final is not None else float(case.load.torque.pp(case.run.end_time))
    return static_normal_force_N(torque, geo.geometry.gear.r_b_mm)


def iso_stiffness(case: Case, geo: GeometryResult, force_N: float | None = None):
    """ISO 6336-1 Method B stiffness of the case's pair (model.stiffness) at its static
    normal force (or ``force_N`` [N]) and material."""
    force = static_force_N(case, geo) if force_N is None else force_N
    return derived_pair_stiffness(geo.geometry, case.gears.rack.dedendum,
                                  force * geo.geometry.gear.r_b_mm,
                                  case.material.youngs_modulus)


def contact_stiffness(case: Case, geo: GeometryResult) -> float:
    """k of the IMPACT law [N/mm^e]: given, or 'derived' (e = 1): the constant pair stiffness
    whose mean over the mesh cycle, ε_α k, is ISO 6336-1's c_γα b (docs/theory.md §4)."""
    if case.contact.stiffness != "derived":
        return float(case.contact.stiffness)
    return iso_stiffness(case, geo).mesh_stiffness_N_mm / geo.geometry.eps_alpha


def case_mesh(case: Case, geo: GeometryResult) -> MeshMode:
    """The mesh linearised at the static load (docs/theory.md §4, §6): with a prescribed pinion
    speed only the gear vibrates, else both gears are free."""
    g, ct = geo.geometry, case.contact
    return mesh_mode(static_force_N(case, geo), g.eps_alpha, contact_stiffness(case, geo),
                     ct.exponent, ct.max_damping, ct.penetration_depth, g.pinion.r_b_mm,
                     g.gear.r_b_mm, geo.mass[0].inertia_t_mm2, geo.mass[1].inertia_t_mm2,
                     pinion_free=case.drive.type != "speed")
