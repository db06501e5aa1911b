"""The report's case-settings tables read the typed case (gearcli.case.schema.Case, internal
units), not the stored case's dict: a value the case sets is shown in the display units with
the unit its schema field records, and a schema key the tables read that is renamed fails
loudly instead of leaving an empty cell (issue 27)."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from gearcli.case.load import load_case
from gearcli.case.schema_mods import Relief
from gearcli.report import tables
from tests.conftest import SEED

MODS = ["modifications.tip_relief.pinion={amount: 0.05, length: 6, shape: parabolic}",
        "errors.runout.gear={eccentricity: 0.02, phase: 30}",
        "errors.pitch_deviation.pinion={values: [0.001, -0.002" + ", 0" * 15 + "]}",
        "gears.gear.bore_diameter=40", "friction.stiction_velocity=0.02"]


def _data(overrides: list[str], units: str = "engineering"):
    """What the case tables read of a ReportData: the typed case and the display units (no
    geometry, no run; the drive table's run cells are not asserted here)."""
    case = load_case(SEED, overrides).case
    scalars = SimpleNamespace(mesh_stiffness_N_mm=None, output_rate_Hz=1000.0)
    return SimpleNamespace(case=case, geometry=None, units=units, scalars=scalars,
                           run=SimpleNamespace(summary=SimpleNamespace(rows=10)),
                           folder="<test>")


def _rows(table) -> dict[str, tuple[str, ...]]:
    return {row[0]: row[1:] for row in table.rows}


def test_modifications_table_shows_the_typed_cases_reliefs_and_errors():
    rows = _rows(tables.modifications_table(_data(MODS)))
    assert rows == {
        "pinion tip relief": ("amount = 0.05 mm, length = 6 mm, shape = parabolic",),
        "gear runout": ("eccentricity = 0.02 mm, phase = 30 deg",),
        # a list of lengths (one per pinion tooth): each value with its unit
        "pinion pitch deviation": ("values = 0.001 mm, -0.002 mm" + ", 0 mm" * 15
                                   + ", seed = 0",),
    }
    assert tables.modifications_table(_data([])) is None  # the seed sets none


def test_settings_are_shown_in_the_display_units_of_their_schema_field():
    # the values are floats in internal units (mm, mm/s, rad/s); the unit comes from the
    # schema field (case/types.field_dim), converted by display_units
    eng, si = _data(MODS), _data(MODS, "si")
    assert _rows(tables.gears_table(eng))["bore diameter"] == ("–", "40 mm")
    assert _rows(tables.gears_table(si))["bore diameter"] == ("–", "0.04 m")
    assert _rows(tables.gears_table(eng))["pressure angle α"] == ("20 deg", "20 deg")
    assert _rows(tables.contact_table(eng))["stiction velocity v_s"] == ("0.02", "mm/s")
    assert _rows(tables.contact_table(si))["stiction velocity v_s"] == ("2e-05", "m/s")
    drive = _rows(tables.drive_table(eng))
    assert drive["drive (pinion)"] == ("speed: STEP(time, 0, 0, 1, 3000) [deg/s]",)
    assert drive["end time"] == ("5 s",)
    # a shaft drive prescribes drive.speed too (the stored dict's drive["shaft"] printed " []")
    shaft = _rows(tables.drive_table(_data(["drive.type=shaft", "drive.shaft={stiffness: 1e7}"])))
    assert shaft["drive (pinion)"] == ("shaft: STEP(time, 0, 0, 1, 3000) [deg/s]",)
    assert shaft["drive shaft"] == ("stiffness 10000 N·m/rad; damping 0 N·m·s/rad",)


def test_a_renamed_schema_field_fails_loudly(monkeypatch):
    data = _data(MODS)
    # the tables iterate the schema's fields and read each as an attribute: a field the
    # model no longer has (a rename half done) is an error, not a silently empty cell
    fields = dict(Relief.model_fields)
    fields["amount_mm"] = fields.pop("amount")
    monkeypatch.setattr(Relief, "model_fields", fields)
    with pytest.raises(AttributeError, match="amount_mm"):
        tables.modifications_table(data)


def test_a_renamed_case_attribute_fails_loudly():
    # a table reading a key the typed case no longer has raises (the dict's .get() gave "–")
    data = _data([])
    friction = data.case.friction.model_copy()
    object.__getattribute__(friction, "__dict__").pop("stiction_velocity")
    data.case = data.case.model_copy(update={"friction": friction})
    with pytest.raises(AttributeError, match="stiction_velocity"):
        tables.contact_table(data)


def test_the_tables_need_the_typed_case():
    data = _data([])
    data.case = None
    with pytest.raises(ValueError, match="typed case"):
        tables.gears_table(data)
