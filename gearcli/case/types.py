"""Annotated pydantic field types for case files: quantities with units and time functions.

A quantity field accepts a bare number in its documented default unit (or in the unit of the
case's declared ``units:`` system, :func:`bare`) or a string with units
(parsed by pint, see :mod:`gearcli.units`) and stores the value in internal units. In JSON
output (the resolved case) it is written back as "<value> <internal unit>", which loads again
to the identical float.
"""

from __future__ import annotations

import functools
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import BeforeValidator, Field, PlainSerializer, WithJsonSchema

from gearcli import guards, units
from gearcli.case.section import compose
from gearcli.units import Dim

#: The unit system of bare numbers while a case validates: its ``units:`` key (None: the
#: default, "adams"; see :data:`gearcli.units.UNIT_SYSTEMS`). Set by the Case's validator.
UNIT_SYSTEM: ContextVar[str | None] = ContextVar("gearcli_case_units", default=None)


@contextmanager
def unit_system(system: str | None):
    """Validate in unit system ``system`` (bare numbers of each quantity in its unit)."""
    token = UNIT_SYSTEM.set(system if system in units.UNIT_SYSTEMS else None)
    try:
        yield
    finally:
        UNIT_SYSTEM.reset(token)


def bare(dim: Dim) -> Dim:
    """``dim`` as bare numbers mean it in the case being validated (its ``units:``)."""
    return units.in_system(dim, UNIT_SYSTEM.get())


def checked_quantity(value: Any, dim: Dim) -> float:
    """:func:`gearcli.units.parse_quantity` behind the guards of :mod:`gearcli.guards`: a
    string must start with a number ("mm" alone is not 1 mm) and have small, unchained
    powers (pint never returns from "9**9**9**9")."""
    if isinstance(value, str):
        guards.check_unit_text(value, need_number=True, example=f"10 {dim.default}")
    return units.parse_quantity(value, dim)


def checked_unit(unit: str, dim: Dim) -> float:
    """:func:`gearcli.units.unit_factor` of a unit string ("N*m") behind the same guards."""
    guards.check_unit_text(unit, need_number=False)
    return units.unit_factor(unit, dim)


def _quantity_validator(dim: Dim):
    def validate(value: Any) -> float:
        return checked_quantity(value, bare(dim))

    validate.dim = dim  # lets error messages show limits in the default unit
    return validate


def field_dim(section: Any, name: str) -> Dim | None:
    """The dimension (:class:`gearcli.units.Dim`) of quantity field ``name`` of a case section
    (a model or its class), from the validator its :func:`quantity` type records; None for a
    plain number, a word or a sub-section. A name the section does not have is a KeyError."""
    cls = section if isinstance(section, type) else type(section)
    return info_dim(cls.model_fields[name])


def info_dim(info) -> Dim | None:
    """The dimension of a quantity field from its pydantic FieldInfo (:func:`field_dim`)."""
    metas, args = list(info.metadata), list(getattr(info.annotation, "__args__", ()))
    while args:  # Length | None, list[Length] | None
        arg = args.pop()
        metas += list(getattr(arg, "__metadata__", ()))
        args += list(getattr(arg, "__args__", ()))
    for meta in metas:
        dim = getattr(getattr(meta, "func", None), "dim", None)
        if dim is not None:
            return dim
    return None


@functools.cache
def quantity(dim: Dim):
    """The annotated float type of a quantity of dimension ``dim``."""
    return Annotated[
        float,
        BeforeValidator(_quantity_validator(dim)),
        PlainSerializer(lambda v: units.format_internal(v, dim), when_used="json"),
        WithJsonSchema(
            {
                "anyOf": [{"type": "number"}, {"type": "string"}],
                "description": f"{dim.name}: a number in {dim.default} or a string with units, "
                f"e.g. {dim.example}",
            }
        ),
    ]


def qfield(dim: Dim, default: float | None = ..., description: str = "", **kw) -> Any:
    """A pydantic Field for a quantity whose ``default`` is written in ``dim.default``.

    The description gets the default unit and value appended, so `gearcli schema` documents it.
    """
    text = f"{description} [{dim.default}]"
    extra = _user_unit_limits(dim, kw)
    if extra:
        text += " (" + ", ".join(f"{_SIGN[k]} {v:g}" for k, v in extra.items()) + ")"
    if default is None:
        return Field(default=None, description=text + " (optional)",
                     json_schema_extra=extra or None, **kw)
    if default is ...:
        return Field(description=text + " (required)", json_schema_extra=extra or None, **kw)
    text += f" (default {default:g} {dim.default})"
    # the schema shows the default as written in a case file (a number in the default unit),
    # not the internal value (20 deg, not 0.349 rad)
    return Field(default=units.default_to_internal(default, dim), description=text,
                 json_schema_extra={**extra, "default": default}, **kw)


#: JSON Schema keyword of each pydantic limit, and its sign for descriptions.
_LIMIT_KEYWORDS = {"gt": "exclusiveMinimum", "ge": "minimum", "lt": "exclusiveMaximum",
                   "le": "maximum"}
_SIGN = {"exclusiveMinimum": ">", "minimum": ">=", "exclusiveMaximum": "<", "maximum": "<="}


def _user_unit_limits(dim: Dim, kw: dict) -> dict:
    """The field's pydantic limits (internal units) as JSON Schema keywords in the default
    unit of the case file (they apply to plain numbers, which are in that unit)."""
    scale = units.default_to_internal(1.0, dim)
    return {_LIMIT_KEYWORDS[k]: kw[k] / scale for k in _LIMIT_KEYWORDS if k in kw}


