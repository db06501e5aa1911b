"""Speed curves with continuation (`design: speed_curve` in a study; docs/theory.md §10.4).

A speed curve as a gear engineer draws it: the dynamic factor against the speed, run up and run
down. Each direction is ONE simulation whose pinion speed is a staircase over the study's mesh
frequencies f_z,1 … f_z,n (ascending for the run-up, descending for the run-down): the first
level is reached from rest by a smooth ramp, every later level by a smooth STEP of
``TRANSITION_CYCLES`` mesh cycles, and each level is held for ``DWELL_CYCLES`` mesh cycles. Every
speed therefore starts from the state the previous speed left (continuation), so the branch of a
nonlinear resonance the pair is on carries over and the jump between branches appears at
different speeds going up and going down (Kahraman & Singh 1990, J. Sound Vib. 142:49-75).

Each level is measured over the second half of its dwell (``MEASURE_FRACTION``; the mesh mode
of a realistic damping ζ = 0.07 decays by e^-5 within 11 cycles at N = 1) from the sampled
output at ``SAMPLES_PER_PERIOD`` samples per period of the highest mesh frequency (the sampled
maximum of a sinusoidal force lies within 1 − cos(π/30) = 0.55 % of its amplitude of the true
one): dynamic factor = max F_total / F_static, DTE peak-to-peak, contact-loss fraction. Each
level gets its own validity (gearcli/pipeline/validity.py) from the DTE, which bounds the pair
penetrations from above for pairs without pitch errors (drive: p ≤ δ; coast: p ≤ −δ − j_n), the
gear's speed over the level and the run's energy residual.

A valid level is ``unsettled`` (docs/theory.md §10.4; its numbers kept, marked in summary.csv
and the figure) when its measured half-dwell is not one steady state: the speed that carries the
mesh (the gear's, and the pinion's when it is free) changes by more than 1 % over it (the
operating-state rule of a run, pipeline/validity.operating_state) or swings by more than
``SETTLED_SPEED`` peak to peak (not one operating speed), or the two halves of it disagree: the
force maxima by more than ``SETTLED_FORCE`` of the static force or the DTE peak-to-peak values
by more than ``SETTLED_DTE`` of the larger. A periodic response repeats in both halves up to
the sampling of its maximum (0.55 %, above); a transient that has not died out (a lightly
damped shaft mode excited by the speed step) or a beating or chaotic response does not. With
pitch deviations or runout the halves see other tooth combinations (the pattern repeats over
the hunting period, far longer than a level: ISO 1328-1 class 6 on cases/iso_pair.yaml measured
7-207 % differences at every level), so there only the speed rules apply.
A run that left the contact tables (pipeline/validity.table_exit) makes every level it did not
finish invalid with that reason.
"""

from __future__ import annotations

import dataclasses
import json
import math
import sys
from dataclasses import dataclass, field

import numpy as np

from gearcli.pipeline.sweep.design import SPEED_CURVE_METRICS
from gearcli.results import SpeedLevel
from gearcli.results.models import IsoResonance
from gearcli.results.run import SPEED_CURVE_COLUMNS

#: Mesh cycles each speed is held, and over which its speed change is made (smooth STEP).
DWELL_CYCLES = 150
TRANSITION_CYCLES = 10
#: The measured part of each dwell: its last half.
MEASURE_FRACTION = 0.5
#: Output samples per mesh period at the highest speed.
SAMPLES_PER_PERIOD = 30
#: Time to reach the first speed from rest [s] when the base case's ramps are shorter.
MIN_START_S = 0.05

#: Largest difference of the two halves of a level's measurement for a settled level: force
#: maxima [fraction of the static force] and DTE peak-to-peak [fraction of the larger].
SETTLED_FORCE = 0.05
SETTLED_DTE = 0.10
#: Largest peak-to-peak swing of the speed that carries the mesh over a settled level
#: [fraction of its mean]: settled levels measure 0.6-1.5 % (the mesh's own speed ripple with
#: a soft drive shaft, cases/iso_pair.yaml at 2000-3000 Hz), unsettled ones 36-83 %.
SETTLED_SPEED = 0.05
#: Status of a valid level that did not settle (module notes).
UNSETTLED = "unsettled"

