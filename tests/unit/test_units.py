"""Unit parsing at the edge: default units, explicit unit strings, wrong dimensions."""

import math

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
