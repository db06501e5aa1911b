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

The loop's phases are small functions inlined into :func:`run`, each over the named loop-state
record of :mod:`gearcli.core.loopstate`: step-size control and the starting step
(:mod:`gearcli.core.stepsize`), the next step or hop (:mod:`gearcli.core.hops`), output
placement (:mod:`gearcli.core.sampling`), and here the start of a chunk, the end of a step
attempt, taking a step and preparing a stage.
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.core.bundles import Work
from gearcli.core.dopri5 import (
    N_STAGES,
    error_norm,
    solution,
    stage_state,
)
from gearcli.core.dopri5 import (
    C as C_STAGE,
)
from gearcli.core.drive import forcing
from gearcli.core.hops import end_hop, hop_next, plan, size_after_step
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
    STATUS_NAN,
    STATUS_OK,
    STATUS_RUNAWAY_PENETRATION,
    STATUS_STALE_CACHE,
    A,
    D,
    N,
    P,
    R,
    S,
    X,
)
from gearcli.core.loopstate import (
    PH_FIRST_STEP,
    PH_HOP,
    PH_HOP_SAMPLE,
    PH_PLAN,
    PH_SAMPLE,
    PH_STAGE,
    PH_START,
    ROW_DY,
    loop_state,
)
from gearcli.core.nrt import jit_noalloc, jit_noalloc_inline
from gearcli.core.records import kinetic_energy, update_extrema, write_row
from gearcli.core.rhs import rhs
from gearcli.core.sampling import record_sample, sample_in_step, solution_point
from gearcli.core.stepsize import control, start_size, start_trial
from gearcli.core.timefunc import pp_eval


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
def _start_loop(st, model, resume, fresh, i_first):
    """Every field of the loop state (loopstate.py) at the start of a chunk: at ``t_start``,
    no step size yet, no crossing predicted, phase PH_START (f(t_start, y) into K[0]).

    Returns the offset [rad] of the prescribed pinion (or motor) angle from the drive's
    antiderivative: ``theta1_init - Theta(t_start)`` on a fresh start, else the last chunk's.
    """
    prm = model.prm
    t = prm[P.t_start]
    speed_mode = int(prm[P.drive_mode]) == DRIVE_SPEED
    first = S.delta if speed_mode else S.s1  # controlled components: first .. S.deltadot
    st.t = t
    st.ts = t
    st.t_new = t
    st.span = prm[P.t_end] - t
    st.h = 0.0
    st.h_step = 0.0
    st.h_min = 0.0
    st.h0 = 0.0
    st.d1 = 0.0
    st.factor = 1.0
    # overlap margin of a loaded crossing (events.py): errors + 10 atol (+ 10 % of |delta|)
    st.err_bound = model.derived[D.error_bound] + 10.0 * prm[P.atol_delta]
    st.t_event = math.inf
    st.t_recheck = -math.inf
    st.hop_limit = 0.0
    st.h_cut = math.inf
    st.hop = 0.0
    st.t_hop = t
    st.phase = PH_START
    st.stage = 0
    st.row = 0
    st.full = 1
    st.i_out = i_first
    st.status = STATUS_OK
    st.first = first
    st.count = S.deltadot + 1 - first
    st.speed_mode = speed_mode
    st.fresh = fresh
    st.rejected_before = 0
    st.nonfinite_last = 0
    st.cut = 0
    st.runaway = 0
    st.predict = 1
    if not fresh:
        return resume[R.theta_offset]
    theta_offset = prm[P.theta1_init]
    if int(prm[P.drive_mode]) != DRIVE_TORQUE:
        angle_pp = model.angle_pp
        theta_offset -= pp_eval(angle_pp[0], angle_pp[1], angle_pp[2], t)
    return theta_offset


