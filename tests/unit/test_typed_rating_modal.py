"""rating.json and the modal JSON's ``linearisation`` as typed documents (issue 27): built from
the pipeline's results, written with ``to_dict()``, read back with ``from_document()`` to the
same document, and the same JSON as the model's own rows (gearcli/model/iso6336, the writer
of rating.json before it had a typed document)."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import pytest

from gearcli.errors import ResultsError
from gearcli.io.results import read_rating
from gearcli.pipeline.rating import SimulatedLoad, rate_case
from gearcli.results import ModalDocument, json_schema
from gearcli.results.models import Linearisation
from gearcli.results.rating_document import EditionRowDocument, RatingDocument

CASES = Path(__file__).resolve().parents[2] / "cases"
NREL = CASES / "nrel5mw_sun_planet.yaml"
#: K_v by Method B (load.iso_dynamic), two duty-cycle bins, and S_H,min 1.2: the sun's flank
#: life at S_H,min is then infinite (null in the JSON), as is the damage of its bin
OVERRIDES = ["rating.dynamic_factor=iso", "rating.minimum_safety.pitting=1.2",
             "rating.duty_cycle=[{torque: 108070.365564, speed: 246.77511, time_share: 0.5}, "
             "{torque: 50000, speed: 100, time_share: 0.5}]"]


@pytest.fixture(scope="module")
def rated():
    """The rating with every part of rating.json: the simulated column with peaks of σ_H
    only (the σ_F entries are left out of ``peaks``)."""
    return rate_case(NREL, OVERRIDES, simulated=SimulatedLoad(
        1.3, sigma_H_peak_MPa=(1100.0, 1000.0)))


def test_rating_json_reads_back_to_the_same_document(rated, tmp_path):
    doc = rated.document()
    text = json.dumps(rated.to_dict(), indent=2) + "\n"
    data = json.loads(text)
    assert data["load"]["iso_dynamic"] is not None and data["duty_cycle"] is not None
    assert data["simulated"]["peaks"]["pinion"].keys() == {
        "sigma_H_peak_MPa", "sigma_H_MPa", "S_H", "S_H_min"}
    assert None in (data["iso"]["pinion"]["life_pitting_h"], data["iso"]["gear"]["life_pitting_h"])
    back = RatingDocument.from_document(data)
    assert back == doc  # every field, nested documents and tuples included
    assert json.dumps(back.to_dict(), indent=2) + "\n" == text  # same keys, order, values
    (tmp_path / "rating.json").write_text(text)
    assert read_rating(tmp_path / "rating.json") == doc


def test_rating_document_is_the_models_rows(rated):
    """The typed document writes what the model's rows write (to_dict of
    gearcli/model/iso6336: the factors, safeties, lives, inspection dimensions, damages and
    edition rows), key for key."""
    data = rated.to_dict()
    assert data["iso"] == rated.iso.to_dict()
    sim = dict(data["simulated"])
    peaks = sim.pop("peaks")
    assert sim == rated.simulated.to_dict()
    assert peaks == {k: v.to_dict() for k, v in rated.simulated_peaks.items()}
    assert data["duty_cycle"] == rated.duty_cycle.to_dict()
    assert data["editions"] == [r.to_dict() for r in rated.editions]
    assert list(data) == ["schema_version", "case", "method", "edition", "verdict", "load",
                          "iso", "duty_cycle", "simulated", "editions", "notes"]
    assert data["load"]["iso_dynamic"]["k_v"] == rated.iso.factor("K_v").value


def test_rating_without_run_or_duty_cycle_has_nulls():
    r = rate_case(NREL)
    data = json.loads(json.dumps(r.to_dict()))
    assert data["simulated"] is None and data["duty_cycle"] is None
    assert data["load"]["iso_dynamic"] is None
    back = RatingDocument.from_document(data)
    assert back.simulated is None and back.duty_cycle is None and back == r.document()


def test_edition_rows_keep_their_year_keys():
    row = EditionRowDocument(symbol="Y_M", gear="gear", value_2006=0.7, value_2019=0.8,
                             unit="-", differs=True)
    data = row.to_dict()
    assert list(data) == ["symbol", "gear", "2006", "2019", "unit", "differs"]
    assert EditionRowDocument.from_document(data) == row


@pytest.mark.parametrize("text, message", [
    ("[1, 2]", "not a rating.json"),
    ('{"schema_version": 999, "iso": {}}', "schema_version 999"),
    ('{"iso": {"pinion": 3}}', "unreadable rating"),
    # a text where a nested document belongs was read as that document's defaults (NaN)
    ('{"iso": {"pinion": "x"}}', "GearRatingDocument: expected an object, got str"),
    ('{"iso": {}, "editions": [1]}', "EditionRowDocument: expected an object, got int"),
    # a text for a number was shown as written ("big" as the pinion's S_H in the report)
    ('{"iso": {"pinion": {"S_H": "big"}}}', r"GearRatingDocument\.S_H: expected int or float"),
    ('{"iso": {"pinion": {"S_H": true}}}', r"GearRatingDocument\.S_H: expected int or float"),
    ("{", "unreadable JSON"),
])
def test_read_rating_refuses_what_is_not_a_rating(tmp_path, text, message):
    path = tmp_path / "rating.json"
    path.write_text(text)
    with pytest.raises(ResultsError, match=message):
        read_rating(path)


#: The keys of the modal JSON's linearisation, in order, as `gearcli modal --json` wrote them
#: before they were a typed document.
LINEARISATION_KEYS = ["static_force_N", "static_deflection_mm", "pair_stiffness_N_mm",
                      "mesh_stiffness_N_mm", "single_pair_stiffness_N_mm",
                      "double_pair_stiffness_N_mm", "mesh_damping_Ns_mm",
                      "motor_curve_damping_Nmms_rad", "load_quadratic_damping_Nmms_rad",
                      "friction"]


@pytest.mark.parametrize("case", ["seed.yaml", "drivetrain.yaml"])
def test_modal_linearisation_reads_back_typed(case):
    from gearcli.pipeline.modal import modal_document, run_modal

    doc = modal_document(run_modal(CASES / case))
    assert isinstance(doc.linearisation, Linearisation)
    text = json.dumps(doc.to_dict(), indent=2)
    data = json.loads(text)
    assert list(data["linearisation"]) == LINEARISATION_KEYS
    assert data["linearisation"]["friction"] == "off"
    back = ModalDocument.from_document(data)
    assert isinstance(back.linearisation, Linearisation)
    assert back.linearisation == doc.linearisation
    assert json.dumps(back.to_dict(), indent=2) == text


def test_modal_schema_describes_the_linearisation_fields():
    lin = json_schema("modal")["properties"]["linearisation"]
    fields = [f.name for f in dataclasses.fields(Linearisation)]
    assert fields == LINEARISATION_KEYS and list(lin["properties"]) == fields
    assert "[N/mm]" in lin["properties"]["mesh_stiffness_N_mm"]["description"]
    assert all(p["description"] for p in lin["properties"].values())


def test_rating_schema_describes_every_field_and_refuses_a_wrong_type(tmp_path):
    """`gearcli schema --results --kind rating`: every field of the typed document (nested
    ones included, the editions under their JSON keys "2006"/"2019") with its description; a
    rating.json whose safety is text is refused."""
    import jsonschema

    schema = json_schema("rating")
    assert set(schema["properties"]) == {f.name for f in dataclasses.fields(RatingDocument)}
    row = schema["properties"]["editions"]["items"]["properties"]
    assert {"2006", "2019"} <= set(row) and "value_2006" not in row
    assert len(row) == len(dataclasses.fields(EditionRowDocument))
    assert all(p.get("description") for p in row.values())
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate({"schema_version": schema["properties"]["schema_version"]["const"],
                             "case": "x", "iso": {"pinion": {"S_H": "high"}}}, schema)
