"""`gearcli modal`: the linearised torsional model of `simulate`, its modes and resonance map.

The model is exactly the one the kernel integrates (core/rhs.py; model.md §6) linearised at the
static load (gearcli.model.mesh, as kernel_input builds it), friction off. Not yet modelled
(issue 5): motor/load inertias and a load shaft, the lateral-torsional option — the kernel
lacks them, and modal must describe the same model as simulate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from gearcli.case.load import LoadedCase, load_case
from gearcli.errors import CaseError
from gearcli.model.mesh import MeshMode, mesh_mode
from gearcli.model.modal import (
    NO_PEAK_DAMPING_RATIO,
    Crossing,
    Margin,
    ModalResult,
    Order,
    TorsionalSystem,
    crossings,
    excitation_orders,
    margins,
    torsional_modes,
)
from gearcli.pipeline.geometry import GeometryResult, run_geometry
from gearcli.pipeline.kernel_input import contact_stiffness, static_force_N

DEG = 180.0 / math.pi
#: Default upper end of the speed range: this multiple of the case speed.
SPEED_RANGE_FACTOR = 1.5


@dataclass
class ModalCheck:
    name: str
    value: float | None
    limit: str
    passed: bool
    note: str = ""


@dataclass
class ModalAnalysis:
    loaded: LoadedCase
    geometry: GeometryResult
    system: TorsionalSystem
    mesh: MeshMode
    result: ModalResult
    orders: tuple[Order, ...]
    crossings: list[Crossing]
    case_speed_deg_s: float | None
    speed_range_deg_s: tuple[float, float]
    margins: list[Margin] = field(default_factory=list)
    checks: list[ModalCheck] = field(default_factory=list)

    @property
    def name(self) -> str:
        return self.loaded.name

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.checks)


def torsional_system(loaded: LoadedCase, geo: GeometryResult, mesh: MeshMode,
                     pinion_speed_rad_s: float | None) -> TorsionalSystem:
    """The case's linearised torsional model (gearcli.model.modal docstring)."""
    case, g = loaded.case, geo.geometry
    dr = case.drive
    c_motor = 0.0
    if dr.type == "torque" and dr.motor_curve is not None:
        # T = T(t) (1 - ω1/ω0): -∂T/∂ω1 = T/ω0 at the final drive torque.
        t_final = dr.torque.pp.final_value()
        t_final = t_final if t_final is not None else float(dr.torque.pp(case.run.end_time))
        c_motor = abs(t_final) / dr.motor_curve.no_load_speed
    omega2 = abs(pinion_speed_rad_s or 0.0) * g.pinion.teeth / g.gear.teeth
    c_load = case.load.viscous + 2.0 * case.load.quadratic * omega2
    return TorsionalSystem(
        J1_t_mm2=geo.mass[0].inertia_t_mm2, J2_t_mm2=geo.mass[1].inertia_t_mm2,
        r_b1_mm=g.pinion.r_b_mm, r_b2_mm=g.gear.r_b_mm,
        mesh_stiffness_N_mm=mesh.mesh_stiffness_N_mm,
        mesh_damping_Ns_mm=mesh.mesh_damping_Ns_mm,
        drive=dr.type,
        shaft_stiffness_Nmm_rad=dr.shaft.stiffness if dr.shaft else 0.0,
        shaft_damping_Nmms_rad=dr.shaft.damping if dr.shaft else 0.0,
        pinion_damping_Nmms_rad=case.bearings.pinion.damping + c_motor,
        gear_damping_Nmms_rad=case.bearings.gear.damping + c_load,
    )


def run_modal(source: str | Path | LoadedCase, overrides: list[str] | None = None,
              speed_range_deg_s: tuple[float, float] | None = None) -> ModalAnalysis:
    """Modes, crossings and the resonance-margin check of a case (see the module docstring)."""
    loaded = source if isinstance(source, LoadedCase) else load_case(source, overrides)
    case = loaded.case
    geo = run_geometry(loaded)
    g = geo.geometry
    ct = case.contact
    mesh = mesh_mode(static_force_N(case, geo), g.eps_alpha, contact_stiffness(case, geo),
                     ct.exponent, ct.max_damping, ct.penetration_depth, g.pinion.r_b_mm,
                     g.gear.r_b_mm, geo.mass[0].inertia_t_mm2, geo.mass[1].inertia_t_mm2,
                     pinion_free=case.drive.type != "speed")
    speed = geo.pinion_speed_rad_s
    system = torsional_system(loaded, geo, mesh, speed)
    result = torsional_modes(system)
    orders = excitation_orders(g.pinion.teeth, g.gear.teeth, case.checks.harmonics)
    cross = crossings(result.modes, orders)
    case_deg_s = abs(speed) * DEG if speed else None
    if speed_range_deg_s is None:
        if case_deg_s:
            top = SPEED_RANGE_FACTOR * case_deg_s
        else:  # no case speed: up to where the first GMF harmonic meets the highest mode
            f_top = max((m.natural_frequency_Hz for m in result.elastic), default=1.0)
            top = SPEED_RANGE_FACTOR * f_top / g.pinion.teeth * 360.0
        speed_range_deg_s = (0.0, top)
    lo, hi = speed_range_deg_s
    if not (0.0 <= lo < hi):
        raise CaseError(f"--speed-range: got {lo:g} {hi:g} deg/s; expected 0 <= A < B")
    out = ModalAnalysis(loaded, geo, system, mesh, result, orders, cross, case_deg_s,
                        (lo, hi))
    if case_deg_s:
        out.margins = margins(result.modes, orders, case_deg_s / 360.0)
    out.checks = [_margin_check(out, case.checks.resonance_margin_percent)]
    return out


