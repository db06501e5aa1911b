"""`gearcli run` on the drivetrain case (rigid-body mode, shafts, motor curve, bearings): the
whole chain works and the report shows no raw Python (issue 19). A summary.json whose
rigid-body mode has a null damping ratio was refused by read_run before (a regression)."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import ROOT

runner = CliRunner()


def test_run_drivetrain_report_is_readable(tmp_path):
    out = tmp_path / "dt"
    res = runner.invoke(app, ["run", str(ROOT / "cases" / "drivetrain.yaml"), "-o", str(out),
                              "--format", "md", "-q", "--set", "run.end_time=0.6"])
    assert res.exit_code in (0, 4), res.output
    text = (out / "report.md").read_text()
    for raw in ("{'", "[{", "see name", "True}", "None,", ": None"):
        assert raw not in text, raw
    assert "no load speed 1000 rpm" in text  # engineering display units (the default)
    # every model part in the tables: the model, inertias, shafts, the lateral bearings
    for row in ("| model | lateral-torsional |", "| drive motor inertia | 0.1 kg·m² |",
                "| load inertia | 0.5 kg·m² |", "| bearings pinion | stiffness x 2000 N/µm"):
        assert row in text, row
    assert "lateral.png" in text and "drivetrain.png" in text  # the lateral/drive figures
    assert runner.invoke(app, ["stress", str(out), "-q"]).exit_code == 0
    si = runner.invoke(app, ["--units", "si", "report", str(out), "--format", "md", "-o",
                             str(tmp_path / "si.md"), "-q", "--force"])
    assert si.exit_code == 0, si.output
    si_text = (tmp_path / "si.md").read_text()
    assert "stress.png" in si_text and "stress.png" not in text  # with gearcli stress only
    # Markdown escapes _ and [ ]
    assert r"| operating centre distance a\_w | 0.21 | m |" in si_text
    assert r"| operating centre distance a\_w | 210 | mm |" in text
    assert r"DTE amplitude \[m\]" in si_text and r"DTE amplitude \[µm\]" in text
    assert r"gear speed amplitude \[rad/s\]" in si_text
    assert r"gear speed amplitude \[rpm\]" in text
    assert "no load speed 104.7 rad/s" in si_text and "rpm" not in si_text.split("```yaml")[0]
    assert "```yaml" in text and "reference_speed: 3000" in text  # the case as written
    assert "results computed (UTC)" in text
    summary = json.loads((out / "summary.json").read_text())
    assert summary["scalars"]["modes"][0]["rigid_body"] is True
    assert summary["scalars"]["modes"][0]["damping_ratio"] is None
    # one meaning of f_z in both files: measured over the window (the torque drive runs at its
    # motor curve's speed, not at reference_speed; summary.json said 141.667 Hz, analysis
    # 139.887 Hz)
    analysis = json.loads((out / "analysis.json").read_text())
    # (a sample on the window's edge may fall either side of the CSV's rounded time: the
    # speed fluctuates by ~1 %, one sample of thousands moves the mean by ~1e-6)
    assert summary["scalars"]["gear_mesh_frequency_Hz"] == pytest.approx(
        analysis["metrics"]["gear_mesh_frequency_Hz"], rel=1e-4)
    assert abs(summary["scalars"]["gear_mesh_frequency_Hz"] - 141.667) > 1.0  # not nominal
