"""CSV text of a float table with every number as C's ``%.10g`` writes it, compiled.

``numpy.savetxt(fmt="%.10g")`` formats each number with Python's correctly rounded
conversion (~0.4 us each, 0.2 s for the 18 135 x 32 values of the seed run). Here each
number is rounded to 10 significant digits d·10^q in floating point and the rounding is then
proved exact: with 10^|q| exactly representable (|q| <= 22), the products v·10^-q and
(2d ± 1)·10^q are split into two doubles without error (Dekker's product, TwoProduct of
Ogita, Rump & Oishi 2005, Algorithm 2.3, no FMA needed), which decides on which side of the
midpoints (d ± 1/2)·10^q the value v lies, ties to even as C and Python round. The digits
are then laid out as ``%g`` does (C11 §7.21.6.1: fixed notation for exponents -4 <= X < 10,
else d.ddde±XX; trailing zeros removed). Values outside that range (|v| < 1e-13, |v| >= 1e32,
NaN, inf) are flagged and left to Python's own formatting by the caller.

References
----------
T. J. Dekker, A floating-point technique for extending the available precision, Numer. Math.
18 (1971) 224-242 (the exact product by splitting).
T. Ogita, S. M. Rump, S. Oishi, Accurate sum and dot product, SIAM J. Sci. Comput. 26 (2005)
1955-1988 (TwoProduct, Algorithm 2.3).
ISO/IEC 9899:2011 §7.21.6.1 (the ``g`` conversion).
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.core.jit import jit
from gearcli.core.nrt import jit_noalloc

#: Significant digits (the %.10g of gearcli's CSV files).
DIGITS = 10
#: Longest field: sign, 10 digits, point, "e-", three exponent digits.
FIELD_MAX = 17
_POW10 = np.array([10.0**i for i in range(23)])  # exact: 10^22 < 2^53 * 2^22
_SPLIT = 134217729.0  # 2^27 + 1 (Veltkamp's splitting constant for doubles)
_D_LOW = 10**(DIGITS - 1)
_D_HIGH = 10**DIGITS
_TEN = np.uint64(10)


@jit
def _two_product(a, b):
    """(p, e) with p + e = a·b exactly, p = fl(a·b) (Dekker; no overflow/underflow here)."""
    p = a * b
    t = _SPLIT * a
    ah = t - (t - a)
    al = a - ah
    t = _SPLIT * b
    bh = t - (t - b)
    bl = b - bh
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl
    return p, e


@jit
def _side(v, n, q):
    """Sign of v − n·10^q / 2 for v > 0, an odd integer n < 2^53 and |q| <= 22, exactly."""
    if q < 0:  # 2 v 10^-q against n: 2 v 10^-q = 2 (p + e); 2p − n is exact (Sterbenz)
        p, e = _two_product(v, _POW10[-q])
        a = 2.0 * p - n
        b = -2.0 * e
    else:  # 2 v against n 10^q = p + e; 2v − p is exact (Sterbenz)
        p, e = _two_product(float(n), _POW10[q])
        a = 2.0 * v - p
        b = e
    return (a > b) - (a < b)


@jit
def _round10(v, k):
    """(d, k): v > 0 rounded to 10 significant digits, d·10^(k−9) with 10^9 <= d < 10^10,
    ties to even; k is the decimal exponent. k = -999 when not provable here."""
    for _ in range(4):
        q = k - (DIGITS - 1)
        if q < -22 or q > 22:
            return 0, -999
        y = v * _POW10[-q] if q < 0 else v / _POW10[q]  # within half an ulp of v·10^-q
        d = int(np.rint(y))
        # |y − d| well below 1/2: the rounding of y (< 1e-5 here, y < 2^34) cannot have moved
        # v·10^-q across a midpoint, d is proved without the exact products
        settled = abs(y - d) < 0.5 - 1e-5 and _D_LOW <= d < _D_HIGH
        for _ in range(0 if settled else 3):  # at most one unit off after the rounding
            up = _side(v, 2 * d + 1, q)
            down = _side(v, 2 * d - 1, q)
            if up > 0 or (up == 0 and d % 2 == 1):
                d += 1
            elif down < 0 or (down == 0 and d % 2 == 1):
                d -= 1
            else:
                break
        if d == _D_HIGH:  # rounded up to the next power of ten
            return _D_LOW, k + 1
        if d > _D_HIGH:
            k += 1
        elif d < _D_LOW:
            k -= 1
        else:
            return d, k
    return 0, -999


@jit_noalloc
def _write_field(x, buf, pos, digits):
    """``%.10g`` of x into buf at pos (``digits``: 10 bytes of scratch); the new position, or
    -1 if x is left to the caller."""
    if not math.isfinite(x):
        return -1
    if x < 0.0 or (x == 0.0 and math.copysign(1.0, x) < 0.0):
        buf[pos] = 45  # '-'
        pos += 1
        x = -x
    if x == 0.0:
        buf[pos] = 48
        return pos + 1
    d, k = _round10(x, int(math.floor(math.log10(x))))
    if k == -999:
        return -1
    nz = 0
    u = np.uint64(d)  # unsigned: division by 10 without the sign fix-ups (3x faster)
    for i in range(DIGITS - 1, -1, -1):
        quotient = u // _TEN
        r = u - quotient * _TEN
        digits[i] = 48 + r
        if nz == 0 and r != 0:
            nz = i + 1  # significant digits left after removing trailing zeros
        u = quotient
    if -4 <= k < DIGITS:  # fixed notation
        if k < 0:
            buf[pos] = 48
            buf[pos + 1] = 46
            pos += 2
            for _ in range(-k - 1):
                buf[pos] = 48
                pos += 1
            for i in range(nz):
                buf[pos] = digits[i]
                pos += 1
            return pos
        for i in range(k + 1):
            buf[pos] = digits[i]
            pos += 1
        if nz > k + 1:
            buf[pos] = 46
            pos += 1
            for i in range(k + 1, nz):
                buf[pos] = digits[i]
                pos += 1
        return pos
    buf[pos] = digits[0]
    pos += 1
    if nz > 1:
        buf[pos] = 46
        pos += 1
        for i in range(1, nz):
            buf[pos] = digits[i]
            pos += 1
    buf[pos] = 101  # 'e'
    buf[pos + 1] = 45 if k < 0 else 43
    pos += 2
    e = -k if k < 0 else k
    if e >= 100:
        buf[pos] = 48 + e // 100
        pos += 1
    buf[pos] = 48 + (e // 10) % 10
    buf[pos + 1] = 48 + e % 10
    return pos + 2


@jit_noalloc
def g10_rows(data, buf, row_end, bad, digits):
    """Rows of ``data`` (2-D float64) as CSV lines into ``buf`` (uint8, at least
    rows·(columns·(FIELD_MAX + 1) + 1) bytes). ``row_end[i]`` gets the end of line i in
    ``buf``; ``bad[i]`` is set for a line with a value left to the caller (its text in ``buf``
    is then incomplete); ``digits``: 10 bytes of scratch. Returns the number of bytes
    written. Without reference counting (nrt.py): one call per number."""
    pos = 0
    for i in range(data.shape[0]):
        for j in range(data.shape[1]):
            if j > 0:
                buf[pos] = 44  # ','
                pos += 1
            end = _write_field(data[i, j], buf, pos, digits)
            if end < 0:
                bad[i] = True
                end = pos
            pos = end
        buf[pos] = 10  # '\n'
        pos += 1
        row_end[i] = pos
    return pos


def csv_text(names: list[str], data: np.ndarray) -> str:
    """Header line of ``names`` and the rows of ``data`` (n x len(names)) as ``%.10g`` CSV:
    the text ``numpy.savetxt(fmt="%.10g", delimiter=",")`` writes, byte for byte."""
    data = np.ascontiguousarray(data, dtype=np.float64).reshape(-1, len(names))
    n, m = data.shape
    buf = np.empty(n * (m * (FIELD_MAX + 1) + 1), np.uint8)
    row_end = np.zeros(n, np.int64)
    bad = np.zeros(n, np.bool_)
    size = g10_rows(data, buf, row_end, bad, np.empty(DIGITS, np.uint8))
    body = buf[:size].tobytes().decode("ascii")
    if bad.any():  # rows with a value out of the exact range: Python's formatting
        line = ",".join(["%.10g"] * m) + "\n"
        pieces, start = [], 0
        for i in np.flatnonzero(bad):
            begin = int(row_end[i - 1]) if i > 0 else 0
            pieces += [body[start:begin], line % tuple(data[i].tolist())]
            start = int(row_end[i])
        body = "".join(pieces) + body[start:]
    return ",".join(names) + "\n" + body
