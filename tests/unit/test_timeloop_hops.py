"""The time loop's planning on its own (core/hops.py): when it stops, the next step, a step cut
short before a predicted crossing and the hop over it (docs/theory.md §6.8), on hand cases.

The crossing time ``tau`` is given by hand (events.next_crossing is tested in
tests/physics); each expected time below is the rule of §6.8 written out. Exact comparisons
where the test evaluates the same expression in the same order.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.core import layout
from gearcli.core.bundles import Out
from gearcli.core.hops import (
    EVENT_HOP,
    EVENT_LANDING,
    EVENT_MIN_OVERSHOOT,
    EVENT_OVERSHOOT,
    EVENT_RESTART,
    begin_attempt,
    end_hop,
    hop_next,
    hop_or_step,
    plan_limits,
    size_after_step,
)
from gearcli.core.layout import P
from gearcli.core.loopstate import LOOP_DTYPE, PH_HOP, PH_HOP_SAMPLE, PH_PLAN, PH_STAGE, ROW_DY
from gearcli.core.records import init_extrema
from gearcli.core.timeloop import new_work


def _state(**fields):
    st = np.zeros(1, LOOP_DTYPE)[0]
    st["t_event"], st["t_recheck"], st["h_cut"] = math.inf, -math.inf, math.inf
    for name, value in fields.items():
        st[name] = value
    return st


def _prm(t_end=2.0, max_step=1e-3, max_steps=1000):
    prm = np.zeros(layout.N_PARAMS)
    prm[P.t_end], prm[P.max_step], prm[P.max_steps] = t_end, max_step, max_steps
    return prm


def _ulp10(t):
    return 10.0 * (np.nextafter(t, math.inf) - t)


def test_the_planner_stops_at_the_end_and_at_max_steps():
    counters = np.zeros(4, dtype=np.int64)
    st = _state(t=2.0, h=1e-4, status=layout.STATUS_OK)
    assert plan_limits(st, counters, _prm(t_end=2.0))
    assert st["status"] == layout.STATUS_OK  # the end: no error
    counters[layout.N.accepted_steps], counters[layout.N.rejected_steps] = 900, 100
    st = _state(t=1.0, h=1e-4)
    assert plan_limits(st, counters, _prm(max_steps=1000))
    assert st["status"] == layout.STATUS_MAX_STEPS


@pytest.mark.parametrize(("t", "h", "expected"), [
    (1.0, 5e-4, 5e-4),  # the controller's size
    (1.0, 0.5, 1e-3),  # at most max_step
    (2.0 - 2e-4, 5e-4, 2.0 - (2.0 - 2e-4)),  # at most to t_end
])
def test_the_planner_limits_the_step(t, h, expected):
    st = _state(t=t, h=h)
    assert not plan_limits(st, np.zeros(4, dtype=np.int64), _prm(t_end=2.0, max_step=1e-3))
    assert st["h"] == expected
    assert st["h_min"] == _ulp10(t)


@pytest.mark.parametrize(("nonfinite_last", "status"), [
    (0, layout.STATUS_STEP_TOO_SMALL), (1, layout.STATUS_NAN)])
def test_a_step_below_the_resolution_of_time_stops_the_loop(nonfinite_last, status):
    t = 1e13  # one unit in the last place of t is 2 ms
    st = _state(t=t, h=1e-3, nonfinite_last=nonfinite_last)
    assert plan_limits(st, np.zeros(4, dtype=np.int64), _prm(t_end=t + 1.0, max_step=1.0))
    assert st["status"] == status


def test_a_far_crossing_leaves_the_step_alone():
    t, h = 1.0, 1e-4
    st = _state(t=t, h=h, h_min=_ulp10(t), phase=PH_STAGE)
    hop_or_step(st, 5e-3, 8.0 * h)  # beyond the window and the step
    assert st["phase"] == PH_STAGE
    assert st["t_event"] == t + 5e-3 and st["t_recheck"] == t + 8.0 * h
    begin_attempt(st, 2.0)
    assert (st["h_step"], st["t_new"], st["cut"], st["stage"]) == (h, t + h, 0, 1)


def test_a_step_is_cut_short_before_the_crossing_and_the_crossing_is_hopped_over():
    """Hand case: a crossing 3e-5 s ahead of a 1e-4 s step. The step ends 1e-3 of its length
    before it; the next plan sees it within the hop limit (EVENT_HOP landing gaps) and hops
    over it with one Euler step ending EVENT_OVERSHOOT of its length past it."""
    t, h, tau = 1.0, 1e-4, 3e-5
    st = _state(t=t, h=h, h_min=_ulp10(t), factor=1.5, phase=PH_STAGE)
    hop_or_step(st, tau, 8.0 * h)
    assert st["phase"] == PH_STAGE  # not yet: further than the hop limit (0 at first)
    begin_attempt(st, 2.0)
    h_step = tau * (1.0 - EVENT_LANDING)
    assert st["cut"] == 1
    assert st["h_step"] == pytest.approx(h_step, rel=1e-9)  # (t_event - t) rounds t_event
    assert st["t_new"] == t + st["h_step"]
    # the step is accepted and taken (timeloop): t moves, the size h stays, the hop is armed
    st["t"] = st["t_new"]
    size_after_step(st)
    assert st["h"] == h  # the undisturbed size, not h_step * factor
    assert st["h_cut"] == st["h_step"] and st["predict"] == 1
    assert st["hop_limit"] == pytest.approx(
        EVENT_HOP * EVENT_LANDING * h_step / (1.0 - EVENT_LANDING), rel=1e-9)
    # the next plan predicts the same crossing again, now a landing gap ahead
    t2 = st["t"]
    tau2 = (t + tau) - t2
    assert tau2 == pytest.approx(EVENT_LANDING * tau, rel=1e-6)
    st["h_min"] = _ulp10(t2)
    hop_or_step(st, tau2, 8.0 * h)
    assert st["phase"] == PH_HOP_SAMPLE
    hop = tau2 + max(EVENT_OVERSHOOT * tau2, EVENT_MIN_OVERSHOOT, 4.0 * _ulp10(t2))
    assert st["hop"] == hop and st["t_hop"] == t2 + hop
    assert st["t_hop"] > t + tau  # just past the crossing
    assert st["t_hop"] - (t + tau) == pytest.approx(EVENT_OVERSHOOT * tau2, rel=1e-6)


def test_a_crossing_within_a_hundred_units_of_the_smallest_step_is_always_hopped():
    t = 1e4  # late in a long run: 4 h_min (7e-11 s) above EVENT_MIN_OVERSHOOT
    h_min = _ulp10(t)
    st = _state(t=t, h=1e-4, h_min=h_min, hop_limit=0.0, phase=PH_STAGE)
    hop_or_step(st, 50.0 * h_min, 8e-4)
    assert st["phase"] == PH_HOP_SAMPLE
    assert st["hop"] == 50.0 * h_min + 4.0 * h_min  # the overshoot's floor: 4 h_min


def test_a_step_ending_within_h_min_of_the_end_is_stretched_to_it():
    t_end = 2.0
    t = t_end - 1e-4
    st = _state(t=t, h=1e-4 - 1e-19, h_min=_ulp10(t))
    begin_attempt(st, t_end)
    assert st["t_new"] == t_end and st["h_step"] == t_end - t


def test_an_uncut_step_takes_the_controllers_factor():
    st = _state(h=9.0, h_step=2e-4, factor=1.7, cut=0)
    size_after_step(st)
    assert st["h"] == 2e-4 * 1.7 and st["predict"] == 0


def test_the_hop_samples_on_its_euler_line_then_jumps_to_its_end():
    t, hop = 0.5, 2e-6
    y = np.array([1.0, -2.0, 0.5])
    K = np.zeros((ROW_DY + 1, 3))
    K[0] = [10.0, 3.0, -4.0]
    ys = np.zeros(3)
    t_out = np.array([0.4, t + 0.5e-6, t + 1.5e-6, t + hop, t + 3e-6])
    st = _state(t=t, hop=hop, t_hop=t + hop, i_out=1, phase=PH_HOP_SAMPLE, full=0)
    seen = []
    while True:
        hop_next(st, t_out, y, K, ys)
        assert st["full"] == 1
        if st["phase"] == PH_HOP:
            break
        assert st["row"] == ROW_DY
        seen.append(st["ts"])
        np.testing.assert_array_equal(ys, np.array([1.0, -2.0, 0.5]) + (st["ts"] - t) * K[0])
        st["i_out"] += 1  # the loop writes the row after the evaluation
    assert seen == list(t_out[1:4])  # the output times inside the hop, its end included
    assert st["i_out"] == 4
    np.testing.assert_array_equal(y, np.array([1.0, -2.0, 0.5]) + hop * K[0])
    np.testing.assert_array_equal(ys, y)
    assert st["t"] == t + hop and st["ts"] == t + hop and st["row"] == 0


@pytest.mark.parametrize("speed_mode", [0, 1])
def test_after_a_hop_the_step_restarts_at_a_quarter_and_the_end_is_a_solution_point(speed_mode):
    prm = _prm()
    prm[P.n_slots], prm[P.extrema_t_start] = 3, 0.5
    w = new_work(prm)
    out = Out(t_out=np.zeros(0), series=np.zeros((0, layout.N_COLUMNS)),
              slot_series=np.zeros((layout.N_FAMILIES, 0, 3)),
              extrema=np.zeros(layout.N_EXTREMA), slot_extrema=np.zeros((3, 3)),
              counters=np.zeros(4, dtype=np.int64), resume=np.zeros(layout.N_RESUME))
    init_extrema(out.extrema, out.slot_extrema)
    w.y[:] = np.arange(w.y.size)
    w.aux[layout.A.s1], w.aux[layout.A.v1], w.aux[layout.A.force_drive] = -1.0, -2.0, 5.0
    t = 0.75
    st = _state(t=t, h=4e-4, h_cut=1e-4, hop_limit=3.0, rejected_before=1,
                speed_mode=speed_mode)
    end_hop(st, w, out, prm)
    assert st["h"] == EVENT_RESTART * 1e-4 and EVENT_RESTART == 0.25  # docs/theory.md §6.8
    assert (st["hop_limit"], st["predict"], st["rejected_before"]) == (0.0, 1, 0)
    assert st["phase"] == PH_PLAN and out.counters[layout.N.rhs_evaluations] == 1
    expected = [-1.0, -2.0] if speed_mode else [layout.S.s1, layout.S.v1]
    assert list(w.y[[layout.S.s1, layout.S.v1]]) == expected  # prescribed: exact copies
    assert out.extrema[layout.X.force_total_max_N] == 5.0
    assert out.extrema[layout.X.force_total_max_t_s] == t