DIRECTIONS = ("up", "down")
#: summary.csv's columns (gearcli.results.SpeedLevel's fields).
COLUMNS = SPEED_CURVE_COLUMNS
#: What each level measures (``metrics:`` keeps these columns of summary.csv; ``checks:`` adds
#: a column ``checks`` as in other studies: gearcli/pipeline/sweep/run.py).
METRICS = SPEED_CURVE_METRICS


@dataclass(frozen=True)
class Staircase:
    """The pinion-speed staircase of one direction."""

    f_z_Hz: tuple[float, ...]  #: mesh frequency of each level, in run order
    expression: str  #: drive.speed [deg/s] as a case-file time function
    windows_s: tuple[tuple[float, float], ...]  #: measured part of each level [s]
    end_time_s: float


def staircase(f_z_Hz, pinion_teeth: int, start_s: float) -> Staircase:
    """The staircase through ``f_z_Hz`` (in the given order) after a ramp from rest that ends
    at ``start_s`` [s]."""
    f = [float(x) for x in f_z_Hz]
    deg_s = [x / pinion_teeth * 360.0 for x in f]
    terms = [f"STEP(time,0,0,{start_s:.6g},{deg_s[0]:.7g})"]
    t = start_s
    windows = []
    for i, fz in enumerate(f):
        dwell = DWELL_CYCLES / fz
        windows.append((t + (1.0 - MEASURE_FRACTION) * dwell, t + dwell))
        t += dwell
        if i + 1 < len(f):
            rise = TRANSITION_CYCLES / min(fz, f[i + 1])
            terms.append(f"STEP(time,{t:.7g},0,{t + rise:.7g},{deg_s[i + 1] - deg_s[i]:.7g})")
            t += rise
    return Staircase(tuple(f), "+".join(terms), tuple(windows), t)


def direction_case_json(base_case_json: str, stairs: Staircase, f_max_Hz: float) -> str:
    """The base case (canonical JSON) with the staircase, its end time and the output rate."""
    data = json.loads(base_case_json)
    data["drive"]["speed"] = {"function": stairs.expression, "unit": "deg/s"}
    run = data.setdefault("run", {})
    run["end_time"] = stairs.end_time_s
    run["output_rate"] = SAMPLES_PER_PERIOD * f_max_Hz
    run.pop("output_steps", None)
    return json.dumps(data, sort_keys=True)


def measure_levels(res, stairs: Staircase, direction: str, f_n_Hz: float, first_point: int):
    """One row per level of a finished run (module notes)."""
    from gearcli.core.layout import DRIVE_SPEED, P
    from gearcli.pipeline.validity import check_validity, reference_deflection_for

    k, ki = res.kernel, res.kernel_input
    t = k.column("t_s")
    force, delta = k.column("force_total_N"), k.column("delta_mm")
    omega1, omega2 = k.column("omega1_rad_s"), k.column("omega2_rad_s")
    from gearcli.pipeline.simulate import static_force_at

    j_n = ki.params[P.backlash_n]
    free_pinion = ki.params[P.drive_mode] != DRIVE_SPEED
    residual = res.summary.energy_relative_residual
    z1 = res.geometry.geometry.pinion.teeth
    rows, floor = [], None
    for i, (fz, (t0, t1)) in enumerate(zip(stairs.f_z_Hz, stairs.windows_s, strict=True)):
        w = (t >= t0) & (t <= t1)
        if res.status != "ok" and t1 > t[-1]:  # stopped where it left the tables
            rows.append(SpeedLevel(
                point=first_point + i, direction=direction, mesh_frequency_Hz=fz,
                pinion_speed_rpm=fz / z1 * 60.0, resonance_ratio=fz / f_n_Hz,
                iso_resonance_ratio=math.nan, status="invalid", error=res.invalid_reason))
            continue
        bound = float(max(delta[w].max(), (-delta[w] - j_n).max(), 0.0))
        floor = floor or reference_deflection_for(res, bound)  # once, when it decides
        status, reason = check_validity(reference_deflection_mm=floor,
            penetration_max_mm=bound, static_deflection_mm=ki.mesh.loaded_deflection_mm,
            module_mm=res.geometry.geometry.module_mm, gear_speed_rad_s=omega2[w],
            pinion_speed_rad_s=omega1[w] if free_pinion else None, window_s=t1 - t0,
            teeth=(z1, res.geometry.geometry.gear.teeth), energy_relative_residual=residual)
        f_max = float(force[w].max())
        # each level's own static force: the resisted torque at its gear speed (§7.3)
        f_static = static_force_at(res, float(omega2[w].mean()))
        valid = status == "ok"
        if valid:
            status, reason = settled(t[w], force[w], delta[w],
                                     {"gear speed": omega2[w],
                                      **({"pinion speed": omega1[w]} if free_pinion else {})},
                                     f_static, halves=not _hunting(res.loaded.case))
        rows.append(SpeedLevel(
            point=first_point + i, direction=direction, mesh_frequency_Hz=fz,
            pinion_speed_rpm=fz / z1 * 60.0, resonance_ratio=fz / f_n_Hz,
            iso_resonance_ratio=math.nan,  # set with the ISO data (run_speed_curve)
            dynamic_factor=f_max / f_static if valid and ki.mesh.static_force_N > 0
            else math.nan,
            force_max_N=f_max if valid else math.nan,
            dte_peak_to_peak_mm=float(np.ptp(delta[w])) if valid else math.nan,
            contact_loss_fraction=float(np.mean(force[w] <= 0.0)) if valid else math.nan,
            status=status, error=reason))
    return rows


