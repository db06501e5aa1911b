"""Involute function and polar helpers for the involute of a circle.

All angles in rad, lengths in mm. Functions accept floats or numpy arrays (vectorised) and
return the same shape. Notation follows ISO 21771:2007 / DIN 3960:

- r_b base radius, r a radius on the involute, α_y the pressure angle at r (cos α_y = r_b / r),
- roll angle ξ = tan α_y (the unwound base-circle arc divided by r_b),
- polar (vectorial) angle of the involute point measured from its origin on the base circle:
  inv α_y = tan α_y − α_y.

References
----------
ISO 21771:2007, Gears — Cylindrical involute gears and gear pairs — Concepts and geometry
(involute function, tooth thickness at any diameter).
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., CUP 2004, chapter
'Spur involute gears' (involute curve, rack-cutter generation).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "inv",
    "inv_inverse",
    "pressure_angle_at_radius",
    "roll_angle_at_radius",
    "radius_at_roll_angle",
    "involute_polar_angle",
    "half_thickness_angle",
    "involute_xy",
]

_NEWTON_MAX_ITER = 60
_SERIES_LIMIT = 0.1  # below this angle [rad] inv α is summed from the Taylor series
# Taylor coefficients of tan α − α = Σ c_k α^(2k+3) (tangent numbers; Abramowitz & Stegun 4.3.67)
_SERIES = (1 / 3, 2 / 15, 17 / 315, 62 / 2835, 1382 / 155925, 21844 / 6081075,
           929569 / 638512875)


def inv(alpha: ArrayLike) -> np.ndarray | float:
    """Involute function.

    Parameters
    ----------
    alpha : float or array
        Pressure angle α [rad], 0 <= α < π/2.

    Returns
    -------
    float or array
        inv α = tan α − α [rad].

    Notes
    -----
    For α < 0.1 rad, tan α − α loses digits to cancellation (relative error ~1e-16 α / inv α);
    there the Taylor series α³/3 + 2α⁵/15 + … (7 terms, truncation < 2e-17 relative) is summed
    instead, so inv and :func:`inv_inverse` stay accurate to round-off for all α.

    References
    ----------
    ISO 21771:2007, eq. (3) (involute function).
    """
    a = np.asarray(alpha, dtype=float)
    a2 = a * a
    series = np.zeros_like(a)
    for c in reversed(_SERIES):
        series = series * a2 + c
    out = np.where(np.abs(a) < _SERIES_LIMIT, series * a2 * a, np.tan(a) - a)
    return float(out) if out.ndim == 0 else out


def inv_inverse(value: ArrayLike) -> np.ndarray | float:
    """Inverse of the involute function: the angle α with tan α − α = value.

    Newton's method on f(α) = tan α − α − v, f′(α) = tan² α, started from an upper bound of
    the root so that the iteration (f increasing and convex on (0, π/2)) converges
    monotonically from above and never leaves (0, π/2). Upper bounds:
    α₀ = (3v)^(1/3) (since tan α − α ≥ α³/3) and α₀ = π/2 − 1/(v + π/2)
    (since tan(π/2 − ε) − (π/2 − ε) ≥ 1/ε − π/2 + 2ε/3); the smaller one is used.
    Iterates until the step is below 1e-16·α (accuracy ~1e-16 relative, below 1e-14 rad).

    Parameters
    ----------
    value : float or array
        inv α [rad], value >= 0.

    Returns
    -------
    float or array
        α [rad] in [0, π/2).

    Raises
    ------
    ValueError
        If any value is negative or not finite.
    """
    v = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(v)) or np.any(v < 0.0):
        raise ValueError(f"inv_inverse: value must be finite and >= 0, got {value!r}")
    half_pi = 0.5 * np.pi
    alpha = np.minimum(np.cbrt(3.0 * v), half_pi - 1.0 / (v + half_pi))
    positive = v > 0.0
    alpha = np.where(positive, alpha, 0.0)
    for _ in range(_NEWTON_MAX_ITER):
        t = np.tan(alpha)
        f = inv(alpha) - v
        fp = np.where(positive, t * t, 1.0)
        step = np.where(positive, f / fp, 0.0)
        alpha = alpha - step
        if np.all(np.abs(step) <= 1e-16 * np.maximum(alpha, 1e-300)):
            break
    return float(alpha) if alpha.ndim == 0 else alpha


def pressure_angle_at_radius(base_radius_mm: ArrayLike, radius_mm: ArrayLike):
    """Pressure angle of the involute at a radius.

    Parameters
    ----------
    base_radius_mm : float or array
        Base radius r_b [mm].
    radius_mm : float or array
        Radius r >= r_b [mm].

    Returns
    -------
    float or array
        α_y = arccos(r_b / r) [rad] (ISO 21771, eq. for the pressure angle at a point).
    """
    out = np.arccos(np.asarray(base_radius_mm, float) / np.asarray(radius_mm, float))
    return float(out) if np.ndim(out) == 0 else out


def roll_angle_at_radius(base_radius_mm: ArrayLike, radius_mm: ArrayLike):
    """Roll angle of the involute point at a radius.

    Parameters
    ----------
    base_radius_mm : float or array
        Base radius r_b [mm].
    radius_mm : float or array
        Radius r >= r_b [mm].

    Returns
    -------
    float or array
        ξ = tan α_y = √((r/r_b)² − 1) [rad]; r_b ξ is the length of the base tangent from
        the point to its tangency point, the involute's radius of curvature (Litvin & Fuentes).
    """
    q = np.asarray(radius_mm, float) / np.asarray(base_radius_mm, float)
    out = np.sqrt(q * q - 1.0)
    return float(out) if np.ndim(out) == 0 else out


def radius_at_roll_angle(base_radius_mm: ArrayLike, roll_rad: ArrayLike):
    """Radius of the involute point with roll angle ξ: r = r_b √(1 + ξ²) [mm]."""
    rb = np.asarray(base_radius_mm, float)
    xi = np.asarray(roll_rad, float)
    out = rb * np.sqrt(1.0 + xi * xi)
    return float(out) if np.ndim(out) == 0 else out


def involute_polar_angle(base_radius_mm: ArrayLike, radius_mm: ArrayLike):
    """Polar angle of the involute point at radius r, measured from the involute origin.

    Returns inv(arccos(r_b / r)) [rad] (ISO 21771, involute in polar coordinates).
    """
    return inv(pressure_angle_at_radius(base_radius_mm, radius_mm))


def half_thickness_angle(
    thickness_mm: float,
    reference_diameter_mm: float,
    pressure_angle_rad: float,
    radius_mm: ArrayLike,
):
    """Half the angular tooth thickness at a radius (angle from tooth centreline to the flank).

    Parameters
    ----------
    thickness_mm : float
        Circular (arc) tooth thickness s on the reference circle [mm].
    reference_diameter_mm : float
        Reference diameter d [mm].
    pressure_angle_rad : float
        Reference pressure angle α [rad].
    radius_mm : float or array
        Radius r_y >= r_b [mm].

    Returns
    -------
    float or array
        ψ_y = s/d + inv α − inv α_y [rad]; the arc thickness at r_y is s_y = 2 r_y ψ_y
        (ISO 21771:2007, tooth thickness at diameter d_y: s_y = d_y (s/d + inv α − inv α_y)).
    """
    rb = 0.5 * reference_diameter_mm * np.cos(pressure_angle_rad)
    out = (
        thickness_mm / reference_diameter_mm
        + inv(pressure_angle_rad)
        - involute_polar_angle(rb, radius_mm)
    )
    return float(out) if np.ndim(out) == 0 else out


def involute_xy(base_radius_mm: float, roll_rad: ArrayLike, start_angle_rad: float = 0.0):
    """Cartesian points of the involute unwound counter-clockwise from a base-circle origin.

    Parameters
    ----------
    base_radius_mm : float
        Base radius r_b [mm].
    roll_rad : float or array
        Roll angle ξ >= 0 [rad].
    start_angle_rad : float
        Polar angle of the involute origin on the base circle [rad].

    Returns
    -------
    (x, y) : tuple of arrays [mm]
        P(ξ) = r_b [e(β₀ + ξ) − ξ e′(β₀ + ξ)] with e(β) = (cos β, sin β), e′ = (−sin β, cos β);
        the tangency point on the base circle is r_b e(β₀ + ξ) and |P − T| = r_b ξ
        (Litvin & Fuentes 2004, eq. 10.2.1, rotated).
    """
    xi = np.asarray(roll_rad, float)
    beta = start_angle_rad + xi
    x = base_radius_mm * (np.cos(beta) + xi * np.sin(beta))
    y = base_radius_mm * (np.sin(beta) - xi * np.cos(beta))
    return x, y
