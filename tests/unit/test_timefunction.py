"""Time functions: PiecewisePolynomial, the safe expression parser and the numba evaluators.

References are independent of the implementation: the Adams STEP/STEP5 formulas written out
with ``D = (t - t0) / (t1 - t0)``, central finite differences and ``scipy.integrate.quad``.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.polynomial import Polynomial
from scipy.integrate import quad

from gearcli.case.expr import ExpressionError, is_expression, parse_time_function
from gearcli.core.timefunc import pp_eval, pp_eval_d
from gearcli.model.timefunction import PiecewisePolynomial as PP

# Rounding only: Horner in the local variable vs the D-formula differ by a few ulps.
RTOL = 1e-13


def adams_step(t, t0, h0, t1, h1):
    d = np.clip((np.asarray(t, float) - t0) / (t1 - t0), 0.0, 1.0)
    return h0 + (h1 - h0) * d * d * (3.0 - 2.0 * d)


def adams_step5(t, t0, h0, t1, h1):
    d = np.clip((np.asarray(t, float) - t0) / (t1 - t0), 0.0, 1.0)
    return h0 + (h1 - h0) * d**3 * (10.0 - 15.0 * d + 6.0 * d * d)


def ramp(t, t0, h0, t1, h1):
    return np.interp(t, [t0, t1], [h0, h1])


def close(actual, expected, scale):
    """|actual - expected| <= RTOL * scale elementwise (scale: the function's magnitude)."""
    np.testing.assert_allclose(actual, expected, rtol=0.0, atol=RTOL * scale)


T = np.linspace(-1.0, 4.0, 1001)


# -- STEP / STEP5 / RAMP values -----------------------------------------------------------------
def test_seed_speed_step_values():
    f = parse_time_function("STEP(time, 0, 0, 1, 3000)")
    # D = 0.25: 3000 * 0.0625 * 2.5 = 468.75; D = 0.5: 1500 (by hand)
    assert f([0.25, 0.5, 1.0, 5.0]).tolist() == pytest.approx([468.75, 1500.0, 3000.0, 3000.0])
    assert f(-1.0) == 0.0 and f(0.0) == 0.0
    close(f(T), adams_step(T, 0, 0, 1, 3000), 3000)


def test_seed_load_step_values():
    f = parse_time_function("STEP(time,0,0,1,4.5e+05)")
    close(f(T), adams_step(T, 0, 0, 1, 4.5e5), 4.5e5)
    assert f(0.5) == pytest.approx(2.25e5, rel=1e-15)


@pytest.mark.parametrize("args", [(0.0, 0.0, 1.0, 1.0), (0.2, -3.0, 1.7, 5.0), (-1, 2, 3, -4)])
def test_step_step5_ramp_against_formulas(args):
    scale = max(abs(args[1]), abs(args[3]))
    close(PP.step(*args)(T), adams_step(T, *args), scale)
    close(PP.step5(*args)(T), adams_step5(T, *args), scale)
    close(PP.ramp(*args)(T), ramp(T, *args), scale)


def test_seed_breakpoints_and_final_values():
    speed = parse_time_function("STEP(time, 0, 0, 1, 3000)")
    load = parse_time_function("STEP(time, 0, 0, 1, 450)")
    assert speed.breakpoints == (0.0, 1.0)
    assert speed.last_breakpoint == 1.0 and speed.final_value() == 3000.0
    assert load.last_breakpoint == 1.0 and load.final_value() == 450.0
    assert speed.max_degree == 3 and not speed.is_constant
    c = PP.constant(2.5)
    assert c.is_constant and c.final_value() == 2.5 and c.last_breakpoint == -np.inf
    assert PP.identity().final_value() is None and not PP.identity().is_constant
    assert PP.step(0, 7, 1, 7).is_constant  # h0 == h1: no breakpoints left


# -- calculus -----------------------------------------------------------------------------------
@pytest.mark.parametrize("text", ["STEP(time,0,0,1,3000)", "STEP5(time,0.5,2,1.5,-1)*time"])
def test_derivative_against_central_differences(text):
    f = parse_time_function(text)
    df = f.derivative()
    h = 1e-5
    t = np.linspace(-0.5, 2.5, 301)
    t = t[np.min(np.abs(t[:, None] - np.array(f.breakpoints)), axis=1) > 2 * h]
    fd = (f(t + h) - f(t - h)) / (2 * h)
    # truncation h^2 |f'''| / 6 <= 1e-10 * 36000 / 6 ~ 6e-7; rounding eps |f| / h ~ 3e-8
    np.testing.assert_allclose(df(t), fd, rtol=0, atol=1e-6 * max(1.0, np.abs(f(t)).max()))
    # the derivative of STEP is 6 (h1 - h0) D (1 - D) / (t1 - t0): zero at both ends
    if text.startswith("STEP("):
        close(df(0.5), 6 * 3000 * 0.25, 4500)
        assert df(0.0) == 0.0 and abs(df(1.0 - 1e-12)) < 1e-6


@pytest.mark.parametrize(
    "text, t_ref",
    [("STEP(time,0,0,1,3000)", 0.0), ("STEP5(time,0.5,2,1.5,-1)*time + 3", 0.7)],
)
def test_antiderivative_against_quad(text, t_ref):
    f = parse_time_function(text)
    big_f = f.antiderivative(t_ref)
    assert big_f(t_ref) == 0.0
    for t in (-0.4, 0.3, 1.0, 1.2, 2.0, 5.0):
        lo, hi = sorted((t_ref, t))
        points = [b for b in f.breakpoints if lo < b < hi] or None
        # Gauss-Kronrod is exact for these polynomials (degree <= 6) on each sub-interval
        value, _ = quad(f, lo, hi, points=points, epsabs=0, epsrel=1e-13)
        expected = value if t >= t_ref else -value
        np.testing.assert_allclose(big_f(t), expected, rtol=1e-12, atol=1e-12)
    # continuity at every breakpoint
    for b in f.breakpoints:
        assert big_f(b) == pytest.approx(big_f(b - 1e-12), rel=1e-9, abs=1e-9)


def test_antiderivative_of_seed_speed_is_the_angle():
    # integral of STEP(0..1, 3000) over [0, 1] is 1500; afterwards 3000 per second
    angle = parse_time_function("STEP(time, 0, 0, 1, 3000)").antiderivative()
    assert angle(1.0) == pytest.approx(1500.0, rel=1e-15)
    assert angle(5.0) == pytest.approx(1500.0 + 4 * 3000.0, rel=1e-15)


# -- arithmetic ---------------------------------------------------------------------------------
def test_sums_and_products_of_steps():
    a, b = (0.0, 0.0, 1.0, 2.0), (0.5, 1.0, 2.0, 3.0)
    fa, fb = PP.step(*a), PP.step5(*b)
    ra, rb = adams_step(T, *a), adams_step5(T, *b)
    assert (fa * fb).breakpoints == (0.0, 0.5, 1.0, 2.0)
    close((fa + fb)(T), ra + rb, 5.0)
    close((fa - fb)(T), ra - rb, 5.0)
    close((fa * fb)(T), ra * rb, 6.0)
    close((2 * fa - fb / 4 + 1)(T), 2 * ra - rb / 4 + 1, 6.0)
    close((fa**2)(T), ra**2, 4.0)
    assert (fa * fb).final_value() == 6.0 and (fa * fb).max_degree == 8
    assert (fa - fa).is_constant and (fa - fa)(0.3) == 0.0


def test_simplification_drops_smooth_breakpoints():
    f = PP.ramp(0, 0, 1, 1) + PP.ramp(1, 0, 2, 1)  # = t on [0, 2], clamped
    assert f.breakpoints == (0.0, 2.0)
    close(f(T), np.clip(T, 0, 2), 2.0)
    zero = PP.step(0, 0, 1, 3) - 3 * PP.step(0, 0, 1, 1)
    assert zero.is_constant and zero.max_degree == 0


def test_local_origins_keep_accuracy_at_60_s():
    # a 1 ms STEP5 at t = 60 s, squared (degree 10) and times time (degree 6)
    args = (60.0, 0.0, 60.001, 1.0)
    f = PP.step5(*args)
    t = np.linspace(59.9995, 60.0015, 2001)
    ref = adams_step5(t, *args)
    close(f(t), ref, 1.0)
    close((f * f)(t), ref**2, 1.0)
    close((f * PP.identity())(t), ref * t, 60.0)
    # the same pieces expanded about t = 0 (numpy Polynomial) lose every digit
    assert (f * f).max_degree == 10
    for g, bound in ((f, 1e3), (f * f, 1e20)):
        local = Polynomial(g.to_arrays()[1][1])
        about_zero = local(Polynomial([-60.0, 1.0]))
        inside = t[(t >= 60.0) & (t < 60.001)]
        assert np.max(np.abs(about_zero(inside) - g(inside))) > bound


def test_immutable():
    f = PP.step(0, 0, 1, 1)
    with pytest.raises(AttributeError):
        f._breaks = np.zeros(2)
    breaks, coefs, origins = f.to_arrays()
    coefs[:] = 0.0  # copies: the function is unchanged
    assert f(0.5) == 0.5


# -- numba kernels ------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "f",
    [
        PP.step(0, 0, 1, 3000),
        PP.step5(60, 1, 60.001, 2) * PP.ramp(59, 0, 61, 1),
        PP.constant(4.5e5),
        PP.identity() * 3 + PP.step(0.2, 1, 0.3, 0),
    ],
)
def test_numba_eval_matches_call(f):
    rng = np.random.default_rng(1)
    lo = min(f.breakpoints, default=0.0) - 1
    hi = max(f.breakpoints, default=0.0) + 1
    t = np.concatenate([rng.uniform(lo, hi, 500), f.breakpoints])
    arrays = f.to_arrays(degree=f.max_degree + 2)  # zero padding changes nothing
    df = f.derivative()
    for ti in t:
        # same Horner sequence in both: equal to the last ulp
        assert pp_eval(*arrays, ti) == pytest.approx(f(ti), rel=1e-15, abs=1e-300)
        value, slope = pp_eval_d(*arrays, ti)
        assert value == pytest.approx(f(ti), rel=1e-15, abs=1e-300)
        assert slope == pytest.approx(df(ti), rel=1e-12, abs=1e-9 * max(1, abs(df(ti))))


