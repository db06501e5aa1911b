"""The designs of a study (gearcli/pipeline/sweep/study.py): which combinations of the
parameters' values are run (grid, zip, one at a time, a Latin hypercube, a speed curve's
speeds), how many, and whether the parameters fit the design."""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from gearcli.results import SpeedLevel, shown

#: A virtual parameter: the gear-mesh frequency f_z [Hz], set through ``drive.speed``.
MESH_FREQUENCY = "mesh_frequency"
#: Most speeds per direction of a speed curve (its staircase is one time-function expression,
#: at most 2000 characters: gearcli/pipeline/speed_curve.py).
MAX_SPEEDS = 40
#: What each level of a speed curve measures: the metrics its ``metrics:`` and ``checks:`` may
#: name (gearcli/pipeline/speed_curve.py; field metadata show="speed_curve" of SpeedLevel).
SPEED_CURVE_METRICS = shown(SpeedLevel, "speed_curve")


@dataclass(frozen=True)
class Parameter:
    """One varied key path: its values as passed to the override, and as numbers in ``unit``."""

    key: str
    unit: str  #: "" for unitless or non-numeric values
    values: tuple  #: override values (numbers, or strings with units)
    numbers: tuple  #: the values as floats in ``unit`` (nan where not numeric)
    log: bool = False
    bounds: tuple[float, float] | None = None  #: a range's ends (for lhs)
    extra: tuple[str, ...] = ()  #: overrides set with the parameter (``with``)

    @property
    def column(self) -> str:
        return f"{self.key} [{self.unit}]" if self.unit else self.key


def design_size(spec, params: list[Parameter]) -> int:
    """Number of points of the design, computed without building it."""
    if spec.design == "grid":
        return math.prod(len(p.values) for p in params)
    if spec.design in ("zip", "speed_curve"):
        return len(params[0].values)
    if spec.design == "one_at_a_time":
        return 1 + sum(len(p.values) for p in params)
    return int(spec.samples or 0)


def check_design(src, spec, params: list[Parameter], ranges: dict) -> None:
    """Refuse a design its parameters do not fit (``ranges``: the parameters given as ranges),
    located in the study file ``src``."""
    if spec.design == "lhs":
        if spec.samples is None:
            raise src.error(("design",), "a Latin hypercube needs 'samples' (and 'seed')")
        return
    for key, r in ranges.items():
        if r.num is None and r.values is None:
            raise src.error(("parameters", key), f"a range in a {spec.design} needs 'num'")
    if spec.design == "speed_curve":
        if [p.key for p in params] != [MESH_FREQUENCY]:
            raise src.error(("parameters",), "a speed_curve takes exactly one parameter, "
                            f"{MESH_FREQUENCY} (the speeds to run up and down)")
        if not 2 <= len(params[0].values) <= MAX_SPEEDS:
            raise src.error(("parameters", MESH_FREQUENCY), f"got {len(params[0].values)} "
                            f"speeds; a speed_curve takes 2 to {MAX_SPEEDS}")
    if spec.design == "zip":
        sizes = {p.key: len(p.values) for p in params}
        if len(set(sizes.values())) > 1:
            raise src.error(("design",), f"zip needs lists of one length; got {sizes}")
    if spec.samples is not None:
        raise src.error(("samples",), "'samples' is for design: lhs only")


def design_points(spec, params: list[Parameter]) -> list[list[tuple[Parameter, int]]]:
    """Each point as a list of (parameter, value index)."""
    if spec.design == "grid":
        return [list(zip(params, idx, strict=True))
                for idx in itertools.product(*(range(len(p.values)) for p in params))]
    if spec.design in ("zip", "speed_curve"):
        return [[(p, i) for p in params] for i in range(len(params[0].values))]
    if spec.design == "one_at_a_time":
        out: list = [[]]  # the base point
        for p in params:
            out.extend([[(p, i)] for i in range(len(p.values))])
        return out
    return _lhs(spec, params)


def _lhs(spec, params: list[Parameter]) -> list[list[tuple[Parameter, int]]]:
    """Latin hypercube (scipy.stats.qmc) over the ranges; lists are sampled by index."""
    from scipy.stats import qmc

    u = qmc.LatinHypercube(d=len(params), seed=spec.seed).random(spec.samples)
    out = []
    sampled: list[Parameter] = []
    for p in params:
        if p.bounds is None:
            sampled.append(p)
            continue
        lo, hi = p.bounds
        x = (np.exp(np.log(lo) + u[:, len(sampled)] * (np.log(hi) - np.log(lo))) if p.log
             else lo + u[:, len(sampled)] * (hi - lo))
        numbers = tuple(float(f"{v:.12g}") for v in x)
        values = tuple(f"{v:.12g} {p.unit}" if p.unit else v for v in numbers)
        sampled.append(Parameter(p.key, p.unit, values, numbers, p.log, p.bounds, p.extra))
    params[:] = sampled
    for i in range(spec.samples):
        combo = []
        for j, p in enumerate(params):
            k = i if p.bounds is not None else min(int(u[i, j] * len(p.values)),
                                                   len(p.values) - 1)
            combo.append((p, k))
        out.append(combo)
    return out
