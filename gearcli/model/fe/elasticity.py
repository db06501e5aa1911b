"""Two-dimensional linear elasticity on a polygon: mesh, stiffness, clamped solve, probes.

The body is a closed polygon meshed by Triangle (Shewchuk 1996; ``pq<angle>a<area>``: a
constrained Delaunay quality mesh whose element size follows the spacing of the boundary
points, so a finely sampled boundary refines the mesh next to it), discretised with quadratic
(P2) triangles in scikit-fem (Gustafsson & McBain 2020) and the isotropic Hooke law in
Lamé form (plane strain: λ = Eν/((1 + ν)(1 − 2ν)); plane stress: λ* = Eν/(1 − ν²); μ = E/(2(1 +
ν)); Timoshenko & Goodier 1970, §§ 16, 17). The thickness is 1 mm: a force F [N] on the 2-D
body is a line load F per mm of face width, so a displacement per unit load is a compliance
in mm/(N/mm); a tooth of face width b has b times smaller compliance in mm/N.

Edges of the polygon carry integer markers; the edges marked as clamped get u = 0 (or given
values). Input vertices keep their index in the mesh (Triangle numbers its input points
first), so a point load goes to a chosen input vertex; with P2 elements the vertex basis
function is 1 there and 0 at every other node, so the nodal force is the point load exactly.

Units: mm, N, MPa (N/mm²).

References
----------
T. Gustafsson, G. D. McBain, "scikit-fem: A Python package for finite element assembly",
J. Open Source Softw. 5(52), 2369, 2020.
J. R. Shewchuk, "Triangle: engineering a 2D quality mesh generator and Delaunay
triangulator", Applied Computational Geometry, LNCS 1148, 203–222, 1996.
S. P. Timoshenko, J. N. Goodier, *Theory of Elasticity*, 3rd ed., McGraw-Hill, 1970.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gearcli.model.fe.deps import require

__all__ = ["PlaneBody", "closed_loop", "mesh_polygon", "lame_2d"]


def lame_2d(youngs_MPa: float, poisson: float, plane_strain: bool) -> tuple[float, float]:
    """(λ, μ) [MPa] of the 2-D Hooke law in plane strain or plane stress (module notes)."""
    mu = youngs_MPa / (2.0 * (1.0 + poisson))
    if plane_strain:
        lam = youngs_MPa * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson))
    else:
        lam = youngs_MPa * poisson / (1.0 - poisson * poisson)
    return lam, mu


def closed_loop(start: int, n: int) -> np.ndarray:
    """Segments (n, 2) of a closed loop of the points start … start + n − 1, in order."""
    i = np.arange(n)
    return np.column_stack([start + i, start + (i + 1) % n])


def mesh_polygon(points_mm: np.ndarray, edge_markers: np.ndarray, max_area_mm2: float,
                 min_angle_deg: float = 30.0, segments=None, holes_mm=None):
    """Quality triangle mesh of a polygonal domain [mm].

    Returns (vertices (n, 2), triangles (m, 3), boundary segments (k, 2), their markers (k,)).
    Without ``segments`` the points form one closed polygon (in order, not repeated): edge i
    joins point i and point i + 1 (the last joins the first). Edge/segment i carries
    ``edge_markers[i]`` (an integer > 0); ``holes_mm`` (h, 2): a point inside each hole.
    """
    _, triangle = require()
    seg = closed_loop(0, len(points_mm)) if segments is None else np.asarray(segments)
    data = {"vertices": np.asarray(points_mm, float), "segments": seg,
            "segment_markers": np.asarray(edge_markers, np.int32).reshape(-1, 1)}
    if holes_mm is not None:
        data["holes"] = np.asarray(holes_mm, float).reshape(-1, 2)
    out = triangle.triangulate(data, f"pq{min_angle_deg:g}a{max_area_mm2:.6g}")
    return (out["vertices"], out["triangles"], out["segments"],
            out["segment_markers"].ravel())


@dataclass
class PlaneBody:
    """A meshed 2-D elastic body with its stiffness matrix and clamped degrees of freedom.

    Build with :meth:`from_polygon`; :meth:`solve` solves for several load vectors at once
    with one factorisation.
    """

    basis: object  #: scikit-fem vector P2 basis
    stiffness: object  #: assembled stiffness matrix (scipy sparse) [N/mm per mm thickness]
    clamped: np.ndarray  #: clamped degrees of freedom
    segments: np.ndarray  #: boundary segments of the mesh (vertex pairs)
    segment_markers: np.ndarray  #: their edge markers
    _lu: object = None

    @classmethod
    def from_polygon(cls, points_mm, edge_markers, *, max_area_mm2: float, youngs_MPa: float,
                     poisson: float, plane_strain: bool, clamp_markers=(1,),
                     min_angle_deg: float = 30.0, segments=None, holes_mm=None) -> PlaneBody:
        """Mesh the domain (:func:`mesh_polygon`), assemble the P2 stiffness, clamp the
        edges with the markers."""
        skfem, _ = require()
        from skfem.models.elasticity import linear_elasticity

        p, t, seg, marks = mesh_polygon(points_mm, edge_markers, max_area_mm2, min_angle_deg,
                                        segments, holes_mm)
        mesh = skfem.MeshTri(np.ascontiguousarray(p.T), np.ascontiguousarray(t.T))
        basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementTriP2()))
        k = skfem.asm(linear_elasticity(*lame_2d(youngs_MPa, poisson, plane_strain)), basis)
        clamped = basis.get_dofs(facets=_facets_of(mesh, seg[np.isin(marks, clamp_markers)]))
        return cls(basis, k.tocsr(), clamped.all(), seg, marks)

    @property
    def vertices_mm(self) -> np.ndarray:
        """Mesh vertices (2, n) [mm]."""
        return self.basis.mesh.p

    @property
    def n_dofs(self) -> int:
        """Number of degrees of freedom."""
        return int(self.basis.N)

    def point_loads(self, vertex_ids, forces_N) -> np.ndarray:
        """Load matrix (n_dofs, k): column j is the force ``forces_N[j]`` (2,) at vertex j [N]."""
        f = np.zeros((self.n_dofs, len(vertex_ids)))
        dofs = self.basis.nodal_dofs[:, np.asarray(vertex_ids)]
        cols = np.arange(len(vertex_ids))
        f[dofs[0], cols] = np.asarray(forces_N)[:, 0]
        f[dofs[1], cols] = np.asarray(forces_N)[:, 1]
        return f

    def traction_load(self, facet_filter, traction) -> np.ndarray:
        """Load vector of a boundary traction [N/mm² × 1 mm thickness].

        ``facet_filter(x)`` selects boundary facets by their midpoints (x: (2, n) [mm]);
        ``traction(x)`` returns the traction (2, ...) [MPa] at quadrature points x.
        """
        skfem, _ = require()
        mesh = self.basis.mesh
        facets = mesh.facets_satisfying(facet_filter, boundaries_only=True)
        fb = skfem.FacetBasis(mesh, self.basis.elem, facets=facets)

        @skfem.LinearForm
        def form(v, w):
            tr = traction(w.x)
            return tr[0] * v[0] + tr[1] * v[1]

        return skfem.asm(form, fb)

    def solve(self, loads, clamped_values=None) -> np.ndarray:
        """Displacements (n_dofs, k) [mm] for loads (n_dofs,) or (n_dofs, k) [N].

        ``clamped_values``: prescribed displacements of the clamped dofs (default 0).
        """
        from scipy.sparse.linalg import splu

        f = np.asarray(loads, float)
        vec = f.ndim == 1
        f = f.reshape(self.n_dofs, -1)
        free = np.setdiff1d(np.arange(self.n_dofs), self.clamped)
        u = np.zeros_like(f)
        if clamped_values is not None:
            u[self.clamped] = np.asarray(clamped_values, float).reshape(-1, 1)
            f = f - self.stiffness[:, self.clamped] @ u[self.clamped]
        if self._lu is None:
            self._lu = splu(self.stiffness[free][:, free].tocsc())
        u[free] = self._lu.solve(np.ascontiguousarray(f[free]))
        return u[:, 0] if vec else u

    def displacement_at(self, u, points_mm) -> np.ndarray:
        """Displacement (2, n_points, k) [mm] of solutions u (n_dofs, k) at points (n, 2)."""
        pts = np.asarray(points_mm, float).reshape(-1, 2)
        probe = self.basis.probes(np.ascontiguousarray(pts.T)).tocsr()
        vals = probe @ np.asarray(u).reshape(self.n_dofs, -1)
        return vals.reshape(2, len(pts), -1)


def _facets_of(mesh, segments) -> np.ndarray:
    """Mesh facet indices of boundary segments given as vertex pairs."""
    index = {tuple(sorted(f)): i for i, f in enumerate(mesh.facets.T.tolist())}
    return np.array([index[tuple(sorted(s))] for s in np.asarray(segments).tolist()], int)
