"""The case-file schema (pydantic v2, unknown keys rejected), values in internal units.

Defaults are documented in each field's description (and by ``gearcli schema``). Physics is
in ``docs/theory.md``; section numbers below refer to it.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    Strict,
    field_validator,
    model_serializer,
    model_validator,
)

from gearcli import units
from gearcli.case.types import (
    Angle,
    AngularVelocity,
    Density,
    Frequency,
    Inertia,
    Length,
    LinearDamping,
    LinearStiffness,
    Mass,
    QuadraticDamping,
    SpeedFunction,
    Stress,
    Time,
    TorqueFunction,
    TorsionalDamping,
    TorsionalStiffness,
    Velocity,
    checked_quantity,
    qfield,
    time_field,
)


class FieldError(ValueError):
    """A validation error that names the key it is about, relative to the validated section."""

    def __init__(self, loc: tuple[str, ...], message: str) -> None:
        super().__init__(message)
        self.loc = loc


Teeth = Annotated[int, Strict(), Field(ge=3, description="number of teeth z (integer >= 3)")]
Coefficient = Annotated[float, Field(allow_inf_nan=False)]


class Section(BaseModel):
    """Base of every section: unknown keys are errors, values are immutable."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


# --- §2 geometry -------------------------------------------------------------------------------
class Rack(Section):
    """Basic rack profile (ISO 53 profile A defaults), coefficients of the module."""

    addendum: Coefficient = Field(1.0, gt=0, description="h_aP* (default 1.0)")
    dedendum: Coefficient = Field(1.25, gt=0, description="h_fP* (default 1.25)")
    root_radius: Coefficient = Field(0.38, ge=0, description="rho_fP* (default 0.38)")


class Material(Section):
    """Isotropic gear material (defaults: the seed's steel, Table 1 text)."""

    density: Density = qfield(units.DENSITY, 7.85e-6, "density", gt=0)
    youngs_modulus: Stress = qfield(units.STRESS, 2.07e5, "Young's modulus E", gt=0)
    poisson_ratio: Coefficient = Field(0.29, gt=0, lt=0.5, description="Poisson's ratio (0.29)")
    contact_fatigue_limit: Stress | None = qfield(units.STRESS, None, "sigma_Hlim", gt=0)
    bending_fatigue_limit: Stress | None = qfield(units.STRESS, None, "sigma_Flim", gt=0)


class InertiaSpec(Section):
    """Mass properties: a solid disc (docs/theory.md §2) or given values, plus extra inertia."""

    model: Literal["disc", "given"] = Field("disc", description="'disc' (default) or 'given'")
    diameter: Length | None = qfield(units.LENGTH, None, "disc diameter; default pitch d", gt=0)
    value: Inertia | None = qfield(units.INERTIA, None, "polar inertia J for model 'given'", gt=0)
    mass: Mass | None = qfield(units.MASS, None, "mass for model 'given'", gt=0)
    extra: Inertia = qfield(units.INERTIA, 0.0, "added inertia (shaft, hub)", ge=0)

    @model_validator(mode="after")
    def _given_needs_value(self):
        if self.model == "given" and self.value is None:
            raise FieldError(("value",), "inertia model 'given' needs a polar inertia 'value'")
        if self.model == "disc" and self.value is not None:
            raise FieldError(("value",), "'value' is only used with inertia model 'given'")
        return self


class Gear(Section):
    """One gear of the pair."""

    teeth: Teeth
    profile_shift: Coefficient = Field(0.0, ge=-1.5, le=2.0, description="x (default 0)")
    tip_shortening: Coefficient = Field(0.0, ge=0, le=1, description="k, tip reduced by k m (0)")
    thickness_allowance: Length = qfield(
        units.LENGTH, 0.0, "reduction of the reference tooth thickness (backlash)", ge=0
    )
    tip_rounding: Length = qfield(units.LENGTH, 0.0, "tip rounding radius (0: sharp)", ge=0)
    bore_diameter: Length | None = qfield(
        units.LENGTH, None, "bore (rim inner) diameter for the tooth law's gear-body compliance "
        "(Sainsot et al. 2004); default: a third of the root diameter (a solid gear on a shaft)",
        gt=0)
    face_width: Length | None = qfield(
        units.LENGTH, None, "face width; default gears.face_width", gt=0
    )
    material: Material | None = Field(None, description="default: the case's material")
    inertia: InertiaSpec = Field(default_factory=InertiaSpec, description="mass properties")


