"""`gearcli sweep` of a study with ``dataset:`` (pipeline/dataset.py; docs/theory.md "Fault
datasets"): a study crossing fault kind and size with noise seeds runs on the sweep machinery,
keeps each point's signals as Parquet and writes one labels table with the labels from each
point's resolved case and its monitoring metrics.

Case: cases/iso_pair.yaml, 0.3 s (pinion: 2 revolutions in the steady window)."""

from __future__ import annotations

import math

import pandas as pd
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import ROOT

STUDY = f"""
name: tiny_faults
base: {ROOT / "cases" / "iso_pair.yaml"}
set:
  run.end_time: 0.35 s  # a whole gear revolution in the steady window at 1340 rpm
  sensors: {{accelerometer: {{housing: [{{frequency: 3 kHz, modal_mass: 2 kg}}]}},
            noise: {{seed: 0}}}}
design: grid
dataset: {{signal: te}}
parameters:
  faults:
    - []
    - [{{kind: root_crack, gear: pinion, tooth: 2, depth: 4 mm, angle: 45 deg}}]
    - [{{kind: root_crack, gear: pinion, tooth: 2, depth: 0 mm}}]
  sensors.noise.seed: [1]
"""


def test_dataset_writes_signals_and_labels(tmp_path):
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    out = tmp_path / "ds"
    res = CliRunner().invoke(app, ["sweep", str(study), "-o", str(out), "-j", "1"])
    assert res.exit_code == 0, res.output
    assert "labels in" in res.output
    labels = pd.read_parquet(out / "labels.parquet")
    assert list(labels["point"]) == [0, 1, 2]
    assert list(labels["status"]) == ["ok"] * 3
    # a zero-size crack is the healthy tooth (docs/theory.md "Tooth faults")
    assert list(labels["fault_kind"]) == ["healthy", "root_crack", "healthy"]
    assert list(labels["fault_size_mm"]) == [0.0, 4.0, 0.0]
    assert labels.loc[1, "fault_gear"] == "pinion" and labels.loc[1, "fault_tooth"] == 2
    assert math.isclose(labels.loc[0, "pinion_speed_rpm"], 1340.0, rel_tol=1e-12)  # the case's
    assert math.isclose(labels.loc[0, "load_torque_Nm"], 300.0, rel_tol=1e-12)
    assert list(labels["noise_seed"]) == [1, 1, 1]
    for i in range(3):
        for name in ("timeseries.parquet", "sensors.parquet", "sensors.json"):
            assert (out / labels.loc[i, "folder"] / name).is_file()
    # the crack's signature in the TE: FM4 of the pinion's TSA (monitoring §8: 6.3 -> 16.2)
    assert labels.loc[1, "pinion_fm4"] > 2.0 * labels.loc[0, "pinion_fm4"]
    assert labels.loc[2, "pinion_fm4"] == labels.loc[0, "pinion_fm4"]  # bit for bit healthy
    csv = pd.read_csv(out / "labels.csv")
    assert list(csv.columns) == list(labels.columns) and len(csv) == 3


def test_dataset_key_is_checked_where_it_is_written(tmp_path):
    """An unknown signal and a speed_curve dataset are located errors of the study file."""
    import pytest

    from gearcli.errors import CaseError
    from gearcli.pipeline.sweep.study import load_study, load_study_text

    assert load_study(ROOT / "cases" / "studies" / "fault_dataset.yaml").dataset.signal \
        == "accel_m_s2"
    bad = STUDY.replace("dataset: {signal: te}", "dataset: {signal: tee}")
    with pytest.raises(CaseError, match="signal 'tee': expected one of te, ") as exc:
        load_study_text(bad, str(tmp_path / "s.yaml"))
    assert exc.value.line == 9  # the dataset: line
    curve = f"""
base: {ROOT / "cases" / "iso_pair.yaml"}
design: speed_curve
dataset: {{}}
parameters:
  mesh_frequency: ["300 Hz", "400 Hz"]
"""
    with pytest.raises(CaseError, match="a speed_curve runs one simulation per direction") \
            as exc:
        load_study_text(curve, str(tmp_path / "c.yaml"))
    assert exc.value.line == 4
