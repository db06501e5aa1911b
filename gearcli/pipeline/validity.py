"""Validity guard of a finished run (docs/theory.md §10.2): a run whose deflections or motions
leave the range of the contact model is reported as ``invalid`` with a one-line reason, never as
a valid dynamic factor.

Checked, in this order (the first that fails is the reason):

1. **Penetration** — the largest pair penetration (true extremum over the whole run) against
   ``min(PENETRATION_PER_STATIC × δ_s, PENETRATION_PER_THICKNESS × s)``, δ_s the static deflection
   of the case's law and load, s = π m/2 the reference tooth thickness. A linear (or power-law)
   tooth is meaningless at penetrations far beyond the static deflection (docs/theory.md §10.2): the
   penetration ratio is the dynamic factor of a linear contact, and ten times the static
   deflection is several times the largest dynamic factors of ISO 6336-1 Method B (K_v of at
   most about 2-3 at the main resonance, docs/theory.md §10.4), i.e. a vibro-impact state of an
   undamped, error-free model, not a gear's response. The thickness term (5 % of the tooth
   thickness) bounds the small-deflection geometry of the gap tables (contact points of the
   rigid profiles) for soft penalty contacts and for runs without load (δ_s = 0). The static
   term is never below the deflection at ISO 6336-1's reference line load of 100 N/mm
   (:func:`reference_deflection_for`): a penetration every loaded gear reaches is inside the
   tooth model's range, so the rattle of a lightly loaded pair (tens of newtons, a ratio of
   tens to its tiny static deflection) is not an excursion out of the model.
2. **Speed reversal** — the gear (and, with a torque drive, the pinion) running backwards (by
   more than one tooth pitch over the window: e.g. a load larger than a torque drive) or turning
   backwards in the steady window by more than 1 % of its mean speed: the pair's kinematics
   (tables of roll position, the drive/coast flank assignment and the output sampling by roll)
   assume a forward-running pair.
3. **Runaway energy** — the energy balance's relative residual (docs/theory.md §6.6) above
   ``ENERGY_RESIDUAL_LIMIT``: the integration did not conserve energy, so no number of the run
   is trustworthy (measured residuals of valid runs: 1e-9 … 1e-5).
4. **Loose tolerances** — a case that loosens the solver tolerances beyond gearcli's defaults
   (``run.rtol`` above 1e-6, ``run.atol`` above the default deflection tolerance) is integrated
   once more at the defaults (for its true extrema); its largest total force or largest
   penetration more than ``TOLERANCE_AGREEMENT`` away from theirs means the run's numbers are
   those of its tolerances (:func:`tolerance_check`). The defaults are the verified ones
   (docs/theory.md §10.3: within 1 % of 100 times tighter tolerances at five speeds); the
   energy residual of item 3 does not see this error (7e-5 with a dynamic factor 31 % off).
   Without load, differences below 1 % of the force and the deflection at the reference line
   load of item 1 are none (:func:`reference_scales`): the gear floats in its backlash, and its
   touches are not converged at the defaults either.

Before these, a run the solver stopped because a penetration left the gap tables (their cap
max(0.05 m, 20 δ_s), above the limit of item 1 whenever there is a load and 10 δ_s sets
that limit; its floor, the deflection at the reference line load, can exceed the cap for a soft,
lightly loaded pair: E 3 GPa, module 1, 0.05 N*m: limit 0.0785 mm, cap 0.05 mm) is ``invalid`` up to
where it stopped (:func:`cut_at_table_exit`, :func:`table_exit`): the same status, folder and
exit code 4 as a run that stays inside the tables but beyond item 1's limit.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

PENETRATION_PER_STATIC = 10.0
PENETRATION_PER_THICKNESS = 0.05
ENERGY_RESIDUAL_LIMIT = 1e-3
#: backward speed, as a fraction of the mean speed, that counts as a reversal (below it: the
#: numerical dither of a quasi-static run, e.g. -2e-4 deg/s at 3 deg/s)
REVERSAL_FRACTION = 0.01

#: Status of a run inside the model's range, and of one outside it.
OK, INVALID = "ok", "invalid"


class Validity(NamedTuple):
    status: str  #: OK or INVALID
    reason: str  #: one line; empty when OK


def penetration_limit_mm(static_deflection_mm: float, module_mm: float,
                         reference_deflection_mm: float = 0.0) -> float:
    """The largest penetration [mm] inside the contact model's range (module notes, item 1);
    ``reference_deflection_mm``: the deflection at the reference line load, the floor of the
    static term (0: none)."""
    thickness = PENETRATION_PER_THICKNESS * math.pi * module_mm / 2.0
    if static_deflection_mm > 0.0:
        return min(max(PENETRATION_PER_STATIC * static_deflection_mm, reference_deflection_mm),
                   thickness)
    return thickness


def reference_deflection_for(res, penetration_mm: float) -> float:
    """The floor of item 1's static term for a run ``res`` (pipeline.simulation
    .SimulationResult) whose largest penetration is ``penetration_mm``: the deflection at the
    reference line load (pipeline.mesh_input.reference_deflection_mm), computed only when it
    decides (a loaded run beyond 10 static deflections), else 0."""
    from gearcli.pipeline.mesh_input import reference_deflection_mm

    static = res.kernel_input.mesh.loaded_deflection_mm
    if not (static > 0.0 and penetration_mm > PENETRATION_PER_STATIC * static):
        return 0.0
    return reference_deflection_mm(res.loaded.case, res.geometry)


def check_validity(*, penetration_max_mm: float, static_deflection_mm: float, module_mm: float,
                   gear_speed_rad_s: np.ndarray, pinion_speed_rad_s: np.ndarray | None,
                   window_s: float, teeth: tuple[int, int],
                   energy_relative_residual: float,
                   reference_deflection_mm: float = 0.0) -> Validity:
    """Validity of one run (module notes). Speeds are the steady window's samples [rad/s]
    (``window_s`` long); ``pinion_speed_rad_s`` only when the pinion is free (torque drive),
    else None; ``teeth`` = (z1, z2); ``reference_deflection_mm``: item 1's floor
    (:func:`reference_deflection_for`)."""
    limit = penetration_limit_mm(static_deflection_mm, module_mm, reference_deflection_mm)
    if not penetration_max_mm <= limit:
        from gearcli.pipeline.mesh_input import REFERENCE_LINE_LOAD_N_MM

        floor = (f", at least the deflection {reference_deflection_mm:.4g} mm at "
                 f"{REFERENCE_LINE_LOAD_N_MM:g} N/mm" if reference_deflection_mm > 0.0 else "")
        return Validity(INVALID, (
            f"tooth penetration {penetration_max_mm:.4g} mm is beyond the contact model's range "
            f"{limit:.4g} mm ({PENETRATION_PER_STATIC:g} x the static deflection "
            f"{static_deflection_mm:.4g} mm{floor}, at most "
            f"{100 * PENETRATION_PER_THICKNESS:g} % of the tooth thickness)"))
    for name, omega, z in (("gear", gear_speed_rad_s, teeth[1]),
                           ("pinion", pinion_speed_rad_s, teeth[0])):
        if omega is None or omega.size == 0:
            continue
        mean = float(np.mean(omega))
        pitches = -mean * window_s * z / (2.0 * math.pi)
        if pitches > 1.0:
            # backwards throughout (e.g. a load torque larger than a torque drive's); a gear
            # creeping back by its deflection in a ring-down at rest is not
            return Validity(INVALID, (
                f"the {name} runs backwards in the steady window (mean speed "
                f"{np.degrees(mean):.4g} deg/s, {pitches:.3g} tooth pitches): the model "
                "assumes a forward-running pair"))
        forward = np.sign(mean) or 1.0
        worst = float(omega[np.argmin(forward * omega)])
        if forward * worst < -REVERSAL_FRACTION * abs(mean):
            return Validity(INVALID, (
                f"the {name} reverses in the steady window (speed {np.degrees(worst):.4g} deg/s "
                f"against its mean of {np.degrees(mean):.4g} deg/s): the model assumes a "
                "forward-running pair"))
    if not energy_relative_residual <= ENERGY_RESIDUAL_LIMIT:
        return Validity(INVALID, (
            f"energy balance residual {energy_relative_residual:.3g} of the largest energy term "
            f"(limit {ENERGY_RESIDUAL_LIMIT:g}): the integration is not trustworthy"))
    return Validity(OK, "")


#: Largest relative difference of the largest total force or penetration between a run at the
#: case's loosened tolerances and the same run at the defaults (module notes, item 4): the
#: defaults themselves agree with 100 x tighter tolerances within 1 % (docs/theory.md §10.3).
TOLERANCE_AGREEMENT = 0.01


def loosened(res) -> bool:
    """Whether the case of the run ``res`` (pipeline.simulation.SimulationResult) loosens the
    solver tolerances beyond gearcli's defaults (module notes, item 4)."""
    (rtol, atol), (rtol_0, atol_0) = _tolerances(res)
    return rtol > rtol_0 or atol > atol_0


