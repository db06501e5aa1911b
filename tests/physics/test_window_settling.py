"""A run whose window starts after its ramps but before the settling time has passed (the
window falls back to the last 20 mesh cycles) is told so (docs/theory.md §7.6).

Measured before: `cases/iso_pair.yaml` with damping ratio 0.005 (settling time 5/(ζ ω_n) =
98 ms) ended at 0.25 s: its window started 7 ms after the ramps, 0.36 time constants, and the
run reported a dynamic factor of 1.404 and DTE peak-to-peak 5.36 µm (settled, 1 s run: 1.357,
4.93 µm) with no warning at all.
"""

from __future__ import annotations

from pathlib import Path

from gearcli.pipeline.simulate import run_simulation

ISO_PAIR = Path(__file__).resolve().parents[2] / "cases" / "iso_pair.yaml"
LOW_DAMPING = ["contact.damping_ratio=0.005"]


def _settling(res):
    return [w for w in res.warnings if w.startswith("not settled")]


def test_a_window_inside_the_settling_time_is_named_with_its_leftover_transient():
    res = run_simulation(ISO_PAIR, [*LOW_DAMPING, "run.end_time=0.25"], zoom=False)
    (warning,) = _settling(res)
    assert "time constants" in warning and "%" in warning


def test_a_settled_window_has_no_such_warning():
    res = run_simulation(ISO_PAIR, [*LOW_DAMPING, "run.end_time=0.4"], zoom=False)
    assert res.window.t0_s < 0.4 - 0.05 and _settling(res) == []


def test_the_leftover_of_an_almost_or_fully_undamped_mesh_reads_as_a_percentage():
    """ζ 1e-6: 0.0015 time constants after the ramps, 99.85 % left, which the warning printed
    as "up to 1e+02 %"; ζ 0 (no settling at all) printed "0 time constants ... settled after
    5, at inf s ... up to 1e+02 %"."""
    (tiny,) = _settling(run_simulation(ISO_PAIR, ["contact.damping_ratio=1e-6",
                                                  "run.end_time=0.4"], zoom=False))
    assert "e+" not in tiny and "up to 99.8 %" in tiny, tiny
    (none,) = _settling(run_simulation(ISO_PAIR, ["contact.damping_ratio=0",
                                                  "run.end_time=0.4"], zoom=False))
    assert "e+" not in none and "inf" not in none and "never" in none, none
