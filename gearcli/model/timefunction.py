"""Piecewise polynomials of time: the exact form of the case file's time functions.

Drive speeds and load torques are written as constants or Adams-style expressions
(``STEP(time, 0, 0, 1, 3000)``, see :mod:`gearcli.case.expr`). Every such expression is a
piecewise polynomial, so it is kept exactly in that form: the solver evaluates, differentiates
and integrates it with :mod:`gearcli.core.timefunc` without approximation.

Each piece is a polynomial in the *local* variable ``s = t - origin_k`` with ``origin_k`` the
piece's left breakpoint (``b_0`` for the first piece, ``0`` when there are no breakpoints). Local
origins keep degree-5 (STEP5) and degree-10 (products) pieces accurate at t = 60 s, where
expanded global coefficients would cancel catastrophically.
"""

from __future__ import annotations

from numbers import Integral, Real

import numpy as np

#: Relative size below which a (width-scaled) coefficient counts as rounding noise.
_RTOL = 64 * np.finfo(float).eps


def _taylor_shift(c: np.ndarray, d: float) -> np.ndarray:
    """Coefficients of ``q(u) = p(u + d)`` from those of ``p`` (repeated synthetic division)."""
    out = np.array(c, dtype=float)
    if d != 0.0:
        n = out.size
        for i in range(n - 1):
            for j in range(n - 2, i - 1, -1):
                out[j] += d * out[j + 1]
    return out


def _origins(breaks: np.ndarray) -> np.ndarray:
    """Local origin of every piece: ``b_0, b_0, b_1, ..., b_{n-1}`` (``0`` without breaks)."""
    if breaks.size == 0:
        return np.zeros(1)
    return np.concatenate([breaks[:1], breaks])


def _widths(breaks: np.ndarray) -> np.ndarray:
    """Characteristic width [s] of each piece, scaling ``c_p`` to ``c_p w**p`` for comparisons.

    The finite width of the piece, else that of the nearest finite neighbour, else 1 s.
    """
    inner = np.diff(breaks)
    if inner.size == 0:
        return np.ones(breaks.size + 1)
    return np.concatenate([inner[:1], inner, inner[-1:]])


def _norm(c: np.ndarray, w: float) -> np.ndarray:
    """``|c_p| w**p``, with 0 for zero coefficients and overflow clamped to the largest float."""
    with np.errstate(over="ignore", invalid="ignore"):
        scaled = np.abs(c) * float(w) ** np.arange(c.size)
    return np.where(c == 0.0, 0.0, np.minimum(scaled, np.finfo(float).max))


def _trim(c: np.ndarray, w: float) -> np.ndarray:
    """Drop trailing coefficients that are zero or rounding noise; keep at least one."""
    scaled = _norm(c, w)
    keep = np.nonzero(scaled > _RTOL * scaled.max())[0]
    return c[: keep[-1] + 1] + 0.0 if keep.size else np.zeros(1)


def _same(a: np.ndarray, b: np.ndarray, w: float) -> bool:
    """Whether two polynomials about the same origin agree to rounding."""
    scale = max(_norm(a, w).max(), _norm(b, w).max())
    return bool(np.all(_norm(_add(a, -b), w) <= _RTOL * scale))


def _is_scalar(x) -> bool:
    return isinstance(x, Real) and not isinstance(x, bool)


