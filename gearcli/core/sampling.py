"""Output placement of the time loop: which output time comes next, its state, its row.

Phases of :func:`gearcli.core.timeloop.run`, inlined into it, over the loop-state record of
:mod:`gearcli.core.loopstate`. An output time inside an accepted step is sampled on the
continuous extension of the step (dopri5.dense, Shampine 1986), one inside a hop over a
discontinuity on the hop's Euler line, one at the start of a chunk from the start state. A
sample's evaluation of the right-hand side writes the scratch row of K (loopstate.ROW_DY) and
never feeds back into the steps (docs/theory.md §6.8).
"""

from gearcli.core.dopri5 import dense, euler
from gearcli.core.layout import A, N, P, S
from gearcli.core.loopstate import ROW_DY
from gearcli.core.nrt import jit_noalloc_inline
from gearcli.core.records import update_extrema, write_row


@jit_noalloc_inline
def sample_in_step(st, t_out, y, K, ys):
    """The next output time inside the accepted step ``st.t .. st.t_new``, if any.

    Output row ``st.i_out`` is due when its time ``t_out[i] <= t_new`` (times are
    non-decreasing; a time equal to the step's end is sampled here, before the step is taken).
    Then ``ys`` is the continuous extension at it (``x = (t_out[i] - t) / h_step``), its time
    ``st.ts``, and the next evaluation is full and writes K's scratch row.

    Returns
    -------
    bool
        A sample is due (the loop evaluates it, then asks again).
    """
    i = st.i_out
    if i < t_out.shape[0] and t_out[i] <= st.t_new:
        ts = t_out[i]
        h_step = st.h_step
        st.ts = ts
        dense(y, K, h_step, (ts - st.t) / h_step, ys)
        st.row = ROW_DY
        st.full = 1
        return True
    return False


@jit_noalloc_inline
def sample_in_hop(st, t_out, y, K, ys):
    """The next output time inside the hop ``st.t .. st.t_hop``, if any: as
    :func:`sample_in_step` on the hop's Euler line ``y + (t_out[i] - t) K[0]``."""
    i = st.i_out
    if i < t_out.shape[0] and t_out[i] <= st.t_hop:
        ts = t_out[i]
        st.ts = ts
        euler(y, K, ts - st.t, ys)
        st.row = ROW_DY
        return True
    return False


@jit_noalloc_inline
def solution_point(st, t, y, w, out, prm):
    """``(t, y)`` is a point of the solution with the full evaluation there in ``w.aux``,
    ``w.slot_force`` (an accepted step's end, a hop's end): in speed mode the integrated
    copies of the prescribed s1, v1 (not error controlled) take the exact values of the
    evaluation; the point enters the true extrema when ``t`` is in the steady window
    (records.update_extrema, docs/theory.md §7.4)."""
    if st.speed_mode:
        y[S.s1] = w.aux[A.s1]
        y[S.v1] = w.aux[A.v1]
    if t >= prm[P.extrema_t_start]:
        update_extrema(out.extrema, out.slot_extrema, t, y, w.aux, w.slot_force,
                       prm[P.lateral] != 0.0)


@jit_noalloc_inline
def record_sample(st, w, out, prm):
    """Write output row ``st.i_out`` from the sample just evaluated at ``(st.ts, w.ys)``;
    samples are points of the solution, so they enter the extrema too."""
    out.counters[N.output_evaluations] += 1
    ts = st.ts
    i = st.i_out
    write_row(out.series, out.slot_series, i, ts, w.ys, w.aux, w.slot_force, prm)
    if ts >= prm[P.extrema_t_start]:
        update_extrema(out.extrema, out.slot_extrema, ts, w.ys, w.aux, w.slot_force,
                       prm[P.lateral] != 0.0)
    st.i_out = i + 1
