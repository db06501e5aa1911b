"""`gearcli modal`: the linearised model of `simulate`, its modes and resonance map.

The model is the one the kernel integrates: bodies, shafts and supports from
gearcli.pipeline.structure.build_structure (the same Structure core/rhs.py gets), the mesh
linearised at the static load (gearcli.pipeline.kernel_input.linearised_mesh, the one simulate
uses), friction off; torsional or lateral-torsional (case key ``model``). See gearcli.model.modal.
:func:`case_modes` and :func:`modes_summary` give `simulate` the same modes for its summary.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from gearcli.case.load import LoadedCase, load_case
from gearcli.case.schema import Case
from gearcli.errors import CaseError
from gearcli.model.mesh import MeshMode
from gearcli.model.modal import (
    NO_PEAK_DAMPING_RATIO,
    Crossing,
    LinearSystem,
    Margin,
    ModalResult,
    Order,
    crossings,
    excitation_orders,
    linear_modes,
    linearised_dampers,
    margins,
)
from gearcli.pipeline.geometry import GeometryResult, run_geometry
from gearcli.pipeline.kernel_input import linearised_mesh
from gearcli.pipeline.structure import build_structure, refuse_unsupported
from gearcli.results import Check, ModalDocument, Mode, StoredMode
from gearcli.results.metrics import json_number
from gearcli.results.models import Crossing as CrossingDoc
from gearcli.results.models import Linearisation, OrderMargin

DEG = 180.0 / math.pi
#: Default upper end of the speed range: this multiple of the case speed.
SPEED_RANGE_FACTOR = 1.5

#: Largest speed of a Campbell diagram [deg/s] (1e5 rad/s, the case files' limit).
MAX_SPEED_DEG_S = 1e5 * 180.0 / math.pi


@dataclass(repr=False)
class ModalAnalysis:
    """Modes of the linearised model, crossings and the resonance-margin check (`gearcli
    modal`, :func:`gearcli.modal`); ``modes`` the typed modes of :meth:`document`."""

    loaded: LoadedCase
    geometry: GeometryResult
    system: LinearSystem
    mesh: MeshMode
    result: ModalResult
    orders: tuple[Order, ...]
    crossings: list[Crossing]
    case_speed_deg_s: float | None
    speed_range_deg_s: tuple[float, float]
    margins: list[Margin] = field(default_factory=list)
    checks: list[Check] = field(default_factory=list)

    @property
    def name(self) -> str:
        return self.loaded.name

    @property
    def notes(self) -> list[str]:
        """What the linearised model leaves out for this case (pipeline/capabilities.py)."""
        from gearcli.pipeline.capabilities import not_included

        return not_included("modal", self.loaded.case)

    @property
    def passed(self) -> bool:
        return not any(c.failed for c in self.checks)

    @property
    def modes(self) -> list[Mode]:
        return list(modal_document(self).modes)

    def document(self) -> dict:
        """What `gearcli modal --json` prints (the JSON data of :func:`modal_document`)."""
        return modal_document(self).to_dict()

    def plot(self, units: str = "engineering"):
        """The Campbell diagram and mode shapes (a ``matplotlib.figure.Figure``); the speed
        axis in the display ``units`` ("engineering": rpm, "si": rad/s)."""
        return campbell_figure(self, units)

    def __repr__(self) -> str:
        f = [round(m.natural_frequency_Hz, 1) for m in self.result.modes if not m.rigid
             and m.natural_frequency_Hz]
        return f"<Modal {self.name}: modes at {f} Hz>"


def _final_drive_torque_Nmm(case: Case) -> float:
    """The drive torque at the end of its ramps (torque drive), else 0 [N·mm]."""
    dr = case.drive
    if dr.type != "torque" or dr.torque is None:
        return 0.0
    final = dr.torque.pp.final_value()
    return final if final is not None else float(dr.torque.pp(case.run.end_time))


def linear_system(case: Case, geo: GeometryResult, mesh: MeshMode,
                  pinion_speed_rad_s: float | None) -> LinearSystem:
    """The case's linearised model (gearcli.model.modal docstring): the Structure of
    build_structure, the mesh k_mesh, c_mesh, and the motor curve and quadratic load term
    linearised at the final drive torque and the pinion speed [rad/s] (None: 0)."""
    structure = build_structure(case, geo)
    c_motor, c_quad = linearised_dampers(structure, _final_drive_torque_Nmm(case),
                                         pinion_speed_rad_s)
    return LinearSystem(structure, mesh.mesh_stiffness_N_mm, mesh.mesh_damping_Ns_mm,
                        motor_curve_damping_Nmms_rad=c_motor,
                        load_quadratic_damping_Nmms_rad=c_quad)


def case_modes(case: Case, geo: GeometryResult, mesh: MeshMode,
               pinion_speed_rad_s: float | None) -> ModalResult:
    """Modes of the case's linearised model (for `simulate`'s summary: see modes_summary).

    A model the schema let through but that cannot be solved raises CaseError (exit 1).
    """
    return _solve(linear_system(case, geo, mesh, pinion_speed_rad_s))


def _solve(system: LinearSystem, file: str | None = None) -> ModalResult:
    try:
        return linear_modes(system)
    except ValueError as err:  # the schema admits only physical values: a bug or a new field
        raise CaseError(f"modal model: {err}", file=file) from err


def modes_summary(result: ModalResult) -> tuple[StoredMode, ...]:
    """The modes as summary.json keeps them (frequency and damping ratio None for rigid-body
    modes)."""
    return tuple(StoredMode(mode=m.number, natural_frequency_Hz=m.natural_frequency_Hz,
                            damping_ratio=m.damping_ratio, description=m.description,
                            rigid_body=m.rigid) for m in result.modes)


def run_modal(source: str | Path | LoadedCase, overrides: list[str] | None = None,
              speed_range_deg_s: tuple[float, float] | None = None) -> ModalAnalysis:
    """Modes, crossings and the resonance-margin check of a case (see the module docstring)."""
    loaded = source if isinstance(source, LoadedCase) else load_case(source, overrides)
    case = loaded.case
    refuse_unsupported(loaded)
    geo = run_geometry(loaded)
    g = geo.geometry
    mesh = linearised_mesh(case, geo)
    speed = geo.pinion_speed_rad_s
    system = linear_system(case, geo, mesh, speed)
    result = _solve(system, loaded.source.file)
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
    if not (0.0 <= lo < hi <= MAX_SPEED_DEG_S):
        raise CaseError(f"--speed-range: got {lo:g} {hi:g} deg/s; expected 0 <= A < B <= "
                        f"{MAX_SPEED_DEG_S:g} deg/s ({MAX_SPEED_DEG_S / 6.0:g} rpm)")
    out = ModalAnalysis(loaded, geo, system, mesh, result, orders, cross, case_deg_s,
                        (lo, hi))
    if case_deg_s:
        out.margins = margins(result.modes, orders, case_deg_s / 360.0)
    out.checks = [_margin_check(out, case.checks.resonance_margin_percent)]
    return out


def _margin_check(res: ModalAnalysis, limit: float) -> Check:
    name, lim = "resonance_margin_percent", f">= {limit:g} %"
    if res.case_speed_deg_s is None:
        speed = res.loaded.case.drive.speed
        why = ("a torque drive without drive.reference_speed" if res.system.drive == "torque"
               else "drive.speed has no constant final value" if speed.pp.final_value() is None
               else "the pinion does not turn")
        return Check(name, None, lim, True, f"not checked: no case speed ({why}); see the "
                          "crossing speeds", checked=False)
    if not res.margins:
        return Check(name, None, lim, True, "not checked: no elastic mode", checked=False)
    near = res.margins[0]
    note = (f"nearest: {near.order} = {near.excitation_Hz:.1f} Hz vs mode {near.mode} "
            f"{near.mode_Hz:.1f} Hz")
    peaked = [m for m in res.margins if m.has_peak]
    no_peak = sorted({m.mode for m in res.margins if not m.has_peak})
    if no_peak:
        note += (f"; mode(s) {', '.join(map(str, no_peak))} have no resonant peak (damping "
                 f"ratio >= {NO_PEAK_DAMPING_RATIO:.3f}) and are not checked")
    if not peaked:
        return Check(name, near.margin_percent, lim, True, "not checked: no mode has a "
                          "resonant peak; " + note, checked=False)
    ok = peaked[0].margin_percent >= limit
    remedy = None
    if peaked and not ok:
        p = peaked[0]
        note += f"; violated by {p.order} vs mode {p.mode} ({p.margin_percent:.1f} %)"
        from gearcli.pipeline.speed_bands import avoid_bands, band_remedy

        rev_s = res.case_speed_deg_s / 360.0  # per_rev: excitations per pinion revolution
        remedy = band_remedy(avoid_bands(
            ((m.excitation_Hz / rev_s, m.mode_Hz, f"{m.order} near mode {m.mode} at "
              f"{m.mode_Hz:.1f} Hz") for m in peaked if m.margin_percent < limit), limit),
            limit)
    return Check(name, near.margin_percent, lim, ok, note, remedy=remedy)


def modal_document(res: ModalAnalysis) -> ModalDocument:
    """The modal JSON (``.to_dict()``); names carry units."""
    from gearcli.io.manifest import RESULTS_SCHEMA_VERSION

    m, st = res.mesh, res.system.structure
    return ModalDocument(
        schema_version=RESULTS_SCHEMA_VERSION,
        case=res.name,
        model=res.loaded.case.model,
        drive=res.system.drive,
        dofs=list(res.result.dofs),
        shape_convention="each coordinate as a length: rotations as the roll distance r_b theta "
                         "at the body's base circle (motor, pinion r_b1; gear, load r_b2), "
                         "centre displacements in mm; largest component = 1",
        bodies={
            "motor_inertia_t_mm2": st.motor_inertia_t_mm2 or None,
            "pinion_inertia_t_mm2": st.J1_t_mm2,
            "gear_inertia_t_mm2": st.J2_t_mm2,
            "load_inertia_t_mm2": st.load_inertia_t_mm2 or None,
            "pinion_mass_t": st.m1_t if st.lateral else None,
            "gear_mass_t": st.m2_t if st.lateral else None,
        },
        linearisation=Linearisation(
            static_force_N=m.static_force_N,
            static_deflection_mm=m.static_deflection_mm,
            pair_stiffness_N_mm=m.pair_stiffness_N_mm,
            mesh_stiffness_N_mm=m.mesh_stiffness_N_mm,
            single_pair_stiffness_N_mm=json_number(m.single_pair_stiffness_N_mm),
            double_pair_stiffness_N_mm=json_number(m.double_pair_stiffness_N_mm),
            mesh_damping_Ns_mm=m.mesh_damping_Ns_mm,
            motor_curve_damping_Nmms_rad=res.system.motor_curve_damping_Nmms_rad,
            load_quadratic_damping_Nmms_rad=res.system.load_quadratic_damping_Nmms_rad,
            friction="off",
        ),
        modes=tuple(Mode(
            mode=md.number, rigid_body=md.rigid, natural_frequency_Hz=md.natural_frequency_Hz,
            damping_ratio=md.damping_ratio, damped_frequency_Hz=md.damped_frequency_Hz,
            undamped_frequency_Hz=md.undamped_frequency_Hz, resonant_peak=md.has_peak,
            description=md.description, shape=dict(zip(res.result.dofs, md.shape, strict=True)),
            strain_energy_share=md.strain_energy, kinetic_energy_share=md.kinetic_energy,
            eigenvalues_1_s=tuple([r.real, r.imag] for r in md.eigenvalues))
            for md in res.result.modes),
        case_speed_deg_s=res.case_speed_deg_s,
        speed_range_deg_s=list(res.speed_range_deg_s),
        orders_per_pinion_rev={o.name: o.per_rev for o in res.orders},
        crossings=tuple(CrossingDoc(c.order, c.mode, c.frequency_Hz,
                                    c.pinion_speed_rev_s * 360.0,
                                    res.speed_range_deg_s[0] <= c.pinion_speed_rev_s * 360.0
                                    <= res.speed_range_deg_s[1]) for c in res.crossings),
        margins_at_case_speed=tuple(OrderMargin(x.order, x.mode, x.excitation_Hz, x.mode_Hz,
                                                x.margin_percent, x.has_peak)
                                    for x in res.margins),
        checks=[c.to_dict() for c in res.checks],  # the remedy only where there is one
        passed=res.passed,
    )


def campbell_figure(res: ModalAnalysis, units: str = "engineering"):
    """Campbell diagram + mode shapes (a matplotlib Figure); shaft speeds in ``units``."""
    from gearcli.plotting.campbell import plot_campbell

    return plot_campbell(res.result, res.orders, res.speed_range_deg_s, res.case_speed_deg_s,
                         title=f"{res.name}: {res.loaded.case.model} model, drive "
                               f"'{res.system.drive}'", units=units)


def save_campbell_plot(res: ModalAnalysis, path: str | Path, units: str = "engineering") -> None:
    """Campbell diagram + mode shapes, written atomically (.png, .svg or .pdf)."""
    from gearcli.io.files import save_figure

    save_figure(campbell_figure(res, units), path, 150)