def settled(t_s, force_N, delta_mm, speeds: dict, f_static_N: float,
            halves: bool = True) -> tuple[str, str]:
    """("ok", "") for a settled level, else (UNSETTLED, why) (module notes); arguments are
    the samples of the level's measured part [s, N, mm, rad/s] and its static force [N];
    ``halves``: compare its two halves (not with pitch deviations or runout, whose halves see
    other tooth combinations)."""
    from gearcli.pipeline.validity import UNSTEADY, operating_state

    state, _, why = operating_state(t_s, speeds, {})
    if state == UNSTEADY:
        text = why.replace("unsteady:", "unsettled:").replace("steady window", "level")
        return UNSETTLED, text.replace(
            "the dynamic factor is not that of one steady operating point",
            "the level has not settled")
    for name, omega in speeds.items():
        swing = float(np.ptp(omega) / abs(np.mean(omega))) if np.mean(omega) else 0.0
        if swing > SETTLED_SPEED:
            return UNSETTLED, (f"unsettled: the {name} swings by {100 * swing:.3g} % peak to "
                               f"peak over the level (settled below {100 * SETTLED_SPEED:g} %): "
                               "not one operating speed")
    half = t_s.size // 2
    if half < 2 or not halves:
        return "ok", ""
    f_a, f_b = float(force_N[:half].max()), float(force_N[half:].max())
    if f_static_N > 0.0 and abs(f_a - f_b) > SETTLED_FORCE * f_static_N:
        return UNSETTLED, (f"unsettled: the force maxima of the two halves of the level differ "
                           f"by {100 * abs(f_a - f_b) / f_static_N:.3g} % of the static force "
                           f"({f_a:.4g} / {f_b:.4g} N; settled below "
                           f"{100 * SETTLED_FORCE:g} %)")
    d_a, d_b = float(np.ptp(delta_mm[:half])), float(np.ptp(delta_mm[half:]))
    if abs(d_a - d_b) > SETTLED_DTE * max(d_a, d_b):
        return UNSETTLED, (f"unsettled: the DTE peak-to-peak of the two halves of the level "
                           f"differ ({1e3 * d_a:.4g} / {1e3 * d_b:.4g} µm; settled within "
                           f"{100 * SETTLED_DTE:g} %)")
    return "ok", ""


@dataclass(frozen=True)
class DirectionTask:
    """One direction of a speed curve as its worker receives it (plain, picklable data)."""

    direction: str  #: "up" or "down" (DIRECTIONS)
    name: str  #: the run's name
    first: int  #: point number of its first level
    case_json: str  #: the direction's resolved case (direction_case_json)
    stairs: Staircase
    pinion_teeth: int  #: z1 (the speed of a level whose simulation failed)


@dataclass(frozen=True)
class DirectionOutcome:
    """What a worker returns for one direction."""

    rows: list[SpeedLevel]  #: a row per level
    f_n_Hz: float  #: the run's mesh natural frequency [Hz] (NaN when it failed)
    error: str = ""  #: the one-line error of a failed simulation ("" when it ran)


