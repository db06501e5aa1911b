"""Output placement of the time loop: which output time comes next, its state, its row.

Phases of :func:`gearcli.core.timeloop.run`, inlined into it, over the loop-state vectors of
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
def prescribed(y, aux, st):
    """Speed mode: the integrated copies of the prescribed s1, v1 set to the exact values of
    the last evaluation (``aux``); they are not error controlled."""
    if st.speed_mode:
        y[S.s1] = aux[A.s1]
        y[S.v1] = aux[A.v1]


@jit_noalloc_inline
def extrema_at(t, y, w, out, prm):
    """Fold the point ``(t, y)`` with the forces of its full evaluation (``w.aux``,
    ``w.slot_force``) into the true extrema when ``t`` is in the steady window
    (records.update_extrema, docs/theory.md §7.4)."""
    if t >= prm[P.extrema_t_start]:
        update_extrema(out.extrema, out.slot_extrema, t, y, w.aux, w.slot_force,
                       prm[P.lateral] != 0.0)


@jit_noalloc_inline
def record_sample(st, w, out, prm):
    """Write output row ``st.i_out`` from the sample just evaluated at ``(st.ts,
    w.ys)``; samples are points of the solution, so they enter the extrema too."""
    out.counters[N.output_evaluations] += 1
    ts = st.ts
    i = st.i_out
    write_row(out.series, out.slot_series, i, ts, w.ys, w.aux, w.slot_force, prm)
    extrema_at(ts, w.ys, w, out, prm)
    st.i_out = i + 1


@jit_noalloc_inline
def rows_at_start(st, t, w, out, prm):
    """Output rows with times ``<= t`` [s], the chunk's start, from the start state ``w.y``
    (the first chunk's rows at ``t_start``)."""
    t_out = out.t_out
    i = st.i_out
    while i < t_out.shape[0] and t_out[i] <= t:
        write_row(out.series, out.slot_series, i, t_out[i], w.y, w.aux, w.slot_force, prm)
        i += 1
    st.i_out = i
