"""gearcli.model.roots.brent_root reproduces scipy.optimize.brentq float for float."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcli.model.roots import brent_root

FUNCTIONS = {
    "cubic": lambda x: x**3 - 2.0 * x - 5.0,
    "cos": lambda x: math.cos(x) - x,
    "exp": lambda x: math.exp(x) - 3.7,
    "flat": lambda x: (x - 0.3) ** 5,
    "kink": lambda x: abs(x - 0.41) ** 0.5 * math.copysign(1.0, x - 0.41),
    "step": lambda x: -1.0 if x < 0.123456 else 2.0,
    "involute": lambda x: math.tan(x) - x - 0.0149044,
}


def _traced(solver, f, a, b, xtol):
    """(root or the exception's type, every x the solver evaluated f at)."""
    calls = []

    def g(x):
        calls.append(x)
        return f(x)

    try:
        return solver(g, a, b, xtol=xtol), calls
    except RuntimeError:  # no convergence in 100 iterations (the flat quintic at tight xtol)
        return RuntimeError, calls


@pytest.mark.parametrize("name", FUNCTIONS)
@pytest.mark.parametrize("xtol", [2e-12, 1e-14, 1e-15, 1e-6])
def test_same_root_and_evaluations_as_scipy(name, xtol):
    f = FUNCTIONS[name]
    rng = np.random.default_rng(16)
    lo, hi = {"cubic": (1.0, 3.0), "exp": (0.0, 3.0), "involute": (0.01, 1.5)}.get(
        name, (-0.5, 1.0))
    for _ in range(40):
        a, b = sorted(rng.uniform(lo, hi, 2))
        if math.copysign(1.0, f(a)) == math.copysign(1.0, f(b)):
            continue
        for lo_, hi_ in ((a, b), (b, a)):
            # the same iterates, not just the same end point
            assert _traced(brent_root, f, lo_, hi_, xtol) == _traced(brentq, f, lo_, hi_, xtol)


def test_refuses_a_bracket_without_sign_change():
    with pytest.raises(ValueError, match="different signs"):
        brent_root(lambda x: x * x + 1.0, -1.0, 1.0)


def test_exact_zero_at_an_end():
    assert brent_root(lambda x: x - 1.0, 1.0, 2.0) == 1.0
