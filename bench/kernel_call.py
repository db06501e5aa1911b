"""The solver kernel's call as a case makes it, kept for timing it again (bench/ab_inprocess.py,
bench/hotspots.py)."""

from __future__ import annotations

import copy


def kernel_call(integrate, run_simulation, path, overrides):
    """Run the case ``path`` (with ``overrides``) once through ``run_simulation`` and return
    the kernel function ``integrate.simulate`` with a deep copy of the arguments it was called
    with: ``(simulate, (args, kwargs))``. ``integrate`` and ``run_simulation`` are passed in,
    so two renamed copies of the package can be timed in one process."""
    got, simulate = [], integrate.simulate

    def keep(*args, **kwargs):
        got.append(copy.deepcopy((args, kwargs)))
        return simulate(*args, **kwargs)

    integrate.simulate = keep
    try:
        run_simulation(path, overrides, zoom=False, notice=None)
    finally:
        integrate.simulate = simulate
    return simulate, got[0]
