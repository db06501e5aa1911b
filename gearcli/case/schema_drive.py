"""Case schema, drive, load and bearings (docs/theory.md §6). Values in internal units (see
:mod:`gearcli.case.types`)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from gearcli import units
from gearcli.case.section import FieldError, Section, raise_all
from gearcli.case.types import (
    AngularVelocity,
    Inertia,
    LinearDamping,
    LinearStiffness,
    QuadraticDamping,
    SpeedFunction,
    TorqueFunction,
    TorsionalDamping,
    TorsionalStiffness,
    qfield,
    time_field,
)


class Shaft(Section):
    """A torsional shaft: the drive shaft (motor to pinion) or the load shaft (gear to load)."""

    stiffness: TorsionalStiffness = qfield(units.TORSIONAL_STIFFNESS, ..., "shaft stiffness", gt=0)
    damping: TorsionalDamping = qfield(units.TORSIONAL_DAMPING, 0.0, "shaft damping", ge=0)


class MotorCurve(Section):
    """Linear motor curve: T = torque(t) (1 - omega1 / no_load_speed)."""

    no_load_speed: AngularVelocity = qfield(units.ANGULAR_VELOCITY, ..., "no-load speed", gt=0)


class Drive(Section):
    """How the pinion is driven (docs/theory.md §6)."""

    type: Literal["speed", "shaft", "torque"] = Field(
        "speed",
        description="'speed' (prescribed pinion speed, Adams MOTION; default), "
        "'shaft' (prescribed speed through a drive shaft), 'torque' (prescribed torque)",
    )
    speed: SpeedFunction | None = time_field(units.ANGULAR_VELOCITY, "pinion/motor speed", None)
    torque: TorqueFunction | None = time_field(units.TORQUE, "drive torque (type torque)", None)
    shaft: Shaft | None = None
    motor_curve: MotorCurve | None = None
    motor_inertia: Inertia | None = qfield(
        units.INERTIA, None, "motor rotor inertia J_m; with type 'torque' and a 'shaft' the "
        "torque drives it and the shaft connects it to the pinion", gt=0)
    initial_speed: AngularVelocity = qfield(units.ANGULAR_VELOCITY, 0.0, "initial pinion speed")
    reference_speed: AngularVelocity | None = qfield(
        units.ANGULAR_VELOCITY, None, "pinion speed for frequencies with a torque drive", gt=0
    )

    @model_validator(mode="after")
    def _consistent(self):
        """Each key belongs to the drive types that read it: a key another type needs is
        missing, a key this type does not read is an error (every one is reported)."""
        t = self.type
        need = {"speed": ("speed",), "shaft": ("speed", "shaft"), "torque": ("torque",)}[t]
        found = [FieldError((key,), "missing", f"'{key}' with drive type '{t}'")
                 for key in need if getattr(self, key) is None]
        if t != "torque":
            found += [FieldError((key,), f"only applies to drive type 'torque', not '{t}'",
                                 f"no '{key}' here, or drive.type: torque")
                      for key in ("torque", "motor_curve") if getattr(self, key) is not None]
        if t == "torque" and self.speed is not None:
            found.append(FieldError(("speed",), "only applies to drive types 'speed' and "
                                    "'shaft', not 'torque' (the pinion's speed follows from "
                                    "the torques)", "no 'speed' here ('reference_speed' gives "
                                    "the frequencies; e.g. --set drive.speed=null)"))
        if t != "torque" and self.reference_speed is not None:
            found.append(FieldError(("reference_speed",), f"only applies to drive type "
                                    f"'torque', not '{t}' (a prescribed speed gives the "
                                    "frequencies)", "no 'reference_speed' here"))
        if t == "speed" and self.shaft is not None:
            found.append(FieldError(("shaft",), "drive type 'speed' prescribes the pinion "
                                    "itself", "drive.type: shaft (a prescribed motor speed) or "
                                    "torque (with a motor_inertia) for a drive shaft"))
        if t == "torque" and (self.shaft is None) != (self.motor_inertia is None):
            key = "motor_inertia" if self.motor_inertia is None else "shaft"
            found.append(FieldError((key,), "missing; a torque drive through a shaft acts on "
                                    "the motor inertia", "both 'shaft' and 'motor_inertia', "
                                    "or neither"))
        if t != "torque" and self.motor_inertia is not None:
            found.append(FieldError(("motor_inertia",), "only applies to drive type 'torque' "
                                    f"with a 'shaft', not '{t}' (a prescribed motion has no "
                                    "inertia effect)",
                                    "no 'motor_inertia' here"))
        raise_all(found)
        return self


class Load(Section):
    """Load torque opposing rotation plus speed-dependent terms (docs/theory.md §6)."""

    applied_to: Literal["gear", "pinion"] = Field("gear", description="body loaded ('gear')")
    torque: TorqueFunction = time_field(units.TORQUE, "load torque", 0.0)
    viscous: TorsionalDamping = qfield(units.TORSIONAL_DAMPING, 0.0, "viscous coefficient", ge=0)
    quadratic: QuadraticDamping = qfield(units.QUADRATIC_DAMPING, 0.0, "quadratic coeff.", ge=0)
    shaft: Shaft | None = Field(None, description="load shaft from the gear to the load inertia")
    inertia: Inertia | None = qfield(
        units.INERTIA, None, "load inertia J_L at the end of the load shaft; the load torque "
        "and the viscous/quadratic terms then act on it", gt=0)

    @model_validator(mode="after")
    def _shaft_and_inertia(self):
        if (self.shaft is None) != (self.inertia is None):
            key = "inertia" if self.inertia is None else "shaft"
            raise FieldError((key,), "missing; a load shaft and a load inertia go together",
                             "both 'shaft' and 'inertia', or neither (the load acts on the "
                             "gear)")
        return self


class Bearing(Section):
    """Bearing of one gear; torsional viscous damping to ground."""

    damping: TorsionalDamping = qfield(units.TORSIONAL_DAMPING, 0.0, "bearing damping c", ge=0)
    # Lateral support (model 'lateral-torsional'): x along the line of centres from the pinion
    # to the gear, y perpendicular, in the direction the pinion's pitch point moves.
    stiffness_x: LinearStiffness | None = qfield(
        units.LINEAR_STIFFNESS, None, "bearing stiffness along the line of centres", gt=0)
    stiffness_y: LinearStiffness | None = qfield(
        units.LINEAR_STIFFNESS, None, "bearing stiffness across the line of centres", gt=0)
    damping_x: LinearDamping = qfield(units.LINEAR_DAMPING, 0.0, "bearing damping along x", ge=0)
    damping_y: LinearDamping = qfield(units.LINEAR_DAMPING, 0.0, "bearing damping along y", ge=0)

    @property
    def lateral(self) -> bool:
        """True when any lateral bearing value is given."""
        return (self.stiffness_x is not None or self.stiffness_y is not None
                or self.damping_x != 0.0 or self.damping_y != 0.0)


class Bearings(Section):
    pinion: Bearing = Field(default_factory=Bearing)
    gear: Bearing = Field(default_factory=Bearing)


