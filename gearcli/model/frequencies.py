"""The rotation frequencies of a gear pair: shafts and gear mesh (docs/theory.md §7). Units:
rad/s in, Hz out."""

from __future__ import annotations

import math

__all__ = ["mesh_frequencies"]


def mesh_frequencies(z1: int, pinion_speed_rad_s: float, i: float) -> tuple[float, float, float]:
    """Gear-mesh and shaft frequencies.

    Parameters
    ----------
    z1 : int
        Pinion teeth.
    pinion_speed_rad_s : float
        Pinion angular speed ω1 [rad/s].
    i : float
        Ratio z2 / z1.

    Returns
    -------
    (f_z, n1, n2) : tuple of float [Hz]
        n1 = ω1 / (2π), n2 = n1 / i, f_z = z1 n1 (docs/theory.md §7).
    """
    n1 = pinion_speed_rad_s / (2.0 * math.pi)
    return z1 * n1, n1, n1 / i
