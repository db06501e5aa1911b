"""`gearcli simulate`: case -> compiled kernel -> a checked result with summary and warnings."""

from __future__ import annotations

import contextlib
import gc
import math
import sys
import time
from pathlib import Path

import numpy as np

from gearcli.case.load import LoadedCase, load_case
from gearcli.errors import SolverError
from gearcli.pipeline.case_checks import check_load, check_run_size, check_static_deflection
from gearcli.pipeline.geometry import run_geometry
from gearcli.pipeline.kernel_input import HARMONICS_RESOLVED, build_kernel_input
from gearcli.pipeline.sensors import check_sensors, output_rate_Hz
from gearcli.pipeline.simulation import SimulationResult
from gearcli.pipeline.spectrum import alias_frequency
from gearcli.pipeline.structure import refuse_unsupported
from gearcli.pipeline.window import MIN_MESH_CYCLES, settling_warnings, steady_window
from gearcli.results import EnergyBalance, Summary
from gearcli.results.metrics import json_number


@contextlib.contextmanager
def cyclic_gc_paused():
    """Pause Python's cyclic garbage collector for a block (reference counting goes on).

    Around the kernel call: the first run compiles, and numba creates millions of
    short-lived IR objects that the collector scans again and again (6 of ~30 s of the first
    run's compilation, measured). The compiled kernel creates no Python objects, so nothing
    piles up; collection resumes when the block ends.
    """
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            gc.enable()




def last_ramp_s(case) -> float:
    """When the drive and load time functions reach their final values [s]."""
    return max(case.drive.speed.pp.last_breakpoint if case.drive.speed else 0.0,
               case.drive.torque.pp.last_breakpoint if case.drive.torque else 0.0,
               case.load.torque.pp.last_breakpoint, 0.0)


def stderr_notice(text: str) -> None:
    print(f"gearcli: {text}", file=sys.stderr, flush=True)


def announce_compilation(notice=stderr_notice) -> bool:
    """Tell ``notice`` (one line, default stderr: terminals and pipelines alike) when this run
    will compile the solver; True when it will, False when the solver is cached or the cache
    cannot be inspected (then nothing is announced)."""
    from gearcli.core.integrate import kernel_cached

    if kernel_cached() is not False:
        return False
    if notice is not None:  # a measured estimate (gearcli/pipeline/compile_time.py)
        from gearcli.pipeline.compile_time import notice_text

        notice(notice_text())
    return True


def run_simulation(source: str | Path | LoadedCase, overrides: list[str] | None = None,
                   status=None, progress=None, notice=stderr_notice,
                   zoom: bool = True) -> SimulationResult:
    """Load the case, check its geometry, run the kernel; failed runs raise SolverError.

    ``status`` is an optional callable(str) told what is happening (compiling, integrating);
    ``progress`` an optional callable(t, t_start, t_end) [s] called as the integration
    advances (gearcli.core.integrate.simulate); ``notice`` an optional callable(str) told once,
    before anything is compiled, that this run compiles the solver (default: a line on
    stderr). ``zoom``: also evaluate the dense output for the figures' zooms (:func:`dense_zoom`,
    one more solve of the same run).
    """
    from gearcli.core.integrate import simulate

    loaded = source if isinstance(source, LoadedCase) else load_case(source, overrides)
    case = loaded.case
    refuse_unsupported(loaded)
    geo = run_geometry(loaded)
    check_run_size(loaded, geo)  # before anything is sized by the run
    check_load(loaded)
    ki = build_kernel_input(case, geo)
    check_static_deflection(loaded, geo, ki.mesh.loaded_deflection_mm)
    check_sensors(loaded, output_rate_Hz(ki.t_out))  # before the run, not after
    compiling = announce_compilation(notice)  # a refused run compiles nothing: no notice
    last_ramp = last_ramp_s(case)
    # the natural frequencies of `gearcli modal` (one model): settling time, summary, margins
    from gearcli.pipeline.modal import case_modes

    modes = case_modes(case, geo, ki.mesh, geo.pinion_speed_rad_s)
    window = steady_window(case.run.end_time, last_ramp, ki.mesh.natural_frequency_Hz,
                           ki.mesh.damping_ratio, ki.gear_mesh_frequency_Hz,
                           modes.slowest_decay_rate_1_s())
    from gearcli.core.layout import P

    params = ki.params.copy()
    params[P.extrema_t_start] = window.t0_s
    if status:
        status("compiling the solver (once; see the notice)" if compiling
               else "integrating")
    t0 = time.perf_counter()
    with cyclic_gc_paused():
        kr = simulate(params, ki.tables.tables, t_out=ki.t_out, drive_pp=ki.drive_pp,
                      load_pp=ki.load_pp, drive_angle_pp=ki.drive_angle_pp,
                      progress=progress, **ki.arrays)
    wall = time.perf_counter() - t0
    if compiling:  # what the next notice on this machine estimates from
        from gearcli.pipeline.compile_time import record

        record(wall)
    from gearcli.core.layout import STATUS_RUNAWAY_PENETRATION
    from gearcli.pipeline.validity import cut_at_table_exit

    left_tables = kr.status == STATUS_RUNAWAY_PENETRATION
    if left_tables:  # an invalid run up to where it left the tables (docs/theory.md §10.2)
        kr, window = cut_at_table_exit(kr, window)
    elif not kr.ok:
        t_reached = kr.extremum("t_reached_s")
        raise SolverError(
            f"{loaded.source.file}: the solver failed at t = {t_reached:.6g} s: {kr.message} "
            f"({kr.counters['accepted_steps']} steps); nothing was written. Check the contact "
            "stiffness/damping, the load and the run tolerances"
        )
    result = SimulationResult(loaded, geo, ki, kr, wall, window, modes, compiled=compiling)
    result.summary = summarize(result)
    result.warnings = collect_warnings(result)
    with cyclic_gc_paused():  # a loosened case's second run at the default tolerances
        result.status, result.invalid_reason = validity_of(result, left_tables, status,
                                                           progress)
    if zoom and ki.gear_mesh_frequency_Hz and not left_tables:
        with cyclic_gc_paused():
            result.zoom = dense_zoom(result, params)
    return result


