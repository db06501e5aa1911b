"""The time loop's step-size control and starting step, each on its own (core/stepsize.py).

The controller against the formula of HNW II.4 eq. 4.13 with its constants (docs/theory.md
§6.7), the starting step against the algorithm of HNW II.4 written out here and against
SciPy's implementation of it (scipy.integrate._ivp.common.select_initial_step) on a closed-form
problem, a harmonic oscillator. Tolerances: rel 1e-13 where the same formula is evaluated in a
different order (rounding only).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.core.dopri5 import ERROR_EXPONENT, MAX_FACTOR, MIN_FACTOR, SAFETY
from gearcli.core.layout import N
from gearcli.core.loopstate import LOOP_DTYPE, PH_PLAN, PH_SAMPLE, ROW_DY
from gearcli.core.stepsize import control, start_size, start_trial


def _state(**fields):
    st = np.zeros(1, LOOP_DTYPE)[0]
    for name, value in fields.items():
        st[name] = value
    return st


def test_controller_constants_are_hnw_and_scipy():
    # HNW II.4 (4.13) with scipy.integrate._ivp.rk's constants; the error estimate has order 4
    assert (SAFETY, MIN_FACTOR, MAX_FACTOR) == (0.9, 0.2, 10.0)
    assert ERROR_EXPONENT == -1.0 / 5.0


@pytest.mark.parametrize("err", [0.0, 1e-12, 1e-4, 0.3, 0.9999])
@pytest.mark.parametrize("rejected_before", [0, 1])
def test_accepted_step_grows_by_the_formula(err, rejected_before):
    h_step = 2.5e-4
    st = _state(h_step=h_step, h=7.0, rejected_before=rejected_before, nonfinite_last=1)
    counters = np.zeros(4, dtype=np.int64)
    assert control(st, err, True, counters)
    expected = MAX_FACTOR if err == 0.0 else min(MAX_FACTOR, SAFETY * err ** -0.2)
    if rejected_before:  # no growth right after a rejection
        expected = min(expected, 1.0)
    assert st["factor"] == pytest.approx(expected, rel=1e-14)
    assert st["h"] == 7.0  # the next size is h_step * factor once the step is taken
    assert (st["phase"], st["rejected_before"], st["nonfinite_last"]) == (PH_SAMPLE, 0, 0)
    assert list(counters[[N.accepted_steps, N.rejected_steps]]) == [1, 0]


@pytest.mark.parametrize("err", [1.0, 1.7, 40.0, 1e9])
def test_rejected_step_shrinks_by_the_formula_at_most_fivefold(err):
    h_step = 2.5e-4
    st = _state(h_step=h_step, factor=3.0)
    counters = np.zeros(4, dtype=np.int64)
    assert not control(st, err, True, counters)
    assert st["h"] == pytest.approx(h_step * max(MIN_FACTOR, SAFETY * err ** -0.2), rel=1e-14)
    assert st["h"] >= MIN_FACTOR * h_step
    assert (st["phase"], st["rejected_before"], st["nonfinite_last"]) == (PH_PLAN, 1, 0)
    assert st["factor"] == 3.0
    assert list(counters[[N.accepted_steps, N.rejected_steps]]) == [0, 1]


@pytest.mark.parametrize("err", [math.nan, math.inf, 0.5])
def test_nonfinite_attempt_is_rejected_with_the_smallest_factor(err):
    st = _state(h_step=1e-3)
    counters = np.zeros(4, dtype=np.int64)
    assert not control(st, err, False, counters)  # finite=False: NaN in the state or stage
    assert st["h"] == 1e-3 * MIN_FACTOR
    assert (st["phase"], st["rejected_before"], st["nonfinite_last"]) == (PH_PLAN, 1, 1)
    # the tally of this one control() call (no integration: nothing adaptive is counted)
    assert list(counters[[N.accepted_steps, N.rejected_steps]]) == [0, 1]


# -- starting step size -------------------------------------------------------------------

OMEGA = 2.0 * math.pi * 150.0  # [rad/s]


def _oscillator(y):
    """Two harmonic oscillators (x, v) side by side: the 4 controlled base states."""
    return np.array([y[1], -OMEGA**2 * y[0], y[3], -OMEGA**2 * y[2]])


def _hnw_starting_step(f, t0, y0, span, atol, rtol):
    """Hairer, Norsett & Wanner (1993), §II.4 "starting step size", p = 4 (the error
    estimate's order), RMS norm scaled by atol + rtol |y0|, interval length ``span``."""
    scale = atol + rtol * np.abs(y0)

    def norm(v):
        return float(np.sqrt(np.mean((v / scale) ** 2)))

    f0 = f(y0)
    d0, d1 = norm(y0), norm(f0)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, span)
    d2 = norm(f(y0 + h0 * f0) - f0) / h0
    if max(d1, d2) <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 5.0)
    return min(100.0 * h0, h1, span), h0


