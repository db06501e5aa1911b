"""FE compliance of one gear's tooth at contact radii: the global part, read below the contact.

Per gear (docs/theory.md, "Finite-element check of the tooth compliance"): the sector of
:mod:`gearcli.model.fe.sector` is clamped at the bore (and on its radial sides, the cut to the
rest of the body), meshed and factorised once; for each contact radius a unit point load
(1 N per mm of face width) acts on the involute along the inward flank normal (the line of
action of a mate in rigid engagement). The displacement of the point at depth h below the
contact, along the normal, projected on the load direction, is the global compliance c_FE(r)
[mm/(N/mm)]: tooth bending, shear, compression, fillet and body, and the half-plane
compression below h. The flattening between the surface and the depth h is not read from the
FE (the point load is singular there): it is Weber's analytical term
(:mod:`gearcli.model.fe.hertz`), added per gear by :mod:`gearcli.model.fe.mesh_stiffness`. The
sum does not depend on the mesh at the load point nor, to O((a/h)²), on h.

Units: mm, N, MPa; compliances per unit face width are mm/(N/mm) = mm²/N.
"""

from __future__ import annotations

import hashlib
import time
from dataclasses import dataclass

import numpy as np

from gearcli.model.fe.elasticity import PlaneBody
from gearcli.model.fe.sector import BORE, SIDE, flank_point_normal, sector_outline
from gearcli.model.toothform import ToothForm

__all__ = ["DEFAULT_CONTROL", "FEToothCompliance", "MeshControl", "fe_tooth_compliance",
           "geometry_key"]


@dataclass(frozen=True)
class MeshControl:
    """Element sizes as fractions of the module, divided by ``refinement``.

    ``fine``: boundary spacing on the loaded tooth; ``coarse``: on the other teeth, the
    sides and the bore; ``max_area``: largest element area in units of m².
    ``depth``: reading depth h below the contact in units of m (module notes).
    """

    refinement: float = 1.0
    fine: float = 0.04
    coarse: float = 0.3
    max_area: float = 4.0
    depth: float = 0.25
    clamp_sides: bool = True


DEFAULT_CONTROL = MeshControl()  #: the default element sizes and reading depth


@dataclass(frozen=True)
class FEToothCompliance:
    """Global FE compliance of one tooth at contact radii (per unit face width)."""

    radius_mm: np.ndarray  #: contact radii on the involute [mm]
    compliance_mm2_N: np.ndarray  #: c_FE(r): displacement at depth h per unit line load
    depth_mm: float  #: reading depth h [mm]
    n_dofs: int  #: degrees of freedom of the model
    n_teeth: int  #: teeth in the sector
    bore_diameter_mm: float  #: clamped bore diameter [mm]
    plane_strain: bool
    seconds: float  #: wall time of mesh + assembly + solve [s] (reported, never asserted)


def geometry_key(gear: ToothForm, radii_mm, **params) -> str:
    """Hash of everything the FE compliance depends on: the generating data, radii, params."""
    text = repr((gear.teeth, gear.module_mm, gear.pressure_angle_rad, gear.profile_shift,
                 gear.thickness_allowance_mm, gear.tip_rounding_mm, gear.rack, gear.d_a_mm,
                 np.round(np.asarray(radii_mm, float), 12).tolist(), sorted(params.items())))
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def fe_tooth_compliance(gear: ToothForm, radii_mm, *, bore_diameter_mm: float,
                        youngs_MPa: float, poisson: float, plane_strain: bool,
                        n_teeth: int | None = None, control: MeshControl = DEFAULT_CONTROL,
                        loads=None, point_of_load=None) -> FEToothCompliance:
    """Global FE compliance c_FE [mm/(N/mm)] of ``gear``'s tooth at involute radii, loaded
    along the inward flank normal, or (``loads`` = (points (n, 2), unit force directions
    (n, 2)) in the tooth frame, points on the loaded tooth's outline, e.g. a tip corner
    loaded along the mate's involute normal) at those points in those directions; the
    displacement is read at the depth h behind each point along its force (module notes).
    ``point_of_load`` (with ``loads``): index of the point of each force when there are more
    forces than (distinct) points. ``radius_mm`` of the result is |point| of each load.

    Raises :class:`gearcli.model.fe.deps.FEUnavailableError` without the extra ``fe``.
    """
    t0 = time.perf_counter()
    if loads is None:
        point, normal = flank_point_normal(gear, radii_mm)
        force = -normal
    else:
        point = np.asarray(loads[0], float).reshape(-1, 2)
        force = np.asarray(loads[1], float).reshape(-1, 2)
    on = np.arange(len(point)) if point_of_load is None else np.asarray(point_of_load, int)
    m = gear.module_mm
    size = m / control.refinement
    outline = sector_outline(gear, None, bore_radius_mm=0.5 * bore_diameter_mm,
                             n_teeth=n_teeth, fine_mm=control.fine * size,
                             coarse_mm=control.coarse * size, load_points_mm=point)
    clamp = (BORE, SIDE) if control.clamp_sides else (BORE,)
    body = PlaneBody.from_polygon(outline.points_mm, outline.edge_markers,
                                  max_area_mm2=control.max_area * size * size,
                                  youngs_MPa=youngs_MPa, poisson=poisson,
                                  plane_strain=plane_strain, clamp_markers=clamp,
                                  segments=outline.segments, holes_mm=outline.holes_mm)
    mesh_pts = body.vertices_mm[:, outline.load_vertex_ids].T
    if not np.allclose(mesh_pts, point, atol=1e-9 * m):
        raise RuntimeError("the mesher moved a load point")  # Triangle keeps input vertices
    u = body.solve(body.point_loads(outline.load_vertex_ids[on], force))
    depth = control.depth * m
    disp = body.displacement_at(u, point[on] + depth * force)  # (2, n_loads, n_loads)
    idx = np.arange(len(on))
    c = disp[0, idx, idx] * force[:, 0] + disp[1, idx, idx] * force[:, 1]
    return FEToothCompliance(np.hypot(point[on, 0], point[on, 1]), c, depth, body.n_dofs,
                             outline.n_teeth, bore_diameter_mm, plane_strain,
                             time.perf_counter() - t0)
