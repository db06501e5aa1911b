"""Planning of the time loop: the next step attempt, or a hop over a loaded table-end crossing.

When a loaded pair slot crosses an end of the gap tables its force jumps (events.py). The loop
ends the step a fraction EVENT_LANDING before the predicted crossing and then hops over it with
one explicit Euler step ending just past it, restarting with a fraction of the last step size
(docs/theory.md §6.8; Hairer, Norsett & Wanner, "Solving ODEs I", 2nd ed. 1993, §II.6,
discontinuous right-hand sides). Phases of :func:`gearcli.core.timeloop.run`, inlined into
it, over the loop-state record of :mod:`gearcli.core.loopstate`; times in [s].
"""

import math

import numpy as np

from gearcli.core.dopri5 import euler
from gearcli.core.events import next_crossing
from gearcli.core.layout import (
    STATUS_MAX_STEPS,
    STATUS_NAN,
    STATUS_STEP_TOO_SMALL,
    N,
    P,
    S,
)
from gearcli.core.loopstate import PH_HOP, PH_HOP_SAMPLE, PH_PLAN, PH_STAGE
from gearcli.core.nrt import jit_noalloc_inline
from gearcli.core.sampling import sample_in_hop, solution_point

#: Landing point of a step cut short by a predicted discontinuity: this fraction of the step
#: before the predicted crossing (absorbs the error of the quadratic prediction).
EVENT_LANDING = 1e-3
#: A crossing closer than this many landing gaps is hopped over with one Euler step.
EVENT_HOP = 2.0
#: The hop ends this fraction of its length (at least EVENT_MIN_OVERSHOOT) past the crossing.
EVENT_OVERSHOOT = 1e-3
EVENT_MIN_OVERSHOOT = 1e-12  # [s]
#: After a hop the next step is this fraction of the last one: the force jump starts a new
#: transient (measured on the seed case: entry needs ~0.4, exit ~0.15 of the step before).
EVENT_RESTART = 0.25
#: The prediction looks this many step sizes ahead and is not repeated before a step would end
#: past the window or the crossing it found (the slot positions move fast against the DTE, so
#: the predicted time stays accurate over the window).
EVENT_LOOKAHEAD = 8.0
#: A crossing within this many units of the smallest step (loop state h_min) is hopped over.
EVENT_HOP_MIN_STEPS = 100.0
#: A hop ends at least this many units of the smallest step past the crossing.
EVENT_HOP_MIN_OVERSHOOT_STEPS = 4.0
#: The smallest step size at t is this many units in the last place of t.
MIN_STEP_ULPS = 10.0


@jit_noalloc_inline
def plan_limits(st, counters, prm):
    """Whether the loop stops before the next step: at ``t_end`` (status unchanged), at
    ``max_steps`` attempts (STATUS_MAX_STEPS), or when the step size ``min(h, max_step,
    t_end - t)`` fell below ``h_min`` (10 units in the last place of t) before the end
    (STATUS_NAN after a non-finite attempt, else STATUS_STEP_TOO_SMALL; status in
    ``st.status``). Sets ``st.h`` to that step size and ``st.h_min``."""
    t = st.t
    t_end = prm[P.t_end]
    if not t < t_end:
        return True
    if counters[N.accepted_steps] + counters[N.rejected_steps] >= prm[P.max_steps]:
        st.status = STATUS_MAX_STEPS
        return True
    h = min(st.h, prm[P.max_step], t_end - t)
    h_min = MIN_STEP_ULPS * (np.nextafter(t, math.inf) - t)
    st.h = h
    st.h_min = h_min
    if h < h_min and t + h < t_end:
        st.status = STATUS_NAN if st.nonfinite_last else STATUS_STEP_TOO_SMALL
        return True
    return False


@jit_noalloc_inline
def hop_or_step(st, tau, window):
    """Record the crossing predicted ``tau`` [s] ahead within ``window`` [s] (``t_event``,
    ``t_recheck``); when it is closer than the hop limit (or ``EVENT_HOP_MIN_STEPS h_min``)
    plan a hop over it: length ``tau + max(EVENT_OVERSHOOT tau, EVENT_MIN_OVERSHOOT,
    4 h_min)``, end ``st.t_hop``, phase PH_HOP_SAMPLE."""
    t = st.t
    h_min = st.h_min
    st.t_event = t + tau
    st.t_recheck = t + min(tau, window)
    if tau <= max(st.hop_limit, EVENT_HOP_MIN_STEPS * h_min):
        hop = tau + max(EVENT_OVERSHOOT * tau, EVENT_MIN_OVERSHOOT,
                        EVENT_HOP_MIN_OVERSHOOT_STEPS * h_min)
        st.hop = hop
        st.t_hop = t + hop
        st.phase = PH_HOP_SAMPLE


