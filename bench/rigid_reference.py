"""Plain scipy reference of the seed case's rigid model, for the solver speed comparison.

The classic line-of-action-only model (`contact.engagement=rigid friction.enabled=false`,
docs/theory.md §3-6) written the way a user would write it with numpy/scipy: a Python right-hand
side, ``scipy.integrate.solve_ivp(method="LSODA")``. It shares no code with the compiled
kernel (only the numbers of the seed case: base radii, inertia, base pitch, path of contact,
slot phases, IMPACT parameters, tolerances), so it also cross-checks the kernel.

Model (internal units mm, N, s, t):
- drive: prescribed pinion speed omega1(t) = STEP(t, 0, 0, 1, 3000 deg/s) (Adams MOTION),
  theta1(t) its integral from 0; load STEP(t, 0, 0, 1, 450 N*m) on the gear;
- state (delta, deltadot), delta = r_b1 theta1 - r_b2 theta2 (DTE along the line of action);
- drive pair j: x1 = ((s1 - s1_0) mod p_b) + j p_b, x2 = x1 - delta, in contact only while
  0 <= x1, x2 <= g_alpha; coast pair: x1 = ((-s1 - s1c_0) mod p_b) + j p_b, x2 = x1 + delta,
  penetration -delta - j_n;
- IMPACT per pair: F = max(0, k p^e + STEP(p, 0, 0, d_max, c_max) pdot) for p > 0;
- J2 theta2'' = r_b2 (sum F - sum F_coast) - T_load; delta'' = r_b1 theta1'' - r_b2 theta2''.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp


def step(x: float, x0: float, h0: float, x1: float, h1: float) -> float:
    """Adams STEP (cubic)."""
    if x <= x0:
        return h0
    if x >= x1:
        return h1
    d = (x - x0) / (x1 - x0)
    return h0 + (h1 - h0) * d * d * (3.0 - 2.0 * d)


@dataclass(frozen=True)
class RigidModel:
    r_b1: float  # mm
    r_b2: float  # mm
    J2: float  # t*mm^2
    p_b: float  # mm
    g_alpha: float  # mm, length of the path of contact (rigid table x_hi)
    s1_0: float  # mm, drive slot phase
    s1c_0: float  # mm, coast slot phase
    j_n: float  # mm, normal backlash
    n_slots: int
    k: float  # N/mm^e
    e: float
    c_max: float  # N*s/mm
    d_max: float  # mm
    omega_final: float  # rad/s
    load_final: float  # N*mm
    ramp: float  # s

    # -- prescribed motion and load (STEP ramps from 0 at t = 0 to the final value at t = ramp)
    def pinion(self, t: float) -> tuple[float, float, float]:
        """theta1 [rad], omega1 [rad/s], alpha1 [rad/s^2]."""
        w, T = self.omega_final, self.ramp
        if t >= T:
            return w * (t - 0.5 * T), w, 0.0
        d = t / T
        # omega = w d^2 (3 - 2 d); theta = w T (d^3 - d^4 / 2); alpha = 6 w d (1 - d) / T
        return w * T * (d**3 - 0.5 * d**4), w * d * d * (3.0 - 2.0 * d), 6.0 * w * d * (1.0 - d) / T

    def load(self, t: float) -> float:
        return step(t, 0.0, 0.0, self.ramp, self.load_final)

    def impact(self, pen: float, rate: float) -> float:
        if pen <= 0.0:
            return 0.0
        return max(0.0, self.k * pen**self.e + step(pen, 0.0, 0.0, self.d_max, self.c_max) * rate)

    def forces(self, s1: float, delta: float, deltadot: float) -> tuple[float, float]:
        """Total drive- and coast-flank normal force [N]."""
        f_drive = 0.0
        f_coast = 0.0
        u = (s1 - self.s1_0) % self.p_b
        uc = (-s1 - self.s1c_0) % self.p_b
        for j in range(self.n_slots):
            x1 = u + j * self.p_b
            x2 = x1 - delta
            if 0.0 <= x1 <= self.g_alpha and 0.0 <= x2 <= self.g_alpha:
                f_drive += self.impact(delta, deltadot)
            x1 = uc + j * self.p_b
            x2 = x1 + delta
            if 0.0 <= x1 <= self.g_alpha and 0.0 <= x2 <= self.g_alpha:
                f_coast += self.impact(-delta - self.j_n, -deltadot)
        return f_drive, f_coast

    def rhs(self, t: float, y: np.ndarray) -> list[float]:
        delta, deltadot = y
        theta1, _, alpha1 = self.pinion(t)
        f_drive, f_coast = self.forces(self.r_b1 * theta1, delta, deltadot)
        alpha2 = (self.r_b2 * (f_drive - f_coast) - self.load(t)) / self.J2
        return [deltadot, self.r_b1 * alpha1 - self.r_b2 * alpha2]


@dataclass
class ReferenceRun:
    wall_s: float
    nfev: int
    t: np.ndarray
    force: np.ndarray  # total drive-flank force at t [N]
    omega2: np.ndarray  # gear speed at t [rad/s]
    status: int
    message: str


def run_reference(model: RigidModel, t_out: np.ndarray, rtol: float, atol: list[float]
                  ) -> ReferenceRun:
    """solve_ivp LSODA from rest to t_out[-1]; samples at t_out."""
    t0 = time.perf_counter()
    sol = solve_ivp(model.rhs, (float(t_out[0]), float(t_out[-1])), [0.0, 0.0], method="LSODA",
                    t_eval=t_out, rtol=rtol, atol=atol)
    wall = time.perf_counter() - t0
    force = np.empty(sol.t.size)
    omega2 = np.empty(sol.t.size)
    for i, (t, delta, deltadot) in enumerate(zip(sol.t, sol.y[0], sol.y[1], strict=True)):
        theta1, omega1, _ = model.pinion(t)
        force[i] = model.forces(model.r_b1 * theta1, delta, deltadot)[0]
        omega2[i] = (model.r_b1 * omega1 - deltadot) / model.r_b2
    return ReferenceRun(wall, int(sol.nfev), sol.t, force, omega2, int(sol.status), sol.message)


def seed_rigid_model(params: np.ndarray, p_names: tuple[str, ...]) -> RigidModel:
    """The reference model with the numbers of gearcli's rigid seed kernel input."""
    p = dict(zip(p_names, (float(v) for v in params), strict=True))
    assert p["x_lo"] == 0.0, "rigid tables start at A"
    return RigidModel(
        r_b1=p["r_b1"], r_b2=p["r_b2"], J2=p["J2"], p_b=p["p_b"], g_alpha=p["x_hi"],
        s1_0=p["s1_0"], s1c_0=p["s1c_0"], j_n=p["backlash_n"], n_slots=int(p["n_slots"]),
        k=p["k_contact"], e=p["exponent"], c_max=p["c_max"], d_max=p["d_max"],
        omega_final=math.radians(3000.0), load_final=4.5e5, ramp=1.0,
    )
