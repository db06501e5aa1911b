"""Step-size control of the time loop: accept or reject a step attempt, and the starting step.

Both are phases of :func:`gearcli.core.timeloop.run`, inlined into it, over the loop-state
record of :mod:`gearcli.core.loopstate` (``st``); docs/theory.md §6.7.

References
----------
E. Hairer, S. P. Norsett, G. Wanner, "Solving Ordinary Differential Equations I", 2nd ed.,
Springer 1993, §II.4: the controller (eq. 4.13, factor in :func:`gearcli.core.dopri5.
step_factor`) and "starting step size" (the algorithm of :func:`start_trial`, :func:`start_size`;
scipy.integrate._ivp.common.select_initial_step is the same algorithm).
"""

import math

from gearcli.core.dopri5 import MIN_FACTOR, euler, scaled_rms, step_factor
from gearcli.core.layout import N
from gearcli.core.loopstate import PH_PLAN, PH_SAMPLE
from gearcli.core.nrt import jit_noalloc_inline

#: Starting step size (HNW II.4): norms below this count as zero [-].
START_TINY_NORM = 1e-5
#: ... and the trial step then [s]; also the fallback when the estimate is not a number.
START_FALLBACK_STEP = 1e-6
#: The estimate h1 = (0.01 / max(d1, d2))^(1/5) targets an error norm of 0.01 (5 = the order
#: of the error estimate + 1) and is at most this many trial steps.
START_GROWTH = 100.0


@jit_noalloc_inline
def control(st, err, finite, counters):
    """Accept or reject the step attempt of size ``st.h_step`` [s] (HNW II.4).

    Parameters
    ----------
    st : loopstate.LOOP_DTYPE record
        Loop state, updated: rejected, ``st.h`` is the size of the next
        attempt and the phase PH_PLAN; accepted, ``st.factor`` is the growth factor of the
        next step and the phase PH_SAMPLE; ``st.rejected_before``, ``st.nonfinite_last``.
    err : float
        Scaled RMS error norm of the attempt (dopri5.error_norm) [-].
    finite : bool
        The norm, the new state and its FSAL stage are finite; if not, the attempt is rejected
        and retried with the smallest factor (dopri5.MIN_FACTOR).
    counters : ndarray
        layout.N counters, the accepted or the rejected one incremented.

    Returns
    -------
    bool
        Accepted (``err < 1`` and finite).
    """
    h_step = st.h_step
    if not finite:
        counters[N.rejected_steps] += 1
        st.h = h_step * MIN_FACTOR
        st.rejected_before = 1
        st.nonfinite_last = 1
        st.phase = PH_PLAN
        return False
    st.nonfinite_last = 0
    rejected_before = st.rejected_before != 0
    if err >= 1.0:
        counters[N.rejected_steps] += 1
        st.h = h_step * step_factor(err, rejected_before)
        st.rejected_before = 1
        st.phase = PH_PLAN
        return False
    counters[N.accepted_steps] += 1
    st.factor = step_factor(err, rejected_before)
    st.rejected_before = 0
    st.phase = PH_SAMPLE
    return True


@jit_noalloc_inline
def start_trial(st, y, K, dy, ys, atol, rtol):
    """Starting step size, first half (HNW II.4 steps a-c): the trial step ``h0``.

    ``d0 = ||y||``, ``d1 = ||f(t, y)||`` (``K[0]``) in the scaled RMS norm of the controlled
    components (dopri5.scaled_rms, ``st.first``, ``st.count``); ``h0 = 0.01 d0 / d1``
    (1e-6 s when either norm is below 1e-5), at most the chunk's span. Writes ``h0`` and ``d1``
    to ``lf``, the Euler trial state ``y + h0 f(t, y)`` to ``ys`` and its time to
    ``st.ts``; ``dy`` keeps ``f(t, y)`` (the trial evaluation overwrites it with
    ``f(t + h0, ys)`` before :func:`start_size`).
    """
    first = st.first
    count = st.count
    d0 = scaled_rms(y, y, first, count, atol, rtol)
    for i in range(y.shape[0]):
        dy[i] = K[0, i]
    d1 = scaled_rms(dy, y, first, count, atol, rtol)
    if d0 < START_TINY_NORM or d1 < START_TINY_NORM:
        h0 = START_FALLBACK_STEP
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, st.span)
    st.h0 = h0
    st.d1 = d1
    st.ts = st.t + h0
    euler(y, K, h0, ys)


@jit_noalloc_inline
def start_size(st, y, K, dy, atol, rtol):
    """Starting step size, second half (HNW II.4 steps d-f): ``st.h``.

    ``dy`` holds ``f(t + h0, y + h0 f(t, y))`` on entry (and the difference to ``K[0]`` on
    return). ``d2 = ||f(t + h0, ...) - f(t, y)|| / h0`` estimates the second derivative;
    ``h1 = (0.01 / max(d1, d2))^(1/5)`` (``max(1e-6, 1e-3 h0)`` when both are below 1e-15),
    ``h = min(100 h0, h1, span)``, 1e-6 s if that is not a positive number.
    """
    for i in range(y.shape[0]):
        dy[i] -= K[0, i]
    h0 = st.h0
    d1 = st.d1
    d2 = scaled_rms(dy, y, st.first, st.count, atol, rtol) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(START_FALLBACK_STEP, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 5.0)
    h = min(START_GROWTH * h0, h1, st.span)
    if not (math.isfinite(h) and h > 0.0):
        h = START_FALLBACK_STEP
    st.h = h