def loosened_tolerance_hint(res) -> str:
    """For an invalid run of a case that loosens the solver tolerances (:func:`loosened`):
    the clause that says so (its invalidity may be the tolerances' doing: a run that
    "reverses" or leaves its energy balance at a 1 m atol); "" otherwise."""
    if not loosened(res):
        return ""
    asked, defaults = _tolerance_texts(res)
    return f"; {asked} are looser than {defaults}: try without run.rtol / run.atol"


def tolerance_reference(res, progress=None):
    """The run ``res`` (pipeline.simulation.SimulationResult) integrated once more at the
    default tolerances (module notes, item 4): its kernel result, with the true extrema from
    the steady window on at the same output times (taken at every accepted step and every
    output sample, docs/theory.md §7.4, so both runs' maxima see the same samples); None when
    the case's tolerances are the defaults or tighter (nothing to compare). ``progress`` as
    for gearcli.core.integrate.simulate."""
    from gearcli.core.integrate import simulate
    from gearcli.core.layout import P

    if not loosened(res):
        return None
    ki = res.kernel_input
    params = ki.params.copy()
    (rtol, atol), (rtol_0, atol_0) = _tolerances(res)
    params[P.rtol], params[P.atol_delta] = min(rtol, rtol_0), min(atol, atol_0)
    params[P.atol_deltadot] *= params[P.atol_delta] / atol  # the same speed scale
    params[P.extrema_t_start] = res.window.t0_s
    return simulate(params, ki.tables.tables, t_out=ki.t_out, drive_pp=ki.drive_pp,
                    load_pp=ki.load_pp, drive_angle_pp=ki.drive_angle_pp, progress=progress,
                    **ki.arrays)


