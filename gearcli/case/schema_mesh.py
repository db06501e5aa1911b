"""Case schema, tooth contact and friction (docs/theory.md §4, §4b, §4c, §5). Values in internal
units (see :mod:`gearcli.case.types`)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, field_validator, model_serializer, model_validator

from gearcli import units
from gearcli.case.section import Coefficient, FieldError, Section, raise_all
from gearcli.case.types import Length, LinearDamping, Velocity, checked_quantity, qfield

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
        raise_all([FieldError((key,), f"applies to law '{other}' only, and this case uses law "
                              f"'{self.law}'",
                              f"no '{key}' here (--set contact.{key}=null removes it), or "
                              f"contact.law: {other}")
                   for key in (IMPACT_KEYS if self.law == "tooth" else TOOTH_KEYS)
                   if key in self.model_fields_set])
        return self

    @model_validator(mode="before")
    @classmethod
    def _derived_is_linear(cls, data):
        """The ISO 6336-1 stiffness is linear per unit deflection: 'derived' implies e = 1."""
        if isinstance(data, dict) and data.get("stiffness") == "derived":
            exponent = data.get("exponent", 1.0)
            if isinstance(exponent, bool):  # refused by the field itself (not_boolean)
                return data
            if exponent != 1 and exponent != 1.0:
                raise FieldError(("exponent",), "the 'derived' (ISO 6336-1) stiffness is "
                                 "linear", "exponent: 1, or no exponent")
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
            raise FieldError(("stiction_velocity",), "", "stiction_velocity < "
                             "transition_velocity (the velocity where friction reaches mu_d)")
        return self


