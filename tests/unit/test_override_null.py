"""`--set key=null` removes the key, so its default applies (the null of a JSON Merge Patch,
RFC 7396): a case written for one contact law can be run under the other from the command line,
and an optional value can be given back to its default."""

from __future__ import annotations

from pathlib import Path

import pytest

from gearcli.case.load import load_case
from gearcli.case.overrides import apply_overrides
from gearcli.case.schema import Case
from gearcli.errors import CaseError

SEED = Path(__file__).resolve().parents[2] / "cases" / "seed.yaml"
IMPACT_KEYS = ("stiffness", "exponent", "max_damping", "penetration_depth")


def test_null_removes_the_key_and_leaves_the_rest():
    data = {"contact": {"law": "impact", "stiffness": 1e5, "exponent": 1.5}, "run": {}}
    out = apply_overrides(data, ["contact.stiffness=null", "contact.exponent=~"], Case)
    assert out == {"contact": {"law": "impact"}, "run": {}}
    assert data["contact"]["stiffness"] == 1e5  # the input is not changed
    # removing what is not there changes nothing and creates no section
    assert apply_overrides({}, ["friction.static_coefficient=null"], Case) == {}


def test_an_impact_case_runs_the_tooth_law_with_its_keys_nulled():
    with pytest.raises(CaseError, match="contact.stiffness"):
        load_case(SEED, ["contact.law=tooth"])  # the IMPACT keys do not apply to it
    loaded = load_case(SEED, ["contact.law=tooth", *(f"contact.{k}=null" for k in IMPACT_KEYS)])
    assert loaded.case.contact.law == "tooth"


def test_null_gives_an_optional_value_back_to_its_default():
    plain = load_case(SEED).case
    loaded = load_case(SEED, ["run.max_step=1 ms", "run.max_step=null"]).case
    assert loaded.run.max_step is None and loaded.run.max_step == plain.run.max_step
