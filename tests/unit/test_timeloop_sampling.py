"""The time loop's output placement on its own (core/sampling.py, the loop state of
core/loopstate.py): which output times an accepted step samples, and the values there.

A quadrature y' = p(t) with p a cubic has the solution y = integral of p, a quartic; the
Dormand-Prince continuous extension is of order 4 (Shampine 1986), so at every sample time
inside the step it reproduces the quartic exactly up to rounding (rel 1e-13 on values of
order one). A quintic is not reproduced: the test can tell.
"""

from __future__ import annotations

import ast
import inspect

import numba
import numpy as np

from gearcli.core import timeloop
from gearcli.core.dopri5 import N_STAGES
from gearcli.core.dopri5 import C as C_STAGE
from gearcli.core.loopstate import LOOP_DTYPE, ROW_DY, loop_state
from gearcli.core.sampling import sample_in_step

T0, H = 0.5, 0.1  # the step [s]


def _samples(p, t_out, i_first):
    """Run the sampling phase over one accepted step T0 .. T0 + H of y' = p(t), y(T0) = 0
    (stages K[k] = p(T0 + c_k H), K[N_STAGES] = p(T0 + H), the FSAL stage): the times it
    samples and the states there, as the loop sees them."""
    K = np.zeros((ROW_DY + 1, 1))
    for k in range(N_STAGES):
        K[k, 0] = p(T0 + C_STAGE[k] * H)
    K[N_STAGES, 0] = p(T0 + H)
    y, ys = np.zeros(1), np.zeros(1)
    st = np.zeros(1, LOOP_DTYPE)[0]
    st["t"], st["h_step"], st["t_new"], st["i_out"] = T0, H, T0 + H, i_first
    times, values = [], []
    while sample_in_step(st, t_out, y, K, ys):
        assert st["row"] == ROW_DY and st["full"] == 1  # scratch row, full evaluation
        times.append(float(st["ts"]))
        values.append(float(ys[0]))
        st["i_out"] += 1  # the loop writes the row after the evaluation
    return times, np.array(values), int(st["i_out"])


def test_samples_are_placed_at_the_output_times_inside_the_step():
    t_out = np.array([0.42, T0, 0.53, 0.53, 0.58, T0 + H, 0.61, 0.7])
    times, _, i_out = _samples(lambda t: 1.0, t_out, 1)
    # from the next row on, every time up to and including the step's end; a repeated time
    # is sampled twice (one row each), a time past the end waits for the next step
    assert times == [T0, 0.53, 0.53, 0.58, T0 + H]
    assert i_out == 6
    assert _samples(lambda t: 1.0, t_out, 6)[0] == []  # nothing due: the step is taken
    assert _samples(lambda t: 1.0, t_out[:3], 3)[0] == []  # past the last output time


def test_dense_output_reproduces_a_quartic_solution():
    a = (0.7, -3.0, 20.0, -45.0)  # p(t) = sum a_k (t - T0)^k, so y = sum a_k (t - T0)^(k+1)/(k+1)

    def p(t):
        return sum(c * (t - T0) ** k for k, c in enumerate(a))

    def y(t):
        return sum(c * (t - T0) ** (k + 1) / (k + 1) for k, c in enumerate(a))

    t_out = T0 + H * np.array([0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0])
    times, values, _ = _samples(p, t_out, 0)
    assert times == list(t_out)
    np.testing.assert_allclose(values, [y(t) for t in t_out], rtol=1e-13, atol=1e-16)


def test_dense_output_does_not_reproduce_a_quintic():
    # the 4th-order extension's error shows at degree 5 (the test above can fail)
    t_out = T0 + H * np.array([0.25, 0.5])
    _, values, _ = _samples(lambda t: (t - T0) ** 4, t_out, 0)
    exact = (t_out - T0) ** 5 / 5.0
    assert np.all(np.abs(values - exact) > 1e-6 * np.abs(exact))


def test_the_loop_state_is_a_zeroed_record_on_the_stack():
    @numba.njit
    def fresh():
        st = loop_state()
        before = st.h + st.phase
        st.h = 2.5
        st.phase = 3
        return before, st.h, st.phase, st.t

    assert fresh() == (0.0, 2.5, 3, 0.0)
    assert all(LOOP_DTYPE[n].itemsize == 8 for n in LOOP_DTYPE.names)
    assert LOOP_DTYPE.isalignedstruct


def test_every_field_of_the_loop_state_is_set_at_the_start_of_a_chunk():
    tree = ast.parse(inspect.getsource(timeloop._start_loop.py_func))
    assigned = {node.attr for node in ast.walk(tree)
                if isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store)
                and isinstance(node.value, ast.Name) and node.value.id == "st"}
    assert assigned == set(LOOP_DTYPE.names)