#: Dense output samples per mesh period in the zoom table (>= 100, so that no
#: transient inside a mesh cycle is drawn as a one-sample line).
ZOOM_POINTS_PER_PERIOD = 128
#: Mesh periods on each side of the force maximum, and at the end of the run.
ZOOM_PERIODS_AROUND_MAX = 2.0
ZOOM_PERIODS_AT_END = 4.0
#: Columns of the zoom table (besides the drive slots' forces).
ZOOM_COLUMNS = ("t_s", "force_total_N", "force_coast_N", "pairs_in_contact", "delta_mm",
                "omega1_rad_s", "omega2_rad_s", "load_torque_Nmm")


def dense_zoom(res: SimulationResult, params) -> dict[str, np.ndarray]:
    """The solver's dense output at ZOOM_POINTS_PER_PERIOD points per mesh period over
    ±2 mesh periods around the force maximum and over the last 4 mesh periods of the run.

    The run is integrated once more with the same parameters, tables, chunks and end time and
    only these output times; the steps do not depend on the output times (output comes from
    the continuous extension between steps, docs/theory.md §6.7), so this is the same
    trajectory, sampled finer. Columns as in timeseries.csv (:data:`ZOOM_COLUMNS` and the drive
    slot forces).
    """
    from gearcli.core.integrate import simulate

    ki, k = res.kernel_input, res.kernel
    period = 1.0 / ki.gear_mesh_frequency_Hz
    t_end = res.loaded.case.run.end_time
    t_max = k.extremum("force_total_max_t_s")
    spans = [(t_end - ZOOM_PERIODS_AT_END * period, t_end)]
    if math.isfinite(t_max):
        spans.insert(0, (t_max - ZOOM_PERIODS_AROUND_MAX * period,
                         t_max + ZOOM_PERIODS_AROUND_MAX * period))
    times = np.unique(np.concatenate([
        np.linspace(max(a, 0.0), min(b, t_end),
                    int(round((min(b, t_end) - max(a, 0.0)) / period * ZOOM_POINTS_PER_PERIOD))
                    + 1) for a, b in spans]))
    kr = simulate(params, ki.tables.tables, t_out=times, drive_pp=ki.drive_pp, load_pp=ki.load_pp,
                  drive_angle_pp=ki.drive_angle_pp, **ki.arrays)
    if not kr.ok:
        return {}
    out = {name: kr.column(name) for name in ZOOM_COLUMNS}
    for j in range(kr.slot_force.shape[1]):
        out[f"force_slot{j}_N"] = kr.slot_force[:, j]
    return out