class Gears(Section):
    """The gear pair: common data, pinion (driver, body 1) and gear (driven, body 2)."""

    module: Length = qfield(units.LENGTH, ..., "module m", gt=0)
    pressure_angle: Angle = qfield(units.ANGLE, 20.0, "pressure angle alpha", gt=0, lt=math.pi / 4)
    face_width: Length = qfield(units.LENGTH, ..., "face width b", gt=0)
    rack: Rack = Field(default_factory=Rack)
    centre_distance: Length | None = qfield(
        units.LENGTH, None, "operating centre distance a_w; default zero-backlash from x1+x2", gt=0
    )
    pinion: Gear
    gear: Gear


# --- §4 contact, §5 friction ---------------------------------------------------------------------
#: Keys of `contact` that only the IMPACT law reads, and the one only the tooth law reads.
IMPACT_KEYS = ("stiffness", "exponent", "max_damping", "penetration_depth")
TOOTH_KEYS = ("damping_ratio",)


class Contact(Section):
    """Contact law per tooth pair and flank: 'tooth' (pair stiffness from the tooth geometry,
    mesh damping; docs/theory.md §4b, §4c) or Adams 'impact' (§4)."""

    law: Literal["tooth", "impact"] = Field(
        "tooth", description="'tooth' (default: potential-energy tooth compliance, Hertz and "
        "gear body, with mesh damping) or 'impact' (Adams IMPACT, the seed article's law)")
    damping_ratio: Coefficient = Field(
        0.07, ge=0, le=1, description="tooth law: damping ratio zeta of the mesh mode (0.07; "
        "measured gear meshes 0.03-0.1, Kahraman & Singh 1990, Ozguven & Houser 1988)")
    exponent: Coefficient = Field(1.5, ge=1.0, le=3.0, description="force exponent e (1.5)")
    stiffness: float | Literal["derived"] = Field(
        1e5,
        description="k [N/mm^e] (default 1e5 N/mm^1.5), or 'derived' (ISO 6336-1 c' b, e = 1)",
        json_schema_extra={"anyOf": [{"type": "number"}, {"type": "string"}]},
    )
    max_damping: LinearDamping = qfield(units.LINEAR_DAMPING, 100.0, "c_max", ge=0)
    penetration_depth: Length = qfield(units.LENGTH, 0.1, "d_max, full damping depth", gt=0)
    engagement: Literal["extended", "rigid"] = Field(
        "extended", description="'extended' (tooth-geometry gap table, default) or 'rigid'"
    )

    @model_serializer(mode="wrap")
    def _only_the_keys_of_the_law(self, handler):
        """The resolved case (manifests, sweeps) lists only what the chosen law reads, so it
        loads again (see _keys_of_the_law)."""
        data = handler(self)
        for key in IMPACT_KEYS if self.law == "tooth" else TOOTH_KEYS:
            data.pop(key, None)
        return data

    @model_validator(mode="after")
    def _keys_of_the_law(self):
        """A key the chosen law does not read is an error, not silently ignored."""
        other = "impact" if self.law == "tooth" else "tooth"
        for key in IMPACT_KEYS if self.law == "tooth" else TOOTH_KEYS:
            if key in self.model_fields_set:
                raise FieldError((key,), f"applies to law '{other}' only; this case uses law "
                                 f"'{self.law}' (set contact.law: {other} to use it)")
        return self

    @model_validator(mode="before")
    @classmethod
    def _derived_is_linear(cls, data):
        """The ISO 6336-1 stiffness is linear per unit deflection: 'derived' implies e = 1."""
        if isinstance(data, dict) and data.get("stiffness") == "derived":
            exponent = data.get("exponent", 1.0)
            if exponent != 1 and exponent != 1.0:
                raise FieldError(("exponent",), f"got {exponent!r}; the 'derived' (ISO 6336-1) "
                                 "stiffness is linear: use exponent 1 or omit it")
            data = {**data, "exponent": 1.0}
        return data

    @field_validator("stiffness", mode="before")
    @classmethod
    def _stiffness_units(cls, value, info):
        if value == "derived":
            return value
        exponent = info.data.get("exponent", 1.5)
        try:
            k = checked_quantity(value, units.contact_stiffness_dim(exponent))
        except ValueError as exc:  # UnitError is one: say the word the field also takes
            raise ValueError(f"{exc}; or 'derived' (ISO 6336-1)") from None
        if not k > 0.0:
            raise ValueError("expected a contact stiffness > 0 (or 'derived')")
        return k


class Friction(Section):
    """Adams contact friction (docs/theory.md §5); velocities are sliding speeds."""

    enabled: bool = Field(True, description="include friction (default true)")
    static_coefficient: Coefficient = Field(0.08, ge=0, description="mu_s (0.08)")
    dynamic_coefficient: Coefficient = Field(0.05, ge=0, description="mu_d (0.05)")
    stiction_velocity: Velocity = qfield(units.VELOCITY, 0.01, "v_s", gt=0)
    transition_velocity: Velocity = qfield(units.VELOCITY, 0.1, "v_d", gt=0)

    @model_validator(mode="after")
    def _ordered(self):
        if not self.stiction_velocity < self.transition_velocity:
            raise FieldError(
                ("stiction_velocity",), "expected stiction_velocity < transition_velocity"
            )
        return self


