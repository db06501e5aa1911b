"""The output-rate warning of `gearcli simulate` (docs/theory.md §7.5): "fewer than 10 samples"
only when the asked rate gives fewer than 10 samples, not whenever the rate is rounded to a
whole number of output intervals (measured before: `run.output_rate=1629.95 Hz` on a 0.6 s run,
978 samples, warned "gives fewer than 10 samples in the run: written at 1630 Hz instead")."""

from __future__ import annotations

from pathlib import Path

from gearcli.pipeline.simulate import run_simulation

ISO_PAIR = Path(__file__).resolve().parents[2] / "cases" / "iso_pair.yaml"
SHORT = ["drive.speed={function: 'STEP(time, 0, 0, 0.1, 1340)', unit: rpm}",
         "load.torque={function: 'STEP(time, 0, 0, 0.1, 300)', unit: N*m}",
         "run.end_time=0.25"]


def _rate_warnings(rate):
    res = run_simulation(ISO_PAIR, [*SHORT, f"run.output_rate={rate}"], zoom=False)
    return [w for w in res.warnings if "fewer than 10 samples" in w]


def test_a_rate_rounded_to_whole_intervals_is_no_short_run():
    assert _rate_warnings(10001.3) == []  # 2501 intervals: 10004 Hz written


def test_a_rate_with_fewer_than_10_samples_is_still_named():
    assert len(_rate_warnings(20)) == 1  # 5 samples asked, 10 written
