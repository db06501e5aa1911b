"""Property-based fuzz (issue 18): mutated seed cases and `--set` values never end in an internal
error (exit 3), a traceback, or a run beyond a time bound — only in results (0, 4) or one
located error (1, 2).

Deterministic (``derandomize``: the same examples on every machine, no example database) and
bounded (a few dozen short runs). The mutations: a key of the seed (or a known optional key)
gets a random value, a value of another type, or its own value scaled by 10^k and/or negated;
``run.end_time`` stays short so that each example is one short run (run sizes are checked by
test_robustness.py).
"""

from __future__ import annotations

import copy
import datetime
import re

import pytest
import yaml
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import SEED

runner = CliRunner()
BASE = yaml.safe_load(SEED.read_text())
#: Each run simulates this long at most (the seed ramps for 1 s: a short transient).
END_TIME_S = 0.2
#: ... with at most this many output samples.
MAX_SAMPLES = 20_000
#: The time bound of one example: generous (a short run takes ~1 s), far below a hang.
BOUND = datetime.timedelta(seconds=60)
FUZZ = settings(max_examples=50, deadline=BOUND, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.filter_too_much,
                                       HealthCheck.function_scoped_fixture])


def _leaves(data, path=()):
    if isinstance(data, dict):
        for key, value in data.items():
            yield from _leaves(value, (*path, key))
    else:
        yield path


EXTRA_KEYS = [("gears", "centre_distance"), ("gears", "pinion", "profile_shift"),
              ("gears", "gear", "tip_rounding"), ("gears", "rack", "addendum"),
              ("drive", "type"), ("drive", "initial_speed"), ("load", "viscous"),
              ("run", "output_steps"), ("run", "max_step"), ("run", "rtol"),
              ("contact", "engagement"), ("model",), ("errors", "runout", "pinion", "eccentricity"),
              ("errors", "pitch_deviation", "gear", "iso1328_grade"),
              ("modifications", "tip_relief", "pinion", "amount"), ("checks", "harmonics"),
              ("bearings", "gear", "damping")]
PATHS = sorted(set(_leaves(BASE)) | set(EXTRA_KEYS))
UNITS = ["mm", "m", "deg", "rad", "rpm", "N*m", "s", "ms", "Hz", "kg", "kg/mm^3", "MPa",
         "N/mm", "N/mm^1.5", "", "mm**2", "deg/s", "%", "furlong"]
NUMBERS = st.one_of(st.integers(-10**6, 10**6), st.integers(),
                    st.floats(allow_nan=True, allow_infinity=True),
                    st.sampled_from([0, -1, 1e-300, 1e300, 1e308, -1e-12, 10**400, 0.5]))
TEXTS = st.one_of(
    st.builds(lambda n, u: f"{n} {u}", NUMBERS, st.sampled_from(UNITS)),
    st.sampled_from(["mm", "STEP(time, 0, 0, 1, 3000)", "STEP(time,1,0,0,1)", "time^10",
                     "9**9**9", "10 ** 10 ** 10 mm", "derived", "torque", "shaft", "rigid",
                     "lateral-torsional", "nan", "inf", "", "STEP(time, 0, 0, 1, 1e308)*1e308",
                     "time*1e300", "(9**9)**9 mm"]),
    st.text(max_size=30))
VALUES = st.recursive(st.one_of(st.none(), st.booleans(), NUMBERS, TEXTS),
                      lambda inner: st.one_of(st.lists(inner, max_size=3),
                                              st.dictionaries(st.sampled_from(
                                                  ["function", "unit", "type", "x"]),
                                                  inner, max_size=2)),
                      max_leaves=5)
SCALE = st.tuples(st.just("scale"), st.one_of(st.integers(-2, 2), st.integers(-15, 15)),
                  st.booleans())
#: Scaling a seed value keeps most cases valid (they run); other values mostly do not.
MUTATIONS = st.lists(st.tuples(st.sampled_from(PATHS), st.one_of(SCALE, SCALE, VALUES)),
                     min_size=1, max_size=2)
_NUMBER = re.compile(r"[-+]?\d+\.?\d*(?:[eE][-+]?\d+)?")


def _get(data, path):
    for part in path:
        if not isinstance(data, dict) or part not in data:
            return None
        data = data[part]
    return data


