"""FE pair stiffness at any roll position, the tip corner included, for the FE loaded contact
(docs/theory.md, "Finite-element check of the tooth compliance", "Corner contact").

At a pinion roll position x (from A; outside [0, g_α] where a tip touches the mate) each tooth
of the pair carries the normal force at the contact point of the unloaded rigid kinematics
(:func:`gearcli.model.pair_stiffness.pair_contact`): on the path the involute point along the
line of action; before A (gear tip) and after E (pinion tip) the tip corner or rounding on
the mate's involute, the force along the mate's involute normal, turned away from the line
of action. In the tooth frame of :mod:`gearcli.model.fe.sector` (loaded flank at x < 0) the
point is (−h_P, y_P) and the unit force on the tooth (cos α_1, −sin α_1): α_1 the load angle
to the normal of the centreline, positive towards the root (checked against the involute's
own normal on the path, tests/unit/test_fe_model.py). Per tooth the FE gives the global
compliance c_FE read at the depth h behind the point along the force
(:func:`gearcli.model.fe.tooth.fe_tooth_compliance` with ``loads``); Weber's flattening above h
at the Hertz half width of the pair's reduced radius R′ (the law's, ``pair_contact``) is added:

    1/k_pair(x) = [c_FE,1(x) + c_FE,2(x)]/b + [δ_1(h) + δ_2(h)](w)/(w b)      [mm/N]

a secant at the line load w, as the tooth law's contact term. So the FE checks the teeth,
the body and the turned force at the corner (the law's "k rises towards the tip edge"); the
local term at the corner is the same model on both sides.

Units: mm, N, MPa.
"""

from __future__ import annotations

import numpy as np

from gearcli.model.contact_compliance import weber_pair_compliance
from gearcli.model.fe.cache import DEFAULT_CACHE, ComplianceCache
from gearcli.model.fe.tooth import DEFAULT_CONTROL, MeshControl, fe_tooth_compliance, geometry_key
from gearcli.model.geometry import PairGeometry
from gearcli.model.pair_stiffness import pair_contact
from gearcli.model.tooth_stiffness import default_bore_diameter

__all__ = ["fe_pair_stiffness", "tooth_loads"]


def tooth_loads(y_point, h_point, angle) -> tuple[np.ndarray, np.ndarray]:
    """Load points (−h_P, y_P) and unit forces (cos α_1, −sin α_1) in the FE tooth frame."""
    pts = np.column_stack([-np.asarray(h_point, float), np.asarray(y_point, float)])
    a = np.asarray(angle, float)
    return pts, np.column_stack([np.cos(a), -np.sin(a)])


def _gear(gear, loads, bore, youngs, poisson, plane, control, cache):
    """(compliance per load [mm/(N/mm)], reading depth [mm]) of one gear. A sharp tip corner
    is one point for every x outside the path: each distinct point enters the mesh once (one
    vertex), loaded once per direction."""
    pts, dirs = loads
    key_pts = np.round(pts / (1e-9 * gear.module_mm))
    _, first, back = np.unique(key_pts, axis=0, return_index=True, return_inverse=True)
    uniq = pts[first]
    key = geometry_key(gear, uniq.ravel(), dirs=np.round(dirs, 12).tolist(), bore=bore,
                       E=youngs, nu=poisson, plane=plane, n_teeth=None, control=repr(control))
    res = cache.get_or_compute(key, lambda: fe_tooth_compliance(
        gear, None, bore_diameter_mm=bore, youngs_MPa=youngs, poisson=poisson,
        plane_strain=plane, control=control, loads=(uniq, dirs), point_of_load=back.ravel()))
    return res.compliance_mm2_N, res.depth_mm


def fe_pair_stiffness(pair: PairGeometry, x_mm, *, face_width_mm: float, load_N_mm: float,
                      E1_MPa: float, nu1: float, E2_MPa: float, nu2: float,
                      plane_strain: bool, bore_diameter1_mm: float | None = None,
                      bore_diameter2_mm: float | None = None,
                      control: MeshControl = DEFAULT_CONTROL,
                      cache: ComplianceCache | None = None) -> np.ndarray:
    """FE pair stiffness k(x) [N/mm] at pinion roll positions ``x_mm`` (inside or outside the
    path), a secant at the line load ``load_N_mm`` w [N/mm] (module notes); the whole gears,
    clamped at the bores (default d_f/3, as the tooth law). One FE model per gear for all x.

    Raises :class:`gearcli.model.fe.deps.FEUnavailableError` without the extra ``fe``.
    """
    cache = DEFAULT_CACHE if cache is None else cache
    x = np.asarray(x_mm, float).ravel()
    c = pair_contact(pair, x)
    bores = (default_bore_diameter(pair.pinion) if bore_diameter1_mm is None
             else bore_diameter1_mm,
             default_bore_diameter(pair.gear) if bore_diameter2_mm is None
             else bore_diameter2_mm)
    (c1, h1) = _gear(pair.pinion, tooth_loads(c.y_point1_mm, c.h_point1_mm, c.angle1_rad), bores[0],
               E1_MPa, nu1, plane_strain, control, cache)
    (c2, h2) = _gear(pair.gear, tooth_loads(c.y_point2_mm, c.h_point2_mm, c.angle2_rad), bores[1],
               E2_MPa, nu2, plane_strain, control, cache)
    local = weber_pair_compliance(load_N_mm, c.reduced_radius_mm, h1, h2,
                                  face_width_mm=face_width_mm, E1_MPa=E1_MPa, nu1=nu1,
                                  E2_MPa=E2_MPa, nu2=nu2, plane_strain=plane_strain)
    return 1.0 / ((c1 + c2) / face_width_mm + local)