# --- §6 drive, load, bearings -------------------------------------------------------------------
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
        need = {"speed": ("speed",), "shaft": ("speed", "shaft"), "torque": ("torque",)}[self.type]
        for key in need:
            if getattr(self, key) is None:
                raise FieldError((key,), f"missing; drive type '{self.type}' needs '{key}'")
        if self.type != "torque" and (self.torque is not None or self.motor_curve is not None):
            key = "torque" if self.torque is not None else "motor_curve"
            raise FieldError((key,), f"only applies to drive type 'torque', not '{self.type}'")
        if self.type == "torque" and self.speed is not None:
            raise FieldError(("speed",), "only applies to drive types 'speed' and 'shaft', not "
                             "'torque' (the pinion's speed follows from the torques; give "
                             "'reference_speed' for the frequencies, and drop 'speed', e.g. "
                             "--set drive.speed=null)")
        if self.type != "torque" and self.reference_speed is not None:
            raise FieldError(("reference_speed",), "only applies to drive type 'torque', not "
                             f"'{self.type}' (a prescribed speed gives the frequencies)")
        if self.type == "speed" and self.shaft is not None:
            raise FieldError(("shaft",), "'shaft' needs drive type 'shaft' (prescribed motor "
                             "speed) or 'torque' (with a motor_inertia); the pinion of type "
                             "'speed' is prescribed")
        if self.type == "torque" and (self.shaft is None) != (self.motor_inertia is None):
            key = "motor_inertia" if self.motor_inertia is None else "shaft"
            raise FieldError((key,), "a torque drive through a shaft needs both 'shaft' and "
                             "'motor_inertia' (the torque acts on the motor inertia)")
        if self.type != "torque" and self.motor_inertia is not None:
            raise FieldError(("motor_inertia",), "only applies to drive type 'torque' with a "
                             f"'shaft', not '{self.type}' (a prescribed motion has no inertia "
                             "effect)")
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
            raise FieldError((key,), "a load shaft and a load inertia go together: give both "
                             "'shaft' and 'inertia' (or neither: the load acts on the gear)")
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


# --- §3 modifications and errors ----------------------------------------------------------------
class Relief(Section):
    """Profile relief on one gear: amount and extent (length along the path, or start diameter)."""

    amount: Length = qfield(units.LENGTH, ..., "relief amount C_a at the tip (or root)", gt=0)
    length: Length | None = qfield(units.LENGTH, None, "relief length along the LoA", gt=0)
    start_diameter: Length | None = qfield(units.LENGTH, None, "diameter where it starts", gt=0)
    shape: Literal["linear", "parabolic"] = Field("linear", description="'linear' or 'parabolic'")

    @model_validator(mode="after")
    def _one_extent(self):
        if (self.length is None) == (self.start_diameter is None):
            raise FieldError(("length",), "give exactly one of 'length' or 'start_diameter'")
        return self


class ReliefPair(Section):
    pinion: Relief | None = None
    gear: Relief | None = None


class Modifications(Section):
    tip_relief: ReliefPair = Field(default_factory=ReliefPair)
    root_relief: ReliefPair = Field(default_factory=ReliefPair)


class Runout(Section):
    eccentricity: Length = qfield(units.LENGTH, ..., "eccentricity e", ge=0)
    phase: Angle = qfield(units.ANGLE, 0.0, "phase of the eccentricity")


class PitchDeviation(Section):
    """Single pitch deviations per tooth: a list, or an ISO 1328-1 grade with a random seed."""

    values: list[Length] | None = Field(None, description="f_pt per tooth [mm], one per tooth")
    iso1328_grade: Annotated[int, Strict()] | None = Field(
        None, ge=1, le=11, description="ISO 1328-1 grade 1..11"
    )
    seed: Annotated[int, Strict()] = Field(0, ge=0, le=2**32 - 1,
                                           description="random seed for the grade (0)")

    @model_validator(mode="after")
    def _one_source(self):
        if (self.values is None) == (self.iso1328_grade is None):
            raise FieldError(("values",), "give exactly one of 'values' or 'iso1328_grade'")
        return self


class RunoutPair(Section):
    pinion: Runout | None = None
    gear: Runout | None = None


class PitchPair(Section):
    pinion: PitchDeviation | None = None
    gear: PitchDeviation | None = None


class Errors(Section):
    runout: RunoutPair = Field(default_factory=RunoutPair)
    pitch_deviation: PitchPair = Field(default_factory=PitchPair)


