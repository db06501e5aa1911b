"""Finite-element check of the tooth compliance (docs/theory.md, "Finite-element check of the
tooth compliance"): a 2-D plane-strain/plane-stress model of each gear body from
gearcli's generated profile, clamped at the bore, with Weber's local contact term.

Needs the optional extra ``fe`` (scikit-fem, triangle): ``pip install 'gearcli[fe]'``. The
libraries are imported only when a model is built, so importing this package is free; without
them the functions raise :class:`FEUnavailableError` with a one-line message.
"""

from gearcli.model.fe.cache import ComplianceCache
from gearcli.model.fe.deps import FEUnavailableError
from gearcli.model.fe.mesh_stiffness import FEMeshStiffness, fe_mesh_stiffness, plane_strain_rule
from gearcli.model.fe.tooth import FEToothCompliance, MeshControl, fe_tooth_compliance

__all__ = ["ComplianceCache", "FEMeshStiffness", "FEToothCompliance", "FEUnavailableError",
           "MeshControl", "fe_mesh_stiffness", "fe_tooth_compliance", "plane_strain_rule"]
