"""`gearcli rate`: the ISO 6336 rating table, --json, -o, exit codes 0/4/1.

Anchor: cases/nrel5mw_sun_planet.yaml against the KISSsoft 03/2017 ISO 6336:2006 printout
(tests/data/kisssoft_nrel5mw_stage02.txt): S_H 1.21/1.38, S_F 2.82/2.04; the sun's S_H is below
the printed S_H,min 1.25, so the printout's verdict (and the command's) is a failure: exit 4.
"""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.io.outdir import RESULT_NAMES
from tests.unit.test_iso6336_anchor import printed, within_print

runner = CliRunner()
NREL = str(Path(__file__).resolve().parents[2] / "cases" / "nrel5mw_sun_planet.yaml")
ISO_PAIR = str(Path(NREL).parent / "iso_pair.yaml")


def _rows(side: dict) -> dict:
    return {f["symbol"]: f["value"] for f in side["factors"]}


def test_json_reproduces_the_printout():
    res = runner.invoke(app, ["rate", NREL, "--json"])
    assert res.exit_code == 4, res.output  # the sun's S_H 1.21 < S_H,min 1.25 (as printed)
    doc = json.loads(res.output)
    sun, planet = doc["iso"]["pinion"], doc["iso"]["gear"]
    # S_H to the printed 2 digits (K_v's rounding, half of it in S_H, leaves them)
    assert printed("SHBD=sigHG/sigHBD")[:2] == ["1.21", "1.38"]
    assert printed("SF=sigFG/sigF")[:2] == ["2.82", "2.04"]
    assert (f"{sun['S_H']:.2f}", f"{planet['S_H']:.2f}") == ("1.21", "1.38")
    assert (f"{sun['S_F']:.2f}", f"{planet['S_F']:.2f}") == ("2.82", "2.04")
    assert (sun["pitting"], planet["pitting"], sun["bending"], planet["bending"]) == (
        "fail", "pass", "pass", "pass")
    assert doc["verdict"] == "fail" and doc["edition"] == "2006"
    pair = {f["symbol"]: f["value"] for f in doc["iso"]["pair"]}
    # printed factors, to their printed digits (values not carrying K_v)
    for symbol, text in (("Z_H", "2.25"), ("Z_E", "189.81"), ("Z_ε", "0.936"),
                         ("K_Fβ", "1.94"), ("ε_α", "1.370"), ("v", "4.88")):
        digits = len(text.split(".")[1])
        assert f"{pair[symbol]:.{digits}f}" == text, symbol
    for side, texts in ((_rows(sun), {"Z_B": "1.08", "Z_NT": "0.857", "Z_L": "1.020",
                                      "Z_v": "0.982", "Z_R": "1.007", "Y_F": "1.47",
                                      "Y_S": "2.04", "Y_NT": "0.854", "Y_M": "1.000",
                                      "σ_FG": "589.60"}),
                        (_rows(planet), {"Z_D": "1.00", "Z_NT": "0.905", "Y_F": "1.38",
                                         "Y_S": "2.18", "Y_NT": "0.886", "Y_M": "0.700",
                                         "Y_δrelT": "1.002", "σ_FG": "429.38"})):
        for symbol, text in texts.items():
            digits = len(text.split(".")[1])
            assert f"{side[symbol]:.{digits}f}" == text, symbol
    # σ_HG carries Z_v of the speed, which the printout rounds to 0.1 rpm: 1e-5 relative
    # (tests/unit/test_iso6336_anchor.py); ours 1295.4264 and 1368.6157
    assert within_print(_rows(sun)["σ_HG"], "1295.42", 1e-5)
    assert within_print(_rows(planet)["σ_HG"], "1368.61", 1e-5)
    assert doc["load"]["dynamic_factor_source"] == "given" and pair["K_v"] == 1.06


def test_table_shows_factors_safeties_and_verdicts():
    res = runner.invoke(app, ["rate", NREL])
    assert res.exit_code == 4, res.output
    out = res.output
    for text in ("ISO 6336:2006 Method B", "Z_B / Z_D", "1.0775", "σ_HG", "1295.43",
                 "1368.62", "S_H (pitting)", "1.2101", "1.3775", "1.2500", "S_F (bending)",
                 "2.8182", "2.0449", "1.5600", "pinion fail, gear pass", "K_Hβ", "2.0600",
                 "Y_M", "0.7000", "ISO 6336-3:2006", "verdict: FAIL"):
        assert text in out, text


def test_exit_0_when_every_safety_meets_its_minimum():
    res = runner.invoke(app, ["rate", NREL, "--set", "rating.minimum_safety.pitting=1.2", "-q"])
    assert res.exit_code == 0, res.output
    assert res.output == ""


def test_out_folder_is_atomic_and_never_silently_replaced(tmp_path):
    target = tmp_path / "r"
    res = runner.invoke(app, ["rate", NREL, "-o", str(target), "-q"])
    assert res.exit_code == 4, res.output  # written, and the verdict still tells
    assert {p.name for p in target.iterdir()} == {"rating.json", "manifest.json"}
    assert {"rating.json", "manifest.json"} <= RESULT_NAMES  # --force replaces them
    doc = json.loads((target / "rating.json").read_text())
    assert f"{doc['iso']['pinion']['S_H']:.2f}" == "1.21"
    manifest = json.loads((target / "manifest.json").read_text())
    assert manifest["resolved_case"]["rating"]["application_factor"] == 1.25
    again = runner.invoke(app, ["rate", NREL, "-o", str(target)])
    assert again.exit_code == 1 and "--force" in again.output
    forced = runner.invoke(app, ["rate", NREL, "-o", str(target), "--force", "-q"])
    assert forced.exit_code == 4


