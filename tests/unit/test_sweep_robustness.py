"""Issue 18 for `gearcli sweep`: designs sized before they are built, checks on real metrics,
bounded network handshakes, readable resume files, workers that end with the sweep."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.errors import CaseError, OutputError
from gearcli.pipeline.sweep.study import MAX_POINTS_YES, load_study
from tests.conftest import ROOT
from tests.unit.sweep_helpers import write_study

runner = CliRunner()


def _error(tmp_path, body: str, **kw) -> str:
    with pytest.raises(CaseError) as err:
        load_study(write_study(tmp_path, body), **kw)
    return str(err.value)


def test_huge_grid_is_refused_before_it_is_built(tmp_path):
    body = ("parameters:\n  gears.module: {linspace: [8, 12], num: 100000}\n"
            "  gears.face_width: {linspace: [60, 140], num: 100000}\n")
    text = _error(tmp_path, body, allow_large=True)
    assert "10,000,000,000 points" in text and f"{MAX_POINTS_YES:,}" in text


def test_huge_lhs_is_refused_before_sampling(tmp_path):
    body = ("design: lhs\nsamples: 1000000000\nseed: 1\n"
            "parameters:\n  gears.module: {linspace: [8, 12]}\n")
    text = _error(tmp_path, body, allow_large=True)
    assert "samples" in text and "1,000,000,000 points" in text


@pytest.mark.parametrize("checks, fragment", [
    ("[{metric: no_such_metric, max: 2}]", "unknown metric 'no_such_metric'"),
    ("[{metric: dynamic_factor}]", "needs 'min' and/or 'max'"),
])
def test_checks_need_a_known_metric_and_a_limit(tmp_path, checks, fragment):
    text = _error(tmp_path, f"parameters:\n  gears.module: [10]\nchecks: {checks}\n")
    assert "checks.0" in text and fragment in text


def test_check_on_a_metric_the_study_drops_is_refused(tmp_path):
    text = _error(tmp_path, "parameters:\n  gears.module: [10]\nmetrics: [force_max_N]\n"
                  "checks: [{metric: dynamic_factor, max: 2}]\n")
    assert "not among the study's metrics" in text


def test_base_must_be_a_case_file_and_is_not_quoted(tmp_path):
    secret = tmp_path / "secret.yaml"
    secret.write_text("top secret line\n")
    study = tmp_path / "s.yaml"
    study.write_text(f"base: {secret}\nparameters:\n  gears.module: [10]\n")
    with pytest.raises(CaseError) as err:
        load_study(study)
    assert "top secret" not in str(err.value) and "base" in str(err.value)
    study.write_text("base: /etc/passwd\nparameters:\n  gears.module: [10]\n")
    with pytest.raises(CaseError, match="expected a case file ending in"):
        load_study(study)


def test_unit_powers_in_a_study_are_bounded(tmp_path):
    text = _error(tmp_path, "parameters:\n  gears.module: ['10 mm**9**9**9', '11 mm']\n")
    assert "parameters" in text


def test_metrics_without_the_trend_metrics_write_trends(tmp_path):
    path = write_study(tmp_path, "parameters:\n  gears.module: [10]\n"
                       "metrics: [force_max_N]\n")
    r = runner.invoke(app, ["sweep", str(path), "-o", str(tmp_path / "out"), "-j", "1", "-q"])
    assert r.exit_code == 0, r.stderr
    assert (tmp_path / "out" / "trends.md").is_file()


@pytest.mark.parametrize("kind", ["binary", "folder"])
def test_unreadable_summary_on_resume_is_exit_1(tmp_path, kind):
    path = write_study(tmp_path, "parameters:\n  gears.module: [10]\n")
    out = tmp_path / "out"
    out.mkdir()
    if kind == "binary":
        (out / "summary.csv").write_bytes(b"\xff\xfe\x00 not text")
    else:
        (out / "summary.csv").mkdir()
    r = runner.invoke(app, ["sweep", str(path), "-o", str(out), "-j", "1", "-q"])
    assert r.exit_code == 1
    assert "summary.csv" in r.stderr and "internal error" not in r.stderr


@pytest.mark.parametrize("address", ["bogus", "tcp://host", "tcp://h:0", "http://h:80"])
def test_bad_scheduler_is_a_usage_error(tmp_path, address):
    path = write_study(tmp_path, "parameters:\n  gears.module: [10]\n")
    r = runner.invoke(app, ["sweep", str(path), "-o", str(tmp_path / "o"),
                            "--scheduler", address])
    assert r.exit_code == 2
    assert "--scheduler" in r.stderr


def test_scheduler_that_never_speaks_dask_times_out():
    from gearcli.pipeline.sweep.run import probe_scheduler

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    accepted = []
    threading.Thread(target=lambda: accepted.append(server.accept()), daemon=True).start()
    port = server.getsockname()[1]
    try:
        with pytest.raises(OutputError, match="no Dask handshake"):
            probe_scheduler(f"tcp://127.0.0.1:{port}", 0.3)
    finally:
        server.close()


def test_refused_connection_is_exit_1():
    from gearcli.pipeline.sweep.run import probe_scheduler

    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()  # nothing listens there now
    with pytest.raises(OutputError, match="cannot connect"):
        probe_scheduler(f"tcp://127.0.0.1:{port}", 1.0)


WORKER = """
import os, sys, time
from gearcli.pipeline.sweep import workers as sweep_run
sweep_run.PARENT_POLL_S = 0.05
parent = os.getpid()
pid = os.fork()
if pid == 0:
    sweep_run.watch_parent(parent)
    time.sleep(120)
    os._exit(0)
