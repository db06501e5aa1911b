"""Issue 32: sweeps survive their workers. A worker process killed from outside fails its own
point ("worker killed") and the study goes on; a point without a result within its timeout
fails; a resume retries points that failed for their environment (killed worker, full disk)
and keeps the others."""

from __future__ import annotations

import errno
import os
import signal
import subprocess
import sys
import time

import pytest

from gearcli.pipeline.sweep import workers
from gearcli.pipeline.sweep.run import SUMMARY, read_summary, run_study, summary_columns
from gearcli.pipeline.sweep.study import load_study
from tests.conftest import ROOT
from tests.unit.sweep_helpers import write_study


def toy(payload: dict) -> dict:
    """A point that returns at once, ends its own process, or hangs."""
    if payload.get("marker"):
        open(payload["marker"], "w").close()
    if payload.get("kill"):
        os.kill(os.getpid(), signal.SIGKILL)
    if payload.get("hang"):
        time.sleep(payload["hang"])
    return {"point": payload["index"], "case_hash": str(payload["index"]), "status": "ok"}


def _payloads(n: int, **special) -> list[dict]:
    out = [{"index": i, "case_hash": str(i)} for i in range(n)]
    for key, i in special.items():
        out[i][key] = 60 if key == "hang" else True
    return out


def test_a_killed_worker_fails_only_its_point_and_the_pool_goes_on():
    rows = list(workers.processes(_payloads(6, kill=2), 2, toy))
    by_point = {r["point"]: r for r in rows}
    assert sorted(by_point) == list(range(6))  # every point has exactly one row
    assert len(rows) == 6
    assert by_point[2]["status"] == "failed" and "worker killed" in by_point[2]["error"]
    assert by_point[2]["cause"] == workers.ENVIRONMENT
    assert all(by_point[i]["status"] == "ok" for i in (0, 1, 3, 4, 5))


def test_a_point_past_its_timeout_fails_and_the_others_finish():
    # the hung point would return "ok" after its 60 s: "timed out" is the timeout acting
    rows = list(workers.processes(_payloads(4, hang=1), 2, toy, timeout=workers.PointTimeout(2)))
    by_point = {r["point"]: r for r in rows}
    assert sorted(by_point) == [0, 1, 2, 3] and len(rows) == 4
    assert by_point[1]["status"] == "failed" and "timed out" in by_point[1]["error"]
    assert by_point[1]["cause"] == workers.ENVIRONMENT


def test_the_default_timeout_follows_the_slowest_point():
    t = workers.PointTimeout()
    assert t.seconds == workers.DEFAULT_POINT_TIMEOUT_S
    t.observe(100.0)
    assert t.seconds == pytest.approx(workers.SLOWEST_FACTOR * 100.0)
    assert workers.PointTimeout(3.0).seconds == 3.0


@pytest.mark.parametrize("exc, cause", [
    (OSError(errno.ENOSPC, "No space left on device"), "environment"),
    (OSError(errno.EDQUOT, "Disk quota exceeded"), "environment"),
    (MemoryError(), "environment"),
    (OSError(errno.ENOENT, "No such file"), "case"),
    (ValueError("bad"), "case"),
])
def test_failure_cause(exc, cause):
    assert workers.failure_cause(exc) == cause


def test_failure_cause_looks_through_a_message_raised_from_none():
    from gearcli.errors import OutputError

    try:
        try:
            raise OSError(errno.ENOSPC, "No space left on device")
        except OSError:
            raise OutputError("cannot write") from None
    except OutputError as exc:
        assert workers.failure_cause(exc) == "environment"


STUDY = """parameters:
  gears.face_width: ["80 mm", "100 mm", "120 mm"]
"""


def test_a_sweep_whose_worker_is_killed_records_it_and_resume_retries_it(tmp_path,
                                                                          monkeypatch):
    """The worker process of point 1 is killed (SIGKILL) while it runs that point: the study
    ends with rows for all points, point 1 failed "worker killed"; a resume runs only it."""
    from gearcli.pipeline.sweep import run as sweep_run

    study = load_study(write_study(tmp_path, STUDY))
    killer = study.points[1].case_json
    original = sweep_run.case_from_json

    def case_from_json(text, name):  # runs in the forked worker
        if text == killer:
            os.kill(os.getpid(), signal.SIGKILL)
        return original(text, name)

    monkeypatch.setattr(sweep_run, "case_from_json", case_from_json)
    out = run_study(study, tmp_path / "o", jobs=2)
    assert (out.ran, out.failed) == (3, 1)
    assert [r["status"] for r in out.rows] == ["ok", "failed", "ok"]
    assert "worker killed" in out.rows[1]["error"] and out.rows[1]["cause"] == "environment"
    monkeypatch.setattr(sweep_run, "case_from_json", original)
    again = run_study(study, tmp_path / "o", jobs=2)
    assert (again.skipped, again.ran, again.failed) == (2, 1, 0)
    assert [r["status"] for r in again.rows] == ["ok"] * 3


