"""`gearcli run` of a case with ``faults:`` writes monitor.json and the report's "Condition
monitoring" section (report/monitoring.py): metrics per shaft, the sideband table, the order
and tooth-by-tooth figures; a healthy case's report has none of them."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from gearcli.cli import app

ROOT = Path(__file__).resolve().parents[2]
CASE = str(ROOT / "cases" / "iso_pair.yaml")
CRACK = "faults=[{kind: root_crack, gear: pinion, tooth: 2, depth: 4 mm, angle: 45 deg}]"
runner = CliRunner()


def _run(folder: Path, *sets: str) -> str:
    args = ["run", CASE, "-o", str(folder), "-q", "--format", "md", "--set",
            "run.end_time=0.35"]
    for s in sets:
        args += ["--set", s]
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return (folder / "report.md").read_text()


def test_faulted_run_report_has_the_monitoring_section(tmp_path):
    text = _run(tmp_path / "crack", CRACK)
    assert "## Condition monitoring" in text and "Faulted: pinion tooth 2." in text
    assert "| fm4 |" in text and "mesh order h z" in text and "21 × 1" not in text
    assert "1 × 21 = 21" in text
    for name in ("monitor_orders.png", "monitor_teeth.png"):
        assert (tmp_path / "crack" / "figures" / name).is_file()
        assert f"figures/{name}" in text
    assert (tmp_path / "crack" / "monitor.json").is_file()


def test_healthy_run_report_has_none(tmp_path):
    text = _run(tmp_path / "healthy")
    assert "Condition monitoring" not in text
    assert not (tmp_path / "healthy" / "monitor.json").exists()
    assert not (tmp_path / "healthy" / "figures" / "monitor_orders.png").exists()


def test_report_monitors_the_accelerometer_when_the_case_has_one(tmp_path):
    """With sensors.accelerometer the section is of the housing accelerometer [m/s^2] (what a
    rig records), not of the TE; without it, of the TE [mm] (test above)."""
    import json

    sensors = "sensors={accelerometer: {housing: [{frequency: 3 kHz, modal_mass: 2 kg}]}}"
    text = _run(tmp_path / "accel", CRACK, sensors)
    assert r"Signal: housing accelerometer (sensors) \[m/s^2\] (the case's " \
        "sensors.accelerometer" in text
    doc = json.loads((tmp_path / "accel" / "monitor.json").read_text())
    assert doc["signal_unit"] == "m/s^2"
    te = _run(tmp_path / "te", CRACK)
    assert "Signal: transmission error" in te and r"\[mm\] (the signal of a case without" in te


def test_a_healthy_report_does_not_import_the_monitoring_model(tmp_path):
    # the monitoring model and scipy.signal take ~1.5 s to import, half a healthy report's time
    # (issue 29's <= 3 s): `report` imports them only for a case with faults
    import subprocess
    import sys

    run = tmp_path / "seed"
    res = runner.invoke(app, ["simulate", str(ROOT / "cases" / "seed.yaml"), "-o", str(run),
                              "-q", "--set", "run.end_time=0.3"])
    assert res.exit_code == 0, res.output
    runner.invoke(app, ["analyze", str(run), "-q", "--no-remedy"])  # exit 4: the seed's findings
    code = ("import sys\nfrom gearcli.cli import app\ntry:\n"
            "    app(['report', sys.argv[1], '-q', '--format', 'md'])\nexcept SystemExit:\n"
            "    pass\nprint(sorted(m for m in ('gearcli.pipeline.monitor', 'scipy.signal') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code, str(run)], capture_output=True,
                         text=True, timeout=300)
    assert (run / "report.md").is_file(), out.stderr
    assert out.stdout.strip().splitlines()[-1] == "[]", out.stdout + out.stderr
