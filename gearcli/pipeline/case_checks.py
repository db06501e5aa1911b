"""Checks of a case before it runs (`gearcli simulate`, pipeline/simulate.run_simulation): a run
too large to hold or shorter than a mesh cycle, a load that would drive the gear, a static
deflection beyond the contact model's range; each a one-line error at the key to change."""

from __future__ import annotations

import math

from gearcli.case.load import LoadedCase
from gearcli.pipeline.geometry import GeometryResult
from gearcli.pipeline.kernel_input import HARMONICS_RESOLVED, SAMPLES_PER_PERIOD
from gearcli.pipeline.window import MIN_MESH_CYCLES


def output_rows(case, f_z: float | None) -> tuple[float, str]:
    """Number of output samples of the run and the key that sets it, computed as
    :func:`gearcli.pipeline.kernel_input.output_times` does but without allocating (a float:
    it may be astronomically large). The unit tests check both agree."""
    run = case.run
    if run.output_steps is not None:
        return float(run.output_steps + 1), "output_steps"
    if run.output_rate is not None:
        rate, key = run.output_rate, "output_rate"
    elif f_z is not None and f_z > 0.0:
        rate, key = SAMPLES_PER_PERIOD * HARMONICS_RESOLVED * f_z, "end_time"
    else:
        rate, key = 10_000.0, "end_time"
    return max(math.ceil(run.end_time * rate) if math.isfinite(run.end_time * rate)
               else math.inf, 10) + 1.0, key


def check_run_size(loaded: LoadedCase, geo: GeometryResult) -> None:
    """Refuse a run too large to hold (output samples) or too short to mean anything (less
    than one mesh cycle), with the key to change. Runs shorter than the steady window needs
    are allowed and flagged (see :func:`collect_warnings`)."""
    from gearcli import guards
    from gearcli.case.bounds import solver_steps_error
    from gearcli.core.layout import PARAM_DEFAULTS
    from gearcli.model.frequencies import mesh_frequencies

    case, g = loaded.case, geo.geometry
    speed = geo.pinion_speed_rad_s
    f_z = mesh_frequencies(g.pinion.teeth, speed, g.ratio)[0] if speed else None
    rows, key = output_rows(case, f_z)
    if rows > guards.MAX_OUTPUT_ROWS:
        raise loaded.error_at(("run", key), guards.output_rows_message(
            rows, f"a run of {case.run.end_time:g} s" + (
                f" with {case.run.output_steps:,} output steps" if key == "output_steps" else
                f" sampled at {rows / case.run.end_time:.6g} Hz")))
    max_steps = PARAM_DEFAULTS["max_steps"]
    too_long = solver_steps_error(case, max_steps)  # the step limit, known up front
    if too_long:
        raise loaded.error_at(("run", "end_time"), too_long)
    if case.run.max_step is not None and case.run.end_time / case.run.max_step > max_steps:
        raise loaded.error_at(("run", "max_step"), f"a run of {case.run.end_time:g} s in steps of "
                           f"at most {case.run.max_step:g} s needs "
                           f"{case.run.end_time / case.run.max_step:.3g} steps; the solver "
                           f"stops at {max_steps:.3g}: expected max_step >= "
                           f"{case.run.end_time / max_steps:.3g} s")
    if f_z and f_z > 0.0 and case.run.end_time < 1.0 / f_z:
        raise loaded.error_at(("run", "end_time"), f"{case.run.end_time:g} s is shorter than one "
                           f"mesh cycle ({1.0 / f_z:.4g} s at f_z = {f_z:.5g} Hz); expected at "
                           f"least one mesh cycle (a steady window needs {MIN_MESH_CYCLES}: "
                           f"{MIN_MESH_CYCLES / f_z:.4g} s)")


def check_load(loaded: LoadedCase) -> None:
    """Refuse a load torque that is negative where the run ends: the load would drive the gear
    and the pair run on its coast flanks, while the static force, the dynamic factor and the
    checks are those of the drive flanks (docs/theory.md §7). A load that is negative only on
    the way (a reversal inside a time function, or after the run) runs."""
    case = loaded.case
    torque = float(case.load.torque.pp(case.run.end_time))  # where the run ends
    if torque < 0.0:
        raise loaded.error_at(("load", "torque"), (
            f"the load torque ends at {torque:g} N*mm: a negative load drives the gear, so the "
            "pair would run on its coast flanks, while the dynamic factor and the checks are "
            "those of the drive flanks; expected a resisting torque >= 0 at the end of the "
            "ramps"))


def check_static_deflection(loaded: LoadedCase, geo: GeometryResult,
                            static_deflection_mm: float) -> None:
    """Refuse a case whose static deflection alone is beyond the contact model's range (the
    thickness bound of the validity guard, pipeline/validity.py, docs/theory.md §10.2): every
    run of it would end invalid, and its linearised mesh mode is meaningless. Names the
    contact stiffness when the case gives one, else Young's modulus."""
    from gearcli.pipeline.validity import PENETRATION_PER_THICKNESS, penetration_limit_mm

    limit = penetration_limit_mm(0.0, geo.geometry.module_mm)
    if not static_deflection_mm > limit:
        return
    contact = loaded.case.contact
    loc = (("contact", "stiffness") if contact.law == "impact"
           and contact.stiffness != "derived" else ("material", "youngs_modulus"))
    raise loaded.error_at(loc, (
        f"the static deflection at the case's load is {static_deflection_mm:.4g} mm, beyond "
        f"the contact model's range of {limit:.4g} mm ({100 * PENETRATION_PER_THICKNESS:g} % "
        "of the tooth thickness); expected a stiffer contact or a smaller load.torque"))