def test_bad_input_is_one_line_and_exit_1():
    res = runner.invoke(app, ["rate", ISO_PAIR])
    assert res.exit_code == 1
    lines = res.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:")
    assert "contact_fatigue_limit" in lines[0] and "bending_fatigue_limit" in lines[0]
    sim = runner.invoke(app, ["rate", NREL, "--set", "rating.dynamic_factor=simulated"])
    assert sim.exit_code == 1 and "rating.dynamic_factor" in sim.output
    assert "simulation run" in sim.output
    bad = runner.invoke(app, ["rate", NREL, "--set", "rating.pinion.idler=maybe"])
    assert bad.exit_code == 1 and "rating.pinion.idler" in bad.output


def test_rate_is_listed_with_an_example():
    res = runner.invoke(app, ["rate", "--help"])
    assert res.exit_code == 0 and "Example: gearcli rate" in res.output
    assert "rate" in runner.invoke(app, ["--help"]).output


def test_duty_cycle_rows_and_their_verdict():
    """One bin at the case's load: the sun flank's damage at S_H,min 1.25 is
    175200/60783 h = 2.88 > 1 (fail), the roots' 0; with S_H,min 1.2 (below the sun's S_H
    1.21) the flank's life at S_H,min is infinite and every damage 0 (pass)."""
    bins = "rating.duty_cycle=[{torque: 108070.365564, speed: 246.77511, time_share: 1}]"
    res = runner.invoke(app, ["rate", NREL, "--set", bins])
    assert res.exit_code == 4, res.output
    assert "duty-cycle damage" in res.output and "2.8824" in res.output
    doc = json.loads(runner.invoke(app, ["rate", NREL, "--set", bins, "--json"]).output)
    assert doc["duty_cycle"]["gear"]["bending"] == 0.0
    assert f"{doc['duty_cycle']['pinion']['pitting']:.2f}" == "2.88"
    ok = runner.invoke(app, ["rate", NREL, "--set", bins, "--set",
                             "rating.minimum_safety.pitting=1.2", "--json"])
    assert ok.exit_code == 0 and json.loads(ok.output)["duty_cycle"]["pinion"]["pitting"] == 0


def test_both_editions_for_the_anchor():
    """ISO 6336:2006 beside :2019 for the NREL case (docs/theory.md, "ISO 6336 rating" §7).
    Printed (2006): Z_β 1.000, Y_β 1.00/1.00, Y_M 1.000/0.700, σ_FG 589.60/429.38, S_F 2.82/2.04.
    2019 by hand: Z_β = 1/√cos 0° = 1, Y_β = (1 − 0)/cos³0° = 1; the planet (idler) Y_M =
    1/(1 + 1.2 (1 − M)/(1 + M)), M = 0.8 − 0.15 Y_S with the printed Y_S 2.18 → M = 0.473,
    Y_M = 0.69963; the printed Y_S carries ±0.005, so Y_M lies between its values at Y_S 2.175
    and 2.185 (0.70004 … 0.69922; the unrounded Y_S 2.1755 gives 0.69999); σ_FG and S_F scale
    with Y_M (σ_FG ∝ Y_M, ISO 6336-3 eq. (3)): 429.38 × 0.69999/0.7 = 429.374."""
    out = {}
    for ed in ("2006", "2019"):
        res = runner.invoke(app, ["rate", NREL, "--json", "--edition", ed])
        assert res.exit_code == 4, res.output
        out[ed] = json.loads(res.output)
        assert out[ed]["edition"] == ed
    rows = {(r["symbol"], r["gear"]): r for r in out["2019"]["editions"]}
    assert out["2006"]["editions"] == out["2019"]["editions"]  # both columns, either way
    assert rows["Z_β", "pair"]["2006"] == rows["Z_β", "pair"]["2019"] == 1.0
    for role in ("pinion", "gear"):
        assert rows["Y_β", role]["2006"] == rows["Y_β", role]["2019"] == 1.0
        assert within_print(rows["S_H", role]["2019"], {"pinion": "1.21", "gear": "1.38"}[role])
    assert rows["Y_M", "pinion"]["2006"] == rows["Y_M", "pinion"]["2019"] == 1.0
    def y_m(y_s: float) -> float:
        m = 0.8 - 0.15 * y_s
        return 1.0 / (1.0 + 1.2 * (1.0 - m) / (1.0 + m))

    planet = {s: rows[s, "gear"] for s in ("Y_M", "σ_FG", "S_F")}
    assert planet["Y_M"]["2006"] == 0.7
    assert y_m(2.185) < planet["Y_M"]["2019"] < y_m(2.175)
    assert abs(planet["Y_M"]["2019"] - 0.69999) < 5e-6  # the unrounded Y_S
    assert within_print(planet["σ_FG"]["2006"], "429.38")
    assert abs(planet["σ_FG"]["2019"] - 429.38 * 0.69999 / 0.7) < 0.006  # printed digits
    assert within_print(planet["S_F"]["2006"], "2.04") and within_print(planet["S_F"]["2019"],
                                                                       "2.04")
    assert [k for k, r in rows.items() if r["differs"]] == [
        ("Y_M", "gear"), ("σ_FG", "gear"), ("S_F", "gear")]
    bad = runner.invoke(app, ["rate", NREL, "--edition", "2017"])
    assert bad.exit_code == 1 and "expected 2006 or 2019" in bad.output
