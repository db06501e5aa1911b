"""Case schema, the ISO 6336 rating section ``rating:`` (docs/theory.md, "ISO 6336 rating").

What an ISO 6336 Method B rating needs beyond the gears, the material and the load of the case:
load factors, the required life and minimum safeties, the lubricant, per gear the ISO 6336-5
material (kind, quality, hardness), roughness, idler and contacts per revolution, and an
optional duty cycle (ISO 6336-6). The given fatigue limits stay in ``material`` (per gear or
shared): ``material.contact_fatigue_limit`` σ_Hlim, ``material.bending_fatigue_limit`` σ_Flim;
without them σ_Hlim, σ_Flim come from ``rating.<gear>.material`` (ISO 6336-5 Table 1).
Values in internal units (:mod:`gearcli.case.types`); the rating's own quantities have their
own default units here (h for the life, µm for roughness and deviations, mm²/s for ν40).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, Strict, field_validator, model_validator

from gearcli.case.section import Coefficient, FieldError, Section
from gearcli.case.types import AngularVelocity, Length, Stress, Torque, qfield, quantity
from gearcli.units import ANGULAR_VELOCITY, LENGTH, STRESS, TORQUE, Dim

__all__ = ["LIFE", "ROUGHNESS", "VISCOSITY", "Rating", "RatingGear", "RatingMaterial",
           "Roughness", "MinimumSafety", "Lubricant", "DutyBin"]

#: A required life: bare numbers in hours (internal s). Its own name: no "time" limit of a run.
LIFE = Dim("life", "h", "s", "'175200 h'", factor=3600.0)
#: Roughness, deviations and misalignments of the rating: bare numbers in µm (internal mm).
ROUGHNESS = Dim("deviation", "um", "mm", "'4.8 um'", factor=1e-3)
#: Kinematic viscosity: bare numbers in mm²/s (cSt).
VISCOSITY = Dim("kinematic viscosity", "mm^2/s", "mm^2/s", "'220 mm^2/s'")

Life = quantity(LIFE)
Micro = quantity(ROUGHNESS)
Viscosity = quantity(VISCOSITY)

MATERIAL_KINDS = ("normalized_steel", "normalized_cast_steel", "black_malleable_iron",
                  "nodular_iron", "grey_iron", "through_hardened_carbon",
                  "through_hardened_alloy", "through_hardened_cast_carbon",
                  "through_hardened_cast_alloy", "case_hardened", "induction_hardened",
                  "nitrided", "nitrided_through_hardening", "nitrocarburized")
MaterialKindName = Literal[MATERIAL_KINDS]  # type: ignore[valid-type]


class RatingMaterial(Section):
    """ISO 6336-5 material of one gear: group, quality grade and surface hardness."""

    kind: MaterialKindName = Field(
        "case_hardened", description="ISO 6336-5 material group ('case_hardened', the default: "
        "Eh; also through_hardened_alloy (V), induction_hardened (IF), nitrided (NT), "
        "normalized_steel (St), nodular_iron (GGG), grey_iron (GG), ...); sets the life-factor "
        "curves, running-in, Y_X, Y_δrelT, Y_RrelT")
    quality: Literal["ML", "MQ", "ME"] = Field(
        "MQ", description="ISO 6336-5 material quality (MQ, the default: what experienced "
        "manufacturers reach; ML modest, ME high demands)")
    hardness: Coefficient | None = Field(
        None, gt=0, description="surface hardness in the scale of the ISO 6336-5 row: HV for "
        "through-hardened, case-hardened, induction-hardened and nitrided steels, HBW for "
        "normalized steel and irons (61 HRC ≈ 720 HV); gives σ_Hlim and σ_Flim when "
        "material.contact_fatigue_limit / bending_fatigue_limit are not given (optional)")
    proof_stress: Stress | None = qfield(
        STRESS, None, "0.2 % proof stress σ_0.2 (St, V, GGG, GTS: notch sensitivity)", gt=0)


class Roughness(Section):
    """Mean roughness R_z of one gear."""

    flank: Micro = qfield(ROUGHNESS, 3.0, "flank mean roughness R_zH", gt=0)
    root: Micro = qfield(ROUGHNESS, 10.0, "root mean roughness R_zF", gt=0)


class RatingGear(Section):
    """What the rating needs of one gear beyond its geometry and fatigue limits."""

    material: RatingMaterial = Field(default_factory=RatingMaterial,
                                     description="ISO 6336-5 material (kind, quality, hardness)")
    roughness: Roughness = Field(default_factory=Roughness, description="R_z of flank and root")
    idler: bool = Field(False, description="an idler (a planet): both flanks loaded, "
                        "alternating bending, Y_M < 1 (default false)")
    contacts_per_revolution: Coefficient = Field(
        1.0, gt=0, description="load cycles of a flank per revolution relative to the carrier "
        "(1; a sun meshing with three planets: 3)")
    base_pitch_deviation: Micro | None = qfield(
        ROUGHNESS, None, "f_pb for K_Hα; default: from errors.pitch_deviation as gearcli mesh "
        "takes it (f_pt cos α), else 0", ge=0)
    accuracy_grade: Annotated[int, Strict()] = Field(
        6, ge=1, le=12, description="ISO 1328 accuracy grade (6; deep tooth factor Y_DT only)")
    rim_thickness: Length | None = qfield(LENGTH, None, "rim thickness s_R below the root "
                                          "(Y_B); default: a solid gear", gt=0)
    thickness_allowances: tuple[Length, Length] | None = Field(
        None, description="upper and lower tooth thickness allowances A_sn [mm], e.g. "
        "[-0.130, -0.190] (inspection dimensions); default: both -gears.<gear>."
        "thickness_allowance")
    ball_diameter: Length | None = qfield(LENGTH, None, "ball/pin diameter D_M for the "
                                          "dimension over balls; default: the next standard "
                                          "size", gt=0)

    @model_validator(mode="after")
    def _ordered_allowances(self):
        a = self.thickness_allowances
        if a is not None and a[0] < a[1]:
            raise FieldError(("thickness_allowances",), "the upper allowance is below the "
                             "lower", "[upper, lower] with upper >= lower, e.g. [-0.13, -0.19]")
        return self


class MinimumSafety(Section):
    """Required minimum safeties (the design's; ISO 6336 leaves them to the contract)."""

    pitting: Coefficient = Field(1.0, gt=0, description="S_H,min (1.0)")
    bending: Coefficient = Field(1.0, gt=0, description="S_F,min (1.0)")


class Lubricant(Section):
    """The lubricant as ISO 6336-2 Method B takes it (Z_L, Z_v)."""

    viscosity_40: Viscosity = qfield(VISCOSITY, 220.0, "kinematic viscosity ν40 at 40 °C", gt=0)


class DutyBin(Section):
    """One bin of a load spectrum, in the case's own terms."""

    torque: Torque = qfield(TORQUE, ..., "load torque, as load.torque (on the body "
                            "load.applied_to; per mesh path)", gt=0)
    speed: AngularVelocity = qfield(ANGULAR_VELOCITY, ..., "pinion speed, as drive.speed "
                                    "(relative to the carrier where there is one)", gt=0)
    time_share: Coefficient = Field(..., gt=0, le=1, description="share of rating.life (the "
                                    "shares sum to 1)")


class Rating(Section):
    """ISO 6336 Method B rating of the pair (`gearcli rate`; docs/theory.md, "ISO 6336
    rating"). The load is the case's (load torque at the end of its ramps, pinion speed)."""

    edition: Literal[2006, 2019] = Field(
        2019, description="ISO 6336 edition followed where they differ (2019; 2006: the idler's "
        "Y_M = 0.7)")
    # K_A adds the external load increments to the nominal load (ISO 6336-1 §6.2; ISO 6336-6
    # Annex A, Table A.1: 1.00 ... 2.25), K_γ is the largest mesh load over the mean one
    # (ISO 6336-1 §6.1): neither is below 1 (K_v may be, in the super-critical range)
    application_factor: Coefficient = Field(1.0, ge=1, description="K_A (1.0)")
    load_sharing_factor: Coefficient = Field(
        1.0, ge=1, description="K_γ, the mesh load / mean mesh load (1.0; planets: e.g. 1.1)")
    dynamic_factor: Literal["iso", "simulated"] | Coefficient = Field(
        "iso", description="K_v: 'iso' (ISO 6336-1 Method B, as gearcli mesh prints it; the "
        "default), 'simulated' (the dynamic factor of a run), or a number",
        json_schema_extra={"anyOf": [{"type": "number"}, {"enum": ["iso", "simulated"]}]})
    face_load_factor: Coefficient | None = Field(
        None, ge=1, description="K_Hβ; default: ISO 6336-1 Method C from the misalignments")
    transverse_load_factor: Coefficient | None = Field(
        None, ge=1, description="K_Hα = K_Fα; default: ISO 6336-1 Method B from f_pb")
    shaft_misalignment: Micro = qfield(ROUGHNESS, 0.0, "f_sh for Method C K_Hβ (0: only ISO's "
                                       "minimum F_βx = 0.005 F_m/b; give your design's)", ge=0)
    manufacturing_misalignment: Micro = qfield(ROUGHNESS, 0.0, "f_ma for Method C K_Hβ", ge=0)
    mesh_stiffness: Coefficient | None = Field(
        None, gt=0, description="c_γα [N/(mm·µm)] for K_Hα and K_Hβ; default: ISO 6336-1 "
        "Method B of the case (with the low-load factor), as gearcli mesh prints it")
    life: Life = qfield(LIFE, 20000.0, "required life L_h", gt=0)
    minimum_safety: MinimumSafety = Field(default_factory=MinimumSafety)
    lubricant: Lubricant = Field(default_factory=Lubricant)
    pitting_permitted: bool = Field(False, description="limited pitting permitted (Z_NT "
                                    "curve; default false)")
    optimum_long_life: bool = Field(
        False, description="life factors stay 1.0 beyond the endurance knee (optimum "
        "material, lubrication and experience); default false: 0.85 at 10^10 cycles")
    duty_cycle: list[DutyBin] | None = Field(
        None, min_length=1, description="load spectrum (ISO 6336-6, Palmgren-Miner): a list of "
        "{torque, speed, time_share}; default: none (the case's load only)")
    pinion: RatingGear = Field(default_factory=RatingGear)
    gear: RatingGear = Field(default_factory=RatingGear)

    @field_validator("duty_cycle")
    @classmethod
    def _shares_sum_to_one(cls, bins):
        if bins is not None:
            total = sum(b.time_share for b in bins)
            if abs(total - 1.0) > 1e-6:
                raise ValueError(f"the time shares sum to {total:.6g}; expected a sum of 1")
        return bins