def validity_of(res: SimulationResult, left_tables: bool = False, status=None, progress=None):
    """The run's :class:`gearcli.pipeline.validity.Validity` (docs/theory.md §10.2);
    ``left_tables``: the solver stopped where a penetration left the gap tables; ``status``,
    ``progress`` as for :func:`run_simulation` (told of the run at the default tolerances that
    checks a case with loosened ones)."""
    from gearcli.core.layout import DRIVE_SPEED, P
    from gearcli.pipeline.validity import (
        Validity,
        check_validity,
        loosened,
        loosened_tolerance_hint,
        reference_deflection_for,
        table_exit,
        tolerance_check,
        tolerance_reference,
    )

    k = res.kernel
    if left_tables:
        return table_exit(k.extremum("penetration_max_mm"), k.extremum("t_reached_s"),
                          res.kernel_input.params[P.penetration_limit])
    w = k.column("t_s") >= res.window.t0_s
    free_pinion = res.kernel_input.params[P.drive_mode] != DRIVE_SPEED
    penetration = k.extremum("penetration_max_mm")
    valid = check_validity(
        penetration_max_mm=penetration,
        reference_deflection_mm=reference_deflection_for(res, penetration),
        # without load the guard is the thickness bound alone (validity.py, item 1)
        static_deflection_mm=res.kernel_input.mesh.loaded_deflection_mm,
        module_mm=res.geometry.geometry.module_mm,
        gear_speed_rad_s=k.column("omega2_rad_s")[w],
        pinion_speed_rad_s=k.column("omega1_rad_s")[w] if free_pinion else None,
        window_s=res.window.t1_s - res.window.t0_s,
        teeth=(res.geometry.geometry.pinion.teeth, res.geometry.geometry.gear.teeth),
        energy_relative_residual=res.summary.energy_relative_residual)
    if valid.status != "ok":
        return Validity(valid.status, valid.reason + loosened_tolerance_hint(res))
    if status and loosened(res):
        status("integrating once more at the default tolerances (the case loosens them)")
    res.reference_kernel = tolerance_reference(res, progress)  # None at the defaults
    return tolerance_check(res, res.reference_kernel)


def static_force_at(res: SimulationResult, omega2_rad_s: float) -> float:
    """The dynamic factor's static force [N] of a run at a steady gear speed [rad/s]: the
    contact model's load torque F_s r_b2 with the gear side's speed-dependent terms
    (model.mesh.static_reference_N, docs/theory.md §7.3)."""
    from gearcli.case.build import gear_side_damping
    from gearcli.model.mesh import static_reference_N

    r_b2 = res.geometry.geometry.gear.r_b_mm
    return static_reference_N(res.kernel_input.mesh.static_force_N * r_b2, r_b2, omega2_rad_s,
                              gear_side_damping(res.loaded.case))


