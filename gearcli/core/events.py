"""Where the right-hand side jumps: a pair slot crossing the end of a gap table while loaded.

A slot is in contact only while its pinion and gear roll positions x1, x2 lie inside the gap
tables [x_lo, x_hi] (rhs.py). When a table ends where the flanks still overlap (the classic
`engagement: rigid` model: G = 0 up to the end of the path), the entering or leaving pair's
force jumps from 0 to k delta^e, the derivative of the state jumps, and an error-controlled
Runge-Kutta method pays for it with a cascade of rejected steps. The time loop instead ends a
step just before the crossing predicted here and hops over it (timeloop.py), the standard
treatment of a discontinuity at a located switching point (Hairer, Norsett & Wanner,
"Solving ODEs I", §II.6, "discontinuous right-hand sides"). Crossings where the overlap at the
table end is clearly negative (extended tables that open the gap smoothly) are not events.

Positions move as in rhs.py: on flank sigma (+1 drive, -1 coast) x1 = x_lo + u + j p_b with
dx1/dt = sigma v1, and x2 = x1 - sigma delta with dx2/dt = sigma (v1 - deltadot).
"""

import math

import numpy as np

from gearcli.core.derive import table_of
from gearcli.core.gaptable import hermite
from gearcli.core.jit import jit
from gearcli.core.layout import DRIVE_FLANKS, GEAR, N_FAMILIES, PINION, D, F, P
from gearcli.core.nrt import jit_noalloc


@jit
def time_to_reach(distance, rate, accel):
    """Smallest tau > 0 with ``rate tau + accel tau^2 / 2 = distance`` [s], ``inf`` if none.

    ``distance`` [mm] has the sign of ``rate`` [mm/s]; ``accel`` [mm/s^2]. Cancellation-free
    root ``2 d / (r + sign(r) sqrt(r^2 + 2 a d))``.
    """
    if rate == 0.0:
        return math.inf
    disc = rate * rate + 2.0 * accel * distance
    if disc < 0.0:
        return math.inf  # decelerates and turns back before reaching it
    root = math.sqrt(disc)
    denom = rate + root if rate > 0.0 else rate - root
    tau = 2.0 * distance / denom
    return tau if tau > 0.0 else math.inf


@jit
def _boundary_ahead(x, rate, x_lo, x_hi):
    """The table end that position ``x`` reaches next moving at ``rate``; NaN if none."""
    if rate > 0.0:
        if x < x_lo:
            return x_lo
        if x < x_hi:
            return x_hi
    elif rate < 0.0:
        if x > x_hi:
            return x_hi
        if x > x_lo:
            return x_lo
    return math.nan


@jit_noalloc
def _flank_crossing(f, s1, v1, a1, delta, deltadot, deltaddot, model, window, margin):
    """Earliest loaded table-end crossing of flank family ``f`` within ``window`` [s]."""
    prm = model.prm
    derived = model.derived
    tables = model.tables
    sigma = 1.0 if f == DRIVE_FLANKS else -1.0
    offset = model.family[f, F.offset]
    g1 = table_of(f, PINION)
    g2 = table_of(f, GEAR)
    # no pair of the family can touch within the window (derive.overlap_bound), or none can be
    # loaded where it crosses a table end (derive.end_gap_bound: extended tables): nothing to find
    reach = sigma * delta + (abs(deltadot) + 0.5 * abs(deltaddot) * window) * window
    if reach - offset + min(model.family[f, F.overlap], -model.family[f, F.end_gap]) <= -margin:
        return math.inf
    p_b = prm[P.p_b]
    x_lo = prm[P.x_lo]
    x_hi = prm[P.x_hi]
    h_grid = derived[D.grid_step]
    inv_h = derived[D.inv_grid_step]
    r = sigma * s1 - model.family[f, F.phase0]
    u = r - np.floor(r * derived[D.inv_p_b]) * p_b
    r1 = sigma * v1  # dx1/dt
    q1 = sigma * a1
    r2 = sigma * (v1 - deltadot)  # dx2/dt
    q2 = sigma * (a1 - deltaddot)
    best = math.inf
    for j in range(-1, int(prm[P.n_slots]) + 1):
        x1 = x_lo + u + j * p_b
        x2 = x1 - sigma * delta
        for coord in range(2):
            if coord == 0:
                x, rate, acc = x1, r1, q1
            else:
                x, rate, acc = x2, r2, q2
            b = _boundary_ahead(x, rate, x_lo, x_hi)
            if math.isnan(b) or abs(b - x) > (abs(rate) + 0.5 * abs(acc) * window) * window:
                continue  # none ahead, or out of reach within the window
            tau = time_to_reach(b - x, rate, acc)
            if tau > window or tau >= best:
                continue
            # both positions at the crossing; the crossing one sits on the table end
            y1 = b if coord == 0 else x1 + (r1 + 0.5 * q1 * tau) * tau
            y2 = b if coord == 1 else x2 + (r2 + 0.5 * q2 * tau) * tau
            if not (x_lo <= y1 <= x_hi and x_lo <= y2 <= x_hi):
                continue  # the other position is off its table: no contact on either side
            _, gap1, _ = hermite(tables, g1, x_lo, x_hi, h_grid, inv_h, y1)
            _, gap2, _ = hermite(tables, g2, x_lo, x_hi, h_grid, inv_h, y2)
            overlap = sigma * (delta + (deltadot + 0.5 * deltaddot * tau) * tau) - offset \
                - gap1 - gap2
            if overlap > -margin:
                best = tau
    return best


@jit_noalloc
def next_crossing(s1, v1, a1, delta, deltadot, deltaddot, model, window, margin):
    """Time [s] from now to the next loaded table-end crossing, ``inf`` if none in ``window``.

    Parameters
    ----------
    s1, v1, a1 : float
        Pinion roll distance [mm], rate [mm/s], acceleration [mm/s^2].
    delta, deltadot, deltaddot : float
        DTE [mm] and its first two derivatives [mm/s, mm/s^2].
    model : gearcli.core.bundles.Model
    window : float
        Look-ahead [s]; positions are extrapolated quadratically.
    margin : float
        A crossing counts when the flank overlap at the table end exceeds ``-margin`` [mm]
        (covers runout and tooth offsets, which are not evaluated here).
    """
    # the family as a loop counter, not a constant: one compiled _flank_crossing for both
    # (numba compiles a function once per literal argument value)
    n_families = N_FAMILIES if model.prm[P.coast_flanks] != 0.0 else DRIVE_FLANKS + 1
    tau = math.inf
    for f in range(n_families):
        tau = min(tau, _flank_crossing(f, s1, v1, a1, delta, deltadot, deltaddot, model,
                                       window, margin))
    return tau
