"""The steady-state window of a run: after every ramp plus the mesh mode's settling time."""

from __future__ import annotations

import math
from dataclasses import dataclass

#: Settling = this many time constants of the slowest decaying mesh-mode pole (e^-5 < 1 %).
SETTLING_TIME_CONSTANTS = 5.0
#: The window must hold at least this many mesh cycles.
MIN_MESH_CYCLES = 20


@dataclass(frozen=True)
class Window:
    t0_s: float
    t1_s: float
    reason: str
    #: when the run is settled: the ramps' end + the settling time (NaN: not known, e.g. a
    #: window given to `gearcli analyze`)
    settled_s: float = math.nan

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
    # z - sqrt(z^2 - 1) written without the cancellation that makes it 0 for a large z
    rate = z * wn if z < 1.0 else wn / (z + math.sqrt(z * z - 1.0))
    return SETTLING_TIME_CONSTANTS / rate if rate > 0.0 else math.inf


def steady_window(
    t_end_s: float,
    last_ramp_s: float,
    natural_frequency_Hz: float,
    damping_ratio: float,
    gear_mesh_frequency_Hz: float | None,
    slowest_decay_rate_1_s: float | None = None,
) -> Window:
    """Automatic window [t0, t_end]: t0 = end of ramps + settling, keeping ≥ 20 mesh cycles.

    Settling: the mesh mode's, or that of the slowest decaying pole of the whole linearised
    model when its rate [1/s] is given and slower (a damped rigid-body mode gives the
    drivetrain's speed settling, often far slower than the mesh mode)."""
    settle = settling_time_s(natural_frequency_Hz, damping_ratio)
    reason = "after the ramps and the mesh mode's settling time"
    slowest = (SETTLING_TIME_CONSTANTS / slowest_decay_rate_1_s
               if slowest_decay_rate_1_s else 0.0)
    if slowest > settle:
        settle = slowest
        reason = "after the ramps and the settling time of the slowest mode"
    t0 = settled = max(last_ramp_s, 0.0) + settle
    if gear_mesh_frequency_Hz:
        latest = t_end_s - MIN_MESH_CYCLES / gear_mesh_frequency_Hz
        if latest <= 0.0:
            return Window(0.0, t_end_s, f"the whole run (shorter than {MIN_MESH_CYCLES} mesh "
                          "cycles)", settled)
        if not t0 <= latest:
            t0 = latest
            reason = f"the last {MIN_MESH_CYCLES} mesh cycles (the run is short for settling)"
    if not t0 < t_end_s:
        t0 = 0.5 * t_end_s
        reason = "the second half of the run (no steady state is reached)"
    return Window(t0, t_end_s, reason, settled)


def settling_warnings(window: Window, ramp_end_s: float, end_time_s: float) -> list[str]:
    """The warnings of a window that is not settled: the run ends before or at the end of
    the drive/load ramps, its window starts before they end, or after them but before the
    settling time has passed (the last 20 mesh cycles of a run short for settling: the
    leftover of the ramps' transient is e^-n of it after n time constants)."""
    t0 = window.t0_s
    if ramp_end_s >= end_time_s:
        return [f"no steady state: the drive/load functions reach their final values at "
                f"{ramp_end_s:g} s, " + ("when" if ramp_end_s == end_time_s else "after")
                + f" the run ends ({end_time_s:g} s); the nominal speed, mesh frequency and "
                "static force are never reached"]
    if window.reason.startswith("the second half"):
        return ["no steady state: the run ends before the ramps have settled"]
    if ramp_end_s > t0:
        return [f"not settled: the window starts at {t0:g} s, before the ramps end "
                f"({ramp_end_s:g} s); its values still carry the ramp"]
    if t0 < window.settled_s and math.isinf(window.settled_s):  # an undamped slowest mode
        return [f"not settled: the window starts at {t0:g} s, after the ramps end "
                f"({ramp_end_s:g} s), but the slowest mode is undamped and its transient never "
                "decays: its values carry the ramps' transient"]
    if t0 < window.settled_s:  # NaN (not known): False
        n = SETTLING_TIME_CONSTANTS * (t0 - max(ramp_end_s, 0.0)) / (
            window.settled_s - max(ramp_end_s, 0.0))
        left = 100.0 * math.exp(-n)  # [%], 3 digits: 99.85 % is not "1e+02 %"
        return [f"not settled: the window starts at {t0:g} s, {n:.2g} time constants of the "
                f"slowest mode after the ramps end ({ramp_end_s:g} s; settled after "
                f"{SETTLING_TIME_CONSTANTS:g}, at {window.settled_s:.4g} s): up to "
                f"{left:.3g} % of the ramps' transient is left in its "
                "values; simulate longer (run.end_time)"]
    return []
