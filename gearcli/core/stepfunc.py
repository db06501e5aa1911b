"""Adams STEP: the cubic blend used by the IMPACT damping ramp and by the friction law.

References
----------
MSC Software, "Adams Solver: Function Reference", STEP function; docs/theory.md §4.
"""

from gearcli.core.jit import jit


@jit
def step(x, x0, h0, x1, h1):
    """Adams ``STEP(x, x0, h0, x1, h1)``.

    Parameters
    ----------
    x : float
        Independent variable [any unit].
    x0, x1 : float
        Start and end of the blend [unit of x], ``x1 > x0``.
    h0, h1 : float
        Values before ``x0`` and after ``x1`` [any unit].

    Returns
    -------
    float
        ``h0`` for ``x <= x0``, ``h1`` for ``x >= x1``, else ``h0 + (h1 - h0) D^2 (3 - 2 D)``
        with ``D = (x - x0) / (x1 - x0)`` [unit of h].
    """
    if x <= x0:
        return h0
    if x >= x1:
        return h1
    d = (x - x0) / (x1 - x0)
    return h0 + (h1 - h0) * d * d * (3.0 - 2.0 * d)
