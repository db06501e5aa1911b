"""Mass properties of the gear bodies (internal units: mm, tonne).

References
----------
Any statics / dynamics text, e.g. J. L. Meriam, L. G. Kraige, *Engineering Mechanics:
Dynamics*, Appendix B (mass moment of inertia of a solid circular cylinder about its axis).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["MassProperties", "disc_mass_inertia", "gear_mass_properties"]


def disc_mass_inertia(
    density_t_mm3: float, diameter_mm: float, face_width_mm: float,
    bore_diameter_mm: float = 0.0,
) -> tuple[float, float]:
    """Mass and polar mass moment of inertia of a disc (gear blank), solid or with a bore.

    Parameters
    ----------
    density_t_mm3 : float
        Density ρ [t/mm³] (steel 7.85e-9 t/mm³ = 7.85e-6 kg/mm³).
    diameter_mm : float
        Disc diameter d [mm] (by default the reference diameter of the gear).
    face_width_mm : float
        Face width b [mm].
    bore_diameter_mm : float
        Bore d_i [mm], 0 for a solid disc (default); less than ``diameter_mm``.

    Returns
    -------
    (mass_t, polar_inertia_t_mm2) : tuple of float
        m = ρ π (d² − d_i²)/4 · b [t] and J = m (d² + d_i²)/8 = π ρ b (r⁴ − r_i⁴)/2 [t·mm²]
        (a hollow cylinder, Meriam & Kraige appendix B; solid: J = m d²/8 = m r²/2).

    Raises
    ------
    ValueError
        If any argument is not a finite positive number.
    """
    for name, value in (("density_t_mm3", density_t_mm3), ("diameter_mm", diameter_mm),
                        ("face_width_mm", face_width_mm)):
        if not (math.isfinite(value) and value > 0.0):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    if not (math.isfinite(bore_diameter_mm) and 0.0 <= bore_diameter_mm < diameter_mm):
        raise ValueError(f"bore_diameter_mm must lie in [0, {diameter_mm!r}), got "
                         f"{bore_diameter_mm!r}")
    mass = density_t_mm3 * math.pi * (diameter_mm**2 - bore_diameter_mm**2) / 4.0 * face_width_mm
    return mass, mass * (diameter_mm**2 + bore_diameter_mm**2) / 8.0


@dataclass(frozen=True)
class MassProperties:
    """Mass and polar inertia of one gear body as the solver uses them."""

    mass_t: float  #: [t]
    inertia_t_mm2: float  #: polar moment of inertia about the gear axis [t·mm²]


def gear_mass_properties(
    model: str,
    density_t_mm3: float,
    diameter_mm: float | None,
    pitch_diameter_mm: float,
    face_width_mm: float,
    inertia_t_mm2: float | None = None,
    mass_t: float | None = None,
    extra_inertia_t_mm2: float = 0.0,
    bore_diameter_mm: float | None = None,
) -> MassProperties:
    """Mass properties of a gear body (docs/theory.md §2.6).

    ``model == "disc"``: a disc of ``diameter_mm`` (default: the pitch diameter) and the face
    width with the gear's given bore ``bore_diameter_mm`` (None: solid), from the density
    (:func:`disc_mass_inertia`); ``"given"``: ``inertia_t_mm2`` (and ``mass_t`` if known, else
    the disc mass). ``extra_inertia_t_mm2`` (shaft, hub) is added to the polar inertia in both
    cases.
    """
    disc_d = diameter_mm if diameter_mm is not None else pitch_diameter_mm
    disc_mass, disc_inertia = disc_mass_inertia(density_t_mm3, disc_d, face_width_mm,
                                                bore_diameter_mm or 0.0)
    if model == "disc":
        return MassProperties(disc_mass, disc_inertia + extra_inertia_t_mm2)
    if model == "given" and inertia_t_mm2 is not None:
        mass = mass_t if mass_t is not None else disc_mass
        return MassProperties(mass, inertia_t_mm2 + extra_inertia_t_mm2)
    raise ValueError(f"inertia model {model!r} needs a given inertia")