def _tolerances(res) -> tuple[tuple[float, float], tuple[float, float]]:
    """((rtol, atol [mm]) of the run, (rtol, atol) of gearcli's defaults for its case)."""
    from gearcli.core.layout import PARAM_DEFAULTS, P
    from gearcli.pipeline.kernel_input import deflection_atol

    ki = res.kernel_input
    return ((float(ki.params[P.rtol]), float(ki.params[P.atol_delta])),
            (PARAM_DEFAULTS["rtol"], deflection_atol(None, ki.mesh.static_deflection_mm)))


def _tolerance_texts(res) -> tuple[str, str]:
    (rtol, atol), (rtol_0, atol_0) = _tolerances(res)
    return (f"the case's solver tolerances (rtol {rtol:.3g}, atol {atol:.3g} mm)",
            f"gearcli's defaults (rtol {rtol_0:g}, atol {atol_0:.3g} mm)")


def tolerance_check(res, ref) -> Validity:
    """Item 4 of the module notes for a run ``res`` valid by items 1-3 and its
    :func:`tolerance_reference` ``ref`` (None: OK, nothing loosened)."""
    if ref is None:
        return Validity(OK, "")
    asked, defaults = _tolerance_texts(res)
    if not ref.ok:
        return Validity(INVALID, (
            f"the run at {asked} finished, but not at {defaults}: {ref.message}; its numbers "
            "are those of the loose tolerances"))
    k = res.kernel
    floors = reference_scales(res)
    for name, key, unit, floor in (("largest total force", "force_total_max_N", "N", floors[0]),
                                   ("largest penetration", "penetration_max_mm", "mm",
                                    floors[1])):
        value, expected = k.extremum(key), ref.extremum(key)
        if math.isnan(value) and math.isnan(expected):  # not recorded in either run
            continue
        reason = _disagreement(name, value, expected, unit, asked, defaults, floor)
        if reason:
            return Validity(INVALID, reason)
    return Validity(OK, "")


def reference_scales(res) -> tuple[float, float]:
    """For a run without load: (normal force [N], static deflection [mm]) of its pair at ISO
    6336-1's reference line load (pipeline.mesh_input.REFERENCE_LINE_LOAD_N_MM, item 1's
    scale when there is no static deflection); item 4 then compares within
    :data:`TOLERANCE_AGREEMENT` of the larger of a value and these, so the touches of a gear
    floating in its backlash (tens of newtons and nanometres, which the defaults do not
    converge either) are no disagreement. (0, 0) for a loaded run: plain relative differences."""
    if res.kernel_input.mesh.loaded_deflection_mm > 0.0:
        return 0.0, 0.0
    from gearcli.pipeline.mesh_input import REFERENCE_LINE_LOAD_N_MM, reference_deflection_mm

    g = res.geometry.geometry
    return (REFERENCE_LINE_LOAD_N_MM * g.narrow_face_width_mm,
            reference_deflection_mm(res.loaded.case, res.geometry))


