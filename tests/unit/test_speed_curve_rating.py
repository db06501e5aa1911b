"""S_H and S_F against speed (issue 28): each level of a speed curve rated by ISO 6336 with its
own speed and its dynamic factor as K_v (pipeline/run_rating.level_safeties), in summary.csv,
speed_curve.json and speed_curve_rating.png.

Anchor: the NREL sun–planet case at its own speed with the printout's K_v 1.06 is the printed
rating (KISSsoft: S_H 1.21/1.38, S_F 2.82/2.04): the smaller S_H is the sun's 1.21, the smaller
S_F the planet's 2.04. Other speeds and K_v are checked against the rating of the case with
drive.speed set to that speed (the path through the case file, not the replaced input).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pandas as pd
import pytest
from typer.testing import CliRunner

from gearcli.case.load import load_case
from gearcli.cli import app
from gearcli.pipeline.rating import SimulatedLoad, rate_case
from gearcli.pipeline.run_rating import level_safeties
from tests.unit.test_iso6336_anchor import within_print

ROOT = Path(__file__).resolve().parents[2]
NREL = str(ROOT / "cases" / "nrel5mw_sun_planet.yaml")
ISO_PAIR = ROOT / "cases" / "iso_pair.yaml"


def test_level_at_the_case_speed_and_printed_kv_is_the_printed_rating():
    (s_h, s_f), = level_safeties(load_case(NREL), [(246.77511, 1.06)])
    assert within_print(s_h, "1.21") and within_print(s_f, "2.04")


@pytest.mark.parametrize("rpm, k_v", [(120.0, 1.0), (400.0, 1.45)])
def test_level_equals_the_case_rated_at_that_speed(rpm, k_v):
    """Same arithmetic on the same inputs by two paths: rel 1e-12."""
    loaded = load_case(NREL)
    (s_h, s_f), = level_safeties(loaded, [(rpm, k_v)])
    at = rate_case(NREL, [f"drive.speed={rpm} rpm"], simulated=SimulatedLoad(k_v)).simulated
    assert s_h == pytest.approx(min(at.pinion.S_H, at.gear.S_H), rel=1e-12)
    assert s_f == pytest.approx(min(at.pinion.S_F, at.gear.S_F), rel=1e-12)


def test_no_rating_without_limits_or_dynamic_factor():
    assert all(math.isnan(x) for x in level_safeties(load_case(ISO_PAIR), [(1000.0, 1.2)])[0])
    assert all(math.isnan(x) for x in level_safeties(load_case(NREL), [(200.0, math.nan)])[0])


def test_speed_curve_writes_the_safeties_per_speed(tmp_path):
    study = tmp_path / "rated.yaml"
    study.write_text(f"""name: rated
base: {ISO_PAIR}
set:
  material.contact_fatigue_limit: 1500 MPa
  material.bending_fatigue_limit: 430 MPa
design: speed_curve
parameters:
  mesh_frequency: {{values: ["1000 Hz", "1600 Hz"]}}
""")
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["sweep", str(study), "-o", str(out), "--jobs", "1"])
    assert res.exit_code == 0, res.output
    df = pd.read_csv(out / "summary.csv")
    assert {"safety_pitting_min", "safety_bending_min"} <= set(df.columns)
    loaded = load_case(ISO_PAIR, ["material.contact_fatigue_limit=1500 MPa",
                                  "material.bending_fatigue_limit=430 MPa"])
    expected = level_safeties(loaded, list(zip(df["pinion_speed [rpm]"], df["dynamic_factor"],
                                               strict=True)))
    for (s_h, s_f), got_h, got_f in zip(expected, df["safety_pitting_min"],
                                        df["safety_bending_min"], strict=True):
        assert got_h == pytest.approx(s_h, rel=1e-9) and got_f == pytest.approx(s_f, rel=1e-9)
    doc = json.loads((out / "speed_curve.json").read_text())
    assert doc["rating"]["minimum_safety"] == {"pitting": 1.0, "bending": 1.0}
    assert (out / doc["rating"]["figure"]).stat().st_size > 10_000