def run_direction(task: DirectionTask) -> DirectionOutcome:
    """Simulate one direction and measure its levels (runs in a worker: plain data in and
    out)."""
    from gearcli.errors import GearcliError
    from gearcli.pipeline.simulate import run_simulation
    from gearcli.pipeline.sweep.run import case_from_json

    stairs = task.stairs
    try:
        res = run_simulation(case_from_json(task.case_json, task.name), zoom=False)
    except GearcliError as exc:  # every level of this direction is a failed row, with the reason
        return failed_direction(task, str(exc).splitlines()[0])
    f_n = res.summary.mesh_natural_frequency_Hz
    rows = measure_levels(res, stairs, task.direction, f_n, task.first)
    ref = res.reference_kernel  # loosened tolerances: each level against the defaults'
    if ref is not None:
        from gearcli.pipeline.validity import converged_levels

        rows = converged_levels(res, rows, measure_levels(dataclasses.replace(
            res, kernel=ref, status="ok"), stairs, task.direction, f_n, task.first)
            if ref.ok else None)
    return DirectionOutcome(rows, f_n)


def failed_direction(task: DirectionTask, error: str, cause: str = "") -> DirectionOutcome:
    """Every level of a direction as a failed row (its solver failed, its worker was killed
    or timed out: pipeline/sweep/workers.py; ``cause`` is not recorded for a speed curve)."""
    rows = [SpeedLevel(point=task.first + i, direction=task.direction,
                       mesh_frequency_Hz=fz, pinion_speed_rpm=fz / task.pinion_teeth * 60.0,
                       status="failed", error=error)
            for i, fz in enumerate(task.stairs.f_z_Hz)]
    return DirectionOutcome(rows, math.nan, error)


def plan(study) -> list[DirectionTask]:
    """The two direction tasks of a speed-curve study."""
    from gearcli.case.types import checked_quantity
    from gearcli.units import FREQUENCY

    param = study.parameters[0]
    f_z = sorted(checked_quantity(v, FREQUENCY) for v in param.values)
    base = json.loads(study.base_case_json)
    teeth = int(base["gears"]["pinion"]["teeth"])
    ramps = [_last_breakpoint(base.get("load", {}).get("torque")),
             _last_breakpoint(base.get("drive", {}).get("torque"))]
    start = max(MIN_START_S, *ramps)
    out = []
    for d, order in zip(DIRECTIONS, (f_z, f_z[::-1]), strict=True):
        stairs = staircase(order, teeth, start)
        out.append(DirectionTask(
            direction=d, name=f"{study.name}-{d}", first=0 if d == "up" else len(f_z),
            case_json=direction_case_json(study.base_case_json, stairs, max(f_z)),
            stairs=stairs, pinion_teeth=teeth))
    return out


def _last_breakpoint(node) -> float:
    if node is None:
        return 0.0
    from gearcli.case.expr import parse_time_function

    text = node["function"] if isinstance(node, dict) else str(node)
    try:
        return parse_time_function(text).last_breakpoint
    except Exception:  # a constant with units ("300 N*m"): no ramp
        return 0.0


@dataclass
class SpeedCurve:
    """A finished speed curve: one row per speed and direction, and the case's mesh mode."""

    name: str
    rows: list[SpeedLevel]
    f_n_Hz: float
    errors: list[str]  #: a direction whose simulation failed: its one-line error
    study_file: str = ""
    base_case_json: str = "{}"
    #: ISO 6336-1 Method B data of the base case (mesh_input.iso_dynamic)
    iso: IsoResonance | None = None
    pinion_teeth: int = 0
    notes: list[str] = field(default_factory=list)  #: what limits the reading of the curve
    accuracy: dict | None = None  #: the case's ISO 1328-1 grade and tolerances (accuracy_doc)
    metrics: list[str] | None = None  #: the study's ``metrics:`` (None: all of METRICS)
    checks: list = field(default_factory=list)  #: the study's ``checks:``

    @property
    def columns(self) -> list[str]:
        """summary.csv's columns: the kept metrics, and ``checks`` when the study has any."""
        kept = [c for c in COLUMNS if c not in METRICS or c in (self.metrics or METRICS)]
        if self.checks:
            kept.insert(kept.index("status"), "checks")
        return kept

    def table(self) -> list[dict]:
        """summary.csv's rows ({column: value}) with the checks' verdicts."""
        from gearcli.pipeline.sweep.run import check_verdict

        out = []
        for r in self.rows:
            row = r.to_row()
            if self.checks:
                row["checks"] = check_verdict(self.checks, row)
            out.append({c: row[c] for c in self.columns})
        return out