def _scaled(value, k: int, negate: bool):
    """``value`` times 10^k (and -1): numbers, or the last number in a string."""
    factor = -(10.0**k) if negate else 10.0**k
    if isinstance(value, bool) or value is None:
        return value
    if isinstance(value, int):
        return value * 10**k * (-1 if negate else 1) if k >= 0 else value * factor
    if isinstance(value, float):
        return value * factor
    if isinstance(value, str):
        found = list(_NUMBER.finditer(value))
        if found:
            m = found[-1]
            return value[:m.start()] + repr(float(m.group()) * factor) + value[m.end():]
    return value


def mutated_case(mutations) -> str:
    data = copy.deepcopy(BASE)
    for path, value in mutations:
        if isinstance(value, tuple) and value[:1] == ("scale",):
            value = _scaled(_get(data, path), value[1], value[2])
        node = data
        for part in path[:-1]:
            if not isinstance(node.get(part), dict):
                node[part] = {}
            node = node[part]
        node[path[-1]] = value
    _keep_short(data.get("run"))
    return yaml.safe_dump(data, allow_unicode=True)


def _keep_short(run) -> None:
    """Keep each example one short run: end_time at most END_TIME_S (a string end time, in
    whatever unit, becomes END_TIME_S), at most MAX_SAMPLES output samples."""
    if not isinstance(run, dict):
        return
    end = run.get("end_time")
    if isinstance(end, str) or (isinstance(end, int | float) and not isinstance(end, bool)
                                and end > END_TIME_S):
        run["end_time"] = END_TIME_S
    steps = run.get("output_steps")
    if isinstance(steps, int) and not isinstance(steps, bool) and steps > MAX_SAMPLES:
        run["output_steps"] = MAX_SAMPLES
    rate = run.get("output_rate")
    if isinstance(rate, str) or (isinstance(rate, int | float) and not isinstance(rate, bool)
                                 and rate > MAX_SAMPLES / END_TIME_S):
        run["output_rate"] = MAX_SAMPLES / END_TIME_S


def assert_clean(result) -> None:
    event(f"exit {result.exit_code}")
    assert result.exit_code in (0, 1, 2, 4), (result.exit_code, result.stderr)
    assert "internal error" not in result.stderr, result.stderr
    assert "Traceback" not in result.stderr, result.stderr


@pytest.fixture(scope="module")
def compiled():
    """One run before the fuzz, so that compiling the solver (first run on a machine) does not
    count against the time bound of an example."""
    r = runner.invoke(app, ["simulate", str(SEED), "-o", "-", "-q", "--set",
                            f"run.end_time={END_TIME_S}"])
    assert r.exit_code == 0, r.stderr


@FUZZ
@given(mutations=MUTATIONS)
def test_mutated_seed_cases_simulate_cleanly(compiled, tmp_path_factory, mutations):
    path = tmp_path_factory.mktemp("fuzz") / "case.yaml"
    path.write_text(mutated_case(mutations))
    assert_clean(runner.invoke(app, ["simulate", str(path), "-o", "-", "-q"]))


@FUZZ
@given(mutations=MUTATIONS)
def test_mutated_seed_cases_geometry_cleanly(tmp_path_factory, mutations):
    path = tmp_path_factory.mktemp("fuzz") / "case.yaml"
    path.write_text(mutated_case(mutations))
    assert_clean(runner.invoke(app, ["geometry", str(path)]))


SET_KEYS = [".".join(p) for p in PATHS] + ["x.y", "gears..module", "", "="]
SET_VALUES = st.one_of(
    st.text(max_size=30),
    st.from_regex(r"[-+]?[0-9]{1,4}(\.[0-9]+)?([eE][-+]?[0-9]{1,3})? ?"
                  r"(mm|m|deg|rpm|N\*m|s|Hz|kg|MPa|N/mm\^1\.5|\*\*[0-9]|\^[0-9]{1,3})?",
                  fullmatch=True),
    st.sampled_from(["{a: 1}", "[1, 2]", "null", "!!python/object:os.system", "&a [*a]",
                     "STEP(time,0,0,1,-1)", "'", "{function: time, unit: rpm}"]))


@FUZZ
@given(sets=st.lists(st.tuples(st.sampled_from(SET_KEYS), SET_VALUES), min_size=1, max_size=2))
def test_set_values_simulate_cleanly(compiled, sets):
    args = ["simulate", str(SEED), "-o", "-", "-q", "--set", f"run.end_time={END_TIME_S}"]
    for key, value in sets:
        if key in ("run.end_time", "run.output_steps", "run.output_rate"):
            continue  # the runs stay short (run sizes: test_robustness.py)
        args += ["--set", f"{key}={value}"]
    assert_clean(runner.invoke(app, args))