Length = quantity(units.LENGTH)
Angle = quantity(units.ANGLE)
AngularVelocity = quantity(units.ANGULAR_VELOCITY)
Torque = quantity(units.TORQUE)
Time = quantity(units.TIME)
Frequency = quantity(units.FREQUENCY)
Mass = quantity(units.MASS)
Density = quantity(units.DENSITY)
Inertia = quantity(units.INERTIA)
Stress = quantity(units.STRESS)
Velocity = quantity(units.VELOCITY)
LinearStiffness = quantity(units.LINEAR_STIFFNESS)
LinearDamping = quantity(units.LINEAR_DAMPING)
TorsionalStiffness = quantity(units.TORSIONAL_STIFFNESS)
TorsionalDamping = quantity(units.TORSIONAL_DAMPING)
QuadraticDamping = quantity(units.QUADRATIC_DAMPING)


@dataclass(frozen=True)
class TimeFunction:
    """A function of time from a case file, kept as written plus the unit of its numbers.

    ``pp`` is the exact piecewise polynomial in internal units (see
    :mod:`gearcli.model.timefunction`).
    """

    expression: str
    unit: str
    dim: Dim

    @functools.cached_property
    def pp(self):
        from gearcli.case.expr import parse_time_function

        return parse_time_function(self.expression).scale(checked_unit(self.unit, self.dim))

    def to_json(self) -> dict[str, str]:
        return {"function": self.expression, "unit": self.unit}


def _time_function_validator(dim: Dim):
    def validate(value: Any) -> TimeFunction:
        from gearcli.case.expr import ExpressionError, is_expression, parse_time_function

        if isinstance(value, TimeFunction):
            return value
        own = bare(dim)  # the unit of its bare numbers (and the exact factor of that unit)
        unit = own.default
        if isinstance(value, dict):
            extra = set(value) - {"function", "unit"}
            if extra or "function" not in value:
                raise ValueError(
                    "expected a mapping with keys 'function' (an expression such as "
                    "'STEP(time, 0, 0, 1, 450)') and optional 'unit'"
                )
            unit_given = "unit" in value
            if unit_given and not (isinstance(value["unit"], str) and value["unit"].strip()):
                # "" read the numbers in the default unit; 5 as a unit is no unit at all
                raise ValueError(f"unit {value['unit']!r}: expected the unit of the function's "
                                 f"numbers, e.g. unit: {own.default}")
            unit = str(value.get("unit", own.default))
            checked_unit(unit, own)  # validates the unit and its dimension
            value = value["function"]
            if isinstance(value, int | float) and not isinstance(value, bool):
                value = repr(float(value))
            if unit_given and isinstance(value, str) and not is_expression(value):
                # a constant is in the mapping's unit, as an expression is (this is also how
                # a case is written back: {function: "52.36", unit: "rad/s"}); "1e3*0.5" and
                # "(500)" are numbers too
                constant = (f"{value} {unit}" if value.lstrip().startswith("(")
                            else f"({value}) {unit}")
                try:
                    checked_quantity(constant, own)
                except ValueError:
                    raise ValueError(
                        f"expected a number or an expression as the function of a mapping "
                        f"with 'unit' ({value!r} carries its own unit besides unit {unit!r}: "
                        "drop one of them)") from None
                value = constant
        if isinstance(value, bool) or not isinstance(value, int | float | str):
            raise ValueError(
                f"expected {units.article(dim.name)} {dim.name} ({own.default}): a number, a "
                "string with units, or an expression such as 'STEP(time, 0, 0, 1, 3000)'"
            )
        if isinstance(value, str) and is_expression(value):
            try:
                parse_time_function(value)
            except ExpressionError as exc:
                raise ValueError(compose(f"malformed expression: {exc}", "an expression of "
                                         "time such as 'STEP(time, 0, 0, 1, 3000)'")) from None
            return TimeFunction(" ".join(value.split()), unit, own)
        constant = checked_quantity(value, own)
        return TimeFunction(repr(constant), dim.internal, dim)

    validate.time_dim = dim  # the dimension of its bare numbers (sweep parameters' units)
    return validate


@functools.cache
def time_function(dim: Dim):
    """The annotated type of a time function of dimension ``dim``."""
    return Annotated[
        TimeFunction,
        BeforeValidator(_time_function_validator(dim)),
        PlainSerializer(lambda v: v.to_json(), when_used="json"),
        WithJsonSchema(
            {
                "anyOf": [
                    {"type": "number"},
                    {"type": "string"},
                    {
                        "type": "object",
                        "properties": {"function": {"type": "string"}, "unit": {"type": "string"}},
                        "required": ["function"],
                        "additionalProperties": False,
                    },
                ],
                "description": f"{dim.name} as a function of time: a number in {dim.default}, a "
                f"string with units, an expression like 'STEP(time, 0, 0, 1, 3000)' in "
                f"{dim.default}, or {{function: ..., unit: ...}}",
            }
        ),
    ]


def time_field(dim: Dim, description: str, default: float | None = ...) -> Any:
    """A Field for a time function; a numeric ``default`` is a constant in ``dim.default``."""
    text = f"{description} [{dim.default}]"
    if default is ...:
        return Field(description=text + " (required)")
    if default is None:
        return Field(default=None, description=text + " (optional)")
    value = units.default_to_internal(default, dim)
    return Field(
        default=TimeFunction(repr(value), dim.internal, dim),
        description=text + f" (default {default:g} {dim.default})",
        json_schema_extra={"default": default},  # as a case file writes it, not the object
    )


SpeedFunction = time_function(units.ANGULAR_VELOCITY)
TorqueFunction = time_function(units.TORQUE)
