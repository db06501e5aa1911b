"""`analyze`'s resonance margin from the summary's modes (issue 5), and the fallback to the mesh
mode of older results folders. Unit level: the check's inputs are the typed stored modes."""

import pytest

from gearcli.case.schema import Checks
from gearcli.pipeline.analyze import resonance_check
from gearcli.pipeline.modal import modes_summary
from gearcli.results import StoredMode

F_Z = 141.67  # Hz, the seed's gear-mesh frequency
CHECKS = Checks()  # 5 harmonics, 10 % margin


NO_MESH_MODE = (float("nan"), float("nan"))  # unused when the summary has modes


def mode(n, f, zeta, rigid=False):
    return StoredMode(n, None if rigid else f, None if rigid else zeta, "", rigid)


def test_all_elastic_modes_are_checked_nearest_first():
    # mode 3 (lightly damped) lies 3 % above 3 f_z = 425.0 Hz; mode 2 is >= 19 % from all k f_z
    modes = [mode(1, None, None, rigid=True), mode(2, 350.0, 0.05), mode(3, 437.8, 0.02)]
    check, per_harmonic, rows = resonance_check(tuple(modes), NO_MESH_MODE, F_Z, CHECKS)
    assert not check.passed
    assert check.value == pytest.approx(abs(3 * F_Z - 437.8) / 437.8 * 100)
    assert "3 x f_z" in check.note and "mode 3" in check.note and "violated" in check.note
    assert {r.mode for r in rows} == {2, 3}  # the rigid-body mode is not a resonance
    assert len(per_harmonic) == CHECKS.harmonics
    assert per_harmonic[2] == pytest.approx(check.value)


def test_mode_without_peak_is_not_checked():
    modes = [mode(1, 437.8, 1.5), mode(2, 1000.0, 0.05)]  # 1000 Hz: 41 % above 5 f_z
    check = resonance_check(tuple(modes), NO_MESH_MODE, F_Z, CHECKS).check
    # the value is the margin to the nearest mode WITH a peak: 5 f_z = 708.3 Hz vs 1000 Hz
    assert check.passed and check.checked
    assert check.value == pytest.approx(abs(5 * F_Z - 1000.0) / 1000.0 * 100)
    assert "mode(s) 1 have no resonant peak" in check.note
    only = resonance_check(tuple(modes[:1]), NO_MESH_MODE, F_Z, CHECKS).check
    assert only.verdict == "not checked" and only.passed is None and only.value is None
    assert only.note.startswith("not checked: no mode has a resonant peak")


def test_older_folders_use_the_mesh_mode_keys():
    # a summary whose modes list is empty (no modal result stored): the mesh mode
    check, _, rows = resonance_check((), (281.19, 0.05), F_Z, CHECKS)
    assert not check.passed  # 2 f_z = 283.3 Hz, 0.76 % away
    assert check.value == pytest.approx(abs(2 * F_Z - 281.19) / 281.19 * 100)
    assert "vs mesh mode 281.2 Hz" in check.note
    assert rows is None  # analysis.json gets no resonance_margins
    # the seed's overdamped mesh: no peak, not checked
    check = resonance_check((), (281.19, 1.89), F_Z, CHECKS).check
    assert check.verdict == "not checked" and check.passed is None and check.value is None


def test_summary_from_modal_result_feeds_the_check():
    from gearcli.pipeline.modal import run_modal
    from tests.conftest import SEED

    result = run_modal(SEED, ["contact.max_damping=1"]).result  # 281.2 Hz, lightly damped
    check = resonance_check(modes_summary(result), NO_MESH_MODE, F_Z, CHECKS).check
    assert not check.passed and "2 x f_z" in check.note and "mode 1" in check.note


def test_a_run_up_window_that_crosses_a_mode_fails_the_margin():
    """A window whose mesh frequency sweeps 100-300 Hz (a run-up): 2 x f_z sweeps 200-600 Hz
    and crosses the 437.8 Hz mode (margin 0, fail) although 2 x the mean 200 Hz is 8.6 % away;
    a steady window (spread <= 5 %) keeps the margin at the mean f_z."""
    modes = [mode(1, 437.8, 0.02)]
    swept = resonance_check(tuple(modes), NO_MESH_MODE, 200.0, CHECKS, (100.0, 300.0)).check
    assert not swept.passed and swept.value == 0.0
    assert "not steady" in swept.note and "100.0-300.0 Hz" in swept.note
    steady = resonance_check(tuple(modes), NO_MESH_MODE, 200.0, CHECKS, (198.0, 202.0)).check
    assert steady.value == pytest.approx(abs(2 * 200.0 - 437.8) / 437.8 * 100)
    # a band that misses the mode: the margin is the distance of the nearer band end
    # (bands k x 100-110 Hz, k = 1..5: the nearest end is 5 x 110 = 550 Hz, 21.4 % below 700)
    miss = resonance_check((mode(1, 700.0, 0.02),), NO_MESH_MODE, 105.0, CHECKS,
                           (100.0, 110.0)).check
    assert miss.passed and miss.value == pytest.approx((700.0 - 550.0) / 700.0 * 100)