def test_numba_eval_propagates_nan():
    # the Horner loop starts at each piece's top nonzero coefficient (timefunc.top_degree):
    # a NaN time must still give NaN, also on a constant piece
    arrays = (PP.step(0, 0, 1, 3000) + PP.constant(2.0)).to_arrays(degree=5)
    assert np.isnan(pp_eval(*arrays, np.nan))
    assert np.isnan(pp_eval_d(*arrays, np.nan)).all()
    assert pp_eval(*arrays, 5.0) == 3002.0 and pp_eval_d(*arrays, 5.0) == (3002.0, 0.0)


def test_to_arrays_shapes():
    breaks, coefs, origins = PP.step(0, 0, 1, 1).to_arrays()
    assert breaks.dtype == coefs.dtype == origins.dtype == np.float64
    assert breaks.shape == (2,) and coefs.shape == (3, 4) and origins.tolist() == [0, 0, 1]
    assert coefs[1].tolist() == [0.0, 0.0, 3.0, -2.0]
    with pytest.raises(ValueError):
        PP.step(0, 0, 1, 1).to_arrays(degree=2)


# -- parser -------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "text, t, expected",
    [
        ("3000", 7.0, 3000.0),
        ("4.5e+05", 0.0, 4.5e5),
        (".5", 0.0, 0.5),
        ("1e5*4.5", 0.0, 4.5e5),
        ("-3", 0.0, -3.0),
        ("-2^2", 0.0, -4.0),
        ("2 ** 3 + 10/4", 0.0, 10.5),
        ("(1 + 2) * -time", 2.0, -6.0),
        ("time^2 - TIME**2", 3.0, 0.0),
        ("time*300", 2.0, 600.0),
        ("2*STEP(time, 0, 0, 1, 3000)", 0.5, 3000.0),
        ("step5(Time, 0, 0, 1, 2)", 0.5, 1.0),
        ("RAMP(time, 1, 0, 3, 4)", 2.0, 2.0),
        ("STEP(time, 0, 1e5*4.5/2, 2-1, -3)", 0.0, 2.25e5),
    ],
)
def test_parser_values(text, t, expected):
    assert parse_time_function(text)(t) == pytest.approx(expected, rel=1e-15)


