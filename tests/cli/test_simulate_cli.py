"""`gearcli simulate`: files, columns, --set, -o -, refusal to overwrite, bad --set."""

import csv
import io
import json

from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import SEED
from tests.physics.simrun import FAST

runner = CliRunner()
SHORT = [a for o in FAST for a in ("--set", o)]


def test_simulate_writes_results(tmp_path):
    out = tmp_path / "run"
    result = runner.invoke(app, ["simulate", str(SEED), "-o", str(out), *SHORT, "--quiet"])
    assert result.exit_code == 0, result.output
    assert {p.name for p in out.iterdir()} == {"timeseries.csv", "summary.json", "manifest.json",
                                               "zoom.csv"}
    header = (out / "timeseries.csv").read_text().splitlines()[0].split(",")
    for col in ("t_s", "theta1_rad", "omega1_rad_s", "theta2_rad", "omega2_rad_s", "delta_mm",
                "force_total_N", "force_slot0_N", "pairs_in_contact", "friction_force_N",
                "drive_torque_Nmm", "load_torque_Nmm"):
        assert col in header
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "ok" and summary["solver"]["accepted_steps"] > 0
    assert isinstance(summary["solver"]["wall_time_includes_compilation"], bool)
    manifest = json.loads((out / "manifest.json").read_text())
    assert len(manifest["case_sha256"]) == 64
    assert manifest["resolved_case"]["run"]["end_time"] == "0.6 s"
    assert manifest["overrides"] == FAST
    assert "numba" in manifest["versions"]


def test_simulate_refuses_to_overwrite(tmp_path):
    out = tmp_path / "run"
    assert runner.invoke(app, ["simulate", str(SEED), "-o", str(out), *SHORT, "-q"]).exit_code == 0
    before = (out / "summary.json").read_text()
    result = runner.invoke(app, ["simulate", str(SEED), "-o", str(out), *SHORT, "-q"])
    assert result.exit_code == 1 and "--force" in result.stderr
    assert (out / "summary.json").read_text() == before
    result = runner.invoke(app, ["simulate", str(SEED), "-o", str(out), *SHORT, "-q", "--force",
                                 "--set", "run.end_time=0.5"])
    assert result.exit_code == 0
    assert json.loads((out / "manifest.json").read_text())["resolved_case"]["run"]["end_time"] \
        == "0.5 s"
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")
                and p.name != ".run.lock"]  # no temp folders (the lock file stays)


def test_simulate_to_stdout():
    result = runner.invoke(app, ["simulate", str(SEED), "-o", "-", *SHORT,
                                 "--set", "run.output_steps=100"])
    assert result.exit_code == 0
    rows = list(csv.reader(io.StringIO(result.stdout)))
    assert rows[0][0] == "t_s" and len(rows) == 102


def test_simulate_bad_set_path(tmp_path):
    result = runner.invoke(app, ["simulate", str(SEED), "-o", str(tmp_path / "r"),
                                 "--set", "contact.stifness=1e5"])
    assert result.exit_code == 1
    assert "did you mean 'stiffness'" in result.stderr
    assert not (tmp_path / "r").exists()


def test_simulate_bad_set_value(tmp_path):
    result = runner.invoke(app, ["simulate", str(SEED), "-o", str(tmp_path / "r"),
                                 "--set", "load.torque=450 N"])
    assert result.exit_code == 1
    assert result.stderr.startswith("error: --set load.torque=450 N: load.torque: got '450 N'")


def test_simulate_json(tmp_path):
    result = runner.invoke(app, ["simulate", str(SEED), "-o", str(tmp_path / "r"), *SHORT,
                                 "--json"])
    assert result.exit_code == 0
    doc = json.loads(result.stdout)
    assert doc["scalars"]["gear_mesh_frequency_Hz"] > 141


def test_simulate_parquet_reads_back_like_csv(tmp_path):
    csv_run, pq_run = tmp_path / "csv", tmp_path / "pq"
    for out, fmt in ((csv_run, "csv"), (pq_run, "parquet")):
        result = runner.invoke(app, ["simulate", str(SEED), "-o", str(out), *SHORT, "-q",
                                     "--format", fmt])
        assert result.exit_code == 0, result.output
    assert {p.name for p in pq_run.iterdir()} == {"timeseries.parquet", "summary.json", "zoom.csv",
                                                  "manifest.json"}
    from gearcli.io.results import read_run

    a, b = read_run(csv_run), read_run(pq_run)
    assert list(a.columns) == list(b.columns)
    for name, col in a.columns.items():  # CSV: 10 significant digits of the same numbers
        assert [float(f"{v:.10g}") for v in b.columns[name]] == col.tolist(), name
    result = runner.invoke(app, ["analyze", str(pq_run)])
    assert result.exit_code in (0, 4), result.output  # analysed (checks may fail on 0.6 s)


def test_simulate_parquet_needs_a_folder():
    result = runner.invoke(app, ["simulate", str(SEED), "-o", "-", *SHORT, "--format",
                                 "parquet"])
    assert result.exit_code == 1 and "-o DIR" in result.stderr