def _disagreement(name: str, value: float, expected: float, unit: str, asked: str,
                  defaults: str, floor: float = 0.0) -> str:
    """The reason ``value`` (at the case's tolerances) is not ``expected`` (at the defaults)
    within :data:`TOLERANCE_AGREEMENT` of the larger of ``expected`` and ``floor`` (the
    value at the reference line load, :func:`reference_scales`), or ""."""
    if abs(value - expected) <= TOLERANCE_AGREEMENT * max(abs(expected), floor):
        return ""
    change = (value - expected) / max(abs(expected), 1e-300)
    of = (f" of {floor:.4g} {unit}, the value at the reference line load"
          if floor > abs(expected) else "")
    return (f"not converged at {asked}: the {name} is {value:.5g} {unit}, at {defaults} "
            f"{expected:.5g} {unit} ({100 * change:+.3g} %, limit "
            f"{100 * TOLERANCE_AGREEMENT:g} %{of}): its numbers are those of the tolerances; "
            "tighten or remove run.rtol / run.atol")


def converged_levels(res, rows: list, reference_rows: list | None) -> list:
    """Speed-curve levels (results.SpeedLevel rows of the run ``res``) against the same
    levels measured on its :func:`tolerance_reference` (``reference_rows``; None when that
    run failed): a level whose largest force is more than :data:`TOLERANCE_AGREEMENT` away
    from the reference's, or valid only at the loose tolerances, is invalid (item 4)."""
    import dataclasses

    asked, defaults = _tolerance_texts(res)
    floor = reference_scales(res)[0]
    out = []
    for i, row in enumerate(rows):
        ref = reference_rows[i] if reference_rows is not None else None
        if row.status == INVALID:
            out.append(row)
            continue
        if ref is None or ref.status == INVALID:
            reason = (f"the level at {asked} is not one at {defaults}: "
                      + (ref.error if ref is not None else res.invalid_reason))
        else:
            reason = _disagreement("largest total force", row.force_max_N, ref.force_max_N,
                                   "N", asked, defaults, floor)
        if reason:
            row = dataclasses.replace(row, status=INVALID, error=reason, dynamic_factor=math.nan,
                                      force_max_N=math.nan, dte_peak_to_peak_mm=math.nan,
                                      contact_loss_fraction=math.nan)
        out.append(row)
    return out


def table_exit(penetration_mm: float, t_s: float, cap_mm: float) -> Validity:
    """The validity of a run the solver stopped at ``t_s`` [s] because a tooth penetration
    (``penetration_mm``) left the gap tables, tabulated to ``cap_mm`` (module notes)."""
    # the run's extrema start with the steady window: before it the value is not recorded
    value = f" ({penetration_mm:.4g} mm)" if math.isfinite(penetration_mm) else ""
    return Validity(INVALID, (
        f"a tooth penetration{value} left the contact tables at t = {t_s:.6g} s (they reach "
        f"{cap_mm:.4g} mm of penetration): the run is outside the contact model's range and "
        "was stopped there"))


def cut_at_table_exit(kr, window):
    """(kernel result, window) of a run stopped where it left the gap tables: the samples up
    to the stop, and the window cut there (its second half when the steady window had not
    begun)."""
    from gearcli.pipeline.window import Window

    n = max(int(kr.n_valid), 1)
    kr = kr._replace(series=kr.series[:n], slot_force=kr.slot_force[:n],
                     slot_force_coast=kr.slot_force_coast[:n])
    t_stop = float(kr.series[-1, 0]) if n > 1 else kr.extremum("t_reached_s")
    if window.t0_s < t_stop:
        window = Window(window.t0_s, t_stop, window.reason + ", cut where the run stopped")
    elif (kr.column("t_s") >= 0.5 * t_stop).any():
        window = Window(0.5 * t_stop, t_stop, "the run up to where it left the contact "
                        "tables, its second half")
    else:  # stopped before the second output sample: the samples there are
        window = Window(0.0, t_stop, "the run up to where it left the contact tables")
    return _sampled_extrema(kr, window.t0_s), window


