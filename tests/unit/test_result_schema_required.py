"""`gearcli schema --results --kind rating|monitor` (results/schema._deep) require every key the
documents always write: a rating.json or monitor.json missing one is refused, at the top and in
nested documents, while what the writers leave out (``omit_none``: the simulated column's
missing σ_F peaks) or write as null (an infinite life) stays valid.

Before this check the two schemas had no ``required`` at all and accepted ``{}``.
"""

from __future__ import annotations

import copy
import json

import jsonschema
import pytest

from gearcli.pipeline.rating import SimulatedLoad, rate_case
from gearcli.results import json_schema
from gearcli.results.monitor import MonitorDocument, ShaftMonitor
from tests.unit.test_typed_rating_modal import NREL, OVERRIDES


@pytest.fixture(scope="module")
def rating_json():
    """rating.json with every part: Method B K_v, a duty cycle, an infinite life (null) and a
    simulated column whose σ_F peaks are left out."""
    rated = rate_case(NREL, OVERRIDES, simulated=SimulatedLoad(
        1.3, sigma_H_peak_MPa=(1100.0, 1000.0)))
    return json.loads(json.dumps(rated.to_dict()))


def test_a_full_rating_json_is_valid_and_one_without_a_key_is_not(rating_json):
    schema = json_schema("rating")
    jsonschema.validate(rating_json, schema)
    assert None in (rating_json["iso"]["pinion"]["life_pitting_h"],
                    rating_json["iso"]["gear"]["life_pitting_h"])  # null lives: valid
    assert "S_F" not in rating_json["simulated"]["peaks"]["pinion"]  # omitted: valid
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate({}, schema)
    for path in (("verdict",), ("iso", "pinion", "S_H"), ("load", "life_h"),
                 ("editions", 0, "2019"), ("iso", "pair", 0, "value")):
        doc = copy.deepcopy(rating_json)
        parent = doc
        for key in path[:-1]:
            parent = parent[key]
        del parent[path[-1]]
        with pytest.raises(jsonschema.ValidationError, match="required property"):
            jsonschema.validate(doc, schema)


def test_monitor_json_requires_its_keys():
    shaft = ShaftMonitor(shaft="pinion", teeth=17, n_revolutions=3, samples_per_revolution=64,
                         normalisation="own", metrics={"rms": 1.0}, tsa=(0.0, 1.0))
    doc = MonitorDocument(case="seed", run="out", signal="TE", signal_unit="µm",
                          window_s=(1.0, 2.0), window_reason="steady",
                          shafts=(shaft,)).to_dict()
    schema = json_schema("monitor")
    jsonschema.validate(doc, schema)  # baseline None: null, valid
    for drop in ("case", "shafts"):
        with pytest.raises(jsonschema.ValidationError, match="required property"):
            jsonschema.validate({k: v for k, v in doc.items() if k != drop}, schema)
    bad = copy.deepcopy(doc)
    del bad["shafts"][0]["n_revolutions"]
    with pytest.raises(jsonschema.ValidationError, match="required property"):
        jsonschema.validate(bad, schema)
