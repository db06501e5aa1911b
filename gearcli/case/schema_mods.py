"""Case schema, tooth modifications and manufacturing errors (docs/theory.md §3): profile
relief, runout, single pitch and profile slope deviations, each per gear
(:func:`~gearcli.case.section.pair`).
Values in internal units (see :mod:`gearcli.case.types`)."""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import Field, Strict, model_validator

from gearcli import units
from gearcli.case.section import Section, pair
from gearcli.case.types import Angle, Length, qfield


class Relief(Section):
    """Profile relief on one gear: amount and extent (length along the path, or start diameter)."""

    amount: Length = qfield(units.LENGTH, ..., "relief amount C_a at the tip (or root)", gt=0)
    length: Length | None = qfield(units.LENGTH, None, "relief length along the LoA", gt=0)
    start_diameter: Length | None = qfield(units.LENGTH, None, "diameter where it starts", gt=0)
    shape: Literal["linear", "parabolic"] = Field("linear", description="'linear' or 'parabolic'")

    @model_validator(mode="after")
    def _one_extent(self):
        return self.exactly_one("length", "start_diameter")


class Modifications(Section):
    tip_relief: pair(Relief) = Field(default_factory=pair(Relief))
    root_relief: pair(Relief) = Field(default_factory=pair(Relief))


class Runout(Section):
    eccentricity: Length = qfield(units.LENGTH, ..., "eccentricity e", ge=0)
    phase: Angle = qfield(units.ANGLE, 0.0, "phase of the eccentricity")


class PitchDeviation(Section):
    """Single pitch deviations per tooth: a list, or an ISO 1328-1 grade with a random seed."""

    pair_name: ClassVar[str] = "Pitch"  #: its pair is "PitchPair" in the JSON Schema

    values: list[Length] | None = Field(None, description="f_pt per tooth [mm], one per tooth")
    iso1328_grade: Annotated[int, Strict()] | None = Field(
        None, ge=1, le=11, description="ISO 1328-1 grade 1..11"
    )
    seed: Annotated[int, Strict()] = Field(0, ge=0, le=2**32 - 1,
                                           description="random seed for the grade (0)")

    @model_validator(mode="after")
    def _one_source(self):
        return self.exactly_one("values", "iso1328_grade")


class ProfileSlopeDeviation(PitchDeviation):
    """Profile slope deviations f_Hα per tooth (ISO 1328-1; docs/theory.md §3.5): a list, or
    an ISO 1328-1 grade with a random seed (gearcli/model/accuracy.py); a bare list is the
    list of values."""

    pair_name: ClassVar[str] = "ProfileSlope"  #: its pair is "ProfileSlopePair"

    values: list[Length] | None = Field(
        None, description="f_Hα per tooth [mm], one per tooth; positive: more material at the "
        "tip (ISO 1328-1 profile diagram)")

    @model_validator(mode="before")
    @classmethod
    def _bare_list(cls, data):
        return {"values": data} if isinstance(data, list) else data


class Errors(Section):
    runout: pair(Runout) = Field(default_factory=pair(Runout))
    pitch_deviation: pair(PitchDeviation) = Field(default_factory=pair(PitchDeviation))
    profile_slope_deviation: pair(ProfileSlopeDeviation) = Field(
        default_factory=pair(ProfileSlopeDeviation))