@jit_noalloc_inline
def _start_chunk(st, w, out, prm):
    """After f(t, y) at the chunk's start (into K[0]): the initial energy of a fresh start, the
    start's extrema and output rows, the first step size (``first_step``, the last chunk's
    next one, or the starting step size's trial evaluation next). False if not finite."""
    out.counters[N.rhs_evaluations] += 1
    y = w.y
    aux = w.aux
    t = st.t
    if st.speed_mode:  # prescribed: keep the (uncontrolled) integrated copies exact
        y[S.s1] = aux[A.s1]
        y[S.v1] = aux[A.v1]
    fresh = st.fresh != 0
    if fresh:
        out.extrema[X.energy_initial_mJ] = kinetic_energy(prm, aux[A.v1], y) \
            + aux[A.contact_energy] + aux[A.spring_energy]
    out.extrema[X.t_reached_s] = t
    if not (_all_finite(y) and _row_finite(w.K, st.row) and _all_finite(aux)):
        return False
    if t >= prm[P.extrema_t_start]:
        update_extrema(out.extrema, out.slot_extrema, t, y, aux, w.slot_force,
                       prm[P.lateral] != 0.0)
    t_out = out.t_out
    i_out = st.i_out
    while i_out < t_out.shape[0] and t_out[i_out] <= t:
        write_row(out.series, out.slot_series, i_out, t_out[i_out], y, aux, w.slot_force, prm)
        i_out += 1
    st.i_out = i_out
    h = prm[P.first_step] if fresh else out.resume[R.h]
    st.h = h
    st.phase = PH_PLAN
    if h <= 0.0 and st.span > 0.0:
        start_trial(st, y, w.K, w.dy, w.ys, w.atol, prm[P.rtol])
        st.row = ROW_DY
        st.phase = PH_FIRST_STEP
    return True


@jit_noalloc_inline
def _finish_attempt(st, w, out, prm):
    """The step attempt is complete (``w.ys`` its 5th-order solution, K[N_STAGES] the FSAL
    evaluation there): error norm and the controller's decision (stepsize.control); an
    accepted step's end is a point of the solution (extrema) and is checked against the
    penetration limit."""
    y = w.y
    y_new = w.y_new
    K = w.K
    for i in range(y.shape[0]):
        y_new[i] = w.ys[i]
    err = error_norm(y, y_new, K, st.h_step, st.first, st.count, w.atol,
                     prm[P.rtol])
    finite = math.isfinite(err) and _all_finite(y_new) and _row_finite(K, st.stage)
    if control(st, err, finite, out.counters):
        solution_point(st, st.t_new, y_new, w, out, prm)
        st.runaway = w.aux[A.max_penetration] > prm[P.penetration_limit]


@jit_noalloc_inline
def _take_step(st, w):
    """Move to the accepted step's end (t, y, K[0] = its FSAL stage) and size the next step
    (hops.size_after_step). True on a runaway penetration (status set): the loop stops."""
    y = w.y
    K = w.K
    st.t = st.t_new
    for i in range(y.shape[0]):
        y[i] = w.y_new[i]
        K[0, i] = K[N_STAGES, i]
    if st.runaway:
        st.status = STATUS_RUNAWAY_PENETRATION
        return True
    size_after_step(st)
    st.phase = PH_PLAN
    return False


@jit_noalloc_inline
def _next_stage(st, y, K, ys):
    """The next evaluation of the attempt: stage ``st.stage`` (1 .. N_STAGES - 1, writes
    row ``s`` of K), or at N_STAGES the 5th-order solution at ``t_new``, whose evaluation is
    the FSAL stage (full: outputs)."""
    s = st.stage
    if s < N_STAGES:
        stage_state(y, K, s, st.h_step, ys, st.first)
        st.ts = st.t + C_STAGE[s] * st.h_step
    else:
        solution(y, K, st.h_step, ys, st.first)
        st.ts = st.t_new
    st.row = s
    st.full = s == N_STAGES


