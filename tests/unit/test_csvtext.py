"""The compiled %.10g CSV writer (core.csvtext) writes numpy.savetxt's text byte for byte."""

import io

import numpy as np
import pytest

from gearcli.core.csvtext import csv_text


def _savetxt(names, data):
    buf = io.StringIO()
    buf.write(",".join(names) + "\n")
    np.savetxt(buf, data, delimiter=",", fmt="%.10g")
    return buf.getvalue()


EDGES = [1.0, -0.0, 0.0, 12345678905.0, 12345678915.0, 1e-5, 9.9999999995e-5, 1e-4,
         9999999999.5, 9999999999.4, 1e10, 1e9, 123456789.05, 0.5, 2.5e-7, 1e-13, 9.99e-14,
         1e32, 9.999999999999e31, 1.5, 0.1, 100.0, -3.0e-300, 5e-324, 1e300,
         float("nan"), float("inf"), float("-inf"), 2.0**53, -(2.0**60), 0.30000000000000004]


def test_edge_values():
    data = np.array([EDGES])
    names = [f"c{i}" for i in range(len(EDGES))]
    assert csv_text(names, data) == _savetxt(names, data)


@pytest.mark.parametrize("seed", range(6))
def test_random_values_and_ties(seed):
    rng = np.random.default_rng(seed)
    n, m = 1500, 40
    data = rng.uniform(1, 10, (n, m)) * 10.0 ** rng.uniform(-25, 40, (n, m))
    data *= rng.choice([-1.0, 1.0], (n, m))
    data[:, :5] = np.round(rng.uniform(-1e6, 1e6, (n, 5)), rng.integers(0, 8))  # decimals
    data[:, 5:10] = rng.integers(-10**12, 10**12, (n, 5)).astype(float)  # integers
    # odd multiples of 1/2^k: exact ties at the 10th digit for 11-digit integer parts
    data[:, 10:15] = (rng.integers(1, 10**11, (n, 5)) * 2 + 1) / 2.0 ** rng.integers(0, 10)
    names = [f"c{i}" for i in range(m)]
    assert csv_text(names, data) == _savetxt(names, data)


def test_empty_table():
    assert csv_text(["a", "b"], np.zeros((0, 2))) == "a,b\n"
