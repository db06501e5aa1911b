"""Sweep figures (issue 29): invalid and failed points break the lines (NaN in the plotted
data) and are marked and named; every axis is labelled from the field metadata in display
units (DTE in µm), never with a raw key."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from gearcli.pipeline.sweep.study import load_study_text
from gearcli.pipeline.sweep.trends import _markdown, speed_figure, trend_figure, trend_rows
from tests.unit.sweep_helpers import FAST_SET


def _study(parameters: str):
    return load_study_text(FAST_SET + f"design: grid\nparameters:\n{parameters}", "t.yaml")


def _frame(study, statuses, dte_mm=0.01):
    rows = []
    for i, (pt, status) in enumerate(zip(study.points, statuses, strict=True)):
        ok = status == "ok"
        value = 1.0 + i if ok else math.nan
        rows.append({"point": pt.index, **pt.values, "status": status,
                     "error": "" if ok else f"{status}: because", "dynamic_factor": value,
                     "force_max_N": 1000.0 * value, "dte_peak_to_peak_mm": dte_mm * value,
                     "gear_speed_gmf_amplitude_rad_s": value, "dte_rms_mm": dte_mm * value,
                     "mesh_natural_frequency_Hz": 400.0})
    return pd.DataFrame(rows)


def _data_lines(ax):
    """The metric lines of a panel (not the markers of bad points or the f_n lines)."""
    return [ln for ln in ax.get_lines() if ln.get_linestyle() == "-"
            and ln.get_marker() == "o"]


def _raw_key(text: str) -> bool:
    return any(s in text for s in ("_mm", "_N", "_rad_s", "_Hz", "_factor", "dynamic_factor"))


def test_an_invalid_point_breaks_the_trend_line_and_is_marked():
    study = _study('  gears.face_width: ["60 mm", "80 mm", "100 mm", "120 mm"]\n')
    df = _frame(study, ["ok", "invalid", "ok", "failed"])
    fig = trend_figure(study, df, study.parameters[0])
    for ax in fig.axes:
        (line,) = _data_lines(ax)
        x, y = line.get_xdata(), line.get_ydata()
        assert list(x) == [60.0, 80.0, 100.0, 120.0]
        assert np.isnan(y[1]) and np.isnan(y[3]) and np.isfinite(y[[0, 2]]).all()
        labels = ax.get_legend_handles_labels()[1]
        assert "invalid (1 points)" in labels and "failed (1 points)" in labels
        assert not _raw_key(ax.get_ylabel()), ax.get_ylabel()
    by_label = {ax.get_ylabel(): ax for ax in fig.axes}
    dte = by_label["DTE, peak to peak [µm]"]
    assert _data_lines(dte)[0].get_ydata()[0] == 10.0  # 0.01 mm shown as 10 µm


def test_a_grid_line_breaks_at_its_own_invalid_point():
    study = _study('  gears.face_width: ["60 mm", "80 mm", "100 mm"]\n'
                   '  contact.max_damping: ["1 N*s/mm", "5 N*s/mm"]\n')
    statuses = ["ok"] * len(study.points)
    width = "gears.face_width [mm]"
    damping = "contact.max_damping [N*s/mm]"
    bad = next(i for i, pt in enumerate(study.points)
               if pt.values[width] == 80.0 and pt.values[damping] == 5.0)
    statuses[bad] = "invalid"
    df = _frame(study, statuses)
    p = next(q for q in study.parameters if q.column == width)
    ax = trend_figure(study, df, p).axes[0]
    ys = {ln.get_label(): ln.get_ydata() for ln in _data_lines(ax)}
    assert np.isnan(ys[f"{damping} = 5"][1]) and np.isfinite(ys[f"{damping} = 1"]).all()


def test_the_speed_sweep_breaks_at_invalid_points_and_shows_dte_in_um():
    study = load_study_text(FAST_SET + 'design: grid\nparameters:\n  mesh_frequency: '
                            '["100 Hz", "150 Hz", "200 Hz", "250 Hz"]\n', "t.yaml")
    df = _frame(study, ["ok", "invalid", "ok", "ok"])
    fig = speed_figure(study, df, study.parameters[0])
    top, bottom = fig.axes
    assert top.get_ylabel() == "dynamic factor F_max / F_static"
    assert bottom.get_ylabel() == "DTE, standard deviation [µm]"
    assert bottom.get_xlabel() == "gear-mesh frequency f_z [Hz]"
    for ax in (top, bottom):
        (line,) = _data_lines(ax)
        assert np.isnan(line.get_ydata()[1]) and np.isfinite(line.get_ydata()[[0, 2, 3]]).all()
        assert "invalid (1 points)" in ax.get_legend_handles_labels()[1]
    assert _data_lines(bottom)[0].get_ydata()[0] == 10.0


def test_trends_md_names_invalid_and_failed_points_apart_and_labels_metrics():
    study = _study('  gears.face_width: ["60 mm", "80 mm", "100 mm", "120 mm"]\n')
    df = _frame(study, ["ok", "invalid", "ok", "failed"])
    text = _markdown(study, df, trend_rows(df, study))
    assert "2 ok, 1 invalid (outside the model's validity), 1 failed (the run did not finish)" \
        in text
    assert "## Invalid points" in text and "## Failed points" in text
    invalid = text.split("## Invalid points")[1].split("##")[0]
    assert "point 1: invalid: because" in invalid and "point 3" not in invalid
    table = [ln for ln in text.splitlines() if ln.startswith("| gears")]
    assert table and not any("dte_peak_to_peak_mm" in ln for ln in table)
    assert any("DTE, peak to peak [µm]" in ln for ln in table)


def test_the_speed_curve_breaks_at_invalid_and_failed_levels():
    from gearcli.plotting.speed_curve import plot_speed_curve
    from gearcli.results import SpeedLevel

    statuses = ["ok", "invalid", "ok", "failed", "ok"]
    rows = [SpeedLevel(point=i, direction="up", resonance_ratio=0.2 * (i + 1),
                       dynamic_factor=1.0 + 0.1 * i, status=s)
            for i, s in enumerate(statuses)]
    ax = plot_speed_curve(rows, 1000.0).axes[0]
    (line,) = [ln for ln in ax.get_lines() if ln.get_label() == "gearcli run-up"]
    y = np.asarray(line.get_ydata(), float)
    assert list(np.isnan(y)) == [s != "ok" for s in statuses]
    labels = ax.get_legend_handles_labels()[1]
    assert "run-up: invalid (outside the model's validity)" in labels
    assert "run-up: failed (the run did not finish)" in labels
