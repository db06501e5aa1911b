"""`gearcli monitor RUN [--baseline RUN] [--json] [-o DIR]` on short iso_pair runs."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.results import json_schema

ROOT = Path(__file__).resolve().parents[2]
CASE = str(ROOT / "cases" / "iso_pair.yaml")
CRACK = ("faults=[{kind: root_crack, gear: pinion, tooth: 2, depth: 4 mm, angle: 45 deg}]")
runner = CliRunner()


def _simulate(folder: Path, *sets: str) -> Path:
    # 0.35 s: iso_pair runs at 1340 rpm since issue 31 (1500 before), the same whole gear
    # revolutions in the steady window as 0.3 s then
    args = ["simulate", CASE, "-o", str(folder), "-q", "--set", "run.end_time=0.35"]
    for s in sets:
        args += ["--set", s]
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return folder


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("monitor")
    return _simulate(base / "healthy"), _simulate(base / "crack", CRACK)


def _json(*args) -> dict:
    res = runner.invoke(app, ["monitor", *map(str, args), "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.output)


def _pinion(doc: dict) -> dict:
    return next(s for s in doc["shafts"] if s["shaft"] == "pinion")["metrics"]


def test_json_fields_and_crack_against_the_healthy_baseline(runs):
    """Pinion NA4 against the healthy run (measured: 0.09 healthy, 6.1e5 cracked) and FM4
    (6.3, 16.2); bounds as in tests/unit/test_monitor_pipeline.py."""
    healthy, crack = runs
    h = _json(healthy, "--baseline", healthy)
    c = _json(crack, "--baseline", healthy)
    for key in ("case", "run", "baseline", "signal", "signal_unit", "window_s", "shafts"):
        assert key in c
    assert [s["shaft"] for s in c["shafts"]] == ["pinion", "gear"]
    for s in c["shafts"]:
        assert {"teeth", "first_tooth", "n_revolutions", "samples_per_revolution",
                "normalisation", "metrics"} <= set(s)
        assert s["n_revolutions"] >= 1 and "baseline" in s["normalisation"]
        for key in ("rms", "kurtosis", "crest_factor", "fm0", "fm4", "m6a", "m8a", "na4",
                    "nb4", "energy_ratio", "sideband_level_factor", "sideband_index"):
            assert isinstance(s["metrics"][key], float), key
    assert _pinion(c)["na4"] > 100.0 * _pinion(h)["na4"]
    assert _pinion(c)["fm4"] > 2.0 * _pinion(h)["fm4"]
    own = _json(crack)
    assert own["baseline"] is None and "own" in own["shafts"][0]["normalisation"]


def test_table_and_output_folder(runs, tmp_path):
    healthy, crack = runs
    res = runner.invoke(app, ["monitor", str(crack), "--baseline", str(healthy)])
    assert res.exit_code == 0, res.output
    assert "fm4" in res.output and "Zakrajsek" in res.output and "gear (43 teeth)" in res.output
    out = tmp_path / "mon"
    res = runner.invoke(app, ["monitor", str(crack), "-o", str(out), "-q"])
    assert res.exit_code == 0, res.output
    doc = json.loads((out / "monitor.json").read_text())
    assert doc["shafts"][0]["metrics"]["fm4"] == _json(crack)["shafts"][0]["metrics"]["fm4"]
    jsonschema.validate(doc, json_schema("monitor"))  # `gearcli schema --results --kind monitor`
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["gearcli_manifest"] == 1 and manifest["resolved_case"]["faults"]
    again = runner.invoke(app, ["monitor", str(crack), "-o", str(out), "-q"])
    assert again.exit_code == 1 and "--force" in again.output
    forced = runner.invoke(app, ["monitor", str(crack), "-o", str(out), "-q", "--force"])
    assert forced.exit_code == 0, forced.output


def test_a_run_shorter_than_a_revolution_is_one_line_exit_1(tmp_path):
    res = runner.invoke(app, ["simulate", CASE, "-o", str(tmp_path / "short"), "-q", "--set",
                              "run.end_time=0.1"])
    assert res.exit_code == 0, res.output
    res = runner.invoke(app, ["monitor", str(tmp_path / "short")])
    assert res.exit_code == 1
    lines = res.output.strip().splitlines()
    assert len(lines) == 1 and "whole revolution" in lines[0], res.output
