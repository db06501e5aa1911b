"""Tooth contact force: Adams IMPACT, per pair and flank, and its elastic potential.

References
----------
MSC Software, "Adams Solver: Function Reference", IMPACT function; docs/theory.md §4.
"""

import math

from gearcli.core.jit import jit
from gearcli.core.stepfunc import step


@jit
def elastic_force(pen, k, e):
    """Elastic part ``k p^e`` of the IMPACT force [N] for a penetration ``pen > 0`` [mm].

    ``k`` [N/mm^e], ``e`` [-]. Exponents 1 and 1.5 (the seed's) avoid the general ``pow``.
    """
    if e == 1.5:
        return k * pen * math.sqrt(pen)
    if e == 1.0:
        return k * pen
    return k * pen ** e


@jit
def impact_force(pen, pen_rate, k, e, c_max, d_max):
    """Adams IMPACT contact force of one tooth pair [N] and its elastic part [N].

    Parameters
    ----------
    pen : float
        Penetration p [mm], positive when the flanks overlap.
    pen_rate : float
        dp/dt [mm/s].
    k : float
        Stiffness [N/mm^e].
    e : float
        Force exponent [-].
    c_max : float
        Maximum damping coefficient [N*s/mm].
    d_max : float
        Penetration at which the damping reaches ``c_max`` [mm].

    Returns
    -------
    force : float
        ``F = max(0, k p^e + STEP(p, 0, 0, d_max, c_max) dp/dt)`` for ``p > 0``, else 0 [N].
    elastic : float
        ``k p^e`` for ``p > 0``, else 0 [N]; ``(F - elastic) dp/dt >= 0`` is the damping
        dissipation rate [N*mm/s].

    Notes
    -----
    docs/theory.md §4: the force never pulls (the max), the damping ramps in with the penetration
    (STEP) so the force is continuous at first touch.
    """
    if pen <= 0.0:
        return 0.0, 0.0
    fel = elastic_force(pen, k, e)
    force = fel + step(pen, 0.0, 0.0, d_max, c_max) * pen_rate
    if force < 0.0:
        force = 0.0
    return force, fel


@jit
def impact_potential(pen, k, e):
    """Potential energy of the elastic part [N*mm]: ``k p^(e+1) / (e+1)`` for ``p > 0``, else 0.

    Its derivative with respect to ``p`` is ``k p^e``, so generalized forces
    ``Q = -F dp/dq`` derived from it conserve energy (docs/theory.md §3-4).
    """
    if pen <= 0.0:
        return 0.0
    return elastic_force(pen, k, e) * pen / (e + 1.0)
