"""The case-file schema (pydantic v2, unknown keys rejected), values in internal units.

Defaults are documented in each field's description (and by ``gearcli schema``). Physics is
in ``docs/theory.md``; section numbers below refer to it. The sections live by topic in
``schema_gears`` (§2), ``schema_mesh`` (§4, §5), ``schema_drive`` (§6) and ``schema_mods`` (§3);
this module assembles the :class:`Case` and re-exports them.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, Strict, model_serializer, model_validator

from gearcli import units
from gearcli.case.schema_drive import Bearing, Bearings, Drive, Load, MotorCurve, Shaft
from gearcli.case.schema_faults import Fault
from gearcli.case.schema_gears import Accuracy, Gear, Gears, InertiaSpec, Material, Rack, Teeth
from gearcli.case.schema_mesh import IMPACT_KEYS, TOOTH_KEYS, Contact, Friction
from gearcli.case.schema_mods import (
    Errors,
    Modifications,
    PitchDeviation,
    ProfileSlopeDeviation,
    Relief,
    Runout,
)
from gearcli.case.schema_rating import Rating
from gearcli.case.schema_sensors import Sensors
from gearcli.case.section import Coefficient, FieldError, Section, pair, raise_all
from gearcli.case.types import Frequency, Length, Time, qfield, unit_system

__all__ = [
    "IMPACT_KEYS", "TOOTH_KEYS", "Bearing", "Bearings", "Case", "Checks", "Coefficient",
    "Contact", "Drive", "Errors", "FieldError", "Friction", "Gear", "Gears", "InertiaSpec",
    "Load", "Material", "Modifications", "MotorCurve", "PitchDeviation", "ProfileSlopeDeviation",
    "Rack",
    "Relief", "Run", "Runout", "Section", "pair", "Shaft", "Teeth",
]


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
            raise FieldError(("output_rate",), "both 'output_steps' and 'output_rate' given",
                             "at most one of them")
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

    units: Literal["adams", "engineering", "si"] | None = Field(
        None, description="the units of bare numbers (a string with units always means what it "
        "says): 'adams' (the default: mm, deg, deg/s, N*mm, kg, kg/mm^3, kg*mm^2, MPa, as each "
        "key's description states), 'engineering' (as adams but rpm, N*m, kg/m^3, kg*m^2, "
        "N*m/rad, N*m*s/rad) or 'si' (m, rad, rad/s, N*m, kg/m^3, kg*m^2, N/m, N*s/m, m/s); "
        "stresses stay in MPa and the Adams contact stiffness in N/mm^e (docs/theory.md §8)")
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
    accuracy: Accuracy = Field(default_factory=Accuracy, description="ISO 1328-1 flank "
                               "tolerance class: seeded pitch deviations of both gears")
    run: Run
    checks: Checks = Field(default_factory=Checks)
    rating: Rating = Field(default_factory=Rating, description="ISO 6336 rating (gearcli rate)")
    faults: list[Fault] = Field(default_factory=list, description="damaged teeth: root_crack, "
                                "spall, chipped_tip, missing_tooth (docs/theory.md, Tooth faults)")
    sensors: Sensors | None = Field(None, description="what a test rig would record: encoders, "
                                    "bearing forces, a housing accelerometer, noise "
                                    "(docs/theory.md, What a sensor sees; optional)")

    def material_of(self, role: str) -> Material:
        """The material of gear ``role`` ('pinion' or 'gear'): its own, else the case's."""
        return getattr(self.gears, role).material or self.material

    @model_validator(mode="wrap")
    @classmethod
    def _in_declared_units(cls, data, handler):
        """Bare numbers in the unit system the case declares (``units:``), the default's
        without one; an unknown system is the Literal's error (validated in the default's)."""
        declared = data.get("units") if isinstance(data, dict) else None
        with unit_system(declared if isinstance(declared, str) else None):
            return handler(data)

    @model_serializer(mode="wrap")
    def _units_when_declared(self, handler):
        """The resolved case names its units only when the file did (its values carry their
        units: the name only records what the file said)."""
        data = handler(self)
        if self.units is None:
            data.pop("units", None)
        if self.sensors is None:  # the resolved case of a run without sensors is unchanged
            data.pop("sensors", None)
        return data

    @model_validator(mode="after")
    def _deviations_of_the_grade(self):
        """``accuracy.grade``: the grade's seeded pitch and profile slope deviations
        (errors.pitch_deviation, errors.profile_slope_deviation) of every gear that has none of
        its own (gearcli/model/accuracy.py; the same seed draws both, pitch first)."""
        acc = self.accuracy
        if acc.grade is None:
            return self
        from gearcli.model.accuracy import gear_seeds

        update = {}
        for key, kind in (("pitch_deviation", PitchDeviation),
                          ("profile_slope_deviation", ProfileSlopeDeviation)):
            given = getattr(self.errors, key)
            fill = {role: kind(iso1328_grade=acc.grade, seed=seed)
                    for role, seed in zip(("pinion", "gear"), gear_seeds(acc.seed), strict=True)
                    if getattr(given, role) is None}
            if fill:
                update[key] = given.model_copy(update=fill)
        if not update:
            return self
        return self.model_copy(update={"errors": self.errors.model_copy(update=update)})

    @model_validator(mode="after")
    def _cross_checks(self):
        """Keys whose meaning depends on another section (every one is reported)."""
        found = [*self._bearings_of_the_model(), *self._pitch_lists(), *self._fault_teeth()]
        if self.load.applied_to == "pinion" and self.drive.type == "speed":
            found.append(FieldError(
                ("load", "applied_to"), "a torque on a motion-driven body never reaches the "
                "mesh (docs/theory.md §9)", "applied_to: gear with drive type 'speed'"))
        raise_all(found)
        return self

    def _bearings_of_the_model(self) -> list[FieldError]:
        found = []
        for name in ("pinion", "gear"):
            b = getattr(self.bearings, name)
            if self.model == "lateral-torsional":
                found += [FieldError(("bearings", name, key), "missing", "the lateral bearing "
                                     "stiffness of both gears in x and y with model "
                                     "'lateral-torsional'")
                          for key in ("stiffness_x", "stiffness_y") if getattr(b, key) is None]
            elif b.lateral:
                key = next(k for k in ("stiffness_x", "stiffness_y", "damping_x", "damping_y")
                           if getattr(b, k) not in (None, 0.0))
                found.append(FieldError(("bearings", name, key), "used only by model "
                                        "'lateral-torsional', and this case's model is "
                                        "'torsional' (gear centres are fixed)",
                                        f"no '{key}' here, or model: lateral-torsional"))
        return found

    def _pitch_lists(self) -> list[FieldError]:
        found = []
        for key in ("pitch_deviation", "profile_slope_deviation"):
            for name in ("pinion", "gear"):
                dev = getattr(getattr(self.errors, key), name)
                teeth = getattr(self.gears, name).teeth
                if dev is not None and dev.values is not None and len(dev.values) != teeth:
                    found.append(FieldError(("errors", key, name, "values"),
                                            f"{len(dev.values)} entries", f"one per tooth of "
                                            f"the {name} (gears.{name}.teeth: {teeth})"))
        return found

    def _fault_teeth(self) -> list[FieldError]:
        return [FieldError(("faults", str(i), "tooth"), f"tooth {f.tooth}",
                           f"0 ... {teeth - 1} (gears.{f.gear}.teeth: {teeth})")
                for i, f in enumerate(self.faults)
                if f.tooth >= (teeth := getattr(self.gears, f.gear).teeth)]
