"""The internal unit system, declared once, and unit-string parsing at the edge.

Internal units (consistent, Adams "MMKS"-compatible so that seed values pass unconverted):

=========  ========  =====================================================
quantity   unit      note
=========  ========  =====================================================
length     mm
force      N         N = t·mm/s², so F = m·a holds without factors
time       s
mass       t         tonne (1 t = 1000 kg); inertia in t·mm² (1 kg·m² = 1000 t·mm²)
angle      rad
=========  ========  =====================================================

Case files take engineering units: each dimensional field has a documented default unit
(mm, N, s, deg, kg based) used for bare numbers, or a string with explicit units parsed by
pint ("450 N*m", "4.5e5 N*mm", "3000 deg/s", "7.85e-6 kg/mm^3", "1e5 N/mm^1.5").
pint is imported lazily (only when a case is loaded).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

INTERNAL_UNITS = {"length": "mm", "force": "N", "time": "s", "mass": "t", "angle": "rad"}


class UnitError(ValueError):
    """A value whose unit is unparseable or has the wrong dimension."""


@dataclass(frozen=True)
class Dim:
    """A physical dimension as case files see it.

    Attributes
    ----------
    name : what the quantity is, for messages ("torque")
    default : unit of bare numbers in case files
    internal : internal unit (see the module table)
    example : an example for error messages
    angular : the quantity involves an angle, so cycle-based units like Hz are refused
    """

    name: str
    default: str
    internal: str
    example: str
    angular: bool = False
    factor: float = 1.0  #: default -> internal factor (checked against pint in the tests)


LENGTH = Dim("length", "mm", "mm", "'10 mm'")
ANGLE = Dim("angle", "deg", "rad", "'20 deg'", True, math.pi / 180.0)
ANGULAR_VELOCITY = Dim(
    "angular velocity", "deg/s", "rad/s", "'3000 deg/s' or '500 rpm'", True, math.pi / 180.0
)
TORQUE = Dim("torque", "N*mm", "N*mm", "'450 N*m'")
FORCE = Dim("force", "N", "N", "'3831 N'")
TIME = Dim("time", "s", "s", "'5 s'")
FREQUENCY = Dim("frequency", "Hz", "Hz", "'10 kHz'")
MASS = Dim("mass", "kg", "t", "'12.5 kg'", factor=1e-3)
DENSITY = Dim("density", "kg/mm^3", "t/mm^3", "'7.85e-6 kg/mm^3'", factor=1e-3)
INERTIA = Dim("polar moment of inertia", "kg*mm^2", "t*mm^2", "'0.05 kg*m^2'", factor=1e-3)
STRESS = Dim("stress", "MPa", "N/mm^2", "'2.07e5 MPa'")
VELOCITY = Dim("velocity", "mm/s", "mm/s", "'0.1 mm/s'")
LINEAR_STIFFNESS = Dim("stiffness", "N/mm", "N/mm", "'1e6 N/mm'")
LINEAR_DAMPING = Dim("damping", "N*s/mm", "N*s/mm", "'100 N*s/mm'")
TORSIONAL_STIFFNESS = Dim("torsional stiffness", "N*mm/rad", "N*mm/rad", "'1e4 N*m/rad'", True)
TORSIONAL_DAMPING = Dim("torsional damping", "N*mm*s/rad", "N*mm*s/rad", "'5 N*m*s/rad'", True)
QUADRATIC_DAMPING = Dim(
    "quadratic torque coefficient", "N*mm*s^2/rad^2", "N*mm*s^2/rad^2", "'1e-3 N*m*s^2'", True
)
MOTOR_SLOPE = Dim("motor-curve slope", "N*mm*s/rad", "N*mm*s/rad", "'2 N*m*s/rad'", True)


def contact_stiffness_dim(exponent: float) -> Dim:
    """Dimension of the Adams IMPACT stiffness k for force exponent e: N/mm^e."""
    e = f"{exponent:g}"
    return Dim("contact stiffness", f"N/mm^{e}", f"N/mm^{e}", f"'1e5 N/mm^{e}'")


@functools.cache
def registry():
    """The pint registry (created on first use; pint import is slow)."""
    import pint

    ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=False)
    ureg.define("rev = revolution")
    return ureg


def parse_quantity(value: object, dim: Dim) -> float:
    """Convert a case-file value to the internal unit of ``dim``.

    Parameters
    ----------
    value : a bare number (in ``dim.default``) or a string "<number> <unit>"
    dim : the expected dimension

    Returns
    -------
    float : the value in ``dim.internal``

    Raises
    ------
    UnitError : unparseable, wrong dimension, non-finite
    """
    expected = (
        f"a {dim.name} as a number in {dim.default} or a string with units, e.g. {dim.example}"
    )
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise UnitError(f"expected {expected}")
    if isinstance(value, int | float):
        number = float(value)
        if not math.isfinite(number):
            raise UnitError(f"expected a finite number ({dim.default})")
        return convert(number, dim.default, dim)
    text = value.strip()
    try:
        number = float(text)
    except ValueError:
        pass
    else:  # a number written as a string: "4.5e5"
        return parse_quantity(number, dim)
    ureg = registry()
    try:
        q = ureg.Quantity(text)
    except Exception as exc:  # pint raises a zoo of types (UndefinedUnitError, AssertionError, ...)
        raise UnitError(
            f"cannot parse units ({type(exc).__name__}: {exc}); expected {expected}"
        ) from None
    if not hasattr(q, "units") or isinstance(q.magnitude, complex):
        raise UnitError(f"expected {expected}")
    _refuse_cycles(text, dim)
    try:
        out = float(q.to(dim.internal).magnitude)
    except Exception:
        raise UnitError(
            f"wrong dimension: '{q.units:~}' is not a {dim.name}; expected {expected}"
        ) from None
    if not math.isfinite(out):
        raise UnitError(f"expected a finite {dim.name}")
    return out


def unit_factor(unit: str, dim: Dim) -> float:
    """Factor that converts a value in ``unit`` to ``dim.internal`` (for time functions)."""
    return parse_quantity(f"1 {unit}", dim)


def convert(number: float, unit: str, dim: Dim) -> float:
    """Convert ``number`` in ``unit`` to ``dim.internal`` (no pint for the default unit)."""
    if unit == dim.default:
        return float(number) * dim.factor
    if unit == dim.internal:
        return float(number)
    return float(registry().Quantity(number, unit).to(dim.internal).magnitude)


def default_to_internal(number: float, dim: Dim) -> float:
    """A documented default, written in the default unit, in internal units."""
    return float(number) * dim.factor


def _refuse_cycles(text: str, dim: Dim) -> None:
    """pint treats Hz as 1/s = rad/s; for angular quantities that silently loses 2π."""
    if dim.angular and any(tok in text for tok in ("Hz", "hertz")):
        raise UnitError(f"'Hz' is ambiguous for a {dim.name}; write rev/s, rpm, deg/s or rad/s")


def format_internal(value: float, dim: Dim) -> str:
    """Render an internal value with its internal unit, loadable back exactly."""
    return f"{value!r} {dim.internal}"
