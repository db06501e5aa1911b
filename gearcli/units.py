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
pint is imported lazily, and only for a unit other than the field's default or internal one:
building its registry takes ~0.3 s after a ~0.35 s import, more than the rest of a
``gearcli geometry`` call. A number followed by exactly the default or the internal unit
("3000 deg/s", and the unit of a time function, "1 deg/s") is converted by the dimension's
own factor, bit-identical to pint's conversion (tests/unit/test_units.py compares the two).
"""

from __future__ import annotations

import functools
import math
import re
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


#: Unit systems of bare numbers in a case file (its ``units:`` key), by quantity (``Dim.name``):
#: the unit a bare number is in and its factor to the internal unit (pint's factor, bit for
#: bit: tests/unit/test_case_units.py compares them). A quantity a system does not list keeps
#: its Dim's default. "adams" is the default: Adams MMKS with degrees (mm, N*mm, kg, deg, deg/s).
#: "engineering": rpm, N*m and kg*m^2 at the shafts, kg/m^3; mm, MPa, deg, Hz, s stay.
#: "si": the coherent SI units (m, rad, rad/s, N*m, kg/m^3, kg*m^2, N/m, ...). Stresses and
#: moduli stay in MPa in every system (ISO 6336's unit, as in the display units of
#: gearcli/display_units.py: 1500 meaning Pa would be a silent slip of 1e6), and the Adams
#: contact stiffness k [N/mm^e] keeps its unit.
#: Shaft quantities in N*m (both named systems).
_N_M = {
    "torque": ("N*m", 1000.0),
    "density": ("kg/m^3", 1.0000000000000002e-12),
    "polar moment of inertia": ("kg*m^2", 1000.0),
    "torsional stiffness": ("N*m/rad", 1000.0),
    "torsional damping": ("N*m*s/rad", 1000.0),
    "quadratic torque coefficient": ("N*m*s^2/rad^2", 1000.0),
    "motor-curve slope": ("N*m*s/rad", 1000.0),
}
UNIT_SYSTEMS: dict[str, dict[str, tuple[str, float]]] = {
    "adams": {},
    "engineering": {"angular velocity": ("rpm", 0.10471975511965977), **_N_M},  # 2 pi / 60
    "si": {
        "length": ("m", 1000.0),
        "angle": ("rad", 1.0),
        "angular velocity": ("rad/s", 1.0),
        "velocity": ("m/s", 1000.0),
        "stiffness": ("N/m", 0.001),
        "damping": ("N*s/m", 0.001),
        **_N_M,
    },
}


@functools.cache
def in_system(dim: Dim, system: str | None) -> Dim:
    """``dim`` with the default unit (and factor) of bare numbers in unit ``system`` (a key of
    :data:`UNIT_SYSTEMS`; None: the default, "adams")."""
    unit, factor = UNIT_SYSTEMS.get(system or "adams", {}).get(dim.name, (dim.default,
                                                                           dim.factor))
    if unit == dim.default:
        return dim
    return Dim(dim.name, unit, dim.internal, dim.example, dim.angular, factor)


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
    expected = (f"{article(dim.name)} {dim.name} as a number in {dim.default} or a string "
                f"with units, e.g. {dim.example}")
    if isinstance(value, bool):  # YAML's true/false/yes/no: never a number
        raise UnitError(f"a YAML boolean, not a number; expected {expected}")
    if not isinstance(value, int | float | str):
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
    own = own_unit_quantity(text, dim)
    if own is not None:
        if not math.isfinite(own):
            raise UnitError(f"expected a finite {dim.name}")
        return own
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
    _refuse_turns(q, text, dim)
    try:
        out = float(q.to(dim.internal).magnitude)
    except Exception:
        raise UnitError(
            f"wrong dimension: '{q.units:~}' is not {article(dim.name)} {dim.name}; "
            f"expected {expected}"
        ) from None
    if not math.isfinite(out):
        raise UnitError(f"expected a finite {dim.name}")
    return out


# "<number> <unit>": a decimal literal as pint's tokenizer reads it (an integer without leading
# zeros, or a float literal) and a unit written without spaces. Anything else goes to pint.
_OWN_UNIT = re.compile(
    r"(?P<number>[+-]?(?:(?:0|[1-9][0-9]*)(?P<frac>\.[0-9]*)?|(?P<dot>\.[0-9]+))"
    r"(?P<exp>[eE][+-]?[0-9]+)?)\s*(?P<unit>\S+)"
)


def own_unit_quantity(text: str, dim: Dim) -> float | None:
    """``text`` in ``dim.internal`` when it is a number followed by exactly ``dim.default`` or
    ``dim.internal`` (no pint needed), else None.

    pint reads an integer literal as an int and a float literal with ``float``, and converts
    by one multiplication with the unit's factor (an int becomes a float first, so "-0 mm" is
    0.0, not -0.0); this does the same arithmetic with :attr:`Dim.factor`.
    """
    m = _OWN_UNIT.fullmatch(text)
    if m is None or m["unit"] not in (dim.default, dim.internal):
        return None
    literal = m["number"]
    is_int = m["frac"] is None and m["dot"] is None and m["exp"] is None
    try:
        number = float(int(literal)) if is_int else float(literal)
    except OverflowError:  # an integer beyond float range: pint's message
        return None
    return convert(number, m["unit"], dim)


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
        raise UnitError(f"'Hz' is ambiguous for {article(dim.name)} {dim.name}; expected rev/s, "
                        "rpm, deg/s or rad/s")


def _refuse_turns(q, text: str, dim: Dim) -> None:
    """pint counts a revolution as 2π rad and an angle as dimensionless, so a frequency given
    as a speed ("60000 rpm", "100 rev/s") converts to Hz 2π too large, and a speed given as a
    bare rate ("3000 1/min") to rad/s 2π too small. A frequency counts cycles per time: a unit
    carrying an angle is refused, with the cycles-per-time value it most likely meant (one
    revolution = one cycle); a shaft speed needs its angle (rpm, rev/s, deg/s, rad/s)."""
    if not q.check("1/[time]"):  # another dimension: the conversion says so
        return
    root = q.to_root_units()
    has_angle = "radian" in dict(root.unit_items())
    if dim is FREQUENCY or dim.name == FREQUENCY.name:
        if has_angle:
            hz = float((q / registry().Quantity(2.0 * math.pi, "rad")).to("Hz").magnitude)
            raise UnitError(f"a frequency, not a speed: write '{hz:.12g} Hz' "
                            f"({hz * 60.0:.12g}/min)")
    elif dim.name == ANGULAR_VELOCITY.name and not has_angle:
        rev_s = float(q.to("1/s").magnitude)  # read as revolutions per second
        raise UnitError(f"no angle in the unit, which for {article(dim.name)} {dim.name} "
                        f"is ambiguous (radians or revolutions?); expected e.g. "
                        f"'{rev_s * 60.0:.12g} rpm' or '{rev_s:.12g} rev/s'")


def article(noun: str) -> str:
    """'a' or 'an' before ``noun`` (by its first letter: "an angular velocity")."""
    return "an" if noun[:1].lower() in "aeiou" else "a"


def format_internal(value: float, dim: Dim) -> str:
    """Render an internal value with its internal unit, loadable back exactly."""
    return f"{value!r} {dim.internal}"


def split_internal(value) -> tuple[float, str]:
    """The inverse of :func:`format_internal` for a stored case value: (number, unit) of
    "10.0 mm" -> (10.0, "mm"), of a number -> (it, ""), of None -> (nan, "")."""
    if value is None:
        return math.nan, ""
    if isinstance(value, int | float):
        return float(value), ""
    number, _, unit = str(value).partition(" ")
    return float(number), unit.strip()


def parse_quantities(texts, dim: Dim) -> tuple[float, ...]:
    """Values given as numbers or texts (``2``, ``"2"``, ``"2 s"``), each in the internal unit
    of ``dim``, by the case file's rules (bare numbers in ``dim.default``; a unit needs a
    number in front; plain powers). Raises UnitError with the offending value."""
    from gearcli import guards

    out = []
    for text in texts:
        value = text
        if isinstance(text, str):
            try:
                value = float(text)
            except ValueError:
                try:
                    guards.check_unit_text(text, need_number=True)
                except ValueError as exc:
                    raise UnitError(f"{text!r}: {exc}") from None
        try:
            out.append(parse_quantity(value, dim))
        except UnitError as exc:
            raise UnitError(f"{text!r}: {exc}") from None
    return tuple(out)
