"""`gearcli mesh`: quasi-static loaded contact from the command line."""

import json

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