print(pid, flush=True)
time.sleep(120)
"""


def test_workers_end_when_the_sweep_is_killed():
    """kill -9 of the sweep: its worker processes notice and end (no orphans)."""
    proc = subprocess.Popen([sys.executable, "-c", WORKER], stdout=subprocess.PIPE, text=True,
                            cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)})
    child = int(proc.stdout.readline())
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    for _ in range(400):  # the orphan is re-parented; once it exits it is gone or a zombie
        if not _running(child):
            break
        time.sleep(0.05)
    else:
        os.kill(child, signal.SIGKILL)
        pytest.fail("the worker outlived the sweep")


def _running(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] not in ("Z", "X")
    except FileNotFoundError:
        return False
    except OSError:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return False
        return True


def test_watching_the_own_process_does_nothing():
    """A LocalCluster's nannies run in the sweep's process: watching "the sweep" from there
    must not end the sweep (it did when the sweep itself was an orphan, e.g. run with &)."""
    from gearcli.pipeline.sweep.workers import watch_parent

    watch_parent(os.getpid())
    assert not any(t.name == "gearcli-parent-watch" for t in threading.enumerate())


def test_another_studys_results_are_not_silently_replaced(tmp_path):
    """Same columns, other cases (here another end time): resuming would drop the first
    study's rows, so the second study is refused unless --force."""
    out = tmp_path / "out"
    first = write_study(tmp_path, "parameters:\n  gears.module: [10]\n", "a.yaml")
    r = runner.invoke(app, ["sweep", str(first), "-o", str(out), "-j", "1", "-q"])
    assert r.exit_code == 0, r.stderr
    before = (out / "summary.csv").read_text()
    second = write_study(tmp_path, "parameters:\n  gears.module: [10]\n", "b.yaml")
    second.write_text(second.read_text().replace("run.end_time: 0.4 s", "run.end_time: 0.3 s"))
    r = runner.invoke(app, ["sweep", str(second), "-o", str(out), "-j", "1", "-q"])
    assert r.exit_code == 1 and "holds 1 result(s) of cases this study does not have" in r.stderr
    assert (out / "summary.csv").read_text() == before
    r = runner.invoke(app, ["sweep", str(second), "-o", str(out), "-j", "1", "-q", "--force"])
    assert r.exit_code == 0, r.stderr
    assert (out / "summary.csv").read_text() != before


def test_a_folder_of_other_files_is_not_a_sweep_folder(tmp_path):
    path = write_study(tmp_path, "parameters:\n  gears.module: [10]\n")
    out = tmp_path / "notes"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    r = runner.invoke(app, ["sweep", str(path), "-o", str(out), "-j", "1", "-q"])
    assert r.exit_code == 1 and "holds other files" in r.stderr
    assert sorted(p.name for p in out.iterdir()) == ["notes.txt"]