def _loop_starting_step(f, t0, y0, span, atol, rtol):
    """The loop's two phases around its one evaluation of f at the trial point."""
    n = y0.size
    K = np.zeros((ROW_DY + 1, n))
    K[0] = f(y0)
    dy, ys = K[ROW_DY], np.zeros(n)
    st = _state(t=t0, span=span, first=0, count=n)
    start_trial(st, y0, K, dy, ys, np.full(n, atol), rtol)
    h0 = st["h0"]
    assert st["ts"] == t0 + h0
    np.testing.assert_array_equal(ys, y0 + h0 * K[0])  # the Euler trial state
    dy[:] = f(ys)  # the loop's evaluation at (ts, ys) writes K's scratch row
    start_size(st, y0, K, dy, np.full(n, atol), rtol)
    return st["h"], h0


@pytest.mark.parametrize(("y0", "span", "atol"), [
    (np.array([0.01, 0.0, -0.002, 3.0]), 1.0, 1e-6),  # generic: h from the 2nd derivative
    (np.array([0.01, 0.0, -0.002, 3.0]), 2e-6, 1e-6),  # short span: both sizes capped
    (np.zeros(4), 1.0, 1e-6),  # y0 = 0: d0 < 1e-5, trial step 1e-6 s; f = 0: h1 from h0
    (np.array([1e-9, 0.0, 0.0, 0.0]), 1.0, 1e-3),  # tiny state: d0, d1 < 1e-5
])
def test_starting_step_is_hnw_and_scipy(y0, span, atol):
    from scipy.integrate._ivp.common import select_initial_step

    rtol, t0 = 1e-6, 0.25
    h, h0 = _loop_starting_step(_oscillator, t0, y0, span, atol, rtol)
    h_ref, h0_ref = _hnw_starting_step(_oscillator, t0, y0, span, atol, rtol)
    assert h0 == pytest.approx(h0_ref, rel=1e-13)
    assert h == pytest.approx(h_ref, rel=1e-13)
    h_scipy = select_initial_step(lambda t, y: _oscillator(y), t0, y0, t0 + span, np.inf,
                                  _oscillator(y0), 1.0, 4, rtol, atol)
    assert h == pytest.approx(h_scipy, rel=1e-13)
    assert 0.0 < h <= span


def test_starting_step_of_the_oscillator_resolves_its_period():
    # closed form: for y = (A, 0, ...) the trial step's second-derivative estimate is
    # omega^2 |A| / scale, so h1 = (0.01 / d2)^(1/5): far below the period 1/150 s
    y0 = np.array([0.01, 0.0, 0.01, 0.0])
    h, _ = _loop_starting_step(_oscillator, 0.0, y0, 1.0, 1e-6, 1e-6)
    assert h < 0.05 / 150.0


def test_starting_step_falls_back_when_the_estimate_is_not_a_positive_number():
    # |f| / scale overflows the norm: d1 = inf, so h0 = 0 and d2 = 0/0; the loop then starts
    # with 1e-6 s instead of a zero or NaN step
    y0 = np.array([0.01, 0.0, 0.01, 0.0])
    h, h0 = _loop_starting_step(lambda y: np.full(4, 1e200), 0.0, y0, 1.0, 1e-6, 1e-6)
    assert h0 == 0.0
    assert h == 1e-6