# --- run, checks --------------------------------------------------------------------------------
class Run(Section):
    """Simulation length, output sampling and solver tolerances."""

    end_time: Time = qfield(units.TIME, ..., "simulated time", gt=0)
    output_steps: Annotated[int, Strict()] | None = Field(
        None,
        ge=10,
        description="number of output intervals (Adams STEPS); default: enough for "
        "checks.harmonics harmonics of the mesh frequency",
    )
    output_rate: Frequency | None = qfield(units.FREQUENCY, None, "output sample rate", gt=0)
    # below 100 machine epsilons a relative tolerance cannot be met in double precision (the
    # floor scipy's solve_ivp raises rtol to)
    rtol: Coefficient = Field(1e-6, ge=2.3e-14, lt=1e-2,
                              description="relative tolerance (1e-6), 2.3e-14 <= rtol < 1e-2")
    atol: Length | None = qfield(
        units.LENGTH, None, "absolute tolerance on deflections; default: 1e-5 of the static "
        "deflection, at most 1e-6 mm (docs/theory.md §6.7)", gt=0)
    max_step: Time | None = qfield(units.TIME, None, "largest solver step", gt=0)

    @model_validator(mode="after")
    def _one_rate(self):
        if self.output_steps is not None and self.output_rate is not None:
            raise FieldError(
                ("output_rate",), "give at most one of 'output_steps' and 'output_rate'"
            )
        return self


class Checks(Section):
    """Limits for analyze/modal checks (documented defaults)."""

    harmonics: Annotated[int, Strict()] = Field(5, ge=1, le=50, description="GMF harmonics (5)")
    speed_ratio_error_percent: Coefficient = Field(0.1, gt=0, description="limit (0.1 %)")
    resonance_margin_percent: Coefficient = Field(10.0, ge=0, description="limit (10 %)")
    dynamic_factor_max: Coefficient = Field(
        2.0, gt=0, description="limit of the dynamic factor max F / F_static (2.0: gearcli's "
        "default, not a standard's; set your design's value)")
    contact_loss_fraction_max: Coefficient = Field(
        0.0, ge=0, le=1, description="limit of the share of the steady window without "
        "drive-flank contact (0: any tooth separation fails)")
    dte_peak_to_peak_max: Length | None = qfield(units.LENGTH, None, "optional DTE limit", gt=0)
    energy_balance_tolerance: Coefficient = Field(0.01, gt=0, description="relative (0.01)")


class Case(Section):
    """A gearcli case: one spur gear pair, its contact, drive, load and run settings."""

    name: str | None = Field(None, description="case name (default: file stem)")
    description: str = Field("", description="free text")
    model: Literal["torsional", "lateral-torsional"] = Field(
        "torsional",
        description="'torsional' (default: gears rotate about fixed centres) or "
        "'lateral-torsional' (each gear also moves in x and y on its bearings)",
    )
    gears: Gears
    material: Material = Field(default_factory=Material)
    contact: Contact = Field(default_factory=Contact)
    friction: Friction = Field(default_factory=Friction)
    drive: Drive
    load: Load = Field(default_factory=Load)
    bearings: Bearings = Field(default_factory=Bearings)
    modifications: Modifications = Field(default_factory=Modifications)
    errors: Errors = Field(default_factory=Errors)
    run: Run
    checks: Checks = Field(default_factory=Checks)

    @model_validator(mode="after")
    def _cross_checks(self):
        for name in ("pinion", "gear"):
            b = getattr(self.bearings, name)
            if self.model == "lateral-torsional":
                for key in ("stiffness_x", "stiffness_y"):
                    if getattr(b, key) is None:
                        raise FieldError(("bearings", name, key),
                                         "missing; model 'lateral-torsional' needs the lateral "
                                         "bearing stiffness of both gears in x and y")
            elif b.lateral:
                key = next(k for k in ("stiffness_x", "stiffness_y", "damping_x", "damping_y")
                           if getattr(b, k) not in (None, 0.0))
                raise FieldError(("bearings", name, key),
                                 "only used with 'model: lateral-torsional' (the model is "
                                 "'torsional': gear centres are fixed)")
        if self.load.applied_to == "pinion" and self.drive.type == "speed":
            raise FieldError(
                ("load", "applied_to"),
                "a load on the pinion with drive type 'speed' is refused: a torque on a "
                "motion-driven body never reaches the mesh (docs/theory.md §9); apply it to the "
                "gear",
            )
        for name in ("pinion", "gear"):
            dev = getattr(self.errors.pitch_deviation, name)
            teeth = getattr(self.gears, name).teeth
            if dev is not None and dev.values is not None and len(dev.values) != teeth:
                raise FieldError(
                    ("errors", "pitch_deviation", name, "values"),
                    f"{len(dev.values)} entries; expected one per tooth ({teeth})",
                )
        return self
