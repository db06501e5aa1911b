"""The steady-state window of a run: after every ramp plus the mesh mode's settling time."""

from __future__ import annotations

import math
from dataclasses import dataclass

#: Settling = this many time constants of the slowest decaying mesh-mode pole (e^-5 < 1 %).
SETTLING_TIME_CONSTANTS = 5.0
#: A root |Re λ| below this fraction of the largest |λ| is a free rigid-body root (round-off).
RIGID_ROOT_FRACTION = 1e-9
#: The window must hold at least this many mesh cycles.
MIN_MESH_CYCLES = 20


@dataclass(frozen=True)
class Window:
    t0_s: float
    t1_s: float
    reason: str

    @property
    def length_s(self) -> float:
        return self.t1_s - self.t0_s


def settling_time_s(natural_frequency_Hz: float, damping_ratio: float) -> float:
    """Time for the mesh mode's free response to decay by e^-5.

    Slowest pole of m ẍ + c ẋ + k x = 0 (any textbook on vibrations, e.g. Rao, Mechanical
    Vibrations §2.6): underdamped −ζω_n; overdamped −ω_n (ζ − √(ζ² − 1)).
    """
    wn = 2.0 * math.pi * natural_frequency_Hz
    z = damping_ratio
    if z <= 0.0 or wn <= 0.0:
        return math.inf
    rate = z * wn if z < 1.0 else wn * (z - math.sqrt(z * z - 1.0))
    return SETTLING_TIME_CONSTANTS / rate


def slowest_settling_time_s(eigenvalues) -> float:
    """Time for the slowest decaying pole of a linear model to decay by e^-5 [s].

    ``eigenvalues``: the state-space roots λ [1/s] (gearcli.model.modal); roots with
    Re λ >= 0 (undamped rigid-body motion, which never settles and has nothing to wait for)
    are skipped. A damped rigid-body mode (a motor curve or a viscous load on a torque drive)
    gives the drivetrain's speed settling, often far slower than the mesh mode.
    """
    scale = max((abs(lam) for lam in eigenvalues), default=0.0)
    # roots within round-off of 0 (free rigid-body modes; same threshold as model.modal)
    rates = [-lam.real for lam in eigenvalues if -lam.real > RIGID_ROOT_FRACTION * scale]
    return SETTLING_TIME_CONSTANTS / min(rates) if rates else 0.0


def steady_window(
    t_end_s: float,
    last_ramp_s: float,
    natural_frequency_Hz: float,
    damping_ratio: float,
    gear_mesh_frequency_Hz: float | None,
    eigenvalues=(),
) -> Window:
    """Automatic window [t0, t_end]: t0 = end of ramps + settling (the mesh mode's, or the
    slowest pole of the whole linearised model when its ``eigenvalues`` are given), keeping
    ≥ 20 mesh cycles."""
    settle = settling_time_s(natural_frequency_Hz, damping_ratio)
    reason = "after the ramps and the mesh mode's settling time"
    slowest = slowest_settling_time_s(eigenvalues)
    if slowest > settle:
        settle = slowest
        reason = "after the ramps and the settling time of the slowest mode"
    t0 = max(last_ramp_s, 0.0) + settle
    if gear_mesh_frequency_Hz:
        latest = t_end_s - MIN_MESH_CYCLES / gear_mesh_frequency_Hz
        if not t0 <= latest:
            t0 = max(latest, 0.0)
            reason = f"the last {MIN_MESH_CYCLES} mesh cycles (the run is short for settling)"
    if not t0 < t_end_s:
        t0 = 0.5 * t_end_s
        reason = "the second half of the run (no steady state is reached)"
    return Window(t0, t_end_s, reason)
