"""Issue 32: the Python API raises only gearcli.errors types for bad arguments. A hypothesis
fuzz over the public functions of gearcli/__init__ (bad types, NaN, negative, huge, wrong
strings): every call returns or raises a GearcliError, never a raw library exception (13 of 76
bad calls did), and the unbounded requests (mesh options) are refused up front.

Kept fast: derandomized, few examples a function, short runs (0.02 s simulated), and the
sweep's study a missing file (every argument is checked before it is read)."""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import gearcli
from gearcli.errors import CaseError, GearcliError
from tests.conftest import ROOT

SEED = str(ROOT / "cases" / "seed.yaml")
FAST = {"run.end_time": 0.02}
FUZZ = settings(max_examples=25, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow,
                                       HealthCheck.function_scoped_fixture])

#: Values of the wrong type, not finite, negative, huge, or wrong text.
junk = st.one_of(
    st.none(), st.booleans(),
    st.integers(min_value=-10**30, max_value=10**30),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([float("nan"), -1.0, 1e300, 10**12, "", "abc", "1e999 s", "-5 mm",
                     "10 rpm", "nan", "\udcff", "x[/bold]", "$\\frac{1$", b"\xff", object()]),
    st.text(max_size=12),
    st.lists(st.integers(min_value=-5, max_value=5), max_size=3),
    st.tuples(st.floats(), st.floats()),
    st.dictionaries(st.text(max_size=4), st.integers(), max_size=2),
)
KEYS = ["gears.module", "gears.pinion.teeth", "gears.gear.teeth", "gears.face_width",
        "run.end_time", "run.output_rate", "contact.exponent", "drive.speed", "load.torque",
        "name", "material.youngs_modulus", "no.such.key"]


def _only_gearcli_errors(call):
    try:
        call()
    except GearcliError:
        pass  # the command line's message; any other exception fails the test


@FUZZ
@given(source=junk)
def test_load_case_of_junk(source):
    _only_gearcli_errors(lambda: gearcli.load_case(source))


@FUZZ
@given(key=st.sampled_from(KEYS), value=junk)
def test_geometry_with_a_junk_override(key, value):
    _only_gearcli_errors(lambda: gearcli.geometry(SEED, set={key: value}))


@FUZZ
@given(set_=junk)
def test_junk_set_argument(set_):
    _only_gearcli_errors(lambda: gearcli.load_case(SEED, set=set_))


@settings(FUZZ, max_examples=12)
@given(progress=junk, zoom=junk, status=junk)
def test_simulate_with_junk_arguments(progress, zoom, status):
    _only_gearcli_errors(lambda: gearcli.simulate(SEED, set=FAST, progress=progress,
                                                  zoom=zoom, status=status))


@settings(FUZZ, max_examples=12)
@given(key=st.sampled_from(["run.end_time", "run.output_rate", "run.max_step"]),
       value=st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(),
                       st.sampled_from(["1e12 Hz", "1e9 s", "-1 s", "0 s", "1e-15 s"])))
def test_simulate_with_unbounded_run_settings(key, value):
    # valid small values would be solved: only values that cannot be valid or are huge
    if isinstance(value, float | int) and math.isfinite(value) and 0 < value < 1e4:
        value = -abs(value)
    _only_gearcli_errors(lambda: gearcli.simulate(SEED, set={**FAST, key: value}))


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    out = tmp_path_factory.mktemp("fuzz") / "run"
    gearcli.simulate(SEED, set={"run.end_time": 0.6}).save(out)
    return str(out)


@settings(FUZZ, max_examples=15)
@given(run=junk, window=junk, flag=junk)
def test_analyze_stress_monitor_with_junk(folder, run, window, flag):
    _only_gearcli_errors(lambda: gearcli.analyze(run))
    _only_gearcli_errors(lambda: gearcli.analyze(folder, window=window, strict=flag))
    _only_gearcli_errors(lambda: gearcli.stress(folder, window=window, require_limits=flag))
    _only_gearcli_errors(lambda: gearcli.monitor(run, baseline=window))
    _only_gearcli_errors(lambda: gearcli.rate(run))


@FUZZ
@given(analysis=junk)
def test_spectra_frame_of_junk(analysis):
    with pytest.raises(CaseError, match="expected the Analysis"):
        gearcli.spectra_frame(analysis)


@settings(FUZZ, max_examples=15)
@given(speed_range=junk)
def test_modal_with_junk_speed_range(speed_range):
    _only_gearcli_errors(lambda: gearcli.modal(SEED, speed_range_deg_s=speed_range))


@settings(FUZZ, max_examples=15)
@given(load=junk, harris=junk, method=junk, option=st.sampled_from(["cycles",
                                                                    "points_per_cycle",
                                                                    "bogus"]),
       value=st.one_of(junk, st.integers(min_value=11, max_value=10**12)))
def test_mesh_with_junk_arguments(load, harris, method, option, value):
    _only_gearcli_errors(lambda: gearcli.mesh(SEED, load_N=load, harris=harris, method=method,
                                              **{option: value}))


@pytest.mark.parametrize("option, value", [("cycles", 10**9), ("points_per_cycle", 10**9),
                                           ("cycles", 0), ("cycles", "a"), ("bogus", 1),
                                           ("points_per_cycle", 2.5)])
def test_mesh_options_are_bounded_up_front(option, value):
    # cycles=1e9 allocated 1.46 TiB (MemoryError); points_per_cycle=1e9 ran for minutes
    with pytest.raises(CaseError, match=option):
        gearcli.mesh(SEED, **{option: value})


@settings(FUZZ, max_examples=30)
@given(out=junk, jobs=junk, scheduler=junk, flag=junk, fmt=junk, timeout=junk)
def test_sweep_arguments_are_checked_before_the_study_is_read(tmp_path, out, jobs, scheduler,
                                                              flag, fmt, timeout):
    missing = tmp_path / "no-such-study.yaml"
    with pytest.raises(GearcliError):
        gearcli.sweep(missing, out=out, jobs=jobs, scheduler=scheduler, force=flag,
                      keep_timeseries=flag, timeseries_format=fmt, point_timeout=timeout)
