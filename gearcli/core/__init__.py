"""Compiled numerical core: numba kernels over floats and float64 arrays.

Imports only numpy, numba and math (checked by tests/unit/test_layers.py).
"""