def summarize(res: SimulationResult) -> Summary:
    """Key scalars over the steady window (internal units; names carry them)."""
    from gearcli.pipeline.modal import modes_summary

    k, ki, g = res.kernel, res.kernel_input, res.geometry.geometry
    t = k.column("t_s")
    w = t >= res.window.t0_s
    force = k.column("force_total_N")[w]
    delta = k.column("delta_mm")[w]
    omega1 = k.column("omega1_rad_s")[w]
    omega2 = k.column("omega2_rad_s")[w]
    mm = ki.mesh
    mesh_f, mesh_zeta = mesh_mode_of(res)
    state, change, _ = steadiness(res)
    f_static = static_force_at(res, float(omega2.mean()))
    return Summary(
        window_s=(res.window.t0_s, res.window.t1_s),
        window_reason=res.window.reason,
        samples_in_window=int(w.sum()),
        output_rate_Hz=ki.output_rate_Hz,
        # measured over the window, as analysis.json's (the nominal one, from the case's speed
        # or reference_speed, sizes the run: output rate, zoom, settling)
        gear_mesh_frequency_Hz=g.pinion.teeth * abs(float(omega1.mean())) / (2.0 * math.pi),
        pinion_speed_mean_deg_s=math.degrees(float(omega1.mean())),
        gear_speed_mean_deg_s=math.degrees(float(omega2.mean())),
        speed_ratio_mean=(float(omega1.mean()) / float(omega2.mean()) if omega2.mean() != 0.0
                          else math.nan),  # at rest, or stopped before the gear moved
        speed_ratio_theory=g.ratio,
        force_mean_N=float(force.mean()),
        force_rms_N=float(np.sqrt(np.mean(force**2))),
        force_max_N=k.extremum("force_total_max_N"),
        force_max_t_s=k.extremum("force_total_max_t_s"),
        force_min_N=k.extremum("force_total_min_N"),
        force_static_N=f_static,
        dynamic_factor=k.extremum("force_total_max_N") / f_static
        if mm.static_force_N > 0 else None,
        dte_mean_mm=float(delta.mean()),
        dte_peak_to_peak_mm=float(np.ptp(delta)),
        dte_rms_mm=float(np.sqrt(np.mean((delta - delta.mean()) ** 2))),
        pairs_in_contact_mean=float(k.column("pairs_in_contact")[w].mean()),
        contact_loss_fraction=float(np.mean(force <= 0.0)),
        coast_force_max_N=float(np.nanmax(k.column("force_coast_N")[w])),
        mesh_stiffness_N_mm=mm.mesh_stiffness_N_mm,
        single_pair_stiffness_N_mm=json_number(mm.single_pair_stiffness_N_mm),
        double_pair_stiffness_N_mm=json_number(mm.double_pair_stiffness_N_mm),
        static_deflection_mm=mm.static_deflection_mm,
        mesh_natural_frequency_Hz=mesh_f,
        mesh_damping_ratio=mesh_zeta,
        operating_state=state,
        operating_change_fraction=change,
        energy_balance=energy_balance(k),
        modes=modes_summary(res.modes) if res.modes is not None else (),
    )


def steadiness(res: SimulationResult) -> tuple[str, float, str]:
    """The window's operating state (pipeline/validity.operating_state, docs/theory.md
    §10.2): the pinion and gear speeds (a body counts when it turns by more than a tooth pitch
    over the window) and the load torque."""
    from gearcli.pipeline.validity import window_state

    k, g = res.kernel, res.geometry.geometry
    w = k.column("t_s") >= res.window.t0_s
    return window_state(*(k.column(c)[w] for c in ("t_s", "omega1_rad_s", "omega2_rad_s",
                                                     "load_torque_Nmm")),
                        (g.pinion.teeth, g.gear.teeth))


def mesh_mode_of(res: SimulationResult) -> tuple[float, float]:
    """(f_n [Hz], ζ) of the mesh mode: the mode of the full linearised model (the one
    `gearcli modal` reports) with the largest share of its strain energy in the mesh; the
    2-DOF estimate of gearcli.model.mesh when there is no modal result."""
    elastic = [m for m in (res.modes.modes if res.modes is not None else ()) if not m.rigid]
    if not elastic:
        return res.kernel_input.mesh.natural_frequency_Hz, res.kernel_input.mesh.damping_ratio
    mode = max(elastic, key=lambda m: m.strain_energy.get("mesh", 0.0))
    return mode.natural_frequency_Hz, mode.damping_ratio


def energy_balance(k) -> EnergyBalance:
    """ΔE_kin + ΔV (contact, shafts, bearings) against the net work in, over the run
    [N·mm = mJ].

    residual = (ΔE_kin + ΔV) − (W_in − W_load − losses); relative to the largest term.
    """
    col = k.column
    d_kin = col("kinetic_energy_mJ")[-1] - col("kinetic_energy_mJ")[0]
    d_pot = col("contact_energy_mJ")[-1] - col("contact_energy_mJ")[0]
    d_spring = col("spring_energy_mJ")[-1] - col("spring_energy_mJ")[0]
    terms = {
        "work_in_mJ": col("work_in_mJ")[-1],
        "work_load_mJ": col("work_load_mJ")[-1],
        "loss_bearing_mJ": col("loss_bearing_mJ")[-1],
        "loss_damping_mJ": col("loss_damping_mJ")[-1],
        "loss_friction_mJ": col("loss_friction_mJ")[-1],
    }
    net = terms["work_in_mJ"] - terms["work_load_mJ"] - terms["loss_bearing_mJ"] \
        - terms["loss_damping_mJ"] - terms["loss_friction_mJ"]
    residual = d_kin + d_pot + d_spring - net
    scale = max(abs(v) for v in (*terms.values(), d_kin, d_pot, d_spring, 1e-300))
    return EnergyBalance(**{k_: float(v) for k_, v in terms.items()},
                         delta_kinetic_mJ=float(d_kin), delta_contact_mJ=float(d_pot),
                         delta_spring_mJ=float(d_spring), residual_mJ=float(residual),
                         relative_residual=float(abs(residual) / scale))


