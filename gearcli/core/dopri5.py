"""Dormand-Prince 5(4): tableau, stage combinations, error estimate, dense output, step control.

The integrator takes the 5th-order solution (local extrapolation), estimates the error with the
embedded 4th-order one, reuses the last stage as the next step's first (FSAL) and interpolates
with Shampine's 4th-order continuous extension (the ``P`` matrix of scipy's ``RK45``).

References
----------
J. R. Dormand, P. J. Prince, "A family of embedded Runge-Kutta formulae", J. Comput. Appl.
Math. 6 (1980) 19-26 (tableau C, A, B and the error weights E).
L. F. Shampine, "Some practical Runge-Kutta formulas", Math. Comp. 46 (1986) 135-150
(dense output P).
E. Hairer, S. P. Norsett, G. Wanner, "Solving Ordinary Differential Equations I", 2nd ed.,
Springer 1993, §II.4 (step-size control, starting step) and §II.6 (dense output).
"""

import math

import numpy as np

from gearcli.core.jit import jit
from gearcli.core.layout import N_DYNAMIC, N_STATE_BASE
from gearcli.core.nrt import jit_noalloc, jit_noalloc_inline

#: Step-size controller (HNW II.4, eq. 4.13; scipy.integrate._ivp.rk constants).
SAFETY = 0.9
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
ERROR_EXPONENT = -1.0 / 5.0  # -1/(q+1), q = 4 the order of the error estimator
N_STAGES = 6  # plus the FSAL stage 7 = f(t + h, y_new)

C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
])
B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
#: Difference 5th - 4th order weights over the 7 stages (the 7th is the FSAL stage).
E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
#: Dense output: y(t + x h) = y + h sum_k K_k sum_p P[k, p] x^(p+1), 0 <= x <= 1.
P_DENSE = np.array([
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408,
     701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
])


@jit_noalloc_inline
def stage_state(y, K, s, h, out, lo):
    """State of stage ``s`` (1..5): ``out = y + h sum_{k<s} A[s, k] K[k]``, components
    ``lo .. N_DYNAMIC - 1`` and the optional ones ``N_STATE_BASE ..`` (below ``lo``: prescribed
    motion; the energy quadratures in between feed nothing back into the right-hand side, so
    only the solution and the dense output need them)."""
    for part in range(2):
        start, stop = (lo, N_DYNAMIC) if part == 0 else (N_STATE_BASE, y.shape[0])
        for i in range(start, stop):
            acc = 0.0
            for k in range(s):
                acc += A[s, k] * K[k, i]
            out[i] = y[i] + h * acc


@jit_noalloc_inline
def solution(y, K, h, out, lo):
    """5th-order solution ``out = y + h sum_k B[k] K[k]``, components ``lo ..``."""
    for i in range(lo, y.shape[0]):
        acc = 0.0
        for k in range(N_STAGES):
            acc += B[k] * K[k, i]
        out[i] = y[i] + h * acc


@jit_noalloc_inline
def error_norm(y, y_new, K, h, first, count, atol, rtol):
    """RMS of the scaled error estimate over components ``first .. first + count - 1`` and the
    optional degrees of freedom ``N_STATE_BASE ..`` (layout.py) when the state has them.

    ``err_i = h sum_k E[k] K[k, i]``, ``scale_i = atol[i] + rtol max(|y_i|, |y_new_i|)``
    (HNW II.4, eq. 4.11). A non-finite result means the step produced NaN or overflow.
    """
    acc = 0.0
    for part in range(2):  # the controlled base states, then the optional ones (layout.py)
        start, stop = (first, first + count) if part == 0 else (N_STATE_BASE, y.shape[0])
        for i in range(start, stop):
            err = 0.0
            for k in range(N_STAGES + 1):
                err += E[k] * K[k, i]
            scale = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
            acc += (h * err / scale) ** 2
    return math.sqrt(acc / (count + max(0, y.shape[0] - N_STATE_BASE)))


@jit_noalloc_inline
def euler(y, K, dt, out):
    """Explicit Euler ``out = y + dt K[0]`` (``out`` may be ``y``): the time loop's hops over a
    discontinuity and the starting step size's trial state (HNW II.4, II.6)."""
    for i in range(y.shape[0]):
        out[i] = y[i] + dt * K[0, i]


@jit_noalloc
def dense(y, K, h, x, out):
    """Continuous extension at ``t_old + x h``, ``0 <= x <= 1`` (Shampine 1986):
    ``out = y + h sum_k b_k(x) K[k]`` with ``b_k(x) = sum_p P[k, p] x^(p+1)``."""
    x2 = x * x
    x3 = x2 * x
    x4 = x3 * x
    b0 = P_DENSE[0, 0] * x + P_DENSE[0, 1] * x2 + P_DENSE[0, 2] * x3 + P_DENSE[0, 3] * x4
    b2 = P_DENSE[2, 1] * x2 + P_DENSE[2, 2] * x3 + P_DENSE[2, 3] * x4
    b3 = P_DENSE[3, 1] * x2 + P_DENSE[3, 2] * x3 + P_DENSE[3, 3] * x4
    b4 = P_DENSE[4, 1] * x2 + P_DENSE[4, 2] * x3 + P_DENSE[4, 3] * x4
    b5 = P_DENSE[5, 1] * x2 + P_DENSE[5, 2] * x3 + P_DENSE[5, 3] * x4
    b6 = P_DENSE[6, 1] * x2 + P_DENSE[6, 2] * x3 + P_DENSE[6, 3] * x4
    for i in range(y.shape[0]):  # row 1 of P is zero; column 0 is zero except P[0, 0] = 1
        out[i] = y[i] + h * (b0 * K[0, i] + b2 * K[2, i] + b3 * K[3, i] + b4 * K[4, i]
                             + b5 * K[5, i] + b6 * K[6, i])


@jit
def step_factor(err, rejected_before):
    """Step-size factor after a step with error norm ``err`` (HNW II.4, eq. 4.13).

    Accepted (``err < 1``): ``min(MAX_FACTOR, SAFETY err^(-1/5))``, at most 1 right after a
    rejection. Rejected: ``max(MIN_FACTOR, SAFETY err^(-1/5))``. (The PI stabilisation of
    Hairer's DOPRI5 code, beta = 0.04 or 0.08, took 10-40 % more steps on the seed case.)
    """
    if err < 1.0:
        if err == 0.0:
            factor = MAX_FACTOR
        else:
            factor = min(MAX_FACTOR, SAFETY * err ** ERROR_EXPONENT)
        if rejected_before and factor > 1.0:
            factor = 1.0
        return factor
    return max(MIN_FACTOR, SAFETY * err ** ERROR_EXPONENT)


@jit_noalloc
def scaled_rms(v, y, first, count, atol, rtol):
    """RMS of ``v_i / (atol_i + rtol |y_i|)`` over the controlled components."""
    acc = 0.0
    for part in range(2):
        start, stop = (first, first + count) if part == 0 else (N_STATE_BASE, y.shape[0])
        for i in range(start, stop):
            acc += (v[i] / (atol[i] + rtol * abs(y[i]))) ** 2
    return math.sqrt(acc / (count + max(0, y.shape[0] - N_STATE_BASE)))


@jit_noalloc
def store_row(K, s, v):
    """``K[s, :] = v`` without creating a view (keeps the hot loop free of reference counts)."""
    for i in range(v.shape[0]):
        K[s, i] = v[i]
