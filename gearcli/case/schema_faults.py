"""Case schema, tooth faults (docs/theory.md "Tooth faults"): the ``faults:`` list, each entry
one damaged tooth of the pinion or the gear, told apart by ``kind``. Values in internal units
(see :mod:`gearcli.case.types`); the physics is :mod:`gearcli.model.faults`.

    faults:
      - {kind: root_crack, gear: pinion, tooth: 3, depth: 2 mm, angle: 45 deg, width: 1}
      - {kind: spall, gear: gear, tooth: 5, diameter: 200 mm, length: 4 mm, width: 0.5,
         depth: 0.02 mm}
      - {kind: chipped_tip, gear: pinion, tooth: 0, height: 2 mm, width: 0.5}
      - {kind: missing_tooth, gear: gear, tooth: 7}

Tooth 0 of each gear is the tooth of the pair whose drive flanks touch at the pitch point at
t = 0; tooth i + 1 enters the mesh one mesh period after tooth i (the index of the pitch
deviations).
"""

from __future__ import annotations

import math
from typing import Annotated, Literal, Union

from pydantic import Field, Strict, model_validator

from gearcli import units
from gearcli.case.section import Coefficient, Section
from gearcli.case.types import Angle, Length, qfield

__all__ = ["RootCrackFault", "SpallFault", "ChippedTipFault", "MissingToothFault", "Fault",
           "fault_records"]

_GEAR = Field(description="the damaged gear: 'pinion' or 'gear'")
_TOOTH = Field(ge=0, description="tooth index: 0 is the tooth in mesh at the pitch point at "
               "t = 0, i + 1 the next to enter the mesh (docs/theory.md, Tooth faults)")


def _share(default, what: str):
    """A share of the face width: ``default`` a number, or ``...`` (required)."""
    text = f"share of the face width {what}, 0 ... 1"
    return Field(default, ge=0.0, le=1.0, description=text + (
        " (required)" if default is ... else f" ({default:g})"))


class RootCrackFault(Section):
    """A straight root crack from the loaded side's 30° tangent point (ISO 6336-3)."""

    kind: Literal["root_crack"]
    gear: Literal["pinion", "gear"] = _GEAR
    tooth: Annotated[int, Strict()] = _TOOTH
    depth: Length = qfield(units.LENGTH, ..., "crack depth along its path", ge=0)
    angle: Angle = qfield(units.ANGLE, 45.0, "angle of the crack path to the tooth centreline",
                          gt=0, le=math.pi / 2)
    width: Coefficient = _share(1.0, "the crack runs through")


class SpallFault(Section):
    """A spall (pit) on the loaded flank: centre, extent along the profile, width, depth."""

    kind: Literal["spall"]
    gear: Literal["pinion", "gear"] = _GEAR
    tooth: Annotated[int, Strict()] = _TOOTH
    diameter: Length | None = qfield(units.LENGTH, None, "diameter of the spall's centre", gt=0)
    roll_angle: Angle | None = qfield(units.ANGLE, None, "roll angle of the involute at the "
                                      "spall's centre", ge=0)
    length: Length = qfield(units.LENGTH, ..., "extent along the profile", ge=0)
    width: Coefficient = _share(..., "the spall covers")
    depth: Length = qfield(units.LENGTH, ..., "pit depth", ge=0)

    @model_validator(mode="after")
    def _one_centre(self):
        return self.exactly_one("diameter", "roll_angle")


class ChippedTipFault(Section):
    """A chipped tip: the lost tip height (radial, from the tip circle) over a width share."""

    kind: Literal["chipped_tip"]
    gear: Literal["pinion", "gear"] = _GEAR
    tooth: Annotated[int, Strict()] = _TOOTH
    height: Length = qfield(units.LENGTH, ..., "lost tip height", ge=0)
    width: Coefficient = _share(1.0, "the chip covers")


class MissingToothFault(Section):
    """A tooth broken off: it carries nothing."""

    kind: Literal["missing_tooth"]
    gear: Literal["pinion", "gear"] = _GEAR
    tooth: Annotated[int, Strict()] = _TOOTH


Fault = Annotated[Union[RootCrackFault, SpallFault, ChippedTipFault, MissingToothFault],  # noqa: UP007
                  Field(discriminator="kind")]
#: The ``kind`` of each fault, as a case file writes it.
FAULT_KINDS = ("root_crack", "spall", "chipped_tip", "missing_tooth")


def fault_records(faults) -> list:
    """The model's fault records (gearcli.model.faults) of the case's ``faults`` entries
    (internal units: lengths mm, angles rad -> the records' degrees)."""
    from gearcli.model.faults import ChippedTip, MissingTooth, RootCrack, Spall

    out = []
    for f in faults:
        if isinstance(f, RootCrackFault):
            out.append(RootCrack(f.gear, f.tooth, f.depth, math.degrees(f.angle), f.width))
        elif isinstance(f, SpallFault):
            out.append(Spall(f.gear, f.tooth, f.length, f.width, f.depth, f.diameter,
                             None if f.roll_angle is None else math.degrees(f.roll_angle)))
        elif isinstance(f, ChippedTipFault):
            out.append(ChippedTip(f.gear, f.tooth, f.height, f.width))
        else:
            out.append(MissingTooth(f.gear, f.tooth))
    return out
