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
)
from gearcli.core.dopri5 import (
    C as C_STAGE,
)
from gearcli.core.drive import forcing
from gearcli.core.events import next_crossing
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


#: What the time loop's one evaluation of the right-hand side is for (:func:`run`).
PH_START = 0  # f(t_start, y): K[0] of the first step
PH_FIRST_STEP = 1  # the starting step size's trial evaluation (HNW II.4)
PH_STAGE = 2  # stage s = 1 .. N_STAGES of a step attempt (the last one is FSAL, full)
PH_SAMPLE = 3  # an output row inside an accepted step (dense output)
PH_HOP_SAMPLE = 4  # an output row inside a hop over a discontinuity (Euler)
PH_HOP = 5  # f at the end of a hop: K[0] of the next step
PH_PLAN = 6  # none: decide the next step or hop
#: The row of K an evaluation writes: the stage's own (0 for f(t, y) at the start and after a
#: hop, 1 .. N_STAGES for the stages) or this scratch row (samples, the trial evaluation).
ROW_DY = N_STAGES + 1


def new_work(prm) -> Work:
    """Work arrays of :func:`run` for the model with parameter vector ``prm`` (Python side,
    zeros, allocated for every chunk by :func:`gearcli.core.integrate.simulate`).

    The vectors and the rows of K live in one block, each on its own 128-byte boundary.
    Allocated one by one (or K packed with 72-byte rows) the same compiled code ran 1.3-1.5
    times slower depending on the build (measured on the seed case; cache-line/aliasing
    effects). The rows are longer than the vectors they hold (``vec`` exceeds every length),
    so K and the slot forces are never contiguous: numba sees one array layout for every case
    and compiles :func:`run` once.
    """
    n_slots = int(prm[P.n_slots])
    extra = prm[P.lateral] != 0.0 or prm[P.motor_J] > 0.0 or prm[P.load_J] > 0.0
    n_state = N_STATE if extra else N_STATE_BASE  # optional states: all of them or none
    vec = 16 * (max(N_STATE, N_AUX, n_slots) // 16 + 1)
    n_vectors = 4 + N_FAMILIES  # y, ys, y_new, aux, one slot-force row per flank family
    size = (n_vectors + ROW_DY + 1) * vec
    raw = np.zeros(size + 16)
    skip = (-raw.ctypes.data % 128) // 8  # the block starts on a 128-byte boundary
    work = raw[skip:skip + size]
    K = work[n_vectors * vec:].reshape((ROW_DY + 1, vec))[:, :n_state]  # K[0] = f(t, y)
    return Work(
        y=work[0:n_state],
        ys=work[vec:vec + n_state],
        y_new=work[2 * vec:2 * vec + n_state],
        aux=work[3 * vec:3 * vec + N_AUX],
        slot_force=work[4 * vec:n_vectors * vec].reshape((N_FAMILIES, vec))[:, :n_slots],
        K=K,
        dy=K[ROW_DY],
        atol=np.zeros(N_STATE),
        scratch=np.zeros((N_SCRATCH, n_slots)),
    )


@jit_noalloc_inline
def _init(model, w, resume, fresh):
    """Absolute tolerances and the state at the start of a chunk (a fresh start from the
    initial values in ``prm``, else the ``resume`` state of the last chunk)."""
    prm = model.prm
    y = w.y
    n_state = y.shape[0]
    atol = w.atol
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
    for i in range(n_state):
        y[i] = 0.0 if fresh else resume[RESUME_Y + i]
    if fresh:
        y[S.s1] = prm[P.r_b1] * prm[P.theta1_init]
        y[S.v1] = prm[P.r_b1] * prm[P.omega1_init]
        y[S.delta] = prm[P.delta_init]
        y[S.deltadot] = prm[P.deltadot_init]
        if n_state > N_STATE_BASE:
            y[S.x1] = prm[P.x1_init]
            y[S.y1] = prm[P.y1_init]
            y[S.x2] = prm[P.x2_init]
            y[S.y2] = prm[P.y2_init]
            y[S.tw_m] = prm[P.tw_m_init]
            y[S.tw_l] = prm[P.tw_l_init]


@jit_noalloc_inline
def _euler(y, K, dt, out):
    """``out = y + dt K[0]`` (a hop's samples and its end)."""
    for i in range(y.shape[0]):
        out[i] = y[i] + dt * K[0, i]


@jit_noalloc
def run(model, w, out, layout_key, i_first):
    """Integrate from ``prm[P.t_start]`` to ``prm[P.t_end]``; see the module docstring.

    One call integrates one chunk of a run: the caller (:mod:`gearcli.core.integrate`) owns the
    outputs and the ``resume`` state and calls again for the next chunk, so the results do not
    depend on how often a progress display looks in.

    The loop evaluates the right-hand side at exactly one place, the top of its body; what the
    evaluation is for is the phase (``PH_*``): a stage of a step attempt, an output sample
    (inside a step or a hop), the end of a hop, the start, the starting step size's trial. One
    call site means one inlined copy of the right-hand side in the compiled code: a second copy
    for the samples, hops and the start (a compiled helper, as it was before) made the first
    run's compilation 1.5 times as long (bench/RESULTS.md, session 9). A call instead of the
    inlined copy passes a dozen arrays every time (the step attempt as a call per step cost
    ~14 % more run time on the seed, A/B when the loop was written; ``flank`` as a call 63 %,
    bench/RESULTS.md session 6).
    Allocation-free (numba's reference counting off, nrt.jit_noalloc), so the caller allocates
    ``w`` (:func:`new_work`) and this is the entry point itself: a compiled wrapper that
    allocates would re-optimise the whole loop in its own library.

    Parameters
    ----------
    model : gearcli.core.bundles.Model
        Read-only data of the run (internal units); ``prm`` holds ``t_start``, ``t_end`` of
        this chunk; ``derived`` and ``family`` from :func:`gearcli.core.derive.derive`.
    w : gearcli.core.bundles.Work
        Work arrays from :func:`new_work`, as it makes them (zeros: the loop reads the
        ``aux`` entries of bodies the model does not have, which nothing writes).
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
    atol = w.atol
    n_state = y.shape[0]
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
    fresh = resume[R.started] == 0.0
    if fresh:
        theta_offset = prm[P.theta1_init]
        if mode != DRIVE_TORQUE:
            angle_pp = model.angle_pp
            theta_offset -= pp_eval(angle_pp[0], angle_pp[1], angle_pp[2], t)
    else:
        theta_offset = resume[R.theta_offset]
    _init(model, w, resume, fresh)

    # Loop state. bool(False) and int(0) are run-time types: numba types a call before it has
    # seen the loop's later assignments, and with a literal start value (False, 0) it would
    # compile the callee once more for that literal (bench/RESULTS.md, session 9).
    status = STATUS_OK
    i_out = i_first
    span = t_end - t
    h = 0.0  # next step size [s]
    h0 = 0.0  # trial step of the starting step size [s]
    d1 = 0.0  # scaled norm of f(t, y) (starting step size)
    h_min = 0.0
    h_step = 0.0  # the step being attempted [s]
    t_new = t
    s = int(0)  # noqa: UP018  (its stage; run-time type, see above)
    cut = False
    err = 0.0
    factor = 1.0
    runaway = False
    hop = 0.0
    t_hop = t
    rejected_before = bool(False)  # noqa: UP018
    nonfinite_last = False
    predict = True  # predict the next discontinuity before the next step
    t_event = math.inf
    t_recheck = -math.inf  # predict again before a step ends past this time [s]
    hop_limit = 0.0  # a crossing closer than this [s] is hopped over
    h_cut = math.inf  # size of the last step cut short by a crossing [s]
    phase = PH_START
    ts = t  # time [s], state (ys) and row of K of the next evaluation
    row = int(0)  # noqa: UP018
    full = True
    for i in range(n_state):
        ys[i] = y[i]
    while True:
        # the one evaluation of the right-hand side: at (ts, ys) into K[row], aux, slot forces
        rhs(ts, ys, K[row], aux, w.slot_force, w.scratch, model,
            forcing(ts, mode, theta_offset, model), full)

        # what it was for
        if phase == PH_STAGE:
            counters[N.rhs_evaluations] += 1
            # Stages 2 .. 5 go straight to the next evaluation; stage 6 and the first stage
            # of an attempt are prepared at the end of the loop body. One place for all six
            # is the same arithmetic but ran 4-5 % slower than this (code layout: seed and
            # iso_pair, three A/B rounds each, bench/RESULTS.md session 9).
            if s < N_STAGES - 1:
                s += 1
                stage_state(y, K, s, h_step, ys, first)
                ts = t + C_STAGE[s] * h_step
                row = s
                continue
            if s < N_STAGES:
                s += 1
            else:  # the step attempt is complete: y_new, the FSAL stage K[6], its error
                for i in range(n_state):
                    y_new[i] = ys[i]
                err = error_norm(y, y_new, K, h_step, first, count, atol, rtol)
                if not (math.isfinite(err) and _all_finite(y_new) and _row_finite(K, s)):
                    counters[N.rejected_steps] += 1
                    h = h_step * MIN_FACTOR
                    rejected_before = True
                    nonfinite_last = True
                    phase = PH_PLAN
                elif err >= 1.0:
                    nonfinite_last = False
                    counters[N.rejected_steps] += 1
                    h = h_step * step_factor(err, rejected_before)
                    rejected_before = True
                    phase = PH_PLAN
                else:
                    # Accepted. Extrema from the FSAL evaluation at (t_new, y_new), then the
                    # output rows inside the step.
                    nonfinite_last = False
                    counters[N.accepted_steps] += 1
                    if speed_mode:
                        y_new[S.s1] = aux[A.s1]
                        y_new[S.v1] = aux[A.v1]
                    if t_new >= ext_start:
                        update_extrema(out.extrema, out.slot_extrema, t_new, y_new, aux,
                                       w.slot_force, lateral)
                    runaway = aux[A.max_penetration] > pen_limit
                    factor = step_factor(err, rejected_before)
                    rejected_before = False
                    phase = PH_SAMPLE
        elif phase == PH_SAMPLE or phase == PH_HOP_SAMPLE:
            out.counters[N.output_evaluations] += 1
            write_row(out.series, out.slot_series, i_out, ts, ys, aux, w.slot_force, prm)
            if ts >= ext_start:  # samples are points of the solution too
                update_extrema(out.extrema, out.slot_extrema, ts, ys, aux, w.slot_force,
                               lateral)
            i_out += 1
        elif phase == PH_HOP:
            counters[N.rhs_evaluations] += 1
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
            phase = PH_PLAN
        elif phase == PH_START:
            counters[N.rhs_evaluations] += 1
            if speed_mode:  # prescribed: keep the (uncontrolled) integrated copies exact
                y[S.s1] = aux[A.s1]
                y[S.v1] = aux[A.v1]
            if fresh:
                extrema[X.energy_initial_mJ] = kinetic_energy(prm, aux[A.v1], y) \
                    + aux[A.contact_energy] + aux[A.spring_energy]
            extrema[X.t_reached_s] = t
            if not (_all_finite(y) and _row_finite(K, row) and _all_finite(aux)):
                return STATUS_NAN, i_first
            if t >= ext_start:
                update_extrema(out.extrema, out.slot_extrema, t, y, aux, w.slot_force, lateral)
            while i_out < n_out and t_out[i_out] <= t:
                write_row(out.series, out.slot_series, i_out, t_out[i_out], y, aux,
                          w.slot_force, prm)
                i_out += 1
            h = prm[P.first_step] if fresh else resume[R.h]
            phase = PH_PLAN
            if h <= 0.0 and span > 0.0:
                # starting step size (HNW II.4; scipy select_initial_step): controlled
                # components only, one trial evaluation at t + h0
                d0 = scaled_rms(y, y, first, count, atol, rtol)
                for i in range(n_state):
                    dy[i] = K[0, i]  # (a row of K would compile scaled_rms a second time)
                d1 = scaled_rms(dy, y, first, count, atol, rtol)
                h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
                h0 = min(h0, span)
                ts = t + h0
                _euler(y, K, h0, ys)
                row = ROW_DY
                phase = PH_FIRST_STEP
                continue
        else:  # PH_FIRST_STEP
            counters[N.rhs_evaluations] += 1
            for i in range(n_state):
                dy[i] -= K[0, i]
            d2 = scaled_rms(dy, y, first, count, atol, rtol) / h0
            if d1 <= 1e-15 and d2 <= 1e-15:
                h1 = max(1e-6, h0 * 1e-3)
            else:
                h1 = (0.01 / max(d1, d2)) ** (1.0 / 5.0)
            h = min(100.0 * h0, h1, span)
            if not (math.isfinite(h) and h > 0.0):
                h = 1e-6
            phase = PH_PLAN

        # the output rows inside an accepted step, then the step is taken
        if phase == PH_SAMPLE:
            if i_out < n_out and t_out[i_out] <= t_new:
                ts = t_out[i_out]
                dense(y, K, h_step, (ts - t) / h_step, ys)
                row = ROW_DY
                full = True
                continue
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
            phase = PH_PLAN

        # the next step, or a hop over a discontinuity
        if phase == PH_PLAN:
            if not t < t_end:
                break
            if counters[N.accepted_steps] + counters[N.rejected_steps] >= max_steps:
                status = STATUS_MAX_STEPS
                break
            h = min(h, max_step, t_end - t)
            h_min = 10.0 * (np.nextafter(t, math.inf) - t)
            if h < h_min and t + h < t_end:
                status = STATUS_NAN if nonfinite_last else STATUS_STEP_TOO_SMALL
                break
            phase = PH_STAGE
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
                    phase = PH_HOP_SAMPLE
            if phase == PH_STAGE:
                hop_limit = 0.0
                h_step = h
                cut = t + h > t_event
                if cut:  # end the step just before the predicted crossing
                    h_step = (t_event - t) * (1.0 - EVENT_LANDING)
                t_new = t + h_step
                if t_new > t_end - h_min:
                    t_new = t_end
                    h_step = t_end - t
                s = 1

        # a hop: its output rows (Euler), then the evaluation at its end
        if phase == PH_HOP_SAMPLE:
            full = True
            if i_out < n_out and t_out[i_out] <= t_hop:
                ts = t_out[i_out]
                _euler(y, K, ts - t, ys)
                row = ROW_DY
                continue
            _euler(y, K, hop, y)
            t = t_hop
            ts = t
            for i in range(n_state):
                ys[i] = y[i]
            row = 0
            phase = PH_HOP
            continue

        # the next stage of the step attempt (Dormand-Prince 5(4), dopri5.py)
        if s < N_STAGES:
            stage_state(y, K, s, h_step, ys, first)
            ts = t + C_STAGE[s] * h_step
        else:  # the 5th-order solution; its evaluation is the FSAL stage K[6]
            solution(y, K, h_step, ys, first)
            ts = t_new
        row = s
        full = s == N_STAGES

    extrema[X.t_reached_s] = t
    resume[R.started] = 1.0
    resume[R.theta_offset] = theta_offset
    resume[R.h] = h
    for i in range(n_state):
        resume[RESUME_Y + i] = y[i]
    return status, i_out
