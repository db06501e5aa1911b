"""Remedies for failed checks (docs/theory.md, "Remedies of failed checks").

* A failed ``dynamic_factor`` or ``contact_loss_fraction``: the linear long tip relief (the
  same on both gears, from the tip down to the limit of single-pair contact) whose amount
  minimises the loaded static transmission error at the case load (`gearcli mesh`'s loaded
  contact, model/ltca.py), and the dynamic factor and contact loss of a short run with it.
* A failed ``resonance_margin_percent``: the pinion speed bands where a checked harmonic
  k f_z lies within the margin of a mode with a resonant peak (gearcli/pipeline/speed_bands.py,
  shared with `gearcli modal`).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from gearcli.case.load import LoadedCase
from gearcli.pipeline.speed_bands import resonance_remedy
from gearcli.pipeline.validity import UNSTEADY
from gearcli.results import AnalysisMetrics, Check, Remedy

#: Checks a tip relief addresses (the mesh's excitation, STE): the metrics whose field says so.
RELIEF_CHECKS = tuple(f.name for f in dataclasses.fields(AnalysisMetrics)
                      if f.metadata.get("remedy") == "tip_relief")
#: Grid of the relief search: amounts s x (mean loaded STE of the unmodified pair), s in
#: 0 .. RELIEF_SPAN; then a golden-section refinement between the best point's neighbours.
RELIEF_SPAN, RELIEF_POINTS, RELIEF_REFINE = 2.5, 11, 8
#: Mesh cycles of the short run that measures the dynamic factor with the relief, after the
#: original run's steady-window start.
SHORT_RUN_MESH_CYCLES = 60
#: Roll positions per mesh cycle of the relief search (one cycle each).
POINTS_PER_CYCLE = 100


def relief_overrides(amount_mm: float, length_mm: float) -> dict[str, str]:
    """The ``--set`` overrides of a linear tip relief ``amount_mm`` over ``length_mm`` (along
    the line of action) on both gears."""
    return {f"modifications.tip_relief.{gear}.{key}": value
            for gear in ("pinion", "gear")
            for key, value in (("amount", f"{float(amount_mm):.6g} mm"),
                               ("length", f"{float(length_mm):.6g} mm"),
                               ("shape", "linear"))}


def _with(loaded: LoadedCase, overrides: dict[str, str]) -> LoadedCase:
    """The case with ``overrides`` (key path -> value text) applied, validated."""
    from gearcli.case.load import validate_source
    from gearcli.case.overrides import apply_overrides
    from gearcli.case.schema import Case

    src = loaded.source
    data = apply_overrides(src.data, [f"{k}={v}" for k, v in overrides.items()], Case)
    return validate_source(dataclasses.replace(src, data=data), loaded.name)


def optimum_tip_relief(loaded: LoadedCase) -> tuple[float, float, float, float]:
    """(amount [mm], length [mm], STE peak to peak with it [mm], without [mm]) of the linear
    long tip relief that minimises the loaded STE at the case's static load.

    Long relief: length (ε_α − 1) p_b along the line of action, the extent of the double-pair
    zone at each end of the path (docs/theory.md §3); the amount is searched on a grid scaled
    by the mean loaded STE of the unmodified pair, then refined by golden section."""
    from gearcli.pipeline.geometry import run_geometry
    from gearcli.pipeline.mesh import run_mesh

    g = run_geometry(loaded).geometry
    length = max(g.eps_alpha - 1.0, 0.05) * g.p_b_mm
    base = _strip_relief(loaded)

    def ste(amount: float) -> float:
        case = base if amount <= 0.0 else _with(base, relief_overrides(amount, length))
        return run_mesh(case, cycles=1, points_per_cycle=POINTS_PER_CYCLE).loaded \
            .ste_peak_to_peak_mm

    unmodified = run_mesh(base, cycles=1, points_per_cycle=POINTS_PER_CYCLE).loaded
    scale = abs(float(unmodified.ste_mm.mean())) or unmodified.ste_peak_to_peak_mm
    grid = np.linspace(0.0, RELIEF_SPAN * scale, RELIEF_POINTS)
    values = [unmodified.ste_peak_to_peak_mm] + [ste(a) for a in grid[1:]]
    i = int(np.argmin(values))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    best_a, best = float(grid[i]), float(values[i])
    phi = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(RELIEF_REFINE):  # golden section on [lo, hi]
        a, b = hi - phi * (hi - lo), lo + phi * (hi - lo)
        fa, fb = ste(a), ste(b)
        for x, fx in ((a, fa), (b, fb)):
            if fx < best:
                best_a, best = float(x), float(fx)
        lo, hi = (lo, b) if fa < fb else (a, hi)
    return best_a, length, best, unmodified.ste_peak_to_peak_mm


def _strip_relief(loaded: LoadedCase) -> LoadedCase:
    """The case without its tip relief (the search replaces it)."""
    data = loaded.source.data
    mods = data.get("modifications") if isinstance(data, dict) else None
    if not (isinstance(mods, dict) and mods.get("tip_relief")):
        return loaded
    from gearcli.case.load import validate_source

    new = dict(data, modifications={k: v for k, v in mods.items() if k != "tip_relief"})
    return validate_source(dataclasses.replace(loaded.source, data=new), loaded.name)


def relief_remedy(loaded: LoadedCase, window_start_s: float, f_z_Hz: float) -> Remedy:
    """The tip-relief remedy: the optimum relief and the dynamic factor and contact loss of a
    short run with it (``SHORT_RUN_MESH_CYCLES`` mesh cycles after ``window_start_s``)."""
    from gearcli.pipeline.simulate import run_simulation

    amount, length, ste_with, ste_without = optimum_tip_relief(loaded)
    end = loaded.case.run.end_time
    if f_z_Hz and f_z_Hz > 0.0:
        end = min(end, window_start_s + SHORT_RUN_MESH_CYCLES / f_z_Hz)
    overrides = relief_overrides(amount, length)
    short = dict(overrides, **{"run.end_time": f"{float(end):.6g} s"})
    sim = run_simulation(_with(_strip_relief(loaded), short), notice=None, zoom=False)
    s = sim.summary
    # a run off one operating point (it ends inside its ramps) measures a transient
    steady = sim.status == "ok" and s.operating_state != UNSTEADY
    factor = s.dynamic_factor if steady else None
    loss = s.contact_loss_fraction if steady else None
    text = (f"a linear tip relief of {1e3 * amount:.3g} µm over {length:.3g} mm of the line of "
            f"action on both gears minimises the loaded STE at the case load "
            f"({1e3 * ste_without:.3g} -> {1e3 * ste_with:.3g} µm peak to peak)")
    if factor is not None:
        text += (f"; with it the dynamic factor is {factor:.3g} and the contact loss "
                 f"{100.0 * loss:.3g} % (a {end:.3g} s run)")
    elif sim.status == "ok":
        text += (f"; the {end:.3g} s run with it is not at one steady operating point, so it "
                 "gives no dynamic factor (simulate longer: run.end_time)")
    else:
        text += f"; the run with it is not valid: {sim.invalid_reason}"
    return Remedy(kind="tip_relief", text=text, tip_relief_amount_mm=amount,
                  tip_relief_length_mm=length, ste_peak_to_peak_um=1e3 * ste_with,
                  ste_peak_to_peak_before_um=1e3 * ste_without, dynamic_factor=factor,
                  contact_loss_fraction=loss, run_end_time_s=end, set=tuple(
                      f"{k}={v}" for k, v in overrides.items() if not k.endswith("shape")))


def _relief_or_none(loaded: LoadedCase, metrics) -> Remedy | bool:
    """:func:`relief_remedy`, or False when the case has none to offer (the search or its run
    refused the case: a remedy never turns a finished analysis into an error)."""
    from gearcli.errors import GearcliError

    try:
        return relief_remedy(loaded, metrics.window_s[0], metrics.gear_mesh_frequency_Hz or 0.0)
    except GearcliError:
        return False


def add_remedies(checks: list[Check], loaded: LoadedCase, metrics) -> list[Check]:
    """``checks`` with a remedy on each failed check that has one (in place, returned)."""
    relief = None
    for i, ck in enumerate(checks):
        if not ck.failed:
            continue
        remedy = None
        if ck.name in RELIEF_CHECKS and (metrics.force_static_N or 0.0) > 0.0:
            if relief is None:
                relief = _relief_or_none(loaded, metrics)
            remedy = relief or None
        elif ck.name == "resonance_margin_percent":
            remedy = resonance_remedy(metrics.resonance_margins,
                                      loaded.case.checks.resonance_margin_percent,
                                      loaded.case.gears.pinion.teeth)
        if remedy is not None:
            checks[i] = dataclasses.replace(ck, remedy=remedy)
    return checks
