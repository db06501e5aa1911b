"""Plausible magnitudes of case values, checked once after validation.

The schema bounds signs and ranges that have a physical meaning (``module > 0``); this guard
bounds magnitudes no gear pair has, by dimension, so that values such as ``module: 1e300``,
``teeth: 10**300`` or ``drive.speed: 1e308`` are refused with the key that holds them instead
of overflowing somewhere in the model. The limits are deliberately generous (a 1 km module
is allowed): they are there to keep the arithmetic finite, not to judge designs.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from pydantic import BaseModel

from gearcli import units
from gearcli.case.types import TimeFunction
from gearcli.units import Dim

#: Largest magnitude per dimension name, in internal units (see gearcli.units).
LIMITS: dict[str, float] = {
    "length": 1e6,  # mm (1 km)
    "angle": 1e4,  # rad
    "angular velocity": 1e5,  # rad/s (~955 000 rpm)
    "torque": 1e12,  # N*mm
    "time": 1e6,  # s
    "frequency": 1e9,  # Hz
    "mass": 1e6,  # t
    "density": 1e-3,  # t/mm^3 (130 times osmium)
    "stress": 1e8,  # MPa
    "velocity": 1e9,  # mm/s
}
#: Any other quantity (stiffness, damping, inertia) and plain coefficients.
DEFAULT_LIMIT = 1e15
#: Smallest magnitude of the material constants, by key name, in internal units: a body
#: lighter than 0.1 kg/m^3 (air is 1.2) or softer than 1 MPa (soft rubber) is no gear, and such
#: values gave runs that ended "ok" at 1e28 rpm with a 5e15 Hz mesh mode.
LOWER_LIMITS: dict[str, tuple[float, str]] = {
    "density": (1e-13, "density"),  # t/mm^3 = 0.1 kg/m^3
    "youngs_modulus": (1.0, "Young's modulus"),  # MPa
}
#: Largest integer per key name; any other integer: INT_LIMIT.
COUNT_LIMITS = {"teeth": 10_000}
INT_LIMIT = 2**63 - 1


def magnitude_errors(case: BaseModel, system: str | None = None
                     ) -> Iterator[tuple[tuple, object, str]]:
    """(key path, value, message) of every value beyond its plausible magnitude; limits are
    shown in the unit of bare numbers in unit ``system`` (the case's ``units:``)."""
    yield from _walk(case, (), system)


def _walk(model: BaseModel, loc: tuple, system) -> Iterator[tuple[tuple, object, str]]:
    for name, field in type(model).model_fields.items():
        value = getattr(model, name)
        dim = _dim_of(field)
        yield from _check(value, (*loc, name), name,
                          units.in_system(dim, system) if dim else None, system)


def _check(value, loc, name, dim, system) -> Iterator[tuple[tuple, object, str]]:
    if isinstance(value, BaseModel):
        yield from _walk(value, loc, system)
    elif isinstance(value, list | tuple):
        for i, item in enumerate(value):
            yield from _check(item, (*loc, i), name, dim, system)
    elif isinstance(value, bool) or value is None or isinstance(value, str):
        return
    elif isinstance(value, int):
        limit = COUNT_LIMITS.get(name, INT_LIMIT)
        if abs(value) > limit:
            yield loc, value, f"expected an integer of at most {limit:,}"
    elif isinstance(value, float):
        if not abs(value) <= _limit(dim):
            yield loc, value, _message(dim)
        elif name in LOWER_LIMITS and abs(value) < LOWER_LIMITS[name][0]:
            lower, label = LOWER_LIMITS[name]
            shown = _shown(lower, dim) if dim else f"{lower:g}"
            yield loc, value, (f"expected a {label} of at least {shown} (no gear material is "
                               "lighter or softer)")
    elif isinstance(value, TimeFunction):
        shown = dim or value.dim  # the field's unit of bare numbers
        if not _function_peak(value) <= _limit(shown):
            yield loc, None, (f"reaches {_shown(_function_peak(value), shown)}; "
                              + _message(shown))


def _function_peak(fn: TimeFunction) -> float:
    """Largest |value| at t = 0, the breakpoints and their end (internal units)."""
    try:
        pp = fn.pp
        times = [0.0, *pp.breakpoints, max(pp.breakpoints, default=0.0) + 1.0]
        return max(abs(float(pp(t))) for t in times)
    except (ValueError, OverflowError, ArithmeticError):
        return math.inf


def _dim_of(field) -> Dim | None:
    for meta in getattr(field, "metadata", ()):
        dim = getattr(getattr(meta, "func", None), "dim", None)
        if dim is not None:
            return dim
    for arg in getattr(field.annotation, "__args__", ()):  # list[Length], Length | None
        for meta in getattr(arg, "__metadata__", ()):
            dim = getattr(getattr(meta, "func", None), "dim", None)
            if dim is not None:
                return dim
    return None


def _limit(dim: Dim | None) -> float:
    return LIMITS.get(dim.name, DEFAULT_LIMIT) if dim is not None else DEFAULT_LIMIT


def _shown(value: float, dim: Dim) -> str:
    return f"{value / dim.factor:.3g} {dim.default}"


def _message(dim: Dim | None) -> str:
    if dim is None:
        return f"expected a magnitude of at most {DEFAULT_LIMIT:g}"
    article = "an" if dim.name[0] in "aeiou" else "a"
    return (f"expected {article} {dim.name} of magnitude at most {_shown(_limit(dim), dim)} "
            "(beyond any gear pair; the arithmetic would overflow)")



#: Fewest solver steps in a mesh cycle that a run may take: one. The mesh stiffness varies in
#: every mesh cycle (a pair enters and one leaves the contact, docs/theory.md §6.8); a solver
#: step longer than the cycle does not resolve that excitation, so a run with more mesh cycles
#: than the solver's step limit either stops at the limit or has not integrated the mesh: it is
#: refused from the case. Measured accepted steps a cycle: 43 (seed), 52 (iso_pair), 11.6 and
#: 4.1 (iso_pair scaled to 10x and 50x its mesh frequency: 210/430 teeth at module 0.5 mm,
#: 1050/2150 at 0.1 mm); the bound stays below all of them.
MIN_STEPS_PER_MESH_CYCLE = 1
#: Samples of each piece of the drive speed's time function for the integral of the speed.
_SPEED_SAMPLES = 64


def mesh_cycles(case) -> float | None:
    """Mesh cycles of the run, z1/(2π)·∫|ω1(t)| dt over [0, run.end_time] (trapezoids over
    each piece of ``drive.speed``; ω1 the prescribed pinion or motor speed [rad/s]); None
    for a torque drive (its speed is the run's result)."""
    import numpy as np

    drive = case.drive
    if drive.type == "torque" or drive.speed is None:
        return None
    pp, end = drive.speed.pp, float(case.run.end_time)
    try:
        cuts = sorted({0.0, end, *(float(b) for b in pp.breakpoints if 0.0 < b < end)})
        t = np.unique(np.concatenate([np.linspace(a, b, _SPEED_SAMPLES)
                                      for a, b in zip(cuts[:-1], cuts[1:], strict=True)]))
        w = np.abs(np.array([float(pp(x)) for x in t]))
        angle_rad = float(np.sum(0.5 * (w[1:] + w[:-1]) * np.diff(t)))
    except (ValueError, OverflowError, ArithmeticError):
        return None
    return case.gears.pinion.teeth * angle_rad / (2.0 * math.pi)


def solver_steps_error(case, max_steps: float) -> str | None:
    """Why the run cannot end within the solver's ``max_steps`` (core/layout.py), or None:
    its mesh cycles need at least :data:`MIN_STEPS_PER_MESH_CYCLE` step each. Known from
    the case alone, so refused before anything is built, not at the step limit minutes
    later."""
    cycles = mesh_cycles(case)
    if cycles is None or not cycles * MIN_STEPS_PER_MESH_CYCLE > max_steps:
        return None
    end, cap = float(case.run.end_time), max_steps / MIN_STEPS_PER_MESH_CYCLE
    return (f"a run of {end:g} s with {case.gears.pinion.teeth:,} pinion teeth at drive.speed "
            f"passes {cycles:.3g} mesh cycles, each needing a solver step at least "
            f"({cycles * MIN_STEPS_PER_MESH_CYCLE:.3g} steps); the solver stops at "
            f"{max_steps:.3g} steps: expected at most {cap:.3g} mesh cycles (run.end_time <= "
            f"{end * cap / cycles:.3g} s, or fewer teeth or a lower speed)")