def run_speed_curve(study, jobs: int | None = None, scheduler: str | None = None,
                    point_timeout: float | None = None) -> SpeedCurve:
    """Run both directions of a ``design: speed_curve`` study (in parallel when jobs allow);
    ``point_timeout`` [s] per direction (pipeline/sweep/workers.py)."""
    from gearcli.pipeline.geometry import run_geometry
    from gearcli.pipeline.mesh_input import iso_dynamic
    from gearcli.pipeline.run_rating import with_level_safeties
    from gearcli.pipeline.sweep.run import case_from_json, execute

    results = list(execute(run_direction, plan(study), jobs, scheduler, failed_direction,
                           point_timeout))
    rows = sorted((r for res in results for r in res.rows), key=lambda r: r.point)
    base = case_from_json(study.base_case_json, study.name)
    geo = run_geometry(base)
    f_n = next((res.f_n_Hz for res in results if not res.error), math.nan)
    if not math.isfinite(f_n):  # both directions failed: the base case's mesh mode
        from gearcli.pipeline.kernel_input import linearised_mesh

        f_n = linearised_mesh(base.case, geo).natural_frequency_Hz
    iso = iso_dynamic(base.case, geo)
    rows = [dataclasses.replace(
        r, iso_resonance_ratio=r.pinion_speed_rpm / iso.resonance_speed_rpm,
        # a failed row: still placed on the axis
        resonance_ratio=r.resonance_ratio if math.isfinite(r.resonance_ratio)
        else r.mesh_frequency_Hz / f_n) for r in rows]
    rows = with_level_safeties(base, rows)  # S_H, S_F at each speed
    return SpeedCurve(study.name, rows, f_n, [res.error for res in results if res.error],
                      str(study.file), study.base_case_json, iso, base.case.gears.pinion.teeth,
                      _notes(base.case), accuracy_doc(base), study.metrics,
                      list(study.checks))


def _hunting(case) -> bool:
    """Whether the case's mesh repeats only over the hunting period (pitch or profile slope
    deviations or runout): the halves of a level then see other tooth combinations
    (:func:`settled`)."""
    e = case.errors
    return any(x is not None for x in (e.pitch_deviation.pinion, e.pitch_deviation.gear,
                                        e.profile_slope_deviation.pinion,
                                        e.profile_slope_deviation.gear,
                                        e.runout.pinion, e.runout.gear))


def _notes(case) -> list[str]:
    """With pitch deviations or runout the mesh force repeats only after the hunting period
    lcm(z1, z2) mesh cycles; a level shorter than that sees other tooth combinations going up
    than going down, so part of an up/down difference is that sampling, not a jump."""
    if not _hunting(case):
        return []
    hunting = math.lcm(case.gears.pinion.teeth, case.gears.gear.teeth)
    measured = MEASURE_FRACTION * DWELL_CYCLES
    if measured >= hunting:
        return []
    return [f"the case has pitch or profile deviations or runout: the pattern repeats every "
            f"{hunting} mesh cycles (hunting period) but each speed measures {measured:g}, so "
            "run-up and "
            "run-down see different tooth combinations and part of their difference is that, "
            "not a nonlinear jump"]


def iso_curve(curve: SpeedCurve, points: int = 400):
    """(N = f_z/f_n [-], K_v [-], ISO ranges) of ISO 6336-1 Method B over the curve's speeds,
    on the figure's axis (the ISO resonance ratio n1/n_E1 mapped through f_z)."""
    n, k_v, n_iso, _ = iso_curves(curve, points)
    return n, k_v, n_iso


def iso_curves(curve: SpeedCurve, points: int = 400):
    """:func:`iso_curve` and K_v without ISO's low-load factor (docs/theory.md §10.5): c′ and
    c_γα unreduced, i.e. divided by L_f = (F_t K_A/b/100)^0.25 < 1 below 100 N/mm, so n_E1
    rises by 1/√L_f and B_p, B_f, B_k change with c′ (equal to the first above 100 N/mm)."""
    from gearcli.model.iso_kv import dynamic_factor
    from gearcli.pipeline.mesh_input import kv_arguments

    iso = curve.iso
    f_z = np.linspace(min(r.mesh_frequency_Hz for r in curve.rows),
                      max(r.mesh_frequency_Hz for r in curve.rows), points)
    n_iso = f_z / curve.pinion_teeth * 60.0 / iso.resonance_speed_rpm
    kv = dynamic_factor(n_iso, **kv_arguments(iso))
    l_f = iso.low_load_factor if iso.low_load_factor > 0.0 else 1.0
    full = kv_arguments(iso) | {"c_prime_N_mm_um": iso.c_prime_N_mm_um / l_f}
    kv_full = dynamic_factor(n_iso * math.sqrt(l_f), **full)
    return f_z / curve.f_n_Hz, kv.k_v, n_iso, kv_full.k_v


