"""`gearcli sweep`: CliRunner runs, one-line input errors, and resume after SIGKILL."""

import os
import signal
import subprocess
import sys
import time

from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.pipeline.sweep.run import SUMMARY
from tests.unit.sweep_helpers import write_study

runner = CliRunner()


def test_sweep_writes_summary_trends_and_plots(tmp_path):
    study = write_study(tmp_path, "parameters:\n  mesh_frequency: [\"100 Hz\", \"200 Hz\"]\n")
    out = tmp_path / "out"
    res = runner.invoke(app, ["sweep", str(study), "-o", str(out), "--jobs", "1",
                              "--keep-timeseries"])
    assert res.exit_code == 0, res.output
    assert "2 points: 2 run, 0 already done, 0 failed" in res.output
    for name in (SUMMARY, "trends.csv", "trends.md", "speed_sweep.png",
                 "trend_mesh_frequency__Hz.png", "points/00001/timeseries.csv"):
        assert (out / name).exists(), name
    res = runner.invoke(app, ["sweep", str(study), "-o", str(out)])
    assert res.exit_code == 0 and "0 run, 2 already done" in res.output
    # --force starts over: the old points' folders go with their rows (they stayed, no longer
    # matching summary.csv)
    other = write_study(tmp_path, "parameters:\n  mesh_frequency: [\"150 Hz\"]\n", "b.yaml")
    res = runner.invoke(app, ["sweep", str(other), "-o", str(out), "--force"])
    assert res.exit_code == 0, res.output
    assert not (out / "points").exists()


def test_bad_study_is_one_line_exit_1(tmp_path):
    study = write_study(tmp_path, "parameters:\n  gears.modul: [9]\n")
    res = runner.invoke(app, ["sweep", str(study), "-o", str(tmp_path / "o")])
    assert res.exit_code == 1
    assert res.output.startswith("error: ") and "unknown key 'modul'" in res.output
    big = write_study(tmp_path, "parameters:\n  contact.max_damping: "
                      "{linspace: [1, 100], num: 1001}\n", "big.yaml")
    res = runner.invoke(app, ["sweep", str(big), "-o", str(tmp_path / "o")])
    assert res.exit_code == 1 and "pass --yes" in res.output


def test_resume_after_sigkill(tmp_path):
    study = write_study(tmp_path, "parameters:\n  mesh_frequency: "
                        "{linspace: [\"100 Hz\", \"200 Hz\"], num: 12}\n")
    out = tmp_path / "out"
    cmd = [sys.executable, "-c", "from gearcli.cli import app; app()",
           "sweep", str(study), "-o", str(out), "--jobs", "1", "-q"]
    proc = subprocess.Popen(cmd, start_new_session=True)
    summary = out / SUMMARY
    # Wait for 3 finished points. Not a timing check: the bound (45 000 polls 20 ms apart, at
    # least 15 min) only stops a broken sweep from hanging the suite; the child may compile
    # the kernel on a busy machine.
    for _ in range(45_000):
        if proc.poll() is not None or (summary.exists()
                                       and len(summary.read_text().splitlines()) >= 4):
            break
        time.sleep(0.02)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    done_before = len(summary.read_text().splitlines()) - 1
    assert 3 <= done_before < 12
    res = runner.invoke(app, ["sweep", str(study), "-o", str(out), "--jobs", "2"])
    assert res.exit_code == 0, res.output
    assert f"{12 - done_before} run, {done_before} already done" in res.output
    lines = summary.read_text().splitlines()
    assert len(lines) == 13 and [ln.split(",")[0] for ln in lines[1:]] == \
        [str(i) for i in range(12)]


def test_api_sweep_returns_the_cli_summary_as_numbers(tmp_path):
    """gearcli.sweep: the rows the command line writes, numeric columns as numbers, the
    outcome in ``attrs`` (the command line's summary line is made from it); the study's
    trends are written as by the command line (issue 17)."""
    import csv

    import gearcli

    study = write_study(tmp_path, "parameters:\n  mesh_frequency: [\"100 Hz\", \"200 Hz\"]\n")
    df = gearcli.sweep(study, tmp_path / "api", jobs=1)
    assert df.attrs["kind"] == "sweep" and df.attrs["ran"] == 2 and df.attrs["failed"] == 0
    assert (tmp_path / "api" / "trends.md").is_file()
    with open(tmp_path / "api" / SUMMARY, newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(df) == len(rows) == 2
    assert df["dynamic_factor"].dtype.kind == "f"
    assert list(df["dynamic_factor"]) == [float(r["dynamic_factor"]) for r in rows]


def test_points_failing_the_study_checks_give_exit_4(tmp_path):
    """A study whose every point fails its check (a dynamic factor is >= 1 > 0.5) exits 4 and
    says how many failed; the rows are written all the same."""
    study = write_study(tmp_path, "parameters:\n  mesh_frequency: [\"100 Hz\", \"200 Hz\"]\n"
                        "checks: [{metric: dynamic_factor, max: 0.5}]\n")
    res = runner.invoke(app, ["sweep", str(study), "-o", str(tmp_path / "o"), "--jobs", "1"])
    assert res.exit_code == 4, res.output
    assert "2 failed the study's checks" in res.output
    assert "2 of 2 points failed the study's checks" in res.output
    assert (tmp_path / "o" / SUMMARY).is_file()
