"""Case schema, gears and materials (docs/theory.md §2): the pair, its rack, each gear's
material and mass properties. Values in internal units (see :mod:`gearcli.case.types`)."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field, Strict, model_validator

from gearcli import units
from gearcli.case.section import Coefficient, FieldError, Section
from gearcli.case.types import Angle, Density, Inertia, Length, Mass, Stress, qfield

Teeth = Annotated[int, Strict(), Field(ge=3, description="number of teeth z (integer >= 3)")]


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
            raise FieldError(("value",), "missing", "a polar inertia 'value' with inertia model "
                             "'given'")
        if self.model == "disc" and self.value is not None:
            raise FieldError(("value",), "not used by inertia model 'disc'",
                             "no 'value', or model: given")
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
        units.LENGTH, None, "bore (rim inner) diameter: the body of the tooth law's gear-body "
        "compliance (Sainsot et al. 2004) and of the disc inertia and mass (taken out of the "
        "disc, docs/theory.md §2.6); default: none in the mass properties (a solid gear, its "
        "shaft seat filled) and a third of the root diameter in the compliance", gt=0)
    face_width: Length | None = qfield(
        units.LENGTH, None, "face width; default gears.face_width", gt=0
    )
    material: Material | None = Field(None, description="default: the case's material")
    inertia: InertiaSpec = Field(default_factory=InertiaSpec, description="mass properties")

    @model_validator(mode="after")
    def _disc_outside_the_bore(self):
        d, bore = self.inertia.diameter, self.bore_diameter
        if self.inertia.model == "disc" and d is not None and bore is not None and d <= bore:
            raise FieldError(("inertia", "diameter"), f"{d:g} mm is not larger than the bore "
                             f"({bore:g} mm)", "a disc diameter larger than bore_diameter")
        return self


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




class Accuracy(Section):
    """ISO 1328-1:2013 flank tolerance class of both gears (docs/theory.md §10.5): seeded
    random single pitch deviations of the class for every gear without its own
    ``errors.pitch_deviation`` (gearcli/model/accuracy.py), and the class's tolerances in ISO
    6336-1 Method B's K_v."""

    grade: Annotated[int, Strict()] | None = Field(
        None, ge=1, le=11, description="ISO 1328-1:2013 flank tolerance class 1..11 (none: no "
        "deviations from a grade)")
    seed: Annotated[int, Strict()] = Field(
        0, ge=0, le=2**32 - 1, description="random seed of the pinion's deviations (the gear's: "
        "seed + 1); the same seed, the same deviations (0)")
