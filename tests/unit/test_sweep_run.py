"""Running studies: executors agree, resume after an interruption, failures are rows, and the
computed trends agree with physics that can be argued."""

import csv
import math

import numpy as np
import pytest

from gearcli.pipeline.sweep.run import (
    SUMMARY,
    TIMING_COLUMNS,
    read_summary,
    run_study,
    summary_columns,
)
from gearcli.pipeline.sweep.study import load_study
from gearcli.pipeline.sweep.trends import parameter_levels, trend_rows, write_trends
from tests.unit.sweep_helpers import write_study

SMALL = """parameters:
  gears.face_width: ["80 mm", "120 mm"]
  mesh_frequency: ["100 Hz", "150 Hz", "200 Hz"]
"""


def _rows(path):
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:
        for c in TIMING_COLUMNS:
            r.pop(c)
    return rows


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    folder = tmp_path_factory.mktemp("small")
    study = load_study(write_study(folder, SMALL))
    out = run_study(study, folder / "serial", jobs=1)
    return study, folder, out


def test_serial_run_writes_one_row_per_point(small):
    study, folder, out = small
    assert (out.total, out.ran, out.skipped, out.failed) == (6, 6, 0, 0)
    rows = _rows(folder / "serial" / SUMMARY)
    assert [int(r["point"]) for r in rows] == list(range(6))
    assert all(r["status"] == "ok" and len(r["case_hash"]) == 64 for r in rows)
    # the measured mesh frequency is the requested one
    for r in rows:
        assert float(r["gear_mesh_frequency_Hz"]) == pytest.approx(float(r["mesh_frequency [Hz]"]))


def test_processes_give_the_same_summary(small):
    study, folder, _ = small
    run_study(study, folder / "procs", jobs=2)
    assert _rows(folder / "procs" / SUMMARY) == _rows(folder / "serial" / SUMMARY)


@pytest.mark.slow
def test_dask_local_cluster_gives_the_same_summary(small):
    pytest.importorskip("distributed")
    study, folder, _ = small
    run_study(study, folder / "dask", jobs=2, scheduler="local")
    assert _rows(folder / "dask" / SUMMARY) == _rows(folder / "serial" / SUMMARY)