#: Coast force [fraction of the static force, of 1 kN without load] that a warning counts.
COAST_FORCE_FRACTION = 1e-3


#: Mesh damping ratio below which a warning says the mesh is nearly undamped: a third of the
#: lowest measured (0.03-0.1, docs/theory.md §4c)
UNDERDAMPED_RATIO = 0.01


def collect_warnings(res: SimulationResult) -> list[str]:
    """Warnings the terminal and the summary show (docs/theory.md §4, §7)."""
    from gearcli.pipeline.mesh_input import bore_notes

    s, ki = res.summary, res.kernel_input
    out = bore_notes(res.loaded.case, res.geometry)
    if s.mesh_damping_ratio > 1.0:
        out.append(f"overdamped mesh: damping ratio {s.mesh_damping_ratio:.2f} > 1 "
                   f"(c_max {res.loaded.case.contact.max_damping:g} N*s/mm); measured gear "
                   "meshes have 0.03-0.1")
    elif s.mesh_damping_ratio < UNDERDAMPED_RATIO:
        out.append(f"nearly undamped mesh: damping ratio {s.mesh_damping_ratio:.2g} < "
                   f"{UNDERDAMPED_RATIO:g}; measured gear meshes have 0.03-0.1, so resonant "
                   "amplitudes and impacts are far larger than a real gear's")
    if s.contact_loss_fraction > 0.0:
        out.append(f"contact loss: no drive-flank contact during "
                   f"{100 * s.contact_loss_fraction:.3g} % of the steady window "
                   "(tooth separation)")
    # a coast contact counts from 0.1 % of the static force (1 N without load): zero backlash
    # leaves the coast flanks touching at round-off forces (1.7e-8 N) that are no impact
    if s.coast_force_max_N > COAST_FORCE_FRACTION * max(ki.mesh.static_force_N, 1e3):
        text = (f"coast-flank impacts: coast force up to {s.coast_force_max_N:.4g} N "
                "in the steady window")
        j_n = res.geometry.geometry.j_n_mm
        if j_n <= 1e-9:
            text += ("; the backlash is zero (the default: no thickness allowance, zero-backlash "
                     "centre distance), so pitch errors, runout or vibration close the coast "
                     "flanks: give gears.<gear>.thickness_allowance or gears.centre_distance "
                     "for a real backlash")
        out.append(text)
    f_z, rate = ki.gear_mesh_frequency_Hz, ki.output_rate_Hz
    asked = res.loaded.case.run.output_rate
    # kernel_input.output_times rounds every rate up to whole intervals: only fewer than 10
    # samples is a change worth a warning
    if asked is not None and math.ceil(res.loaded.case.run.end_time * asked) < 10:
        out.append(f"output rate {asked:g} Hz gives fewer than 10 samples in the run: "
                   f"written at {rate:g} Hz instead")
    if f_z:
        harmonics = res.loaded.case.checks.harmonics
        nyquist = rate / 2.0
        if f_z >= nyquist:
            out.append(f"output aliasing: {rate:g} Hz sampling is below 2 x f_z; the "
                       f"{f_z:.2f} Hz mesh line aliases to {alias_frequency(f_z, rate):.2f} Hz")
        elif harmonics * f_z >= nyquist:
            n_ok = int(nyquist // f_z)
            out.append(f"output aliasing: {rate:g} Hz sampling resolves only {n_ok} of the "
                       f"{harmonics} analysed mesh harmonics (default rate resolves "
                       f"{HARMONICS_RESOLVED})")
    ramp_end, end_time = last_ramp_s(res.loaded.case), res.loaded.case.run.end_time
    out += settling_warnings(res.window, ramp_end, end_time)
    unsteady = steadiness(res)[2]
    if unsteady:
        out.append(unsteady)
    if res.window.reason.startswith("the whole run"):
        out.append(f"short run: fewer than {MIN_MESH_CYCLES} mesh cycles; the spectra and "
                   "steady-state values are not meaningful")
    return out

