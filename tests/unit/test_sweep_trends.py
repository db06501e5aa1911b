"""Trend arithmetic of gearcli sweep (issue 19): the change from the lowest to the highest level
with the right sign and ratio, directions from the rank correlation, and grid plots with one
line per combination of the other parameters."""

from __future__ import annotations

import pandas as pd
import pytest

from gearcli.pipeline.sweep.study import load_study_text
from gearcli.pipeline.sweep.trends import _trend_lines, trend_rows
from tests.unit.sweep_helpers import FAST_SET

COL = "gears.face_width [mm]"


def _study(parameters: str, design: str = "grid"):
    return load_study_text(FAST_SET + f"design: {design}\nparameters:\n{parameters}", "t.yaml")


def _frame(study, values):
    rows = []
    for pt, v in zip(study.points, values, strict=True):
        rows.append({"point": pt.index, **pt.values, "status": "ok", "dynamic_factor": v,
                     "force_max_N": v, "dte_peak_to_peak_mm": v,
                     "gear_speed_gmf_amplitude_rad_s": v})
    return pd.DataFrame(rows)


@pytest.mark.parametrize("values, change, ratio, direction", [
    ([1.0, 1.2, 7.0], 600.0, 7.0, "increases"),      # a 7x rise is +600 %, not +17 %
    ([2.0, 1.0, 3.0], 50.0, 1.5, "non-monotonic"),   # a rise overall, with a dip: positive
    ([4.0, 3.0, 1.0], -75.0, 0.25, "decreases"),
])
def test_change_is_the_highest_level_against_the_lowest(values, change, ratio, direction):
    study = _study("  gears.face_width: [\"60 mm\", \"80 mm\", \"100 mm\"]\n")
    row = next(r for r in trend_rows(_frame(study, values), study)
               if r["metric"] == "dynamic_factor")
    assert row["change_percent"] == pytest.approx(change)
    assert row["ratio"] == pytest.approx(ratio)
    assert row["direction"] == direction
    assert (row["metric_at_min"], row["metric_at_max"]) == (values[0], values[-1])


def test_grid_plots_one_line_per_combination_of_the_others():
    study = _study("  gears.face_width: [\"60 mm\", \"100 mm\"]\n"
                   "  contact.max_damping: [\"1 N*s/mm\", \"5 N*s/mm\"]\n")
    # a peak in neither case: the averaged curve would invent one
    values = {(60.0, 1.0): 1.0, (60.0, 5.0): 3.0, (100.0, 1.0): 3.0, (100.0, 5.0): 1.0}
    df = _frame(study, [values[(pt.values[COL], pt.values["contact.max_damping [N*s/mm]"])]
                        for pt in study.points])
    p = next(q for q in study.parameters if q.column == COL)
    lines = _trend_lines(df, study, p, "dynamic_factor")
    assert len(lines) == 2
    by_label = {label: list(y) for label, _, y in lines}
    assert by_label == {"contact.max_damping [N*s/mm] = 1": [1.0, 3.0],
                        "contact.max_damping [N*s/mm] = 5": [3.0, 1.0]}


def test_grid_trend_uses_only_combinations_that_ran_at_every_level():
    # third adversarial run: one invalid point made the max_damping "trend" an average of 3
    # points at one level against 4 at the other, +8.6 % where matched pairs went both ways
    study = _study("  gears.face_width: [\"60 mm\", \"100 mm\"]\n"
                   "  contact.max_damping: [\"1 N*s/mm\", \"5 N*s/mm\", \"9 N*s/mm\"]\n")
    damping = "contact.max_damping [N*s/mm]"
    values = {(60.0, 1.0): 1.0, (60.0, 5.0): 1.0, (60.0, 9.0): 1.0,
              (100.0, 1.0): 2.0, (100.0, 5.0): 2.0, (100.0, 9.0): 2.0}
    df = _frame(study, [values[(pt.values[COL], pt.values[damping])] for pt in study.points])
    bad = (df[COL] == 100.0) & (df[damping] == 9.0)
    df.loc[bad, "status"] = "invalid"  # the 100 mm combination misses the 9 N*s/mm level
    row = next(r for r in trend_rows(df, study)
               if r["parameter"] == damping and r["metric"] == "dynamic_factor")
    assert row["direction"] == "no effect" and row["change_percent"] == pytest.approx(0.0)
    row = next(r for r in trend_rows(df, study)
               if r["parameter"] == COL and r["metric"] == "dynamic_factor")
    assert row["change_percent"] == pytest.approx(100.0)  # the 1 and 5 N*s/mm pairs: 1 -> 2


def test_a_rank_correlation_at_the_threshold_is_monotonic():
    # 5 levels with two swaps: rho = 1 - 6·4/(5·24) = 0.8, which floating point may give an ulp
    # below; the rule must not depend on that last bit
    study = _study("  gears.face_width: [\"60 mm\", \"70 mm\", \"80 mm\", \"90 mm\", "
                   "\"100 mm\"]\n")
    row = next(r for r in trend_rows(_frame(study, [2.0, 1.0, 4.0, 3.0, 5.0]), study)
               if r["metric"] == "dynamic_factor")
    assert row["spearman_rho"] == pytest.approx(0.8) and row["direction"] == "increases"