def _margin_check(res: ModalAnalysis, limit: float) -> ModalCheck:
    name, lim = "resonance_margin_percent", f">= {limit:g} %"
    if res.case_speed_deg_s is None:
        return ModalCheck(name, None, lim, True, "no case speed (torque drive without "
                          "drive.reference_speed): see the crossing speeds")
    if not res.margins:
        return ModalCheck(name, None, lim, True, "no elastic mode")
    near = res.margins[0]
    note = (f"nearest: {near.order} = {near.excitation_Hz:.1f} Hz vs mode {near.mode} "
            f"{near.mode_Hz:.1f} Hz")
    peaked = [m for m in res.margins if m.has_peak]
    no_peak = sorted({m.mode for m in res.margins if not m.has_peak})
    if no_peak:
        note += (f"; mode(s) {', '.join(map(str, no_peak))} have no resonant peak (damping "
                 f"ratio >= {NO_PEAK_DAMPING_RATIO:.3f}) and are not checked")
    ok = not peaked or peaked[0].margin_percent >= limit
    if peaked and not ok:
        p = peaked[0]
        note += f"; violated by {p.order} vs mode {p.mode} ({p.margin_percent:.1f} %)"
    return ModalCheck(name, near.margin_percent, lim, ok, note)


def modal_document(res: ModalAnalysis) -> dict:
    """JSON-ready report; names carry units."""
    m = res.mesh
    return {
        "case": res.name,
        "model": "torsional",
        "drive": res.system.drive,
        "dofs": list(res.result.dofs),
        "linearisation": {
            "static_force_N": m.static_force_N,
            "static_deflection_mm": m.static_deflection_mm,
            "pair_stiffness_N_mm": m.pair_stiffness_N_mm,
            "mesh_stiffness_N_mm": m.mesh_stiffness_N_mm,
            "single_pair_stiffness_N_mm": m.single_pair_stiffness_N_mm,
            "double_pair_stiffness_N_mm": m.double_pair_stiffness_N_mm,
            "mesh_damping_Ns_mm": m.mesh_damping_Ns_mm,
            "friction": "off",
        },
        "modes": [{
            "mode": md.number,
            "rigid_body": md.rigid,
            "natural_frequency_Hz": md.natural_frequency_Hz,
            "damping_ratio": md.damping_ratio,
            "damped_frequency_Hz": md.damped_frequency_Hz,
            "resonant_peak": md.has_peak,
            "description": md.description,
            "shape": dict(zip(res.result.dofs, md.shape, strict=True)),
            "eigenvalues_1_s": [[r.real, r.imag] for r in md.eigenvalues],
        } for md in res.result.modes],
        "case_speed_deg_s": res.case_speed_deg_s,
        "speed_range_deg_s": list(res.speed_range_deg_s),
        "orders_per_pinion_rev": {o.name: o.per_rev for o in res.orders},
        "crossings": [{"order": c.order, "mode": c.mode, "frequency_Hz": c.frequency_Hz,
                       "pinion_speed_deg_s": c.pinion_speed_rev_s * 360.0,
                       "in_range": res.speed_range_deg_s[0] <= c.pinion_speed_rev_s * 360.0
                       <= res.speed_range_deg_s[1]} for c in res.crossings],
        "margins_at_case_speed": [{"order": x.order, "mode": x.mode,
                                   "excitation_Hz": x.excitation_Hz, "mode_Hz": x.mode_Hz,
                                   "margin_percent": x.margin_percent,
                                   "resonant_peak": x.has_peak} for x in res.margins],
        "checks": [{"name": c.name, "value": c.value, "limit": c.limit, "passed": c.passed,
                    "note": c.note} for c in res.checks],
        "passed": res.passed,
    }


def save_campbell_plot(res: ModalAnalysis, path: str | Path) -> None:
    """Campbell diagram + mode shapes, written atomically (.png, .svg or .pdf)."""
    import io

    from gearcli.io.files import write_atomic
    from gearcli.plotting.campbell import plot_campbell

    fig = plot_campbell(res.result, res.orders, res.speed_range_deg_s, res.case_speed_deg_s,
                        title=f"{res.name}: torsional modes, drive '{res.system.drive}'")
    buf = io.BytesIO()
    fig.savefig(buf, format=Path(path).suffix.lower().lstrip(".") or "png", dpi=150)
    write_atomic(path, buf.getvalue())