def test_resume_after_a_torn_summary(small):
    study, folder, _ = small
    target = folder / "resume"
    run_study(study, target, jobs=1)
    path = target / SUMMARY
    lines = path.read_text().splitlines(keepends=True)
    # as after a SIGKILL: two complete rows, then half a line
    path.write_text("".join(lines[:3]) + lines[3][: len(lines[3]) // 2])
    assert len(read_summary(path, summary_columns(study))) == 2
    again = run_study(study, target, jobs=2)
    assert (again.skipped, again.ran) == (2, 4)
    assert _rows(path) == _rows(folder / "serial" / SUMMARY)
    assert run_study(study, target, jobs=2).ran == 0  # complete: nothing to do


def test_summary_of_another_study_is_refused(small, tmp_path):
    study, folder, _ = small
    other = load_study(write_study(tmp_path, "parameters:\n  gears.module: [9]\n"))
    from gearcli.errors import OutputError

    with pytest.raises(OutputError, match="different study"):
        run_study(other, folder / "serial", jobs=1)


def test_failed_points_are_recorded_not_fatal(tmp_path):
    study = load_study(write_study(tmp_path, """parameters:
  gears.pressure_angle: ["20 deg", "17 deg"]
checks:
  - {metric: dynamic_factor, max: 1.0}
"""))
    out = run_study(study, tmp_path / "out", jobs=1)
    assert (out.ran, out.failed) == (2, 1)
    ok, bad = _rows(tmp_path / "out" / SUMMARY)
    assert ok["status"] == "ok" and ok["checks"].startswith("fail: dynamic_factor")
    assert bad["status"] == "failed" and "interference" in bad["error"]
    assert bad["force_max_N"] == ""
    paths = write_trends(tmp_path / "out", study, out.rows)
    assert "point 1:" in (tmp_path / "out" / "trends.md").read_text()
    assert all(p.exists() for p in paths)


def _derived_study(folder, body: str, speed_deg_s: float = 3000, end_s: float = 0.4):
    """A study on the seed with the ISO 6336-1 derived (linear) stiffness."""
    from tests.unit.sweep_helpers import SEED

    path = folder / "derived.yaml"
    path.write_text(f"""base: {SEED}
set:
  run.end_time: {end_s} s
  drive.speed: STEP(time, 0, 0, 0.2, {speed_deg_s})
  load.torque: STEP(time, 0, 0, 0.2, 4.5e+05)
  contact.stiffness: derived
  contact.exponent: 1
  contact.max_damping: 5 N*s/mm
  contact.penetration_depth: 0.001 mm
design: one_at_a_time
""" + body)
    return load_study(path)


def test_stiffer_mesh_has_a_higher_natural_frequency(tmp_path):
    """Mesh mode (docs/theory.md §6): f_n = sqrt(k / m_eq) / 2 pi, so 4x the (linear) pair stiffness
    gives 2x f_n; the transmission error fluctuation falls with stiffness (delta ~ F / k)."""
    study = _derived_study(tmp_path, """parameters:
  contact.stiffness: ["5e5 N/mm", "1e6 N/mm", "2e6 N/mm"]
""")
    out = run_study(study, tmp_path / "out", jobs=1)
    assert out.failed == 0
    write_trends(tmp_path / "out", study, out.rows)
    import pandas as pd

    df = pd.read_csv(tmp_path / "out" / SUMMARY)
    k, f_n = parameter_levels(df, study, "contact.stiffness [N/mm]", "mesh_natural_frequency_Hz")
    assert np.all(np.diff(f_n) > 0)
    assert f_n[-1] / f_n[0] == pytest.approx(math.sqrt(k[-1] / k[0]), rel=0.01)
    trends = {t["metric"]: t for t in trend_rows(df, study)}
    assert trends["dte_peak_to_peak_mm"]["direction"] == "decreases"
    # the derived (ISO 6336-1) base point: c' b ~ 0.9e6 N/mm, f_n between the 5e5 and 2e6 ones
    base = df[df["point"] == 0].iloc[0]
    assert 5e5 < base["single_pair_stiffness_N_mm"] < 2e6
    assert f_n[0] < base["mesh_natural_frequency_Hz"] < f_n[-1]


def test_tip_relief_sized_for_the_load_lowers_dte(tmp_path):
    """Tip relief about the single-pair deflection F/c' (here ~0.004 mm) on both gears smooths
    the load transfer at the ends of the double-contact zones, so the transmission error
    fluctuates less than with unmodified involutes (Harris 1958; Smith, Gear Noise and
    Vibration, ch. 4). Low speed, so the quasi-static error dominates."""
    study = _derived_study(tmp_path, """parameters:
  modifications.tip_relief.pinion.amount:
    values: ["0.005 mm"]
    with: {modifications.tip_relief.pinion.length: 8 mm,
           modifications.tip_relief.gear.amount: "{value}",
           modifications.tip_relief.gear.length: 8 mm}
""", speed_deg_s=600, end_s=0.6)
    out = run_study(study, tmp_path / "out", jobs=1)
    base, relieved = out.rows
    deflection = base["force_static_N"] / base["single_pair_stiffness_N_mm"]
    assert 0.5 * deflection < 0.005 < 2.0 * deflection  # "sized for the load"
    assert relieved["dte_peak_to_peak_mm"] < 0.9 * base["dte_peak_to_peak_mm"]


@pytest.mark.slow
def test_dask_external_scheduler_address_gives_the_same_summary(small):
    # An existing cluster reached by its tcp:// address (here one started on loopback).
    distributed = pytest.importorskip("distributed")
    study, folder, _ = small
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        assert cluster.scheduler_address.startswith("tcp://")
        run_study(study, folder / "tcp", jobs=2, scheduler=cluster.scheduler_address)
    assert _rows(folder / "tcp" / SUMMARY) == _rows(folder / "serial" / SUMMARY)
