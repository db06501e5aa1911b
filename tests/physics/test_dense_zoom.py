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


def test_samples_do_not_steer_the_steps():
    """The zoom's premise, exactly: the time loop evaluates the right-hand side at one call
    site for the stages, the output samples (dense output inside a step, Euler inside a hop
    over a loaded table end), the hop ends and each chunk's start (core/timeloop.run), and a
    sample must leave the steps untouched. The seed with rigid engagement (every entry and
    exit a loaded table end: a force jump the loop hops over, docs/theory.md §6.8) and
    friction, over 2.5 s: two chunks (integrate.chunk_ends). Same process and compiled code,
    so the comparison is exact."""
    from gearcli.core.integrate import chunk_ends, simulate

    r = run_simulation(SEED, [*FAST[:2], "run.end_time=2.5", "contact.engagement=rigid"],
                       zoom=False)
    ki = r.kernel_input
    assert len(chunk_ends(0.0, 2.5)) == 2

    def run(times):
        return simulate(ki.params.copy(), ki.tables.tables, t_out=times, drive_pp=ki.drive_pp,
                        load_pp=ki.load_pp, drive_angle_pp=ki.drive_angle_pp, **ki.arrays)

    times = np.linspace(0.0, 2.5, 50001)  # ~2.8 samples per mesh period
    fine, coarse = run(times), run(times[::500])
    assert fine.ok and coarse.ok
    c = fine.counters
    for name in ("accepted_steps", "rejected_steps", "rhs_evaluations"):
        assert c[name] == coarse.counters[name], name
    # RHS evaluations: 6 per step attempt, 1 at each chunk's start, 1 for the starting step
    # size, 1 at the end of every hop: the run hopped over table ends
    hops = c["rhs_evaluations"] - 6 * (c["accepted_steps"] + c["rejected_steps"]) - 2 - 1
    assert hops > 100
    assert c["output_evaluations"] > 100 * coarse.counters["output_evaluations"]
    assert np.array_equal(fine.series[::500], coarse.series, equal_nan=True)
    assert np.array_equal(fine.slot_force[::500], coarse.slot_force, equal_nan=True)
