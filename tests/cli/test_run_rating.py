"""`gearcli run` rates the pair (issue 28): rating.json with the ISO column and the simulated
one (K_v = the run's F_max/F_static), and a "Rating (ISO 6336)" section in the report; a case
without fatigue limits gets one line saying what is missing.

Check of the two columns: they differ only in K_v (and what follows from it), so by ISO 6336-2
(σ_H ∝ √(K_A K_γ K_v K_Hβ K_Hα)) and ISO 6336-3 (σ_F ∝ K_A K_γ K_v K_Fβ K_Fα) the safeties'
ratio is that of the factor products; pure arithmetic on printed floats: rel 1e-9.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import jsonschema
import pytest
from typer.testing import CliRunner

from gearcli.case.load import load_case
from gearcli.cli import app
from gearcli.pipeline.run_rating import simulated_safeties
from gearcli.results import SummaryDocument, json_schema, sweep_metrics

runner = CliRunner()
ISO_PAIR = str(Path(__file__).resolve().parents[2] / "cases" / "iso_pair.yaml")
SHORT = ["--set", "run.end_time=0.3", "--format", "md", "-q"]
LIMITS = ["--set", "material.contact_fatigue_limit=1500",
          "--set", "material.bending_fatigue_limit=430"]


def _k(column: dict, *symbols: str) -> float:
    rows = {f["symbol"]: f["value"] for f in column["pair"]}
    return math.prod(rows[s] for s in symbols)


def test_run_writes_rating_json_with_both_columns_and_the_report_section(tmp_path):
    out = tmp_path / "rated"
    res = runner.invoke(app, ["run", ISO_PAIR, "-o", str(out), *SHORT, *LIMITS])
    assert res.exit_code == 0, res.output
    rating = json.loads((out / "rating.json").read_text())
    jsonschema.validate(rating, json_schema("rating"))  # `gearcli schema --results --kind rating`
    iso, sim = rating["iso"], rating["simulated"]
    assert sim is not None
    summary = json.loads((out / "summary.json").read_text())["scalars"]
    k_v_run = summary["force_max_N"] / summary["force_static_N"]
    assert _k(sim, "K_v") == pytest.approx(k_v_run, rel=1e-9)
    h = _k(iso, "K_v", "K_Hβ", "K_Hα") / _k(sim, "K_v", "K_Hβ", "K_Hα")
    f = _k(iso, "K_v", "K_Fβ", "K_Fα") / _k(sim, "K_v", "K_Fβ", "K_Fα")
    for role in ("pinion", "gear"):
        assert sim[role]["S_H"] == pytest.approx(iso[role]["S_H"] * math.sqrt(h), rel=1e-9)
        assert sim[role]["S_F"] == pytest.approx(iso[role]["S_F"] * f, rel=1e-9)
    # summary.json carries the safeties of both columns as typed fields, valid by the schema
    doc = json.loads((out / "summary.json").read_text())
    jsonschema.validate(doc, json_schema("summary"))
    typed = SummaryDocument.from_document(doc).rating
    assert typed.edition == rating["edition"] and typed.verdict == rating["verdict"]
    for column, full in ((typed.iso, iso), (typed.simulated, sim)):
        assert column.dynamic_factor == _k(full, "K_v")
        for role in ("pinion", "gear"):
            g, f = getattr(column, role), full[role]
            assert (g.S_H, g.S_H_min, g.pitting) == (f["S_H"], f["S_H_min"], f["pitting"])
            assert (g.S_F, g.S_F_min, g.bending) == (f["S_F"], f["S_F_min"], f["bending"])
        assert column.safety_pitting_min == min(full[r]["S_H"] for r in ("pinion", "gear"))
    for role in ("pinion", "gear"):
        assert getattr(typed.simulated, role).S_H_peak == sim["peaks"][role]["S_H"]
    assert typed.iso.pinion.S_H_peak is None and "S_H_peak" not in doc["rating"]["iso"]["gear"]
    # the stress evaluation the simulated column comes from: the Stress section and its figure
    stress = json.loads((out / "stress.json").read_text())
    for role in ("pinion", "gear"):
        assert sim["peaks"][role]["sigma_H_peak_MPa"] == stress[role]["peak_sigma_H"]["MPa"]
        assert sim["peaks"][role]["sigma_F_peak_MPa"] == stress[role]["peak_sigma_F"]["MPa"]
    report = (out / "report.md").read_text()
    assert "stars mark the critical positions" in report
    assert "span W\\_k, nominal, pinion / gear" in report  # the geometry table's inspection
    assert (out / "figures" / "stress.png").is_file()
    assert "## Rating (ISO 6336)" in report
    section = report.split("## Rating (ISO 6336)")[1].split("\n## ")[0]
    assert "| pinion | S\\_H |" in section and "| gear | S\\_F |" in section
    assert "simulated" in section and "Not rated" not in section
    # the sweep's metrics: the same rating from the point's dynamic factor alone
    loaded = load_case(ISO_PAIR, ["run.end_time=0.3", "material.contact_fatigue_limit=1500",
                                  "material.bending_fatigue_limit=430"])
    s_h, s_f = simulated_safeties(loaded, summary["dynamic_factor"])
    assert s_h == pytest.approx(min(sim[r]["S_H"] for r in ("pinion", "gear")), rel=1e-9)
    assert s_f == pytest.approx(min(sim[r]["S_F"] for r in ("pinion", "gear")), rel=1e-9)
    assert simulated_safeties(load_case(ISO_PAIR), 1.3) == (None, None)
    assert "safety_pitting_min" in sweep_metrics("sweep")


def test_run_without_limits_says_what_is_missing(tmp_path):
    out = tmp_path / "unrated"
    res = runner.invoke(app, ["run", ISO_PAIR, "-o", str(out), *SHORT])
    assert res.exit_code == 0, res.output
    assert not (out / "rating.json").exists() and not (out / "stress.json").exists()
    assert "rating" not in json.loads((out / "summary.json").read_text())
    section = (out / "report.md").read_text().split("## Rating (ISO 6336)")[1].split("\n## ")[0]
    lines = [x for x in section.strip().splitlines() if x.strip()]
    assert len(lines) == 1 and lines[0].startswith("Not rated")
    text = lines[0].replace("\\", "")  # Markdown escapes the underscores
    assert "pinion contact_fatigue_limit" in text and "gear bending_fatigue_limit" in text


def test_run_of_a_pair_below_its_minimum_safety_exits_4_and_says_so(tmp_path):
    # a contact fatigue limit far below the case's contact stress: S_H < S_H,min in both
    # columns, so the run's exit is 4 (a finding) even when the dynamics' checks pass
    out = tmp_path / "weak"
    weak = ["--set", "material.contact_fatigue_limit=200",
            "--set", "material.bending_fatigue_limit=430"]
    res = runner.invoke(app, ["run", ISO_PAIR, "-o", str(out), "--set", "run.end_time=0.3",
                              "--format", "md", *weak])
    assert res.exit_code == 4, res.output
    assert "ISO 6336 rating (rating.json)" in res.output
    lines = [ln for ln in res.output.splitlines() if ln.startswith("rating (")]
    assert len(lines) == 2 and all(ln.endswith("FAIL") for ln in lines), lines
    assert json.loads((out / "rating.json").read_text())["verdict"] == "fail"


def test_a_run_off_its_operating_point_gets_no_simulated_rating_column(tmp_path):
    # iso_pair ended at 0.15 s, inside its 0.2 s ramps: its F_max/F_static (1.0) is no
    # operating point's dynamic factor; measured before: the simulated column rated with it
    # (the NREL case ended at 0.15 s: S_H 1.113 from its transient's 1.25) with no word of it
    out = tmp_path / "short"
    res = runner.invoke(app, ["run", ISO_PAIR, "-o", str(out), "--set", "run.end_time=0.15",
                              "--format", "md", *LIMITS])
    assert res.exit_code in (0, 4), res.output
    rating = json.loads((out / "rating.json").read_text())
    assert rating["simulated"] is None and rating["iso"] is not None
    assert any("not one steady operating point" in n for n in rating["notes"])


def test_a_sweep_point_off_its_operating_point_has_no_safeties():
    # the sweep's safety_pitting_min / safety_bending_min rate the point with its K_v: none
    # from a window that is not one steady operating point (measured before: S_H 2.70 from
    # the transient)
    from gearcli.pipeline.simulate import run_simulation
    from gearcli.pipeline.sweep.metrics import point_metrics

    limits = [LIMITS[1], LIMITS[3]]
    short = point_metrics(run_simulation(ISO_PAIR, [*limits, "run.end_time=0.15"], zoom=False))
    assert short["safety_pitting_min"] is None and short["safety_bending_min"] is None
    steady = point_metrics(run_simulation(ISO_PAIR, [*limits, "run.end_time=0.3"], zoom=False))
    assert steady["safety_pitting_min"] > 1.0