@jit_noalloc
def run(model, w, out, layout_key, i_first):
    """Integrate from ``prm[P.t_start]`` to ``prm[P.t_end]``; see the module docstring.

    One call integrates one chunk of a run: the caller (:mod:`gearcli.core.integrate`) owns the
    outputs and the ``resume`` state and calls again for the next chunk, so the results do not
    depend on how often a progress display looks in.

    The loop evaluates the right-hand side at exactly one place, the top of its body; what the
    evaluation is for is the phase (``st.phase``, loopstate.PH_*): a stage of a step
    attempt, an output sample (inside a step or a hop), the end of a hop, the start, the
    starting step size's trial. One call site means one inlined copy of the right-hand side in
    the compiled code: a second copy for the samples, hops and the start (a compiled helper,
    as it was before) made the first run's compilation 1.5 times as long (bench/RESULTS.md,
    session 9). A call instead of the inlined copy passes a dozen arrays every time (the step
    attempt as a call per step cost ~14 % more run time on the seed, A/B when the loop was
    written; ``flank`` as a call 63 %, bench/RESULTS.md session 6). The phases themselves are
    small functions inlined here (numba IR, nrt.jit_noalloc_inline) over the named loop-state
    record ``st`` (loopstate.py) on the stack of this function.
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
    st = loop_state()
    y = w.y
    ys = w.ys
    K = w.K
    mode = int(prm[P.drive_mode])
    fresh = out.resume[R.started] == 0.0
    _init(model, w, out.resume, fresh)
    theta_offset = _start_loop(st, model, out.resume, fresh, i_first)
    for i in range(y.shape[0]):
        ys[i] = y[i]
    while True:
        # the one evaluation of the right-hand side: at (ts, ys) into K[row], aux, slot forces
        ts = st.ts
        rhs(ts, ys, K[st.row], w.aux, w.slot_force, w.scratch, model,
            forcing(ts, mode, theta_offset, model), st.full != 0)

        # what it was for
        phase = st.phase
        if phase == PH_STAGE:
            out.counters[N.rhs_evaluations] += 1
            # Stages 2 .. 5 go straight to the next evaluation; stage 6 and the first stage
            # of an attempt are prepared at the end of the loop body. One place for all six
            # is the same arithmetic but ran 4-5 % slower than this (code layout: seed and
            # iso_pair, three A/B rounds each, bench/RESULTS.md session 9).
            if st.stage < N_STAGES - 1:
                s = st.stage + 1
                stage_state(y, K, s, st.h_step, ys, st.first)
                st.ts = st.t + C_STAGE[s] * st.h_step
                st.stage = s
                st.row = s
                continue
            if st.stage < N_STAGES:
                st.stage += 1
            else:  # the step attempt is complete
                _finish_attempt(st, w, out, prm)
        elif phase == PH_SAMPLE or phase == PH_HOP_SAMPLE:
            record_sample(st, w, out, prm)
        elif phase == PH_HOP:
            end_hop(st, w, out, prm)
        elif phase == PH_START:
            if not _start_chunk(st, w, out, prm):
                return STATUS_NAN, i_first
            if st.phase == PH_FIRST_STEP:
                continue
        else:  # PH_FIRST_STEP
            out.counters[N.rhs_evaluations] += 1
            start_size(st, y, K, w.dy, w.atol, prm[P.rtol])
            st.phase = PH_PLAN

        # the output rows inside an accepted step, then the step is taken
        if st.phase == PH_SAMPLE:
            if sample_in_step(st, out.t_out, y, K, ys):
                continue
            if _take_step(st, w):
                break
        # the next step, or a hop over a discontinuity
        if st.phase == PH_PLAN and plan(st, y, K, model, out.counters):
            break
        # a hop: its output rows (Euler), then the evaluation at its end
        if st.phase == PH_HOP_SAMPLE:
            hop_next(st, out.t_out, y, K, ys)
            continue
        # the next stage of the step attempt (Dormand-Prince 5(4), dopri5.py)
        _next_stage(st, y, K, ys)
    out.extrema[X.t_reached_s] = st.t
    resume = out.resume
    resume[R.started] = 1.0
    resume[R.theta_offset] = theta_offset
    resume[R.h] = st.h
    for i in range(y.shape[0]):
        resume[RESUME_Y + i] = y[i]
    return st.status, st.i_out
