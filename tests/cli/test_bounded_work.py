"""Issue 32: drawing and analysis sizes are limited up front. `geometry --plot` took 180 s at
3000 teeth; a 29 MB Parquet time series that decodes to 51 GB took `analyze` past 3 GB."""

from __future__ import annotations

import numpy as np
import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.plotting.geometry import MAX_DRAWN_TEETH
from tests.conftest import ROOT

runner = CliRunner()
SEED = str(ROOT / "cases" / "seed.yaml")


def test_plot_of_too_many_teeth_is_refused_before_drawing(tmp_path):
    fig = tmp_path / "g.png"
    r = runner.invoke(app, ["geometry", SEED, "--set", "gears.gear.teeth=3000",
                            "--set", "gears.pinion.teeth=3000", "--plot", str(fig)])
    assert r.exit_code == 1, r.output
    assert f"at most {MAX_DRAWN_TEETH} teeth" in r.stderr and "z2 = 3000" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert not fig.exists()


def test_plot_at_the_limit_is_drawn(tmp_path, monkeypatch):
    # the check itself, at the limit (drawing 500 teeth takes seconds: a smaller pair with the
    # limit lowered stands for it)
    import gearcli.plotting.geometry as geo

    monkeypatch.setattr(geo, "MAX_DRAWN_TEETH", 25)
    fig = tmp_path / "g.png"
    assert runner.invoke(app, ["geometry", SEED, "--plot", str(fig)]).exit_code == 0
    r = runner.invoke(app, ["geometry", SEED, "--set", "gears.gear.teeth=26", "--plot",
                            str(tmp_path / "h.png")])
    assert r.exit_code == 1 and "z2 = 26" in r.stderr and "z1" not in r.stderr


def test_the_report_leaves_out_the_drawing_of_a_pair_above_the_limit(tmp_path, monkeypatch):
    # `run` of a pair too large to draw writes its report without the geometry figure (the
    # limit lowered below the seed's 25 teeth stands for a 600-tooth gear)
    import gearcli.plotting.geometry as geo

    monkeypatch.setattr(geo, "MAX_DRAWN_TEETH", 20)
    out = tmp_path / "run"
    r = runner.invoke(app, ["run", SEED, "-o", str(out), "-q", "--set", "run.end_time=0.3"])
    assert r.exit_code in (0, 4), r.output  # the seed's findings may fail its checks
    assert (out / "report.html").is_file()
    figures = {p.stem for p in (out / "figures").iterdir()}
    assert "geometry" not in figures and "spectra" in figures, figures


@pytest.fixture(scope="module")
def parquet_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("pq") / "run"
    r = runner.invoke(app, ["simulate", SEED, "-o", str(out), "-q", "--format", "parquet",
                            "--set", "run.end_time=0.3"])
    assert r.exit_code == 0, r.output
    return out


def test_a_parquet_series_above_the_bound_is_refused_from_its_metadata(parquet_run,
                                                                       monkeypatch):
    import gearcli.io.results as results
    import gearcli.io.tables as tables

    decoded = []
    monkeypatch.setattr(tables, "parquet_to_columns", lambda p: decoded.append(p))
    monkeypatch.setattr(results, "MAX_PARQUET_VALUES", 1000)
    r = runner.invoke(app, ["analyze", str(parquet_run)])
    assert r.exit_code == 1, r.output
    assert "values; expected at most 1,000" in r.stderr
    assert decoded == []  # refused before any decoding


def test_a_parquet_series_with_more_rows_than_its_summary_is_refused(parquet_run, tmp_path):
    import shutil

    import pyarrow as pa
    import pyarrow.parquet as pq

    copy = tmp_path / "run"
    shutil.copytree(parquet_run, copy)
    path = copy / "timeseries.parquet"
    table = pq.read_table(path)
    n = 10 * table.num_rows  # a file that decodes to more than summary.json says
    pq.write_table(pa.table({c: np.zeros(n) for c in table.column_names}), path,
                   compression="zstd")
    r = runner.invoke(app, ["analyze", str(copy)])
    assert r.exit_code == 1, r.output
    assert "but summary.json says" in r.stderr


# --- the solver's step limit, known from the case -------------------------------------------
ISO = str(ROOT / "cases" / "iso_pair.yaml")
HUGE = ["--set", "gears.pinion.teeth=10000", "--set", "gears.gear.teeth=10000",
        "--set", "run.output_steps=1000"]  # few samples: only the steps are too many


def test_a_run_past_the_solvers_step_limit_is_refused_before_building(tmp_path, monkeypatch):
    """10 000 teeth at iso_pair's 1340 rpm for 30 s: 6.6e6 mesh cycles, each at least one
    step; the solver stops at 5e6. Refused from the case, before the kernel input is built."""
    import gearcli.pipeline.simulate as sim

    def never(*_a, **_k):
        raise AssertionError("built the run")

    monkeypatch.setattr(sim, "build_kernel_input", never)
    out = tmp_path / "big"
    r = runner.invoke(app, ["simulate", ISO, "-o", str(out), *HUGE, "--set", "run.end_time=30"])
    assert r.exit_code == 1, r.output
    line = r.stderr.strip().splitlines()[0]
    assert "run.end_time: got 30" in line and "mesh cycles" in line and "5e+06" in line
    assert not out.exists()


def test_the_step_bound_is_a_lower_bound_of_real_runs():
    """The bound counts the mesh cycles of the speed ramp (seed: 5 s, 0 -> 8.33 rev/s in 1 s,
    17 teeth: 637.5 cycles) and admits a run at 20 s of the 10 000-tooth pair (bound 22.6 s)."""
    from gearcli.case.bounds import MIN_STEPS_PER_MESH_CYCLE, mesh_cycles, solver_steps_error
    from gearcli.case.load import load_case
    from gearcli.core.layout import PARAM_DEFAULTS

    seed = load_case(SEED).case
    assert mesh_cycles(seed) == pytest.approx(17 * (0.5 * 1 + 4) * 3000 / 360, rel=1e-9)
    # the seed run took 27 630 accepted steps (summary.json): 43 a cycle, above the bound's 1
    assert 27630 / mesh_cycles(seed) > MIN_STEPS_PER_MESH_CYCLE
    big = load_case(ISO, ["gears.pinion.teeth=10000", "gears.gear.teeth=10000",
                          "run.end_time=20"]).case
    assert solver_steps_error(big, PARAM_DEFAULTS["max_steps"]) is None
    assert solver_steps_error(big, 0.8 * PARAM_DEFAULTS["max_steps"]) is not None


def test_a_run_stopped_before_its_second_sample_is_invalid_not_a_crash(tmp_path):
    """Found in the closing check of issue 32: a run that left the contact tables before its
    second output sample had an empty window and ended in exit 3 (numpy ptp of nothing)."""
    out = tmp_path / "stop"
    r = runner.invoke(app, ["simulate", ISO, "-o", str(out), *HUGE, "--set", "run.end_time=1",
                            "--set", "load.torque=1e2 N*mm", "-q"])
    assert r.exit_code == 4, r.output
    assert "marked invalid" in r.stderr and "internal error" not in r.output
    assert (out / "summary.json").is_file()