def test_resume_after_a_full_disk_retries_only_that_point(tmp_path, monkeypatch):
    """Point 1's results cannot be written (ENOSPC): it fails with cause 'environment'; the
    resume reruns it alone and keeps the other points' rows."""
    import gearcli.pipeline.outputs as outputs

    study = load_study(write_study(tmp_path, STUDY))
    original = outputs.write_simulation

    def full_disk(res, target, *args, **kw):
        if str(target).endswith("00001"):
            raise OSError(errno.ENOSPC, "No space left on device")
        return original(res, target, *args, **kw)

    monkeypatch.setattr(outputs, "write_simulation", full_disk)
    out = run_study(study, tmp_path / "o", jobs=1, keep_timeseries=True)
    bad = out.rows[1]
    assert (out.ran, out.failed) == (3, 1)
    assert bad["status"] == "failed" and "No space left on device" in bad["error"]
    rows = read_summary(tmp_path / "o" / SUMMARY, summary_columns(study))
    assert sorted(r["cause"] for r in rows.values()) == ["", "", "environment"]
    kept = {h: r["wall_time_s"] for h, r in rows.items() if r["status"] == "ok"}
    monkeypatch.setattr(outputs, "write_simulation", original)
    again = run_study(study, tmp_path / "o", jobs=1, keep_timeseries=True)
    assert (again.skipped, again.ran, again.failed) == (2, 1, 0)
    rows = read_summary(tmp_path / "o" / SUMMARY, summary_columns(study))
    assert {h: r["wall_time_s"] for h, r in rows.items() if h in kept} == kept  # not rerun
    assert (tmp_path / "o" / "points" / "00001" / "summary.json").is_file()


def test_a_point_failed_by_its_case_is_not_retried(tmp_path):
    study = load_study(write_study(tmp_path, 'parameters:\n  gears.pressure_angle: '
                                   '["20 deg", "17 deg"]\n'))
    out = run_study(study, tmp_path / "o", jobs=1)
    assert out.rows[1]["status"] == "failed" and out.rows[1]["cause"] == "case"
    assert run_study(study, tmp_path / "o", jobs=1).ran == 0


def test_a_summary_without_the_cause_column_is_resumed(tmp_path):
    study = load_study(write_study(tmp_path, 'parameters:\n  gears.face_width: ["80 mm"]\n'))
    run_study(study, tmp_path / "o", jobs=1)
    path = tmp_path / "o" / SUMMARY
    import csv

    with open(path, newline="") as fh:
        old = list(csv.DictReader(fh))
    cols = [c for c in summary_columns(study) if c != "cause"]
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, cols, extrasaction="ignore", lineterminator="\n")
        w.writeheader()
        w.writerows(old)
    assert run_study(study, tmp_path / "o", jobs=1).skipped == 1


def test_tls_without_a_tls_configuration_is_a_clear_error():
    pytest.importorskip("distributed")
    from gearcli.errors import OutputError

    with pytest.raises(OutputError, match="tls:// needs the Dask TLS configuration"):
        workers.tls_security("tls://127.0.0.1:8786")


def test_tls_scheduler_on_the_command_line_is_exit_1(tmp_path):
    pytest.importorskip("distributed")
    from typer.testing import CliRunner

    from gearcli.cli import app

    path = write_study(tmp_path, 'parameters:\n  gears.face_width: ["80 mm"]\n')
    r = CliRunner().invoke(app, ["sweep", str(path), "-o", str(tmp_path / "o"),
                                 "--scheduler", "tls://127.0.0.1:8786"])
    assert r.exit_code == 1, r.output
    assert "TLS configuration" in r.stderr


@pytest.mark.slow
def test_a_dead_external_dask_worker_times_out_per_point(tmp_path):
    """The only worker of an external cluster dies mid-sweep: the points time out and are
    recorded, the sweep does not wait forever."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=0, processes=True,
                                  dashboard_address=None) as cluster:
        env = {**os.environ, "PYTHONPATH": str(ROOT)}
        worker = subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_worker", cluster.scheduler_address,
             "--no-nanny", "--nthreads", "1", "--no-dashboard"],
            cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            with distributed.Client(cluster.scheduler_address) as client:
                client.wait_for_workers(1, timeout=120)
            marker = tmp_path / "started"
            payloads = [{**p, "hang": 60, "marker": str(marker)} for p in _payloads(3)]
            rows = workers.dask(payloads, 1, cluster.scheduler_address, toy,
                                timeout=workers.PointTimeout(4))
            killer = _kill_when(worker, marker)
            got = list(rows)
            killer.join()
        finally:
            worker.kill()
            worker.wait()
    assert sorted(r["point"] for r in got) == [0, 1, 2]
    # every point "timed out" (a hung point would have returned "ok" after its 60 s)
    assert all(r["status"] == "failed" and "timed out" in r["error"] for r in got)


def _kill_when(proc, marker):
    """Kill ``proc`` once a point has started on it (``marker`` exists)."""
    import threading

    def kill():
        for _ in range(1200):
            if marker.exists():
                break
            time.sleep(0.05)
        proc.kill()

    t = threading.Thread(target=kill, daemon=True)
    t.start()
    return t


def test_the_command_line_says_a_rerun_retries_environment_failures(tmp_path, monkeypatch):
    from typer.testing import CliRunner

    import gearcli.pipeline.outputs as outputs
    from gearcli.cli import app

    def full_disk(res, target, *args, **kw):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(outputs, "write_simulation", full_disk)
    path = write_study(tmp_path, 'parameters:\n  gears.face_width: ["80 mm"]\n')
    r = CliRunner().invoke(app, ["sweep", str(path), "-o", str(tmp_path / "o"), "-j", "1",
                                 "--keep-timeseries", "-q"])
    assert r.exit_code == 4, r.output
    assert "1 failed for their environment" in r.stderr
    assert "the same command again retries them" in r.stderr
