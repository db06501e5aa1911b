"""Validity guard of a finished run (docs/theory.md §10.2): a run whose deflections or motions
leave the range of the contact model is reported as ``invalid`` with a one-line reason, never as
a valid dynamic factor.

Checked, in this order (the first that fails is the reason):

1. **Penetration** — the largest pair penetration (true extremum over the whole run) against
   ``min(PENETRATION_PER_STATIC × δ_s, PENETRATION_PER_THICKNESS × s)``, δ_s the static deflection
   of the case's law and load, s = π m/2 the reference tooth thickness. A linear (or power-law)
   tooth is meaningless at penetrations far beyond the static deflection (docs/theory.md §10.2): the
   penetration ratio is the dynamic factor of a linear contact, and ten times the static
   deflection is several times the largest dynamic factors of ISO 6336-1 Method B (K_v of at
   most about 2-3 at the main resonance, docs/theory.md §10.4), i.e. a vibro-impact state of an
   undamped, error-free model, not a gear's response. The thickness term (5 % of the tooth
   thickness) bounds the small-deflection geometry of the gap tables (contact points of the
   rigid profiles) for soft penalty contacts and for runs without load (δ_s = 0).
2. **Speed reversal** — the gear (and, with a torque drive, the pinion) running backwards (by
   more than one tooth pitch over the window: e.g. a load larger than a torque drive) or turning
   backwards in the steady window by more than 1 % of its mean speed: the pair's kinematics
   (tables of roll position, the drive/coast flank assignment and the output sampling by roll)
   assume a forward-running pair.
3. **Runaway energy** — the energy balance's relative residual (docs/theory.md §6.6) above
   ``ENERGY_RESIDUAL_LIMIT``: the integration did not conserve energy, so no number of the run
   is trustworthy (measured residuals of valid runs: 1e-9 … 1e-5).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

PENETRATION_PER_STATIC = 10.0
PENETRATION_PER_THICKNESS = 0.05
ENERGY_RESIDUAL_LIMIT = 1e-3
#: backward speed, as a fraction of the mean speed, that counts as a reversal (below it: the
#: numerical dither of a quasi-static run, e.g. -2e-4 deg/s at 3 deg/s)
REVERSAL_FRACTION = 0.01

#: Status of a run inside the model's range, and of one outside it.
OK, INVALID = "ok", "invalid"


class Validity(NamedTuple):
    status: str  #: OK or INVALID
    reason: str  #: one line; empty when OK


def penetration_limit_mm(static_deflection_mm: float, module_mm: float) -> float:
    """The largest penetration [mm] inside the contact model's range (module notes, item 1)."""
    thickness = PENETRATION_PER_THICKNESS * math.pi * module_mm / 2.0
    if static_deflection_mm > 0.0:
        return min(PENETRATION_PER_STATIC * static_deflection_mm, thickness)
    return thickness


def check_validity(*, penetration_max_mm: float, static_deflection_mm: float, module_mm: float,
                   gear_speed_rad_s: np.ndarray, pinion_speed_rad_s: np.ndarray | None,
                   window_s: float, teeth: tuple[int, int],
                   energy_relative_residual: float) -> Validity:
    """Validity of one run (module notes). Speeds are the steady window's samples [rad/s]
    (``window_s`` long); ``pinion_speed_rad_s`` only when the pinion is free (torque drive),
    else None; ``teeth`` = (z1, z2)."""
    limit = penetration_limit_mm(static_deflection_mm, module_mm)
    if not penetration_max_mm <= limit:
        return Validity(INVALID, (
            f"tooth penetration {penetration_max_mm:.4g} mm is beyond the contact model's range "
            f"{limit:.4g} mm ({PENETRATION_PER_STATIC:g} x the static deflection "
            f"{static_deflection_mm:.4g} mm, at most {100 * PENETRATION_PER_THICKNESS:g} % of "
            "the tooth thickness)"))
    for name, omega, z in (("gear", gear_speed_rad_s, teeth[1]),
                           ("pinion", pinion_speed_rad_s, teeth[0])):
        if omega is None or omega.size == 0:
            continue
        mean = float(np.mean(omega))
        pitches = -mean * window_s * z / (2.0 * math.pi)
        if pitches > 1.0:
            # backwards throughout (e.g. a load torque larger than a torque drive's); a gear
            # creeping back by its deflection in a ring-down at rest is not
            return Validity(INVALID, (
                f"the {name} runs backwards in the steady window (mean speed "
                f"{np.degrees(mean):.4g} deg/s, {pitches:.3g} tooth pitches): the model "
                "assumes a forward-running pair"))
        forward = np.sign(mean) or 1.0
        worst = float(omega[np.argmin(forward * omega)])
        if forward * worst < -REVERSAL_FRACTION * abs(mean):
            return Validity(INVALID, (
                f"the {name} reverses in the steady window (speed {np.degrees(worst):.4g} deg/s "
                f"against its mean of {np.degrees(mean):.4g} deg/s): the model assumes a "
                "forward-running pair"))
    if not energy_relative_residual <= ENERGY_RESIDUAL_LIMIT:
        return Validity(INVALID, (
            f"energy balance residual {energy_relative_residual:.3g} of the largest energy term "
            f"(limit {ENERGY_RESIDUAL_LIMIT:g}): the integration is not trustworthy"))
    return Validity(OK, "")
