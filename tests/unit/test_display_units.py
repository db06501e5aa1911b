"""Display units (gearcli/display_units.py, issue 19): every conversion factor against pint's,
an independent implementation of the same unit definitions, and the command line's --units."""

from __future__ import annotations

import math

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.display_units import _TABLE, SYSTEMS, convert, unit_and_factor

runner = CliRunner()

#: How pint spells our display units (the tables print the typographic forms).
PINT = {"N·m": "N*m", "N/µm": "N/um", "N·s/mm": "N*s/mm", "N·s/m": "N*s/m",
        "N·m/rad": "N*m/rad", "N·m·s/rad": "N*m*s/rad", "N·m·s²/rad²": "N*m*s**2/rad**2",
        "kg·m²": "kg*m**2", "kg/m³": "kg/m**3", "µm": "um", "N/(mm·µm)": "N/(mm*um)",
        "N/m²": "N/m**2", "N/mm (line load)": "N/mm"}


@pytest.mark.parametrize("stored", sorted(u for u in _TABLE if u != "fraction"))
@pytest.mark.parametrize("system", SYSTEMS)
def test_every_factor_equals_pints_conversion(stored, system):
    from gearcli.units import registry

    ureg = registry()
    shown, factor = unit_and_factor(stored, system)
    expected = ureg.Quantity(1.0, PINT.get(stored, stored.replace("^", "**"))).to(
        PINT.get(shown, shown))
    assert factor == pytest.approx(expected.magnitude, rel=1e-12)


def test_deflections_in_micrometres_and_fractions_in_percent():
    assert convert(0.0084, "mm", "engineering", fine=True) == (pytest.approx(8.4), "µm")
    assert convert(0.0084, "mm", "si", fine=True) == (pytest.approx(8.4e-6), "m")
    assert convert(0.0084, "mm", "engineering") == (0.0084, "mm")  # a length, not a deflection
    assert convert(0.055, "fraction", "si") == (pytest.approx(5.5), "%")
    assert convert([3000.0, None], "deg/s", "engineering") == ([pytest.approx(500.0), None],
                                                               "rpm")
    assert convert(12.0, "Hz", "si") == (12.0, "Hz")  # not listed: as stored
    with pytest.raises(ValueError, match="engineering, si"):
        unit_and_factor("mm", "imperial")


def test_cli_units_option_and_environment(monkeypatch):
    seed = "cases/seed.yaml"
    eng = runner.invoke(app, ["geometry", seed])
    si = runner.invoke(app, ["--units", "si", "geometry", seed])
    assert eng.exit_code == 0 and si.exit_code == 0
    assert "500 │ rpm" in eng.output
    assert f"{math.radians(3000):.6g} │ rad/s" in si.output
    d_row = next(line for line in si.output.splitlines() if "reference diameter d " in line)
    assert [c.strip() for c in d_row.split("│")[2:5]] == ["0.17", "0.25", "m"]  # 170/250 mm
    monkeypatch.setenv("GEARCLI_UNITS", "si")
    assert "rad/s" in runner.invoke(app, ["geometry", seed]).output
    bad = runner.invoke(app, ["--units", "imperial", "geometry", seed])
    assert bad.exit_code == 1 and "--units imperial: expected one of engineering, si" in \
        bad.output
    monkeypatch.setenv("GEARCLI_UNITS", "imperial")  # named as the user gave it
    bad = runner.invoke(app, ["geometry", seed])
    assert bad.exit_code == 1 and "GEARCLI_UNITS=imperial: expected one of engineering, si" in \
        bad.output


def test_options_take_quantities_with_units():
    a = runner.invoke(app, ["modal", "cases/seed.yaml", "--json", "--speed-range", "0 rpm",
                            "6000 rpm"])
    b = runner.invoke(app, ["modal", "cases/seed.yaml", "--json", "--speed-range", "0",
                            "36000"])
    assert a.exit_code in (0, 4) and a.output == b.output  # 6000 rpm = 36000 deg/s
    bad = runner.invoke(app, ["modal", "cases/seed.yaml", "--speed-range", "0", "6000 Hz"])
    assert bad.exit_code == 1 and "--speed-range '6000 Hz'" in bad.output


def test_table_headers_keep_their_bracketed_units():
    """rich reads "[m]", "[rpm]" or "[rad/s]" as markup and drops it: the CLI escapes them."""
    modal = runner.invoke(app, ["--units", "si", "modal", "cases/seed.yaml"])
    assert "pinion speed [rad/s]" in modal.output
    mesh = runner.invoke(app, ["--units", "si", "mesh", "cases/iso_pair.yaml", "--harris"])
    assert mesh.exit_code == 0 and "STE peak-to-peak [m]" in mesh.output
    assert "resonance speed n_E1 (both gears free)" in mesh.output
