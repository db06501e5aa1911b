"""`gearcli mesh`: quasi-static loaded contact from the command line."""

import json

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import SEED

runner = CliRunner()


def test_mesh_json_files_and_plot(tmp_path):
    res = runner.invoke(app, ["mesh", str(SEED), "--json", "-o", str(tmp_path / "m"),
                              "--plot", str(tmp_path / "m.svg")])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    assert doc["force_N"] > 3800 and doc["ste"]["peak_to_peak_um"] > 0
    assert set(doc["ste"]["harmonics_um"]) == {"1fz", "2fz", "3fz"}
    files = {p.name for p in (tmp_path / "m").iterdir()}
    assert files == {"mesh.json", "mesh.csv", "mesh.png", "manifest.json"}
    header = (tmp_path / "m" / "mesh.csv").read_text().splitlines()[0]
    assert header.startswith("roll_mm,ste_um,unloaded_te_um,mesh_stiffness_N_mm")
    assert (tmp_path / "m.svg").read_text().startswith("<?xml")
    # existing results are never silently replaced
    again = runner.invoke(app, ["mesh", str(SEED), "-o", str(tmp_path / "m")])
    assert again.exit_code == 1 and "--force" in again.output


def test_mesh_table_and_bad_load():
    res = runner.invoke(app, ["mesh", str(SEED), "--load", "2000"])
    assert res.exit_code == 0, res.output
    assert "Static transmission error" in res.output and "2000 N" in res.output
    bad = runner.invoke(app, ["mesh", str(SEED), "--load", "-5"])
    assert bad.exit_code == 1 and "--load must be a force > 0 N" in bad.output


def test_bore_outside_the_body_compliance_fit_is_noted(tmp_path):
    """iso_pair's pinion root circle is d_f = 96 mm: an 8 mm bore gives h_fi = d_f / bore = 12,
    beyond the upper end 7 of Sainsot et al.'s fit (theory §4b); its own 40 mm bore (2.4) and
    a 15 mm one (6.4) are inside."""
    from tests.conftest import ROOT

    case = ROOT / "cases" / "iso_pair.yaml"
    for bore, noted in (("40 mm", False), ("15 mm", False), ("8 mm", True)):
        r = runner.invoke(app, ["mesh", str(case), "--json", "--set",
                                f"gears.pinion.bore_diameter={bore}"])
        assert r.exit_code == 0, r.output
        notes = json.loads(r.stdout)["notes"]
        hit = [n for n in notes if "gears.pinion.bore_diameter" in n]
        assert bool(hit) == noted, notes
        if noted:
            assert "h_fi = r_f/r_int = 12.00" in hit[0] and "extrapolated" in hit[0]


def test_harris_map_at_the_case_load_is_the_static_transmission_error():
    # the map was computed on a coarser roll grid (100 points per cycle against 200), so with
    # tip relief its row at the case load missed the STE's peak (2.1016 against 2.1079 µm)
    relief = "{amount: 0.006, length: 4}"
    r = runner.invoke(app, ["mesh", str(SEED).replace("seed.yaml", "iso_pair.yaml"), "--json",
                            "--harris", "--set", f"modifications.tip_relief.pinion={relief}",
                            "--set", f"modifications.tip_relief.gear={relief}"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    loads = doc["harris"]["force_N"]
    i = min(range(len(loads)), key=lambda j: abs(loads[j] - doc["force_N"]))
    assert loads[i] == pytest.approx(doc["force_N"], rel=1e-12)  # 1.0 x the load, to round-off
    assert doc["harris"]["ste_peak_to_peak_um"][i] == pytest.approx(
        doc["ste"]["peak_to_peak_um"], rel=1e-9)  # the same equilibria at a load 1e-16 apart


def test_a_load_below_the_solvers_resolution_is_refused_not_answered():
    """iso_pair (tooth law, F = k p): 1e-9 N deflects the mesh by ~4e-15 mm, below Brent's
    1e-13 mm tolerance; before, the answer had roll positions with no pair in contact and a
    4.2 µm STE; now one line naming the load, exit 1. The seed's IMPACT law (F = k p^e,
    e > 1) compresses by (F/k)^(1/e), resolvable at the same force: answered."""
    res = runner.invoke(app, ["mesh", "cases/iso_pair.yaml", "--load", "1e-9", "-q"])
    assert res.exit_code == 1, res.output
    assert "--load 1e-09 N" in res.output and "expected a larger load" in res.output
    for case, load in (("cases/iso_pair.yaml", "1e-3"), (str(SEED), "1e-9")):
        ok = runner.invoke(app, ["mesh", case, "--load", load, "--json"])
        assert ok.exit_code == 0, ok.output
        assert json.loads(ok.output)["sharing"]["pairs_in_contact_min"] >= 1


def test_single_pair_limit_note_quotes_the_cap_in_the_display_units(tmp_path):
    """The stub-toothed iso_pair of tests/unit/test_single_pair_limit.py has no single-pair
    limit within the gap tables, and mesh.json's note names the tables' cap. Like every other
    quantity of the command it follows ``--units``: the same cap in mm (engineering) and in m
    (si), 1e-3 apart to the printed 3 digits."""
    import re

    from tests.conftest import ROOT

    case = ROOT / "cases" / "iso_pair.yaml"
    stub = "gears.rack={addendum: 0.7, dedendum: 1.0, root_radius: 0.25}"
    caps = {}
    for system, unit in (("engineering", "mm"), ("si", "m")):
        out = tmp_path / system
        r = runner.invoke(app, ["--units", system, "mesh", str(case), "--set", stub,
                                "-o", str(out), "--quiet"])
        assert r.exit_code == 0, r.output
        note = json.loads((out / "mesh.json").read_text())["sharing"]["single_pair_limit_note"]
        hit = re.search(r"touches past (\S+) (\S+),", note)
        assert hit is not None, note
        assert hit.group(2) == unit, note
        caps[system] = float(hit.group(1))
    assert caps["si"] == pytest.approx(1e-3 * caps["engineering"], rel=5e-3)  # 3 digits each
