"""Turn a validated :class:`~gearcli.case.schema.Case` into the model's plain inputs."""

from __future__ import annotations

from dataclasses import dataclass

from gearcli.case.schema import Case, Gear
from gearcli.model.geometry import GearSpec, PairSpec, RackSpec


def pair_spec(case: Case) -> PairSpec:
    """Geometry input (internal units) of the case's gear pair."""
    g = case.gears

    def gear(spec: Gear) -> GearSpec:
        return GearSpec(
            teeth=spec.teeth,
            face_width_mm=spec.face_width if spec.face_width is not None else g.face_width,
            profile_shift=spec.profile_shift,
            tip_shortening_coef=spec.tip_shortening,
            thickness_allowance_mm=spec.thickness_allowance,
            tip_rounding_mm=spec.tip_rounding,
        )

    return PairSpec(
        module_mm=g.module,
        pressure_angle_rad=g.pressure_angle,
        pinion=gear(g.pinion),
        gear=gear(g.gear),
        rack=RackSpec(g.rack.addendum, g.rack.dedendum, g.rack.root_radius),
        centre_distance_mm=g.centre_distance,
    )


@dataclass(frozen=True)
class MassInput:
    """How to get one gear's mass properties (internal units: t, mm)."""

    model: str  # "disc" or "given"
    density_t_mm3: float
    diameter_mm: float | None  # disc diameter; None = pitch diameter
    inertia_t_mm2: float | None  # given polar inertia
    mass_t: float | None  # given mass
    extra_inertia_t_mm2: float
    bore_diameter_mm: float | None = None  # the gear's given bore (None: solid body)


def mass_inputs(case: Case) -> tuple[MassInput, MassInput]:
    """Mass-property inputs of (pinion, gear); the gear's own material overrides the case's.
    The body is the one the tooth law's gear-body compliance sees: a given ``bore_diameter``
    is taken out of the disc (docs/theory.md §2.6)."""

    def one(spec: Gear) -> MassInput:
        material = spec.material or case.material
        i = spec.inertia
        return MassInput(i.model, material.density, i.diameter, i.value, i.mass, i.extra,
                         spec.bore_diameter)

    return one(case.gears.pinion), one(case.gears.gear)


def nominal_pinion_speed(case: Case) -> float | None:
    """Steady pinion speed [rad/s] for reporting frequencies, or None when unknown.

    Speed drives: the final value of the speed function (after every ramp). Torque drives:
    ``drive.reference_speed`` when given.
    """
    d = case.drive
    if d.reference_speed is not None:
        return d.reference_speed
    if d.speed is not None:
        return d.speed.pp.final_value()
    return None


def gear_side_damping(case: Case) -> tuple[float, float]:
    """(c_v + c_2 [N*mm*s/rad], c_q [N*mm*s²/rad²]): the speed-dependent torques the gear's
    side resists (the load's viscous and quadratic terms and the gear bearing's damping;
    docs/theory.md §6.3, §7.3)."""
    return case.load.viscous + case.bearings.gear.damping, case.load.quadratic