@jit_noalloc_inline
def begin_attempt(st, t_end):
    """The next step attempt from ``st.t``: size ``st.h``, or cut short to end a
    fraction EVENT_LANDING before the predicted crossing ``st.t_event`` (``st.cut``),
    stretched to ``t_end`` when it would end within ``h_min`` of it. Sets ``h_step``,
    ``t_new`` and stage 1."""
    t = st.t
    h = st.h
    t_event = st.t_event
    st.hop_limit = 0.0
    h_step = h
    cut = t + h > t_event
    if cut:  # end the step just before the predicted crossing
        h_step = (t_event - t) * (1.0 - EVENT_LANDING)
    t_new = t + h_step
    if t_new > t_end - st.h_min:
        t_new = t_end
        h_step = t_end - t
    st.h_step = h_step
    st.t_new = t_new
    st.cut = cut
    st.stage = 1


@jit_noalloc_inline
def plan(st, y, K, model, counters):
    """Decide what follows the accepted state ``(st.t, y)``: stop (True, plan_limits), or
    a step attempt (phase PH_STAGE) or a hop (PH_HOP_SAMPLE). The crossing is predicted again
    after an event or when the step would end past ``t_recheck``."""
    if plan_limits(st, counters, model.prm):
        return True
    st.phase = PH_STAGE
    if st.predict or st.t + st.h > st.t_recheck:
        # the next loaded table-end crossing within EVENT_LOOKAHEAD steps (at least the hop
        # limit): overlap margin err_bound + 0.1 |delta| (+ the centres' approach along either
        # line of action in the lateral model)
        st.predict = 0
        margin = st.err_bound + 0.1 * abs(y[S.delta])
        if model.prm[P.lateral] != 0.0:
            margin += abs(y[S.x1] - y[S.x2]) + abs(y[S.y1] - y[S.y2])
        window = max(EVENT_LOOKAHEAD * st.h, st.hop_limit)
        tau = next_crossing(y[S.s1], y[S.v1], K[0, S.v1], y[S.delta], y[S.deltadot],
                            K[0, S.deltadot], model, window, margin)
        hop_or_step(st, tau, window)
    if st.phase == PH_STAGE:
        begin_attempt(st, model.prm[P.t_end])
    return False


@jit_noalloc_inline
def size_after_step(st):
    """The step size after an accepted step: the controller's ``h_step factor``, or after a
    step cut short before a crossing the undisturbed ``st.h`` kept, the hop limit set to
    EVENT_HOP landing gaps and the crossing predicted again (the hop comes next)."""
    h_step = st.h_step
    if st.cut:
        st.hop_limit = EVENT_HOP * EVENT_LANDING * h_step / (1.0 - EVENT_LANDING)
        st.h_cut = h_step
        st.predict = 1
    else:
        st.h = h_step * st.factor


@jit_noalloc_inline
def hop_next(st, t_out, y, K, ys):
    """The next evaluation inside the hop: an output sample on its Euler line
    (sampling.sample_in_hop), else its end: ``y`` and ``t`` jump to it (phase PH_HOP, the
    evaluation there is the next step's K[0])."""
    st.full = 1
    if sample_in_hop(st, t_out, y, K, ys):
        return
    euler(y, K, st.hop, y)
    t = st.t_hop
    st.t = t
    st.ts = t
    for i in range(y.shape[0]):
        ys[i] = y[i]
    st.row = 0
    st.phase = PH_HOP


@jit_noalloc_inline
def end_hop(st, w, out, prm):
    """After the evaluation at the hop's end: a point of the solution (extrema), and a new
    transient starts: the next step is EVENT_RESTART of the smaller of the last step and the
    cut step, and the next crossing is predicted."""
    out.counters[N.rhs_evaluations] += 1
    solution_point(st, st.t, w.y, w, out, prm)
    st.h = EVENT_RESTART * min(st.h, st.h_cut)
    st.hop_limit = 0.0
    st.predict = 1
    st.rejected_before = 0
    st.phase = PH_PLAN
