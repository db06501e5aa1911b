"""The loop-state record made on a compiled function's stack (loopstate.loop_state): zeros at
first, every field written and read back by name at its own offset (the stack slot is typed
field by field for LLVM, the record's layout is LOOP_DTYPE's)."""

from __future__ import annotations

import numpy as np
from numba import njit

from gearcli.core.loopstate import LOOP_DTYPE, LOOP_FLOAT_NAMES, LOOP_INT_NAMES, loop_state


@njit
def _round_trip(out):
    st = loop_state()
    out[0] = st.t + st.t_hop + st.phase + st.predict  # zeros before anything is written
    st.t = 1.5
    st.t_hop = -2.25
    st.phase = 7
    st.stage = 3
    st.i_out = 123456789012
    st.predict = -1
    out[1] = st.t
    out[2] = st.t_hop
    out[3] = st.phase
    out[4] = st.stage
    out[5] = st.i_out
    out[6] = st.predict
    out[7] = st.h  # a field never written stays zero


def test_the_stack_record_starts_at_zero_and_keeps_every_field_apart():
    out = np.full(8, np.nan)
    _round_trip(out)
    assert out.tolist() == [0.0, 1.5, -2.25, 7.0, 3.0, 123456789012.0, -1.0, 0.0]


def test_the_record_is_eight_bytes_a_field_floats_first():
    assert LOOP_DTYPE.itemsize == 8 * (len(LOOP_FLOAT_NAMES) + len(LOOP_INT_NAMES))
    offsets = [LOOP_DTYPE.fields[n][1] for n in LOOP_FLOAT_NAMES + LOOP_INT_NAMES]
    assert offsets == [8 * i for i in range(len(offsets))]
