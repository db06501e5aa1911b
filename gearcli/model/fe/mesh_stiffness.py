"""FE tooth-pair and mesh stiffness of a spur pair (docs/theory.md, "Finite-element check of
the tooth compliance").

Per roll position x (pinion, from A along the line of action) the contact radii of rigid
engagement are r_1 = √(r_b1² + (|T1A| + x)²), r_2 = √(r_b2² + (|T1T2| − |T1A| − x)²); each
gear's global FE compliance c_i(r_i) comes from :func:`gearcli.model.fe.tooth.fe_tooth_compliance`
(read at the depth h_i below the contact) and the flattening above h_i from Weber's term δ_i
(:mod:`gearcli.model.fe.hertz`) at the pair's line load w_p and the Hertz half width
a(w_p, R′(x)), R′ = ρ_1 ρ_2/(ρ_1 + ρ_2), ρ_1 = |T1A| + x, ρ_2 = |T1T2| − ρ_1 (involute radii
of curvature). In series, per face width b:

    1/k_pair(x; w_p) = [c_1(r_1) + c_2(r_2)] / b + [δ_1 + δ_2](w_p) / (w_p b)     [mm/N]

The pairs on the path (0 ≤ x + j p_b ≤ g_α) act in parallel with the rigid-engagement load
sharing of the LTCA without modifications: all pairs have the same approach, so
w_j ∝ k_pair,j, solved by a fixed point (the local term depends on w_j only through ln a);
k_mesh = Σ_j k_pair,j, the loaded static transmission error is F/k_mesh.

Plane state (face-width rule): plane strain when b ≥ 5 m (the face is at least about twice
the tooth height 2.25 m, so the mid-face section is constrained across the face), plane stress
otherwise; either can be forced.

Units: mm, N, MPa.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline

from gearcli.model.fe.cache import DEFAULT_CACHE, ComplianceCache
from gearcli.model.fe.hertz import contact_modulus, hertz_half_width, weber_approach
from gearcli.model.fe.tooth import (
    DEFAULT_CONTROL,
    FEToothCompliance,
    MeshControl,
    fe_tooth_compliance,
    geometry_key,
)
from gearcli.model.geometry import PairGeometry
from gearcli.model.tooth_stiffness import default_bore_diameter

__all__ = ["FEMeshStiffness", "fe_mesh_stiffness", "plane_strain_rule"]

PLANE_STRAIN_MIN_WIDTH_MODULES = 5.0  #: b/m at and above which the model is plane strain
_SHARING_ITERATIONS = 8  # fixed point of the load shares (ln a dependence: converges fast)


def plane_strain_rule(face_width_mm: float, module_mm: float) -> bool:
    """Plane strain when b ≥ 5 m, plane stress below (module notes)."""
    return face_width_mm >= PLANE_STRAIN_MIN_WIDTH_MODULES * module_mm


@dataclass(frozen=True)
class FEMeshStiffness:
    """FE single-tooth compliances, pair and mesh stiffness of a pair (module notes)."""

    x_mm: np.ndarray  #: roll positions from A on the path [mm]
    radius1_mm: np.ndarray  #: pinion contact radii [mm]
    radius2_mm: np.ndarray  #: gear contact radii [mm]
    tooth1_mm_N: np.ndarray  #: pinion global FE compliance c_1/b [mm/N]
    tooth2_mm_N: np.ndarray  #: gear global FE compliance c_2/b [mm/N]
    local_mm_N: np.ndarray  #: Weber flattening of both bodies at the full load, /(w b) [mm/N]
    pair_N_mm: np.ndarray  #: single-pair stiffness carrying the full load [N/mm]
    pitch_pair_N_mm: float  #: k_pair at the pitch point C [N/mm]
    mesh_x_mm: np.ndarray  #: roll position of the leading pair over one base pitch [mm]
    mesh_N_mm: np.ndarray  #: mesh stiffness with rigid-engagement load sharing [N/mm]
    mesh_pairs: np.ndarray  #: pairs in contact
    mean_N_mm: float  #: mean mesh stiffness over a base pitch [N/mm]
    ste_um: np.ndarray  #: loaded static transmission error F/k_mesh [µm] along the LoA
    load_N_mm: float  #: line load w = F/b [N/mm]
    depth1_mm: float  #: reading depth below the contact, pinion [mm]
    depth2_mm: float  #: gear [mm]
    plane_strain: bool
    n_dofs: tuple[int, int]  #: FE model sizes (pinion, gear)
    seconds: float  #: wall time, FE solves included unless cached [s] (reported only)


def _gear_compliance(gear, radii, bore, youngs, poisson, plane, n_teeth, control, cache):
    key = geometry_key(gear, radii, bore=bore, E=youngs, nu=poisson, plane=plane,
                       n_teeth=n_teeth, control=repr(control))
    return cache.get_or_compute(key, lambda: fe_tooth_compliance(
        gear, radii, bore_diameter_mm=bore, youngs_MPa=youngs, poisson=poisson,
        plane_strain=plane, n_teeth=n_teeth, control=control))


@dataclass(frozen=True)
class _PairLaw:
    """Pair compliance on the roll grid: splines of the two global parts + the local term."""

    c_global: CubicSpline  #: (c_1 + c_2)/b [mm/N] of x
    pair: PairGeometry
    depths: tuple[float, float]
    mats: tuple[float, float, float, float]
    plane: bool
    b: float

    def compliance(self, x, w):
        """1/k_pair [mm/N] at roll positions x for pair line loads w [N/mm]."""
        e1, nu1, e2, nu2 = self.mats
        rho1 = self.pair.A_mm + x
        r_red = rho1 * (self.pair.T1T2_mm - rho1) / self.pair.T1T2_mm
        a = hertz_half_width(w, r_red, contact_modulus(e1, nu1, e2, nu2))
        local = (weber_approach(w, self.depths[0], a, e1, nu1, self.plane)
                 + weber_approach(w, self.depths[1], a, e2, nu2, self.plane))
        return self.c_global(x) + local / (w * self.b)


def _mesh(law: _PairLaw, w: float, n_points: int):
    """Mesh stiffness over one base pitch with rigid-engagement load sharing."""
    p_b, g_a = law.pair.p_b_mm, law.pair.g_alpha_mm
    x = np.linspace(0.0, p_b, n_points, endpoint=False)
    shifts = x[None, :] + p_b * np.arange(int(math.ceil(g_a / p_b)) + 1)[:, None]
    inside = shifts <= g_a
    xs = np.where(inside, shifts, 0.0)
    share = inside / inside.sum(axis=0)
    for _ in range(_SHARING_ITERATIONS):
        k = np.where(inside, 1.0 / law.compliance(xs, np.maximum(share * w, 1e-12)), 0.0)
        share = k / k.sum(axis=0)
    k_mesh = k.sum(axis=0)
    return x, k_mesh, inside.sum(axis=0)


def fe_mesh_stiffness(pair: PairGeometry, *, face_width_mm: float, load_N_mm: float,
                      E1_MPa: float, nu1: float, E2_MPa: float, nu2: float,
                      bore_diameter1_mm: float | None = None,
                      bore_diameter2_mm: float | None = None,
                      plane_strain: bool | None = None, n_roll: int = 21,
                      n_teeth: int | None = None, control: MeshControl = DEFAULT_CONTROL,
                      cache: ComplianceCache | None = None,
                      n_mesh_points: int = 400) -> FEMeshStiffness:
    """FE pair and mesh stiffness of ``pair`` along its path of contact (module notes).

    Parameters
    ----------
    pair : PairGeometry
        From :func:`gearcli.model.geometry.compute_pair_geometry`.
    face_width_mm : float
        Contact face width b [mm].
    load_N_mm : float
        Line load w = F_bn/b [N/mm] of the mesh (normal force per face width); the Weber term
        is evaluated at each pair's share of it.
    E1_MPa, nu1, E2_MPa, nu2 : float
        Young's modulus [MPa] and Poisson's ratio of pinion and gear.
    bore_diameter1_mm, bore_diameter2_mm : float, optional
        Clamped bore diameters [mm]; default
        :func:`gearcli.model.tooth_stiffness.default_bore_diameter` (d_f/3), as the tooth law.
    plane_strain : bool, optional
        Plane state; default :func:`plane_strain_rule`.
    n_roll : int
        FE load positions per gear, equally spaced on the path (ends included).
    n_teeth : int, optional
        Odd tooth count of a sector clamped on its sides; None (default): the whole gear.
    control : MeshControl
        Element sizes and reading depth.
    cache : ComplianceCache, optional
        Where influence coefficients are kept; default the process-wide in-memory cache.
    n_mesh_points : int
        Samples over one base pitch of the mesh stiffness.

    Raises
    ------
    gearcli.model.fe.deps.FEUnavailableError
        Without the optional extra ``fe``.
    """
    t0 = time.perf_counter()
    cache = DEFAULT_CACHE if cache is None else cache
    plane = plane_strain_rule(face_width_mm, pair.module_mm) if plane_strain is None \
        else plane_strain
    x = np.linspace(0.0, pair.g_alpha_mm, n_roll)
    rho1 = pair.A_mm + x
    r1 = np.hypot(pair.pinion.r_b_mm, rho1)
    r2 = np.hypot(pair.gear.r_b_mm, pair.T1T2_mm - rho1)
    bores = (default_bore_diameter(pair.pinion) if bore_diameter1_mm is None
             else bore_diameter1_mm,
             default_bore_diameter(pair.gear) if bore_diameter2_mm is None
             else bore_diameter2_mm)
    c1: FEToothCompliance = _gear_compliance(pair.pinion, r1, bores[0], E1_MPa, nu1, plane,
                                             n_teeth, control, cache)
    c2: FEToothCompliance = _gear_compliance(pair.gear, r2, bores[1], E2_MPa, nu2, plane,
                                             n_teeth, control, cache)
    b = face_width_mm
    t1, t2 = c1.compliance_mm2_N / b, c2.compliance_mm2_N / b
    law = _PairLaw(CubicSpline(x, t1 + t2), pair, (c1.depth_mm, c2.depth_mm),
                   (E1_MPa, nu1, E2_MPa, nu2), plane, b)
    full = law.compliance(x, np.full(x.size, load_N_mm))
    x_c = pair.C_mm - pair.A_mm
    mx, k_mesh, pairs = _mesh(law, load_N_mm, n_mesh_points)
    return FEMeshStiffness(
        x, r1, r2, t1, t2, full - t1 - t2, 1.0 / full,
        float(1.0 / law.compliance(np.array([x_c]), np.array([load_N_mm]))[0]),
        mx, k_mesh, pairs, float(k_mesh.mean()), 1e3 * load_N_mm * b / k_mesh, load_N_mm,
        c1.depth_mm, c2.depth_mm, plane, (c1.n_dofs, c2.n_dofs), time.perf_counter() - t0)