def accuracy_doc(base) -> dict | None:
    """The case's ISO 1328-1 grade, seeds and tolerances per gear [µm] (model/accuracy.py),
    for speed_curve.json; None without ``accuracy.grade``."""
    from gearcli.model.accuracy import gear_seeds, tolerances
    from gearcli.pipeline.geometry import run_geometry

    acc = base.case.accuracy
    if acc.grade is None:
        return None
    g = run_geometry(base).geometry
    doc = {"standard": "ISO 1328-1:2013", "grade": acc.grade, "seed": acc.seed}
    for role, seed in zip(("pinion", "gear"), gear_seeds(acc.seed), strict=True):
        tol = tolerances(acc.grade, getattr(g, role).d_mm, g.module_mm)
        doc[role] = {"seed": seed, "tolerances_um": {k: v for k, v in vars(tol).items()
                                                      if k != "grade"},
                     "tolerances_rounded_um": tol.rounded()}
    return doc


def write_speed_curve(curve: SpeedCurve, out, force: bool) -> None:
    """``out``/summary.csv (a row per speed and direction), speed_curve.json and
    speed_curve.png, written atomically (never over an earlier folder without ``force``)."""
    import csv
    import io

    from gearcli.io.files import save_figure, write_atomic
    from gearcli.io.manifest import versions
    from gearcli.io.outdir import atomic_dir
    from gearcli.pipeline.run_rating import write_rating_figure
    from gearcli.plotting.speed_curve import plot_speed_curve

    with atomic_dir(out, force) as tmp:
        buf = io.StringIO()
        writer = csv.DictWriter(buf, fieldnames=curve.columns, lineterminator="\n")
        writer.writeheader()
        for r in curve.table():
            writer.writerow({c: "" if isinstance(v, float) and math.isnan(v) else v
                             for c, v in r.items()})
        write_atomic(tmp / "summary.csv", buf.getvalue())
        doc = {"name": curve.name, "mesh_natural_frequency_Hz": curve.f_n_Hz,
               "dwell_cycles": DWELL_CYCLES, "transition_cycles": TRANSITION_CYCLES,
               "measured_fraction": MEASURE_FRACTION, "samples_per_period": SAMPLES_PER_PERIOD,
               "iso6336_method_b": curve.iso.to_dict() if curve.iso else None,
               "iso_kv_curve": _iso_kv_doc(curve) if curve.iso else None,
               "accuracy": curve.accuracy,
               "errors": curve.errors, "notes": curve.notes}
        doc["rating"] = write_rating_figure(curve, tmp)  # S_H, S_F against speed
        write_atomic(tmp / "speed_curve.json", json.dumps(doc, indent=2) + "\n")
        provenance = {"gearcli_manifest": 1, "kind": "speed_curve", "versions": versions(),
                      "study_file": str(curve.study_file), "command_line": sys.argv,
                      "resolved_case": json.loads(curve.base_case_json)}
        write_atomic(tmp / "manifest.json", json.dumps(provenance, indent=2) + "\n")
        curves = iso_curves(curve) if curve.iso else None
        fig = plot_speed_curve(curve.rows, curve.f_n_Hz, title=curve.name,
                               iso=curves[:3] if curves else None,
                               iso_factors=(curve.iso.B_p, curve.iso.B_f, curve.iso.B_k)
                               if curve.iso else (0.0, 0.0, 1.0),
                               iso_without_low_load=curves[3] if curves else None,
                               grade=curve.accuracy["grade"] if curve.accuracy else None)
        save_figure(fig, tmp / "speed_curve.png", 110)


def _iso_kv_doc(curve: SpeedCurve) -> dict:
    """The figure's ISO lines as data (speed_curve.json ``iso_kv_curve``), 100 points."""
    n, k_v, n_iso, k_v_full = iso_curves(curve, 100)
    return {"resonance_ratio": n.tolist(), "iso_resonance_ratio": n_iso.tolist(),
            "k_v": np.asarray(k_v).tolist(),
            "k_v_without_low_load_factor": np.asarray(k_v_full).tolist(),
            "low_load_factor": curve.iso.low_load_factor}
