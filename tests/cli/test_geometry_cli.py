"""`gearcli geometry`: JSON values of the seed case, table, plot files, warnings."""

import json

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import SEED

runner = CliRunner()

# Seed pair textbook values (issue 2), relative tolerance 1e-4 (the stated values' precision).
EXPECTED = {
    ("pinion", "d_mm"): 170.0,
    ("gear", "d_mm"): 250.0,
    ("pinion", "d_b_mm"): 159.748,
    ("gear", "d_b_mm"): 234.923,
    ("pinion", "d_a_mm"): 190.0,
    ("gear", "d_a_mm"): 270.0,
    ("pinion", "d_f_mm"): 145.0,
    ("gear", "d_f_mm"): 225.0,
    ("pinion", "p_b_mm"): 29.5213,
    ("pair", "a_w_mm"): 210.0,
    ("pair", "path_of_contact_mm"): 46.1485,
    ("pair", "contact_ratio"): 1.56323,
    ("pair", "gear_mesh_frequency_Hz"): 141.667,
}


def test_geometry_json_seed_values():
    result = runner.invoke(app, ["geometry", str(SEED), "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    for (section, key), value in EXPECTED.items():
        assert data[section][key] == pytest.approx(value, rel=1e-4), (section, key)
    # 17 teeth is just below z_min = 17.1 for the ISO 53 A rack: a (tiny) undercut warning
    assert [w["code"] for w in data["warnings"]] == ["undercut"]
    assert data["pair"]["backlash_normal_mm"] == 0.0


def test_geometry_table_on_terminal():
    result = runner.invoke(app, ["geometry", str(SEED)])
    assert result.exit_code == 0
    assert "contact ratio" in result.stdout and "1.56323" in result.stdout
    assert "warning: pinion: undercut" in result.stderr


@pytest.mark.parametrize("suffix", [".png", ".svg"])
def test_geometry_plot(tmp_path, suffix):
    out = tmp_path / f"pair{suffix}"
    result = runner.invoke(app, ["geometry", str(SEED), "--plot", str(out)])
    assert result.exit_code == 0, result.output
    head = out.read_bytes()[:200]
    assert head.startswith(b"\x89PNG") if suffix == ".png" else b"<svg" in out.read_bytes()
    assert not list(tmp_path.glob(".*.tmp"))  # atomic write leaves no temp file


def test_geometry_plot_bad_suffix(tmp_path):
    result = runner.invoke(app, ["geometry", str(SEED), "--plot", str(tmp_path / "p.txt")])
    assert result.exit_code == 1
    assert ".png, .svg or .pdf" in result.stderr


def test_profile_shifted_case(seed_text, write_case):
    # Positive shift sum: a_w grows per the inv α_w relation (ISO 21771).
    text = seed_text.replace("    teeth: 17 ", "    teeth: 17\n    profile_shift: 0.3 ", 1)
    data = json.loads(runner.invoke(app, ["geometry", str(write_case(text)), "--json"]).stdout)
    assert data["pair"]["a_w_mm"] > 210.0
    assert data["pinion"]["undercut"] is False
