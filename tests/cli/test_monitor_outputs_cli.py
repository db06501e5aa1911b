"""`gearcli monitor RUN --signal --orders --teeth --wav` (docs/theory.md, "Condition-monitoring
signals" §3–§4, "What a sensor sees"): figures written, the sensor signal as audio of the run's
length at 44.1 kHz, 16-bit, peak-normalised; a bad signal name is one line, exit 1."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.io import wavfile
from typer.testing import CliRunner

from gearcli.cli import app

ROOT = Path(__file__).resolve().parents[2]
CASE = str(ROOT / "cases" / "iso_pair.yaml")
SETS = ["run.end_time=0.35",
        "faults=[{kind: root_crack, gear: pinion, tooth: 2, depth: 4 mm, angle: 45 deg}]",
        "sensors={sample_rate: 10 kHz, accelerometer: {housing: [{frequency: 3 kHz, "
        "damping_ratio: 0.05, modal_mass: 2 kg}]}, noise: {seed: 4, snr_db: 30}}"]
runner = CliRunner()


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("monout") / "crack"
    args = ["simulate", CASE, "-o", str(folder), "-q"]
    for s in SETS:
        args += ["--set", s]
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return folder


def test_figures_wav_and_sidebands(run, tmp_path):
    orders, teeth, wav = tmp_path / "o.png", tmp_path / "t.png", tmp_path / "a.wav"
    res = runner.invoke(app, ["monitor", str(run), "--signal", "accel_m_s2", "--orders",
                              str(orders), "--teeth", str(teeth), "--wav", str(wav), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    assert doc["signal_unit"] == "m/s^2" and "accelerometer" in doc["signal"]
    pinion = next(s for s in doc["shafts"] if s["shaft"] == "pinion")
    assert pinion["faulted_teeth"] == [2]
    assert [r["order"] for r in pinion["sidebands"]] == [21, 42, 63]
    assert len(pinion["tsa"]) == pinion["samples_per_revolution"]
    for f in (orders, teeth):
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rate, samples = wavfile.read(wav)
    sensors = json.loads((run / "sensors.json").read_text())
    assert sensors["sample_rate_Hz"] == 10_000.0
    # real time: the run's 0.35 s at 44.1 kHz, t_k = k/44100 for k = 0 ... floor(0.35 * 44100)
    assert rate == 44_100 and samples.dtype == np.int16
    assert samples.size == round(0.35 * 44_100) + 1  # 0.35 * 44100 = 15434.999... in floats
    assert int(np.max(np.abs(samples))) == round(0.9 * 32767)  # peak-normalised, headroom
    assert abs(float(samples.mean())) < 0.01 * 32767  # mean removed (before normalising)


def test_unknown_signal_is_one_line(run):
    res = runner.invoke(app, ["monitor", str(run), "--signal", "nope"])
    assert res.exit_code == 1
    assert "--signal nope" in res.output and "accel_m_s2" in res.output


def test_te_signal_of_a_run_without_sensors_table_is_refused_cleanly(run, tmp_path):
    folder = tmp_path / "plain"
    res = runner.invoke(app, ["simulate", CASE, "-o", str(folder), "-q", "--set",
                              "run.end_time=0.35"])
    assert res.exit_code == 0, res.output
    res = runner.invoke(app, ["monitor", str(folder), "--signal", "accel_m_s2"])
    assert res.exit_code == 1 and "no sensors table" in res.output
