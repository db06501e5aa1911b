"""gearcli.plotting.decimate.minmax_decimate: the polyline for drawing keeps every pixel
column's extrema, in time order, in at most 4 points per column."""

from __future__ import annotations

import numpy as np
import pytest

from gearcli.plotting.decimate import minmax_decimate


def _signal(n: int = 200_000, seed: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """A mesh-force-like signal: a ramp, a 700 Hz tone, noise and a few one-sample spikes (the
    extrema a stride would miss), on an irregular (sorted) time grid."""
    rng = np.random.default_rng(seed)
    t = np.sort(rng.uniform(0.0, 5.0, n))
    y = 40.0 * t + 10.0 * np.sin(2 * np.pi * 700.0 * t) + rng.normal(0.0, 1.0, n)
    spikes = rng.choice(n, 7, replace=False)
    y[spikes] += rng.choice([-1.0, 1.0], 7) * 300.0
    return t, y


def _columns(t: np.ndarray, t0: float, span: float, n: int) -> np.ndarray:
    return np.minimum(((t - t0) * (n / span)).astype(np.int64), n - 1)


@pytest.mark.parametrize("n_columns", [1, 7, 1200])
def test_same_extrema_per_column_and_overall(n_columns):
    t, y = _signal()
    td, yd = minmax_decimate(t, y, n_columns)
    assert yd.min() == y.min() and yd.max() == y.max()
    span = t[-1] - t[0]
    col, cold = _columns(t, t[0], span, n_columns), _columns(td, t[0], span, n_columns)
    # every column of the raw signal is present, with the same min and max
    lo = np.full(n_columns, np.inf)
    hi = np.full(n_columns, -np.inf)
    np.minimum.at(lo, col, y)
    np.maximum.at(hi, col, y)
    lod = np.full(n_columns, np.inf)
    hid = np.full(n_columns, -np.inf)
    np.minimum.at(lod, cold, yd)
    np.maximum.at(hid, cold, yd)
    assert np.array_equal(lo, lod) and np.array_equal(hi, hid)
    # a subset of the raw samples, in time order, 4 per column at most, first and last kept
    assert np.all(np.diff(td) >= 0)
    assert np.isin(td, t).all()
    assert td.size <= 4 * n_columns
    assert (td[0], yd[0], td[-1], yd[-1]) == (t[0], y[0], t[-1], y[-1])


def test_decimation_reduces_a_long_signal():
    t, y = _signal()
    td, _ = minmax_decimate(t, y, 1200)
    assert 2 * 1200 <= td.size <= 4 * 1200  # every column holds samples: its min and max


def test_short_signals_and_zero_span_are_returned_whole():
    t = np.linspace(0.0, 1.0, 40)
    y = np.sin(t)
    td, yd = minmax_decimate(t, y, 10)
    assert np.array_equal(td, t) and np.array_equal(yd, y)
    td, yd = minmax_decimate(np.zeros(100), np.arange(100.0), 5)
    assert td.size == 100


def test_nan_samples_do_not_hide_the_extrema():
    t, y = _signal(20_000)
    y[100:300] = np.nan  # a gap inside the first columns
    td, yd = minmax_decimate(t, y, 50)
    assert np.nanmin(yd) == np.nanmin(y) and np.nanmax(yd) == np.nanmax(y)
    assert np.isnan(yd).any()  # the gap stays a gap


def test_bad_arguments():
    with pytest.raises(ValueError, match="one length"):
        minmax_decimate(np.arange(5.0), np.arange(4.0), 2)
    with pytest.raises(ValueError, match="n_columns"):
        minmax_decimate(np.arange(5.0), np.arange(5.0), 0)