def test_points_that_cannot_run_make_the_sweep_exit_4(tmp_path):
    # the rows are written all the same; a script must not read exit 0 as a complete study
    path = write_study(tmp_path, "parameters:\n  gears.pinion.teeth: [17, 5]\n")
    r = runner.invoke(app, ["sweep", str(path), "-o", str(tmp_path / "out"), "-j", "1", "-q"])
    assert r.exit_code == 4, r.output
    assert "1 of 2 points failed (status 'failed'" in r.stderr
    assert (tmp_path / "out" / "summary.csv").read_text().count("\n") == 3


@pytest.mark.parametrize("level", ["0 Hz", "-500 Hz"])
def test_a_speed_curve_level_at_or_below_zero_is_refused(tmp_path, level):
    study = tmp_path / "sc.yaml"
    study.write_text(f"base: {ROOT / 'cases' / 'iso_pair.yaml'}\ndesign: speed_curve\n"
                     f"parameters:\n  mesh_frequency: [\"{level}\", \"1000 Hz\"]\n")
    r = runner.invoke(app, ["sweep", str(study), "-o", str(tmp_path / "out")])
    assert r.exit_code == 1, r.output  # 0 Hz ended in exit 3
    assert f"parameters.mesh_frequency: got '{level}'; expected a mesh frequency > 0 Hz" \
        in r.stderr


def test_parquet_without_kept_time_series_is_refused(tmp_path):
    path = write_study(tmp_path, "parameters:\n  gears.module: [10]\n")
    r = runner.invoke(app, ["sweep", str(path), "-o", str(tmp_path / "out"), "--format",
                            "parquet"])
    assert r.exit_code == 1 and "expected --keep-timeseries with it" in r.stderr
    assert not (tmp_path / "out").exists()


def test_a_parameter_whose_other_level_failed_is_not_called_unvaried(tmp_path):
    path = write_study(tmp_path, "parameters:\n  gears.pinion.teeth: [17, 5]\n")
    out = tmp_path / "out"
    r = runner.invoke(app, ["sweep", str(path), "-o", str(out), "-j", "1", "-q"])
    assert r.exit_code == 4, r.output
    text = (out / "trends.md").read_text()
    assert "fewer than 2 of its levels have a value" in text and "not varied" not in text


def test_points_that_resolve_to_one_case_run_it_once(tmp_path):
    path = write_study(tmp_path, 'parameters:\n  gears.module: ["10 mm", "0.01 m", 9]\n')
    out = tmp_path / "out"
    r = runner.invoke(app, ["sweep", str(path), "-o", str(out), "-j", "1"])
    assert r.exit_code == 0, r.output
    assert "3 points: 2 run, 0 already done" in r.output
    import pandas as pd

    df = pd.read_csv(out / "summary.csv")
    assert list(df["point"]) == [0, 1, 2] and df["case_hash"][0] == df["case_hash"][1]
    assert df["force_max_N"][0] == df["force_max_N"][1] != df["force_max_N"][2]


@pytest.mark.parametrize("design", ["grid", "speed_curve"])
def test_mesh_frequency_on_a_torque_drive_is_refused(tmp_path, design):
    # a torque drive's speed follows from the torques: the points ran at the motor curve's
    # speed while their rows claimed the swept ones (dynamic factor 1.615 in every row)
    path = tmp_path / "tq.yaml"
    path.write_text(f"base: {ROOT / 'cases' / 'seed.yaml'}\ndesign: {design}\n"
                    "set: {drive.type: torque, drive.speed: null, drive.torque: 1e5}\n"
                    "parameters:\n  mesh_frequency: [100 Hz, 200 Hz]\n")
    with pytest.raises(CaseError, match="parameters.mesh_frequency: sets the pinion speed "
                                        r"\(drive.speed\), which a torque drive does not"):
        load_study(path)


@pytest.mark.parametrize("override, key, fragment", [
    ("drive.type=torque", "drive.speed", "only applies to drive types 'speed' and 'shaft'"),
    ("drive.reference_speed=100", "drive.reference_speed", "only applies to drive type "
                                                           "'torque', not 'speed'"),
])
def test_drive_keys_of_another_drive_type_are_refused(override, key, fragment):
    # a leftover drive.speed set a torque drive's f_z and steady window (141.7 Hz, not 305)
    from gearcli.case.load import load_case

    extra = ["drive.torque=1e5"] if "torque" in override else []
    with pytest.raises(CaseError) as err:
        load_case(ROOT / "cases" / "seed.yaml", [override, *extra])
    assert key in str(err.value) and fragment in str(err.value)
