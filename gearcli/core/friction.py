"""Adams contact friction coefficient as a function of the sliding velocity.

References
----------
MSC Software, "Adams Solver: Function Reference", IMPACT/contact friction (stiction and
dynamic friction transition); docs/theory.md §5.
"""

from gearcli.core.jit import jit
from gearcli.core.stepfunc import step


@jit
def adams_mu(v, mu_s, mu_d, v_s, v_d):
    """Signed friction coefficient mu(v) [-]: opposes sliding, zero at ``v = 0``.

    Parameters
    ----------
    v : float
        Sliding velocity [mm/s].
    mu_s, mu_d : float
        Static and dynamic coefficients [-].
    v_s, v_d : float
        Stiction and dynamic transition velocities [mm/s], ``0 < v_s < v_d``.

    Returns
    -------
    float
        ``-sign(v) mu_d`` for ``|v| >= v_d``;
        ``-sign(v) STEP(|v|, v_s, mu_s, v_d, mu_d)`` for ``v_s <= |v| < v_d``;
        ``STEP(v, -v_s, mu_s, v_s, -mu_s)`` for ``|v| < v_s`` (no true stick).
        ``mu(v) v <= 0`` for every ``v``, so friction never delivers power.
    """
    av = abs(v)
    if av < v_s:
        return step(v, -v_s, mu_s, v_s, -mu_s)
    sign = 1.0 if v > 0.0 else -1.0
    if av >= v_d:
        return -sign * mu_d
    return -sign * step(av, v_s, mu_s, v_d, mu_d)