def _sampled_extrema(kr, t0_s: float):
    """``kr`` with the window's force and DTE extrema that the solver did not record (its
    extrema start at the planned window, after the stop) taken from the samples."""
    from gearcli.core.layout import EXTREMA_NAMES

    t = kr.column("t_s")
    w = t >= t0_s
    if not w.any():
        return kr
    extrema = kr.extrema.copy()
    for name, column, pick in (("force_total_max", "force_total_N", np.argmax),
                               ("force_total_min", "force_total_N", np.argmin),
                               ("delta_max", "delta_mm", np.argmax),
                               ("delta_min", "delta_mm", np.argmin)):
        unit = "N" if column.endswith("_N") else "mm"
        i = EXTREMA_NAMES.index(f"{name}_{unit}")
        if math.isnan(extrema[i]):
            values = kr.column(column)[w]
            k = int(pick(values))
            extrema[i] = values[k]
            extrema[EXTREMA_NAMES.index(f"{name}_t_s")] = t[w][k]
    return kr._replace(extrema=extrema)


#: Change of a speed or of the load torque over the steady window (least-squares trend times
#: the window's length, relative to the mean) above which the run is not at one operating
#: point: 1 % moves the mesh frequency by less than the half-power band 2 ζ f_n of a mesh
#: mode with ζ ≥ 0.005 (measured meshes: 0.03-0.1, docs/theory.md §4.4). Steady runs measure
#: at most 0.12 % (seed 8e-6, cases/iso_pair.yaml 5e-6, cases/nrel5mw_sun_planet.yaml 1e-6,
#: cases/drivetrain.yaml 1.2e-3: its motor curve still creeping to the operating point).
UNSTEADY_FRACTION = 0.01
#: Operating state of a run whose speeds and load hold still over the window, and of one
#: whose do not (its dynamic factor is not that of a steady operating point).
STEADY, UNSTEADY = "steady", "unsteady"


def trend_change(t_s: np.ndarray, values: np.ndarray) -> float:
    """The change of ``values`` over ``t_s`` from their least-squares straight line, relative
    to their mean (nan without two samples or with a zero mean)."""
    if t_s.size < 2 or np.ptp(t_s) <= 0.0:
        return math.nan
    mean = float(np.mean(values))
    if mean == 0.0:
        return math.nan
    slope = np.polyfit(t_s - t_s[0], values, 1)[0]
    return float(slope * (t_s[-1] - t_s[0]) / abs(mean))


def operating_state(t_s: np.ndarray, signals: dict[str, np.ndarray],
                    turning: dict[str, bool]) -> tuple[str, float, str]:
    """(STEADY or UNSTEADY, the largest relative change, a one-line reason) of the steady
    window's samples: each signal ({name: values}) changes by at most
    :data:`UNSTEADY_FRACTION` of its mean over the window; a speed counts only when its body
    turns (``turning[name]``: e.g. more than a tooth pitch over the window), a signal with a
    zero mean not at all."""
    worst, name = 0.0, ""
    for key, values in signals.items():
        if not turning.get(key, True):
            continue
        change = trend_change(t_s, values)
        if math.isfinite(change) and abs(change) > abs(worst):
            worst, name = change, key
    if abs(worst) <= UNSTEADY_FRACTION:
        return STEADY, worst, ""
    return UNSTEADY, worst, (
        f"unsteady: the {name} changes by {100 * worst:+.3g} % over the steady window "
        f"(trend; steady below {100 * UNSTEADY_FRACTION:g} %): the dynamic factor is not that "
        "of one steady operating point")


def window_state(t_s: np.ndarray, omega1_rad_s: np.ndarray, omega2_rad_s: np.ndarray,
                 load_torque_Nmm: np.ndarray, teeth: tuple[int, int]) -> tuple[str, float, str]:
    """:func:`operating_state` of a window's samples: the pinion and gear speeds [rad/s] (a
    body counts when it turns by more than a tooth pitch over the window; ``teeth`` = (z1,
    z2)) and the load torque [N·mm]."""
    span = float(np.ptp(t_s)) if t_s.size else 0.0
    signals = {"pinion speed": omega1_rad_s, "gear speed": omega2_rad_s,
               "load torque": load_torque_Nmm}
    turning = {name: abs(float(np.mean(w))) * span * z > 2.0 * math.pi if w.size else False
               for name, w, z in (("pinion speed", omega1_rad_s, teeth[0]),
                                  ("gear speed", omega2_rad_s, teeth[1]))}
    return operating_state(t_s, signals, turning)


def drift_phrase(unsteady_reason: str) -> str:
    """The "the gear speed changes by +87.6 % over the steady window" part of a reason of
    :func:`operating_state`, for notes of other documents."""
    return unsteady_reason.removeprefix("unsteady: ").split(" (trend")[0]
