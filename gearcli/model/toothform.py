"""What generates one gear's tooth: the basic rack and the gear's own generating data.

:class:`ToothForm` is the input of every function of :mod:`gearcli.model.profile`. It is built
first by :func:`gearcli.model.geometry.compute_pair_geometry` (which owns the ISO 21771
formulas of its diameters and thickness), so the profile never sees a half-built gear; the
complete :class:`~gearcli.model.geometry.GearGeometry` extends it with the quantities that
follow from the profile (form diameters) and from the mate. Units: mm, rad; coefficients in
units of the module.

References
----------
ISO 53:1998 Standard basic rack tooth profile.
ISO 21771:2007 Cylindrical involute gears and gear pairs — Concepts and geometry.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["RackSpec", "ToothForm"]


@dataclass(frozen=True)
class RackSpec:
    """Basic rack (ISO 53), coefficients of the module. Defaults: ISO 53 profile A."""

    addendum_coef: float = 1.0  #: h_aP* (gear addendum)
    dedendum_coef: float = 1.25  #: h_fP* (gear dedendum = generating tool addendum)
    root_radius_coef: float = 0.38  #: ρ_fP* (tool tip rounding generating the fillet)


@dataclass(frozen=True)
class ToothForm:
    """Generating data of one gear: the rack, its position and the gear's circles [mm, rad].

    Everything :mod:`gearcli.model.profile` reads to generate the fillet, the involute and
    the tip; diameters as in :class:`~gearcli.model.geometry.GearGeometry`, which extends it.
    """

    teeth: int  #: z
    module_mm: float  #: m [mm]
    pressure_angle_rad: float  #: α [rad]
    profile_shift: float  #: x
    thickness_allowance_mm: float  #: A_s: reduction of s at the reference circle [mm]
    tip_rounding_mm: float  #: ρ_a [mm]
    rack: RackSpec  #: basic rack the gear is generated with
    d_mm: float  #: reference diameter d = m z
    d_b_mm: float  #: base diameter d_b = d cos α
    d_a_mm: float  #: tip diameter d_a = d + 2m(h_aP* + x − k)
    d_f_mm: float  #: root diameter d_f = d − 2m(h_fP* − x)
    s_mm: float  #: reference arc tooth thickness m(π/2 + 2x tan α) − A_s
    undercut: bool  #: x < x_min: the tool flank end cuts into the involute

    r_mm = property(lambda self: 0.5 * self.d_mm, doc="Reference radius [mm].")
    r_b_mm = property(lambda self: 0.5 * self.d_b_mm, doc="Base radius [mm].")
    r_a_mm = property(lambda self: 0.5 * self.d_a_mm, doc="Tip radius [mm].")
    r_f_mm = property(lambda self: 0.5 * self.d_f_mm, doc="Root radius [mm].")