def _add(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    size = max(a.size, b.size)
    return np.pad(a, (0, size - a.size)) + np.pad(b, (0, size - b.size))


def _simplify(b: np.ndarray, pieces: list[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
    """Trim every piece and drop breakpoints between pieces that are the same polynomial."""
    widths, origins = _widths(b), _origins(b)
    pieces = [_trim(p, w) for p, w in zip(pieces, widths, strict=True)]
    kept_breaks, kept, origin = [], [pieces[0]], origins[0]  # origin: that of kept[-1]
    for k in range(b.size):
        shifted = _taylor_shift(kept[-1], b[k] - origin)
        if not _same(shifted, pieces[k + 1], max(widths[k], widths[k + 1])):
            kept_breaks.append(b[k])
            kept.append(pieces[k + 1])
            origin = b[k]
    new_breaks = np.array(kept_breaks, dtype=float)
    shift = _origins(new_breaks)[0] - origins[0]  # the first piece's origin may have moved
    kept[0] = _trim(_taylor_shift(kept[0], shift), _widths(new_breaks)[0])
    return new_breaks, kept


class PiecewisePolynomial:
    """An immutable piecewise polynomial of time ``t`` [s].

    Parameters
    ----------
    breaks : sequence of float
        Breakpoints ``b_0 < ... < b_{n-1}`` [s], ``n >= 0``, finite.
    pieces : sequence of sequence of float
        ``n + 1`` coefficient lists for the pieces ``(-inf, b_0), [b_0, b_1), ...,
        [b_{n-1}, +inf)``; ``pieces[k][p]`` multiplies ``(t - origin_k)**p`` with ``origin_k``
        the piece's left breakpoint (``b_0`` for the first piece, ``0`` when ``n == 0``).

    Notes
    -----
    The constructor simplifies: breakpoints whose neighbouring pieces are the same polynomial
    are dropped and trailing zero coefficients are trimmed (both up to rounding, comparing
    ``c_p w**p`` with ``w`` the piece width). Arithmetic merges breakpoints and re-expands each
    operand about the new local origins (Taylor shift), so results stay exact polynomials.
    """

    __slots__ = ("_breaks", "_coefs", "_origins")
    __array_ufunc__ = None  # numpy scalars and arrays defer to our reflected operators

    def __init__(self, breaks, pieces) -> None:
        b = np.array(breaks, dtype=float).reshape(-1)
        raw = [np.array(p, dtype=float).reshape(-1) for p in pieces]
        if len(raw) != b.size + 1:
            raise ValueError(f"{b.size} breakpoints need {b.size + 1} pieces, got {len(raw)}")
        if not np.all(np.isfinite(b)) or np.any(np.diff(b) <= 0.0):
            raise ValueError("breakpoints must be finite and strictly increasing")
        if any(p.size == 0 or not np.all(np.isfinite(p)) for p in raw):
            raise ValueError("time function has empty or non-finite coefficients")
        b, kept = _simplify(b, raw)
        coefs = np.zeros((len(kept), max(p.size for p in kept)))
        for k, p in enumerate(kept):
            coefs[k, : p.size] = p
        origins = _origins(b)
        for name, array in (("_breaks", b), ("_coefs", coefs), ("_origins", origins)):
            array.setflags(write=False)
            object.__setattr__(self, name, array)

    def __setattr__(self, name, value):
        raise AttributeError(f"{type(self).__name__} is immutable")

    # -- constructors ------------------------------------------------------------------------
    @classmethod
    def constant(cls, c: float) -> PiecewisePolynomial:
        """The constant function ``c``."""
        return cls([], [[c]])

    @classmethod
    def identity(cls) -> PiecewisePolynomial:
        """The variable ``time`` itself, ``f(t) = t``."""
        return cls([], [[0.0, 1.0]])

    @classmethod
    def _smooth_step(cls, t0, h0, t1, h1, shape) -> PiecewisePolynomial:
        t0, h0, t1, h1 = (float(x) for x in (t0, h0, t1, h1))
        if not all(np.isfinite([t0, h0, t1, h1])):
            raise ValueError("step and ramp arguments must be finite")
        if not t1 > t0:
            raise ValueError(f"a step or ramp needs t1 > t0, got t0 = {t0:g} and t1 = {t1:g}")
        dt, dh = np.float64(t1 - t0), np.float64(h1 - h0)
        with np.errstate(all="ignore"):  # overflow shows as non-finite coefficients
            middle = [h0 + dh * shape[0]] + [dh * a / dt**p for p, a in enumerate(shape) if p]
        if not (np.isfinite(dt) and np.isfinite(dh)) or (dh != 0.0 and middle[-1] == 0.0):
            raise ValueError("t1 - t0 or h1 - h0 is out of the range of floats")
        return cls([t0, t1], [[h0], middle, [h1]])

    @classmethod
    def step(cls, t0: float, h0: float, t1: float, h1: float) -> PiecewisePolynomial:
        """Adams STEP: cubic blend from ``h0`` at ``t0`` to ``h1`` at ``t1`` [s].

        ``h0`` for ``t <= t0``, ``h1`` for ``t >= t1``, else ``h0 + (h1 - h0) D**2 (3 - 2 D)``
        with ``D = (t - t0) / (t1 - t0)``. Requires ``t1 > t0``.

        References
        ----------
        MSC Software, "Adams Solver: Function Reference", STEP function.
        """
        return cls._smooth_step(t0, h0, t1, h1, (0.0, 0.0, 3.0, -2.0))

    @classmethod
    def step5(cls, t0: float, h0: float, t1: float, h1: float) -> PiecewisePolynomial:
        """Adams STEP5: quintic blend, ``h0 + (h1 - h0) D**3 (10 - 15 D + 6 D**2)`` between.

        Clamped to ``h0`` / ``h1`` outside ``[t0, t1]`` like :meth:`step`; its first and second
        derivatives vanish at both ends.

        References
        ----------
        MSC Software, "Adams Solver: Function Reference", STEP5 function.
        """
        return cls._smooth_step(t0, h0, t1, h1, (0.0, 0.0, 0.0, 10.0, -15.0, 6.0))

    @classmethod
    def ramp(cls, t0: float, h0: float, t1: float, h1: float) -> PiecewisePolynomial:
        """Linear ramp ``h0 + (h1 - h0) D`` between ``t0`` and ``t1``, clamped outside."""
        return cls._smooth_step(t0, h0, t1, h1, (0.0, 1.0))

    # -- properties --------------------------------------------------------------------------
    @property
    def breakpoints(self) -> tuple[float, ...]:
        """The breakpoints ``b_0 < ... < b_{n-1}`` [s]."""
        return tuple(float(b) for b in self._breaks)

    @property
    def last_breakpoint(self) -> float:
        """End of every ramp [s]: the last breakpoint, ``-inf`` when there is none."""
        return float(self._breaks[-1]) if self._breaks.size else -np.inf

    @property
    def max_degree(self) -> int:
        """Highest polynomial degree over all pieces."""
        return self._coefs.shape[1] - 1

    @property
    def is_constant(self) -> bool:
        """Whether the function is one constant for all t."""
        return self._breaks.size == 0 and self.max_degree == 0

    def final_value(self) -> float | None:
        """Value for ``t >= last_breakpoint`` if the last piece is constant, else ``None``."""
        last = self._coefs[-1]
        return float(last[0]) if not np.any(last[1:]) else None

    def _piece(self, k: int, origin: float | None = None) -> np.ndarray:
        c = self._coefs[k]
        nz = np.nonzero(c)[0]
        c = c[: nz[-1] + 1] if nz.size else c[:1]
        return c.copy() if origin is None else _taylor_shift(c, origin - self._origins[k])

    def _pieces(self) -> list[np.ndarray]:
        return [self._piece(k) for k in range(self._coefs.shape[0])]

    def to_arrays(self, degree: int | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Plain float64 arrays for :func:`gearcli.core.timefunc.pp_eval`.

        Parameters
        ----------
        degree : int, optional
            Number of columns minus one (zero padded), to give several functions one shape;
            at least :attr:`max_degree`. Default :attr:`max_degree`.

        Returns
        -------
        breaks : ndarray, shape (n,)
            Breakpoints [s].
        coefs : ndarray, shape (n + 1, degree + 1)
            ``coefs[k, p]`` multiplies ``(t - origins[k])**p`` on piece ``k``.
        origins : ndarray, shape (n + 1,)
            Local origin of each piece [s].
        """
        degree = self.max_degree if degree is None else int(degree)
        if degree < self.max_degree:
            raise ValueError(f"degree {degree} < max_degree {self.max_degree}")
        coefs = np.zeros((self._coefs.shape[0], degree + 1))
        coefs[:, : self._coefs.shape[1]] = self._coefs
        return self._breaks.copy(), coefs, self._origins.copy()

    # -- evaluation and calculus -------------------------------------------------------------
    def __call__(self, t):
        """Value at ``t`` [s] (scalar or array; vectorised, Horner in the local variable)."""
        t_arr = np.asarray(t, dtype=float)
        k = np.searchsorted(self._breaks, t_arr, side="right")
        s = t_arr - self._origins[k]
        out = np.zeros_like(s)
        for p in range(self.max_degree, -1, -1):
            out = out * s + self._coefs[k, p]
        return float(out) if out.ndim == 0 else out

    def derivative(self) -> PiecewisePolynomial:
        """The derivative d/dt (piecewise; jumps of the function are not represented)."""
        pieces = [c[1:] * np.arange(1, c.size) if c.size > 1 else [0.0] for c in self._pieces()]
        return PiecewisePolynomial(self._breaks, pieces)

    def antiderivative(self, t_ref: float = 0.0) -> PiecewisePolynomial:
        """The continuous antiderivative ``F`` with ``F(t_ref) = 0`` [value * s]."""
        pieces, constant = [], 0.0
        for k, c in enumerate(self._pieces()):
            if k >= 2:  # value of the previous piece at its right end b_{k-1}
                prev = pieces[-1]
                s = self._breaks[k - 1] - self._origins[k - 1]
                constant = float(np.polynomial.polynomial.polyval(s, prev))
            pieces.append(np.concatenate([[constant], c / np.arange(1, c.size + 1)]))
        result = PiecewisePolynomial(self._breaks, pieces)
        return result - result(float(t_ref))

    # -- arithmetic --------------------------------------------------------------------------
    def _combine(self, other: PiecewisePolynomial, op) -> PiecewisePolynomial:
        breaks = np.union1d(self._breaks, other._breaks)
        origins = _origins(breaks)
        pieces = []
        for k, origin in enumerate(origins):
            left = breaks[k - 1] if k else -np.inf
            i = np.searchsorted(self._breaks, left, side="right")
            j = np.searchsorted(other._breaks, left, side="right")
            pieces.append(op(self._piece(i, origin), other._piece(j, origin)))
        return PiecewisePolynomial(breaks, pieces)

    def __add__(self, other) -> PiecewisePolynomial:
        if _is_scalar(other):
            other = PiecewisePolynomial.constant(float(other))
        if not isinstance(other, PiecewisePolynomial):
            return NotImplemented
        return self._combine(other, _add)

    __radd__ = __add__

    def __neg__(self) -> PiecewisePolynomial:
        return self.scale(-1.0)

    def __sub__(self, other) -> PiecewisePolynomial:
        if not (_is_scalar(other) or isinstance(other, PiecewisePolynomial)):
            return NotImplemented
        return self + (-other)

    def __rsub__(self, other) -> PiecewisePolynomial:
        return -self + other

    def __mul__(self, other) -> PiecewisePolynomial:
        if _is_scalar(other):
            return self.scale(other)
        if not isinstance(other, PiecewisePolynomial):
            return NotImplemented
        return self._combine(other, np.convolve)

    __rmul__ = __mul__

    def __truediv__(self, other) -> PiecewisePolynomial:
        if not _is_scalar(other):
            return NotImplemented
        if other == 0:
            raise ZeroDivisionError("division of a time function by zero")
        return PiecewisePolynomial(self._breaks, [c / float(other) for c in self._pieces()])

    def __pow__(self, exponent: int) -> PiecewisePolynomial:
        if not isinstance(exponent, Integral) or isinstance(exponent, bool) or exponent < 0:
            return NotImplemented
        result = PiecewisePolynomial.constant(1.0)
        for _ in range(exponent):
            result = result * self
        return result

    def scale(self, factor: float) -> PiecewisePolynomial:
        """The function times ``factor`` (e.g. a unit conversion)."""
        return PiecewisePolynomial(self._breaks, [c * float(factor) for c in self._pieces()])

    def __repr__(self) -> str:
        pieces = ", ".join(str(c.tolist()) for c in self._pieces())
        return f"PiecewisePolynomial(breaks={list(self.breakpoints)}, pieces=[{pieces}])"
