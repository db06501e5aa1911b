"""The ISO 6336 rating of a finished run, for `gearcli run`: the ISO column and the
"simulated" column beside it (pipeline.rating.rate_case with the run's
:class:`~gearcli.pipeline.rating.SimulatedLoad`: K_v = F_max/F_static of the run, the peak σ_H,
σ_F of `gearcli stress`); docs/theory.md, "ISO 6336 rating".

A case without the fatigue limits the rating needs (material.contact_fatigue_limit,
material.bending_fatigue_limit, or rating.<gear>.material hardness) is not rated: the reason is
returned instead, and the run goes on without a rating.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from gearcli.case.load import LoadedCase
from gearcli.errors import GearcliError
from gearcli.model.iso6336.document import RatingResult
from gearcli.pipeline.rating import (
    CaseRating,
    PeakSafety,
    SimulatedLoad,
    rate_case,
    rating_input,
    simulated_load_of,
)
from gearcli.results.rating import GearSafeties, RatingColumn, RatingSummary

__all__ = ["rate_run", "simulated_safeties", "rating_summary", "write_rating",
           "level_safeties", "with_level_safeties", "speed_curve_rating",
           "write_rating_figure"]


def _first_line(exc: Exception) -> str:
    return str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__


def rate_run(folder: str | Path, loaded: LoadedCase, stress_files: bool = False
             ) -> tuple[CaseRating | None, str]:
    """(the rating of the run in ``folder`` of the case ``loaded``, "") or (None, why not).

    The case is checked first (rating_input: fatigue limits, load, speed), so a case that
    cannot be rated costs no stress evaluation of the run. ``stress_files``: also write the
    stress evaluation the simulated column comes from (stress.json, stress.csv: the report's
    Stress section and its figure, with the critical positions marked)."""
    from gearcli.pipeline.stress import compute_stress, write_stress

    try:
        rating_input(loaded)
    except GearcliError as exc:
        return None, _first_line(exc)
    try:
        res = compute_stress(folder, None)
        if stress_files:
            write_stress(res)
        off = _off_operating_point(res.run)
        if off and loaded.case.rating.dynamic_factor != "simulated":
            rating = rate_case(loaded)  # the ISO column alone, with the case's own K_v
            return dataclasses.replace(rating, notes=(*rating.notes, off)), ""
        if off:
            return None, off
        return rate_case(loaded, simulated=simulated_load_of(res)), ""
    except GearcliError as exc:
        return None, _first_line(exc)


def _off_operating_point(run) -> str:
    """Why the run's F_max/F_static is no operating point's dynamic factor (its window is not
    one steady operating point: summary.json's operating_state, docs/theory.md §10.2), or ""
    when it is."""
    from gearcli.pipeline.validity import UNSTEADY, drift_phrase

    s = run.summary
    if s.scalars.operating_state != UNSTEADY:
        return ""
    drift = next((w for w in s.warnings if w.startswith("unsteady:")), "")
    return ("no simulated column: the run's window is not one steady operating point"
            + (f" ({drift_phrase(drift)})" if drift else "")
            + ", so its F_max/F_static is no operating point's K_v")


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


def _column(result: RatingResult, source: str, peaks: dict | None = None) -> RatingColumn:
    """The safeties of one column of the rating (with the peak safeties of ``peaks``)."""
    gears = {}
    for g in (result.pinion, result.gear):
        peak = (peaks or {}).get(g.name) or PeakSafety()
        gears[g.name] = GearSafeties(
            S_H=g.S_H, S_H_min=g.S_H_min, pitting="pass" if g.pitting_ok else "fail",
            S_F=g.S_F, S_F_min=g.S_F_min, bending="pass" if g.bending_ok else "fail",
            S_H_peak=peak.S_H, S_F_peak=peak.S_F)
    return RatingColumn(
        dynamic_factor=result.factor("K_v").value, dynamic_factor_source=source,
        pinion=gears["pinion"], gear=gears["gear"],
        safety_pitting_min=min(g.S_H for g in gears.values()),
        safety_bending_min=min(g.S_F for g in gears.values()),
        verdict="pass" if result.ok else "fail")


def rating_summary(rating: CaseRating) -> RatingSummary:
    """summary.json's ``rating`` of a run's rating: S_H, S_F per gear of the ISO and the
    simulated column, against their minimums, with verdicts (gearcli/results/rating.py)."""
    sim = rating.simulated
    return RatingSummary(
        edition=rating.iso.edition, iso=_column(rating.iso, rating.dynamic_factor_source),
        simulated=None if sim is None else _column(
            sim, "simulated: the run's F_max/F_static", rating.simulated_peaks),
        verdict="pass" if rating.ok else "fail")


def write_rating(folder: str | Path, rating: CaseRating) -> None:
    """rating.json (every factor, both columns) into the run's ``folder``, and the safeties
    into its summary.json's ``rating`` (:func:`rating_summary`)."""
    import json

    from gearcli.io.files import write_atomic
    from gearcli.io.results import read_json

    folder = Path(folder)
    write_atomic(folder / "rating.json", json.dumps(rating.to_dict(), indent=2) + "\n")
    summary = read_json(folder / "summary.json")  # every other entry as written
    summary["rating"] = rating_summary(rating).to_dict()  # SummaryDocument.rating
    write_atomic(folder / "summary.json", json.dumps(summary, indent=2) + "\n")


def level_safeties(loaded: LoadedCase, levels: list[tuple[float, float]]
                   ) -> list[tuple[float, float]]:
    """(min S_H, min S_F) over pinion and gear of the ISO 6336 rating of the case at each
    (pinion speed [rpm], K_v [-]) of ``levels`` (a speed curve's speeds and their dynamic
    factors: the simulated rating at each speed; the speed enters Z_v, N_L and so the life
    factors); NaN where the case cannot be rated or a level has no dynamic factor."""
    import math

    from gearcli.model.iso6336.rate import rate

    nan = (math.nan, math.nan)
    try:
        inp = rating_input(loaded)[0]
    except GearcliError:
        return [nan] * len(levels)
    out = []
    for speed_rpm, k_v in levels:
        if not (math.isfinite(k_v) and k_v > 0.0 and math.isfinite(speed_rpm)
                and speed_rpm > 0.0):
            out.append(nan)
            continue
        r = rate(dataclasses.replace(inp, pinion_speed_rpm=speed_rpm, dynamic_factor=k_v))
        out.append((min(r.pinion.S_H, r.gear.S_H), min(r.pinion.S_F, r.gear.S_F)))
    return out


def with_level_safeties(loaded: LoadedCase, rows: list) -> list:
    """A speed curve's rows (gearcli.results.SpeedLevel) with their :func:`level_safeties`."""
    pairs = level_safeties(loaded, [(r.pinion_speed_rpm, r.dynamic_factor) for r in rows])
    return [dataclasses.replace(r, safety_pitting_min=h, safety_bending_min=f)
            for r, (h, f) in zip(rows, pairs, strict=True)]


def speed_curve_rating(loaded: LoadedCase, rows: list) -> dict | None:
    """speed_curve.json's ``rating``: what the rows' safety columns are and the minimums they
    are held against; None when no row was rated."""
    import math

    if not any(math.isfinite(r.safety_pitting_min) for r in rows):
        return None
    r = loaded.case.rating
    return {"method": "ISO 6336 Method B", "edition": str(r.edition),
            "dynamic_factor": "each speed's F_max/F_static (the row's dynamic_factor); "
                              "summary.csv's safety columns: the smaller S_H, S_F of the gears",
            "minimum_safety": {"pitting": r.minimum_safety.pitting,
                               "bending": r.minimum_safety.bending}}


def _points(rows, value) -> dict[str, list[tuple[float, float]]]:
    """{direction: [(N, value(row))]} of the rows with a finite value."""
    import math

    out: dict[str, list[tuple[float, float]]] = {}
    for r in rows:
        if math.isfinite(value(r)):
            out.setdefault(r.direction, []).append((r.resonance_ratio, value(r)))
    return out


def write_rating_figure(curve, folder: Path) -> dict | None:
    """speed_curve_rating.png (S_H, S_F against speed, gearcli/plotting/speed_curve_rating.py)
    of a finished speed curve (pipeline.speed_curve.SpeedCurve) into ``folder`` when its rows
    were rated; returns speed_curve.json's ``rating`` (:func:`speed_curve_rating`) or None."""
    from gearcli.case.load import load_case_text
    from gearcli.io.files import save_figure
    from gearcli.plotting.speed_curve_rating import plot_speed_curve_rating

    loaded = load_case_text(curve.base_case_json, f"{curve.name} (resolved case)")
    info = speed_curve_rating(loaded, curve.rows)
    if info is None:
        return None
    m = info["minimum_safety"]
    panels = [("S_H", m["pitting"], _points(curve.rows, lambda r: r.safety_pitting_min)),
              ("S_F", m["bending"], _points(curve.rows, lambda r: r.safety_bending_min))]
    fig = plot_speed_curve_rating(panels, curve.f_n_Hz,
                                  title=f"{curve.name}: safeties against speed")
    save_figure(fig, Path(folder) / "speed_curve_rating.png", 110)
    info["figure"] = "speed_curve_rating.png"
    return info
