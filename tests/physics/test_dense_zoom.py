"""The figures' zooms come from the solver's dense output (issue 15): >= 100 points per mesh
period, the same trajectory as the run (pipeline/simulate.dense_zoom)."""

from __future__ import annotations

import numpy as np
import pytest

from gearcli.pipeline.simulate import ZOOM_POINTS_PER_PERIOD, run_simulation
from tests.conftest import SEED
from tests.physics.simrun import FAST


@pytest.fixture(scope="module")
def res():
    return run_simulation(SEED, FAST)


def test_zoom_is_dense_and_covers_the_maximum_and_the_end(res):
    z, k = res.zoom, res.kernel
    period = 1.0 / res.kernel_input.gear_mesh_frequency_Hz
    t = z["t_s"]
    assert ZOOM_POINTS_PER_PERIOD >= 100
    assert np.all(np.diff(t) > 0.0)
    steps = np.diff(t)
    assert steps.min() == pytest.approx(period / ZOOM_POINTS_PER_PERIOD, rel=1e-6)
    t_max = k.extremum("force_total_max_t_s")
    assert t.min() <= t_max - 1.9 * period and t.max() >= t_max + 1.9 * period
    assert t[-1] == pytest.approx(res.loaded.case.run.end_time, abs=1e-12)
    for name in ("force_total_N", "delta_mm", "pairs_in_contact", "force_slot0_N"):
        assert name in z and z[name].shape == t.shape and np.all(np.isfinite(z[name]))


def test_zoom_is_the_same_trajectory(res):
    """Same steps, sampled finer: the dense maximum cannot exceed the solver's true maximum
    (taken at its steps and samples, docs/theory.md §7.4) by more than the continuous
    extension's interpolation between them, and at the last output time (the run's end, in
    both tables) the values agree to rounding."""
    z, k = res.zoom, res.kernel
    f_max = k.extremum("force_total_max_N")
    assert z["force_total_N"].max() == pytest.approx(f_max, rel=1e-3)
    for name in ("delta_mm", "force_total_N", "omega2_rad_s"):
        assert z[name][-1] == pytest.approx(k.column(name)[-1], rel=1e-9, abs=1e-12), name


def test_sweep_points_skip_the_zoom():
    r = run_simulation(SEED, [*FAST[:2], "run.end_time=0.3"], zoom=False)
    assert r.zoom == {}
