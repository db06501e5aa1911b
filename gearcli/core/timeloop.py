"""The compiled time loop of ``gearcli simulate`` (called through :mod:`gearcli.core.integrate`).

:func:`run` integrates the model of :mod:`gearcli.core.rhs` from ``t_start`` to ``t_end`` with
Dormand-Prince 5(4) (:mod:`gearcli.core.dopri5`) in one compiled function: adaptive steps, dense
output exactly at the requested output times, extrema of the forces at every accepted step
(true extrema, not only at the samples), counters and a status code (layout.STATUS_*). On an
error status the rows not reached stay NaN and ``n_valid`` says how many rows are filled.

Error control (HNW II.4): RMS norm of the local error scaled by ``atol_i + rtol max(|y|, |y_new|)``
over (s1, v1, delta, deltadot) with atol ``atol_delta`` [mm] for s1 and delta and
``atol_deltadot`` [mm/s] for v1 and deltadot. ``atol_delta`` is the absolute accuracy of the
small relative coordinate; s1 and v1 grow large and are effectively controlled relatively
(rtol). In speed mode s1 and v1 are prescribed and only (delta, deltadot) are controlled. The
energy quadratures are integrated with the same stages but not error controlled.
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.core.bundles import Work
from gearcli.core.dopri5 import (
    MIN_FACTOR,
    N_STAGES,
    dense,
    error_norm,
    scaled_rms,
    solution,
    stage_state,
    step_factor,
    store_row,
)
from gearcli.core.dopri5 import (
    C as C_STAGE,
)
from gearcli.core.drive import forcing
from gearcli.core.events import next_crossing
from gearcli.core.jit import jit
from gearcli.core.layout import (
    DRIVE_SPEED,
    DRIVE_TORQUE,
    LAYOUT_KEY,
    N_AUX,
    N_FAMILIES,
    N_SCRATCH,
    N_STATE,
    N_STATE_BASE,
    RESUME_Y,
    STATUS_MAX_STEPS,
    STATUS_NAN,
    STATUS_OK,
    STATUS_RUNAWAY_PENETRATION,
    STATUS_STALE_CACHE,
    STATUS_STEP_TOO_SMALL,
    A,
    D,
    N,
    P,
    R,
    S,
    X,
)
from gearcli.core.nrt import jit_noalloc, jit_noalloc_inline
from gearcli.core.records import (
    kinetic_energy,
    update_extrema,
    write_row,
)
from gearcli.core.rhs import rhs
from gearcli.core.timefunc import pp_eval

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


@jit_noalloc
def _all_finite(y):
    for i in range(y.shape[0]):
        if not math.isfinite(y[i]):
            return False
    return True


@jit_noalloc
def _row_finite(K, s):
    for i in range(K.shape[1]):
        if not math.isfinite(K[s, i]):
            return False
    return True


@jit_noalloc
def _evaluate(t, y, dy, aux, slot_force, scratch, model, mode, theta_offset):
    """One full RHS evaluation at ``t`` with the time functions evaluated there (off the hot
    path: start, hops, output samples)."""
    rhs(t, y, dy, aux, slot_force, scratch, model, forcing(t, mode, theta_offset, model), True)


@jit_noalloc_inline
def _attempt(t, h, t_new, model, work, mode, theta_offset, first, count, rtol):
    """One Dormand-Prince step attempt from (t, y) with K[0] = f(t, y) (``work``, bundles.Work):
    stages 2..6, the solution ``y_new`` at ``t_new = t + h``, the FSAL stage K[6] = f(t_new,
    y_new) (its ``aux`` and slot forces stay in the work arrays) and the scaled error norm
    (dopri5.error_norm). Only components ``first ..`` are integrated (speed mode: s1, v1 are
    prescribed and the rhs ignores their entries of the state).

    The hot path of the kernel: forcing and rhs are inlined here, and this function into
    :func:`_march` (nrt.jit_noalloc_inline).
    """
    y = work.y
    K = work.K
    ys = work.ys
    y_new = work.y_new
    for s in range(1, N_STAGES + 1):
        if s < N_STAGES:
            stage_state(y, K, s, h, ys, first)
            ts = t + C_STAGE[s] * h
        else:
            solution(y, K, h, ys, first)
            ts = t_new
        # writes straight into the row of K (a view costs nothing without reference counts)
        rhs(ts, ys, K[s], work.aux, work.slot_force, work.scratch, model,
            forcing(ts, mode, theta_offset, model), s == N_STAGES)
    for i in range(y.shape[0]):
        y_new[i] = ys[i]
    return error_norm(y, y_new, K, h, first, count, work.atol, rtol)


@jit_noalloc
def _starting_step(t, model, work, mode, theta_offset, first, count, rtol, span):
    """Starting step size [s] (HNW II.4, "starting step size"; scipy select_initial_step).

    Uses the controlled components only and one extra RHS evaluation (written into ``dy``,
    ``aux`` and the slot forces of ``work``, which are scratch here); f(t, y) is ``K[0]``.
    """
    y = work.y
    f0 = work.K[0]
    ys = work.ys
    dy = work.dy
    atol = work.atol
    d0 = scaled_rms(y, y, first, count, atol, rtol)
    d1 = scaled_rms(f0, y, first, count, atol, rtol)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, span)
    for i in range(y.shape[0]):
        ys[i] = y[i] + h0 * f0[i]
    _evaluate(t + h0, ys, dy, work.aux, work.slot_force, work.scratch, model, mode, theta_offset)
    for i in range(y.shape[0]):
        dy[i] -= f0[i]
    d2 = scaled_rms(dy, y, first, count, atol, rtol) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 5.0)
    h = min(100.0 * h0, h1, span)
    return h if math.isfinite(h) and h > 0.0 else 1e-6


@jit
def run(model, out, layout_key, i_first):
    """Integrate from ``prm[P.t_start]`` to ``prm[P.t_end]``; see the module docstring.

    One call integrates one chunk of a run: the caller (:mod:`gearcli.core.integrate`) owns the
    outputs and the ``resume`` state and calls again for the next chunk, so the results do not
    depend on how often a progress display looks in.

    Parameters
    ----------
    model : gearcli.core.bundles.Model
        Read-only data of the run (internal units); ``prm`` holds ``t_start``, ``t_end`` of
        this chunk; ``derived`` and ``family`` from :func:`gearcli.core.derive.derive`.
    out : gearcli.core.bundles.Out
        Output times (non-decreasing, whole run: rows ``i_first ..`` with ``t_out <= t_end``
        are written by this chunk), output rows, running extrema (start values from
        records.init_extrema), counters (incremented) and ``resume`` (layout.R, in/out:
        ``started == 0`` is a fresh start from the initial values in ``prm`` and sets
        ``energy_initial_mJ``; otherwise the state, the prescribed-angle offset [rad] and the
        next step size [s] where the last chunk ended; written on return for the next chunk).
    layout_key : int
        layout.LAYOUT_KEY as seen by the caller (stale-cache guard).
    i_first : int
        First output row of this chunk.

    Returns
    -------
    status : int
    i_out : int
        Next output row (rows ``i_first .. i_out - 1`` were written).
    """
    if layout_key != LAYOUT_KEY:
        return STATUS_STALE_CACHE, i_first
    prm = model.prm
    resume = out.resume
    n_slots = int(prm[P.n_slots])
    mode = int(prm[P.drive_mode])
    t = prm[P.t_start]
    fresh = resume[R.started] == 0.0
    if fresh:
        theta_offset = prm[P.theta1_init]
        if mode != DRIVE_TORQUE:
            angle_pp = model.angle_pp
            theta_offset -= pp_eval(angle_pp[0], angle_pp[1], angle_pp[2], t)
    else:
        theta_offset = resume[R.theta_offset]

    # optional degrees of freedom (layout.STATE_NAMES): all of them or none are integrated
    extra = prm[P.lateral] != 0.0 or prm[P.motor_J] > 0.0 or prm[P.load_J] > 0.0
    n_state = N_STATE if extra else N_STATE_BASE
    atol = np.zeros(N_STATE)
    atol[S.s1] = prm[P.atol_delta]
    atol[S.v1] = prm[P.atol_deltadot]
    atol[S.delta] = prm[P.atol_delta]
    atol[S.deltadot] = prm[P.atol_deltadot]
    for pos, rate in ((S.x1, S.vx1), (S.y1, S.vy1), (S.x2, S.vx2), (S.y2, S.vy2)):
        atol[pos] = prm[P.atol_delta]  # centre displacements and rates: like the DTE
        atol[rate] = prm[P.atol_deltadot]
    atol[S.tw_m] = prm[P.atol_delta] / prm[P.r_b1]  # twists [rad]: the same at the base radius
    atol[S.tw_m_dot] = prm[P.atol_deltadot] / prm[P.r_b1]
    atol[S.tw_l] = prm[P.atol_delta] / prm[P.r_b2]
    atol[S.tw_l_dot] = prm[P.atol_deltadot] / prm[P.r_b2]

    # Work vectors and the rows of K in one block, each starting on its own 128-byte boundary.
    # Allocated one by one (or K packed with 72-byte rows) the same code ran 1.3-1.5 times
    # slower depending on the build (measured on the seed case; cache-line/aliasing effects).
    vec = 16 * ((max(N_STATE, N_AUX, n_slots) + 15) // 16)
    n_vectors = 5 + N_FAMILIES  # y, dy, ys, y_new, aux, one slot-force row per flank family
    work = np.zeros((n_vectors + N_STAGES + 1) * vec)
    w = Work(
        y=work[0:n_state],
        dy=work[vec:vec + n_state],
        ys=work[2 * vec:2 * vec + n_state],
        y_new=work[3 * vec:3 * vec + n_state],
        aux=work[4 * vec:4 * vec + N_AUX],
        slot_force=work[5 * vec:n_vectors * vec].reshape((N_FAMILIES, vec))[:, :n_slots],
        K=work[n_vectors * vec:].reshape((N_STAGES + 1, vec))[:, :n_state],  # K[0] = f(t, y)
        atol=atol,
        scratch=np.zeros((N_SCRATCH, n_slots)),
    )
    y = w.y
    if not fresh:
        for i in range(n_state):
            y[i] = resume[RESUME_Y + i]
    else:
        y[S.s1] = prm[P.r_b1] * prm[P.theta1_init]
        y[S.v1] = prm[P.r_b1] * prm[P.omega1_init]
        y[S.delta] = prm[P.delta_init]
        y[S.deltadot] = prm[P.deltadot_init]
    if extra and fresh:
        y[S.x1] = prm[P.x1_init]
        y[S.y1] = prm[P.y1_init]
        y[S.x2] = prm[P.x2_init]
        y[S.y2] = prm[P.y2_init]
        y[S.tw_m] = prm[P.tw_m_init]
        y[S.tw_l] = prm[P.tw_l_init]

    # f(t, y) here, not in _march: numba then compiles _evaluate in this simpler context
    # (6 s instead of 20 s of the first run's compilation, measured)
    _evaluate(t, y, w.dy, w.aux, w.slot_force, w.scratch, model, mode, theta_offset)
    return _march(model, w, out, i_first, theta_offset, fresh, n_state)


@jit_noalloc_inline
def _sample(out, i_out, ts, ys, w, model, mode, theta_offset, ext_start, lateral):
    """Output row ``i_out`` at ``ts`` [s] from the state ``ys`` there (and its extrema).
    Inlined: as a call it would pass every array of three bundles per output row."""
    _evaluate(ts, ys, w.dy, w.aux, w.slot_force, w.scratch, model, mode, theta_offset)
    out.counters[N.output_evaluations] += 1
    write_row(out.series, out.slot_series, i_out, ts, ys, w.aux, w.slot_force, model.prm)
    if ts >= ext_start:  # samples are points of the solution too
        update_extrema(out.extrema, out.slot_extrema, ts, ys, w.aux, w.slot_force, lateral)


@jit_noalloc
def _march(model, w, out, i_first, theta_offset, fresh, n_state):
    """The time loop of :func:`run`, from its work arrays ``w`` (bundles.Work) with
    ``w.dy = f(t_start, y)``.

    Allocation-free, so that the step attempt can be inlined here: in :func:`run` (which
    allocates, hence counts references) the inlined views cost 4x the run time, and as a call
    per step the attempt's ~170 words of array arguments cost ~14 % of it (seed case, A/B).
    """
    prm = model.prm
    t_out = out.t_out
    counters = out.counters
    extrema = out.extrema
    resume = out.resume
    y = w.y
    dy = w.dy
    ys = w.ys
    y_new = w.y_new
    aux = w.aux
    K = w.K
    n_out = t_out.shape[0]
    mode = int(prm[P.drive_mode])
    speed_mode = mode == DRIVE_SPEED
    t = prm[P.t_start]
    t_end = prm[P.t_end]
    rtol = prm[P.rtol]
    max_step = prm[P.max_step]
    max_steps = prm[P.max_steps]
    ext_start = prm[P.extrema_t_start]
    pen_limit = prm[P.penetration_limit]
    # overlap margin of a loaded crossing (events.py): errors + 10 atol (+ 10 % of |delta|)
    err_bound = model.derived[D.error_bound] + 10.0 * prm[P.atol_delta]
    lateral = prm[P.lateral] != 0.0
    first = S.delta if speed_mode else S.s1  # controlled components: first .. S.deltadot
    count = S.deltadot + 1 - first
    store_row(K, 0, dy)
    counters[N.rhs_evaluations] += 1
    if speed_mode:  # prescribed: keep the (uncontrolled) integrated copies exact
        y[S.s1] = aux[A.s1]
        y[S.v1] = aux[A.v1]
    if fresh:
        extrema[X.energy_initial_mJ] = kinetic_energy(prm, aux[A.v1], y) \
            + aux[A.contact_energy] + aux[A.spring_energy]
    extrema[X.t_reached_s] = t
    if not (_all_finite(y) and _all_finite(dy) and _all_finite(aux)):
        return STATUS_NAN, i_first
    if t >= ext_start:
        update_extrema(out.extrema, out.slot_extrema, t, y, aux, w.slot_force, lateral)
    i_out = i_first
    while i_out < n_out and t_out[i_out] <= t:
        write_row(out.series, out.slot_series, i_out, t_out[i_out], y, aux, w.slot_force, prm)
        i_out += 1

    span = t_end - t
    h = prm[P.first_step] if fresh else resume[R.h]
    if h <= 0.0 and span > 0.0:
        h = _starting_step(t, model, w, mode, theta_offset, first, count, rtol, span)
        counters[N.rhs_evaluations] += 1

    status = STATUS_OK
    rejected_before = False
    nonfinite_last = False
    predict = True  # predict the next discontinuity before the next step
    t_event = math.inf
    t_recheck = -math.inf  # predict again before a step ends past this time [s]
    hop_limit = 0.0  # a crossing closer than this [s] is hopped over
    h_cut = math.inf  # size of the last step cut short by a crossing [s]
    while t < t_end:
        if counters[N.accepted_steps] + counters[N.rejected_steps] >= max_steps:
            status = STATUS_MAX_STEPS
            break
        h = min(h, max_step, t_end - t)
        h_min = 10.0 * (np.nextafter(t, math.inf) - t)
        if h < h_min and t + h < t_end:
            status = STATUS_NAN if nonfinite_last else STATUS_STEP_TOO_SMALL
            break
        if predict or t + h > t_recheck:
            predict = False
            margin = err_bound + 0.1 * abs(y[S.delta])
            if lateral:  # the centres' approach along either line of action, at most
                margin += abs(y[S.x1] - y[S.x2]) + abs(y[S.y1] - y[S.y2])
            window = max(EVENT_LOOKAHEAD * h, hop_limit)
            tau = next_crossing(y[S.s1], y[S.v1], K[0, S.v1], y[S.delta], y[S.deltadot],
                                K[0, S.deltadot], model, window, margin)
            t_event = t + tau
            t_recheck = t + min(tau, window)
            if tau <= max(hop_limit, 100.0 * h_min):
                # Hop over the discontinuity with one Euler step ending just past it.
                hop = tau + max(EVENT_OVERSHOOT * tau, EVENT_MIN_OVERSHOOT, 4.0 * h_min)
                t_hop = t + hop
                while i_out < n_out and t_out[i_out] <= t_hop:
                    ts = t_out[i_out]
                    for i in range(n_state):
                        ys[i] = y[i] + (ts - t) * K[0, i]
                    _sample(out, i_out, ts, ys, w, model, mode, theta_offset, ext_start, lateral)
                    i_out += 1
                for i in range(n_state):
                    y[i] += hop * K[0, i]
                t = t_hop
                _evaluate(t, y, dy, aux, w.slot_force, w.scratch, model, mode, theta_offset)
                counters[N.rhs_evaluations] += 1
                store_row(K, 0, dy)
                if speed_mode:
                    y[S.s1] = aux[A.s1]
                    y[S.v1] = aux[A.v1]
                if t >= ext_start:
                    update_extrema(out.extrema, out.slot_extrema, t, y, aux, w.slot_force, lateral)
                # the jump starts a new transient: restart below the last step size
                h = EVENT_RESTART * min(h, h_cut)
                hop_limit = 0.0
                predict = True
                rejected_before = False
                continue
        hop_limit = 0.0
        h_step = h
        cut = t + h > t_event
        if cut:  # end the step just before the predicted crossing
            h_step = (t_event - t) * (1.0 - EVENT_LANDING)
        t_new = t + h_step
        if t_new > t_end - h_min:
            t_new = t_end
            h_step = t_end - t
        err = _attempt(t, h_step, t_new, model, w, mode, theta_offset, first, count, rtol)
        counters[N.rhs_evaluations] += N_STAGES
        if not (math.isfinite(err) and _all_finite(y_new) and _row_finite(K, N_STAGES)):
            counters[N.rejected_steps] += 1
            h = h_step * MIN_FACTOR
            rejected_before = True
            nonfinite_last = True
            continue
        nonfinite_last = False
        if err >= 1.0:
            counters[N.rejected_steps] += 1
            h = h_step * step_factor(err, rejected_before)
            rejected_before = True
            continue

        # Accepted. Extrema from the FSAL evaluation at (t_new, y_new), before sampling.
        counters[N.accepted_steps] += 1
        if speed_mode:
            y_new[S.s1] = aux[A.s1]
            y_new[S.v1] = aux[A.v1]
        if t_new >= ext_start:
            update_extrema(out.extrema, out.slot_extrema, t_new, y_new, aux, w.slot_force,
                           lateral)
        runaway = aux[A.max_penetration] > pen_limit
        while i_out < n_out and t_out[i_out] <= t_new:
            ts = t_out[i_out]
            dense(y, K, h_step, (ts - t) / h_step, ys)
            _sample(out, i_out, ts, ys, w, model, mode, theta_offset, ext_start, lateral)
            i_out += 1
        factor = step_factor(err, rejected_before)
        rejected_before = False
        t = t_new
        for i in range(n_state):
            y[i] = y_new[i]
            K[0, i] = K[N_STAGES, i]
        if runaway:
            status = STATUS_RUNAWAY_PENETRATION
            break
        if cut:  # keep the step size of the undisturbed solution; hop next
            hop_limit = EVENT_HOP * EVENT_LANDING * h_step / (1.0 - EVENT_LANDING)
            h_cut = h_step
            predict = True
        else:
            h = h_step * factor

    extrema[X.t_reached_s] = t
    resume[R.started] = 1.0
    resume[R.theta_offset] = theta_offset
    resume[R.h] = h
    for i in range(n_state):
        resume[RESUME_Y + i] = y[i]
    return status, i_out
