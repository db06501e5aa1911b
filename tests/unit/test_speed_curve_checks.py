"""Issue 32: speed-curve studies apply `metrics:` and `checks:` like other studies (they were
silently ignored): summary.csv keeps the named metrics, a column `checks` holds each level's
verdict, and a failed check is exit 4."""

from __future__ import annotations

import pandas as pd
import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.errors import CaseError
from gearcli.pipeline.sweep.study import load_study
from tests.unit.sweep_helpers import write_study

CURVE = """design: speed_curve
parameters:
  mesh_frequency: ["300 Hz", "400 Hz"]
"""


def test_speed_curve_metrics_and_checks_are_applied(tmp_path):
    # a dynamic factor is >= 1 at any level with contact (max F >= mean F = static): the
    # check max 0.5 fails at every ok level, min 0.5 passes
    path = write_study(tmp_path, CURVE + "metrics: [dynamic_factor]\n"
                       "checks: [{metric: dynamic_factor, max: 0.5}]\n")
    r = CliRunner().invoke(app, ["sweep", str(path), "-o", str(tmp_path / "o"), "-j", "1"])
    assert r.exit_code == 4, r.output
    assert "failed the study's checks" in r.stderr
    df = pd.read_csv(tmp_path / "o" / "summary.csv", keep_default_na=False)
    assert "force_max_N" not in df.columns and "dte_peak_to_peak_mm" not in df.columns
    assert "dynamic_factor" in df.columns and len(df) == 4
    ok = df[df["status"] == "ok"]
    assert len(ok) > 0 and ok["checks"].str.startswith("fail: dynamic_factor").all()
    assert (df.loc[df["status"] != "ok", "checks"] == "").all()


def test_speed_curve_check_that_holds_is_exit_0(tmp_path):
    path = write_study(tmp_path, CURVE + "checks: [{metric: dynamic_factor, min: 0.5}]\n")
    r = CliRunner().invoke(app, ["sweep", str(path), "-o", str(tmp_path / "o"), "-j", "1"])
    assert r.exit_code == 0, r.output
    df = pd.read_csv(tmp_path / "o" / "summary.csv", keep_default_na=False)
    assert set(df.loc[df["status"] == "ok", "checks"]) == {"pass"}
    assert "force_max_N" in df.columns  # no metrics: all of them


@pytest.mark.parametrize("extra, fragment", [
    ("metrics: [mesh_stiffness_mean_N_mm]\n", "a speed curve measures"),
    ("checks: [{metric: gear_mesh_frequency_Hz, max: 1}]\n", "a speed curve measures"),
    ("metrics: [force_max_N]\nchecks: [{metric: dynamic_factor, max: 2}]\n",
     "not among the study's metrics"),
])
def test_speed_curve_metrics_it_does_not_measure_are_refused(tmp_path, extra, fragment):
    with pytest.raises(CaseError, match=fragment):
        load_study(write_study(tmp_path, CURVE + extra))