@pytest.mark.parametrize("value", [52.35987755982988, 1e-05, -0.0, 5e-324, 1.7976931348623157e308])
def test_parser_reads_float_repr_exactly(value):
    # the case layer stores constants as repr(float) and parses them again
    f = parse_time_function(repr(value))
    assert f.is_constant and f(0.0) == value


@pytest.mark.parametrize(
    "text, message",
    [
        ("STEP(time, 0, 0, 1)", "STEP takes 5 arguments (time, t0, h0, t1, h1), got 4 at column 1"),
        ("x + ramp(time, 0, 0, 1, 2, 3)", "unknown name 'x'"),
        ("1 + ramp(time, 0, 0, 1, 2, 3)", "RAMP takes 5 arguments (time, t0, h0, t1, h1), got 6"),
        ("SIN(time)", "unknown name 'SIN'; expected `time`, STEP, STEP5 or RAMP at column 1"),
        ("__import__('os')", 'unexpected character "\'"'),
        ("time.__class__", "unexpected character '.'"),
        ("STEP(time, 0, 0, 1, 3000) 2", "unexpected '2' after a complete expression"),
        ("", "empty expression"),
        ("   ", "empty expression"),
        ("1/time", "division by a time-varying expression"),
        (
            "STEP(t, 0, 0, 1, 3000)",
            "the first argument of STEP must be `time`, got 't' at column 6",
        ),
        ("STEP((time), 0, 0, 1, 3)", "the first argument of STEP must be `time`"),
        ("STEP(time, 1, 0, 1, 3000)", "STEP needs t1 > t0, got t0 = 1 and t1 = 1 at column 1"),
        ("step5(time, 2, 0, 1, 3)", "STEP5 needs t1 > t0"),
        ("nan", "'nan' is not a finite number at column 1"),
        ("2*inf", "'inf' is not a finite number at column 3"),
        ("1e999", "out of range at column 1"),
        ("1e200 * 1e200", "the result of '*' is not finite at column 7"),
        ("1/(2-2)", "division by zero at column 2"),
        ("STEP(time, 0, 0, 1e-200, 1)", "the result of 'STEP' is not finite at column 1"),
        ("time^11", "exponent must be a constant integer from 0 to 10 at column 6"),
        ("time^0.5", "exponent must be a constant integer"),
        ("time^-1", "exponent must be a constant integer"),
        ("STEP(time, 0, 0, time, 1)", "argument t1 of STEP must be a constant"),
        ("(1 + 2", "expected ')' to close the parenthesis, got end of text at column 7"),
        ("1 +", "expected a number, `time`, a function or '('"),
        ("2 time", "unexpected 'time' after a complete expression"),
        ("STEP(time, 0, 0, 1, 3000 deg/s)", "unexpected 'deg' in STEP(time, t0, h0, t1, h1)"),
        ("(" * 80 + "1" + ")" * 80, "nested more than"),
    ],
)
def test_parser_errors(text, message):
    with pytest.raises(ExpressionError) as info:
        parse_time_function(text)
    text_of_error = str(info.value)
    assert message in text_of_error
    assert "\n" not in text_of_error and text_of_error.endswith(f"column {info.value.column}")
    assert isinstance(info.value, ValueError)


@pytest.mark.parametrize(
    "text, expected",
    [
        ("450", False),
        ("4.5e5", False),
        ("-3", False),
        ("450 N*m", False),
        ("4.5e5 N*mm", False),
        ("3000 deg/s", False),
        ("1e5 N/(mm^1.5)", False),
        ("7.85e-6 kg/mm^3", False),
        ("STEP(time, 0, 0, 1, 4.5e5)", True),
        ("2*STEP(time, 0, 0, 1, 3000)", True),
        ("time*300", True),
        ("TIME", True),
        ("step5 (time, 0, 0, 1, 1)", True),
        ("SIN(2)", True),  # looks like a call: the parser then says what is allowed
    ],
)
def test_is_expression(text, expected):
    assert is_expression(text) is expected
