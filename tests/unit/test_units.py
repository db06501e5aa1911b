"""Unit parsing at the edge: default units, explicit unit strings, wrong dimensions."""

import math
import random

import pytest

from gearcli import units
from gearcli.units import UnitError, parse_quantity

ALL_DIMS = [v for v in vars(units).values() if isinstance(v, units.Dim)]


@pytest.mark.parametrize("dim", ALL_DIMS, ids=lambda d: d.name)
def test_default_factor_matches_pint(dim):
    # The literal factors (used without importing pint) must agree with pint to rounding.
    expected = units.registry().Quantity(1.0, dim.default).to(dim.internal).magnitude
    assert dim.factor == pytest.approx(expected, rel=1e-15)


@pytest.mark.parametrize(
    "value, dim, expected",
    [
        ("450 N*m", units.TORQUE, 4.5e5),
        ("4.5e5 N*mm", units.TORQUE, 4.5e5),
        (4.5e5, units.TORQUE, 4.5e5),
        ("3000 deg/s", units.ANGULAR_VELOCITY, 3000 * math.pi / 180),
        ("500 rpm", units.ANGULAR_VELOCITY, 500 * 2 * math.pi / 60),
        ("50 rev/s", units.ANGULAR_VELOCITY, 100 * math.pi),
        ("7.85e-6 kg/mm^3", units.DENSITY, 7.85e-9),
        ("7850 kg/m^3", units.DENSITY, 7.85e-9),
        ("2.07e5 MPa", units.STRESS, 2.07e5),
        ("207 GPa", units.STRESS, 2.07e5),
        ("0.1 mm", units.LENGTH, 0.1),
        ("1 kg*m^2", units.INERTIA, 1000.0),  # 1 kg m^2 = 1e-3 t * 1e6 mm^2
        ("20 deg", units.ANGLE, math.radians(20)),
        ("1e5", units.LENGTH, 1e5),  # YAML 1.1 reads 1e5 as a string
    ],
)
def test_parse_quantity(value, dim, expected):
    assert parse_quantity(value, dim) == pytest.approx(expected, rel=1e-12)


def test_fractional_exponent_stiffness():
    dim = units.contact_stiffness_dim(1.5)
    assert parse_quantity("1e5 N/mm^1.5", dim) == pytest.approx(1e5)
    # 1 N/m^1.5 = 1 N / (1000 mm)^1.5
    assert parse_quantity("1e5 N/m^1.5", dim) == pytest.approx(1e5 / 1000**1.5)
    with pytest.raises(UnitError, match="not a contact stiffness"):
        parse_quantity("1e5 N/mm", dim)


@pytest.mark.parametrize(
    "value, dim, match",
    [
        ("450 N", units.TORQUE, "wrong dimension"),
        ("10 furlongz", units.LENGTH, "cannot parse units"),
        ("3 N*", units.LENGTH, "cannot parse units"),
        (float("nan"), units.LENGTH, "finite"),
        ("inf mm", units.LENGTH, "finite"),
        (True, units.LENGTH, "expected a length"),
        ([1, 2], units.LENGTH, "expected a length"),
        ("3 Hz", units.ANGULAR_VELOCITY, "ambiguous"),
    ],
)
def test_parse_quantity_errors(value, dim, match):
    with pytest.raises(UnitError, match=match):
        parse_quantity(value, dim)


def test_internal_round_trip():
    for dim in ALL_DIMS:
        v = parse_quantity("1.2345 " + dim.default, dim)
        assert parse_quantity(units.format_internal(v, dim), dim) == v


# Number literals of every form the fast path takes (pint reads integers as int, the rest with
# float; signs are pint's unary operators), as the default and as the internal unit.
LITERALS = ["5", "0", "-0", "+7", "-0.0", "1e5", "1E-3", ".5", "5.", "-2.5e+3", "3000",
            "123456789012345678901234567890", "0.1", "7.85e-6", "2.07e5", "1e-300", "450000"]


@pytest.mark.parametrize("dim", ALL_DIMS + [units.contact_stiffness_dim(1.5)],
                         ids=lambda d: d.name)
def test_own_unit_path_is_bit_identical_to_pint(dim):
    ureg = units.registry()
    rng = random.Random(16)
    numbers = LITERALS + [repr(rng.uniform(-1e4, 1e4)) for _ in range(50)] + \
        [repr(10.0 ** rng.uniform(-12, 12)) for _ in range(50)]
    for unit in {dim.default, dim.internal}:
        for number in numbers:
            for text in (f"{number} {unit}", f"{number}{unit}"):
                fast = units.own_unit_quantity(text, dim)
                slow = float(ureg.Quantity(text).to(dim.internal).magnitude)
                assert fast is not None, text
                assert math.copysign(1.0, fast) == math.copysign(1.0, slow), text
                assert fast == slow, text


@pytest.mark.parametrize("text", ["450 N*m", "5 N * mm", "07 N*mm", "1_000 N*mm", "2*3 N*mm",
                                  "inf N*mm", "1/2 N*mm", "N*mm"])
def test_own_unit_path_leaves_the_rest_to_pint(text):
    assert units.own_unit_quantity(text, units.TORQUE) is None
