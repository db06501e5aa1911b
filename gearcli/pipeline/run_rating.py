"""The ISO 6336 rating of a finished run, for `gearcli run` (issue 28): the ISO column and the
"simulated" column beside it (pipeline.rating.rate_case with the run's
:class:`~gearcli.pipeline.rating.SimulatedLoad`: K_v = F_max/F_static of the run, the peak σ_H,
σ_F of `gearcli stress`); docs/theory.md, "ISO 6336 rating".

A case without the fatigue limits the rating needs (material.contact_fatigue_limit,
material.bending_fatigue_limit, or rating.<gear>.material hardness) is not rated: the reason is
returned instead, and the run goes on without a rating.
"""

from __future__ import annotations

from pathlib import Path

from gearcli.case.load import LoadedCase
from gearcli.errors import GearcliError
from gearcli.pipeline.rating import (
    CaseRating,
    SimulatedLoad,
    rate_case,
    rating_input,
    simulated_load,
)

__all__ = ["rate_run", "simulated_safeties"]


def _first_line(exc: Exception) -> str:
    return str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__


def rate_run(folder: str | Path, loaded: LoadedCase) -> tuple[CaseRating | None, str]:
    """(the rating of the run in ``folder`` of the case ``loaded``, "") or (None, why not).

    The case is checked first (rating_input: fatigue limits, load, speed), so a case that
    cannot be rated costs no stress evaluation of the run."""
    try:
        rating_input(loaded)
    except GearcliError as exc:
        return None, _first_line(exc)
    try:
        simulated, _ = simulated_load(folder)
        return rate_case(loaded, simulated=simulated), ""
    except GearcliError as exc:
        return None, _first_line(exc)


def simulated_safeties(loaded: LoadedCase, dynamic_factor: float | None
                       ) -> tuple[float | None, float | None]:
    """(min S_H, min S_F) over pinion and gear of the ISO 6336 rating with K_v = the run's
    F_max/F_static (a sweep point's metrics); (None, None) when the case cannot be rated."""
    if dynamic_factor is None or not dynamic_factor > 0.0:
        return None, None
    try:
        sim = rate_case(loaded, simulated=SimulatedLoad(float(dynamic_factor))).simulated
    except GearcliError:
        return None, None
    gears = (sim.pinion, sim.gear)
    return min(g.S_H for g in gears), min(g.S_F for g in gears)
