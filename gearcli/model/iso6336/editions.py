"""ISO 6336:2006 beside :2019: the factors whose formulas differ between the editions as
implemented, and what follows from them, for one rating input (docs/theory.md, "ISO 6336
rating" §7).

Edition-dependent as implemented: Z_β (ISO 6336-2: √cos β in 2006, 1/√cos β in 2019), Y_β
(ISO 6336-3: 2019 divides the 2006 form by cos³β) — both 1 for spur gears — and the mean stress
factor Y_M of an idler or reversed bending (2006: 0.7; 2019: 1/(1 − R (1 − M)/(1 + M))). The
rows also carry σ_FG, S_F and S_H, so that what the editions change in the verdict is seen.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from gearcli.model.iso6336.common import Edition, Factor
from gearcli.model.iso6336.document import RatingResult
from gearcli.model.iso6336.inputs import RatingInput
from gearcli.model.iso6336.rate import Evaluation, evaluate

__all__ = ["EditionRow", "EDITION_PAIR_SYMBOLS", "EDITION_GEAR_SYMBOLS", "edition_rows"]

#: Pair factors that depend on the edition (as implemented).
EDITION_PAIR_SYMBOLS = ("Z_β",)
#: Gear factors shown for both editions: the edition-dependent ones and σ_FG that follows
#: (each gear's S_F and S_H rows are shown after them).
EDITION_GEAR_SYMBOLS = ("Y_β", "Y_M", "σ_FG")


@dataclass(frozen=True)
class EditionRow:
    """One factor under both editions."""

    symbol: str
    gear: str  #: "pair", "pinion" or "gear"
    value_2006: float
    value_2019: float
    unit: str

    @property
    def differs(self) -> bool:
        """The two values differ beyond rounding (relative 1e-12)."""
        return not math.isclose(self.value_2006, self.value_2019, rel_tol=1e-12)

    def to_dict(self) -> dict:
        return {"symbol": self.symbol, "gear": self.gear, "2006": self.value_2006,
                "2019": self.value_2019, "unit": self.unit, "differs": self.differs}


def _rows_of(rated: RatingResult | Evaluation) -> dict[str, dict[str, Factor]]:
    """{"pair" | "pinion" | "gear": {symbol: row}} of a rating document or an evaluation."""
    gears = (rated.pinion, rated.gear)
    return {"pair": {f.symbol: f for f in rated.pair_factors},
            **{role: {f.symbol: f for f in g.factors}
               for role, g in zip(("pinion", "gear"), gears, strict=True)}}


def edition_rows(inp: RatingInput, rated: RatingResult | None = None) -> tuple[EditionRow, ...]:
    """The rows of :data:`EDITION_PAIR_SYMBOLS` and, per gear, :data:`EDITION_GEAR_SYMBOLS`,
    S_F and S_H, rated by ISO 6336:2006 and :2019 (``rated``: the rating of ``inp`` already at
    hand, reused for its own edition; the other edition is evaluated without the lives and
    inspection dimensions, which it does not change)."""
    by = {}
    for ed in (Edition.ISO2006, Edition.ISO2019):
        if rated is not None and rated.edition == ed.value:
            by[ed.value] = _rows_of(rated)
        else:
            by[ed.value] = _rows_of(evaluate(dataclasses.replace(inp, edition=ed)))
    a, b = by["2006"], by["2019"]
    wanted = [("pair", s) for s in EDITION_PAIR_SYMBOLS] + [  # and the safeties S_H, S_F
        (role, s) for role in ("pinion", "gear")
        for s in (*EDITION_GEAR_SYMBOLS, *(x for x in a[role] if x.startswith("S_")))]
    return tuple(EditionRow(s, where, a[where][s].value, b[where][s].value, a[where][s].unit)
                 for where, s in wanted)
