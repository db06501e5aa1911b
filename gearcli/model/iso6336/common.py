"""Shared pieces of the ISO 6336 rating: edition, factor rows, involute functions.

The involute function inv α = tan α − α and its inverse are those of ISO 21771 (docs/theory.md
§2 and "ISO 6336 rating"); :func:`inverse_involute` solves tan α − α = v by Newton's method
from Cheng's starting value α₀ = (3v)^(1/3) − 2v/5, which converges for 0 ≤ v ≤ 1.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

__all__ = ["Edition", "Factor", "involute", "inverse_involute", "log_interpolate"]


class Edition(enum.StrEnum):
    """Edition of ISO 6336 parts 1-3 followed (docs/theory.md, "ISO 6336 rating", editions)."""

    ISO2006 = "2006"
    ISO2019 = "2019"


@dataclass(frozen=True)
class Factor:
    """One row of a rating document: a factor or stress with its symbol, value and source."""

    symbol: str  #: ISO symbol, e.g. "Z_H"
    value: float  #: in ``unit``
    unit: str  #: "-" for dimensionless factors, "N/mm²", "N", "h", ...
    clause: str  #: the standard and clause/equation it comes from
    name: str  #: plain-language name

    def to_dict(self) -> dict:
        """Plain JSON types; a non-finite value (an infinite life) becomes None."""
        value = self.value if math.isfinite(self.value) else None
        return {"symbol": self.symbol, "value": value, "unit": self.unit,
                "clause": self.clause, "name": self.name}


def involute(alpha_rad: float) -> float:
    """inv α = tan α − α [rad] of a pressure angle α [rad] (ISO 21771)."""
    return math.tan(alpha_rad) - alpha_rad


def inverse_involute(value_rad: float) -> float:
    """α [rad] with inv α = ``value_rad`` [rad], 0 ≤ value ≤ 1 (Newton, relative step < 1e-15)."""
    v = float(value_rad)
    if not 0.0 <= v <= 1.0:
        raise ValueError(f"involute value {v:g} rad outside 0…1")
    if v == 0.0:
        return 0.0
    a = (3.0 * v) ** (1.0 / 3.0) - 0.4 * v
    for _ in range(50):
        step = (involute(a) - v) / math.tan(a) ** 2
        a -= step
        if abs(step) < 1e-15 * a:
            break
    return a


def log_interpolate(n: float, n_lo: float, f_lo: float, n_hi: float, f_hi: float) -> float:
    """Value at ``n`` on the straight line through (log n_lo, log f_lo), (log n_hi, log f_hi).

    The S-N curves of ISO 6336-2 (Table 2), -3 (Table 3) and the influence factors between
    their static and reference values are straight in log-log coordinates; n is clamped to
    [n_lo, n_hi] (the flat parts outside the knees).
    """
    if n <= n_lo:
        return f_lo
    if n >= n_hi:
        return f_hi
    t = math.log(n / n_lo) / math.log(n_hi / n_lo)
    return f_lo * (f_hi / f_lo) ** t
