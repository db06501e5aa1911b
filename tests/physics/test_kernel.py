"""The compiled simulation kernel (gearcli.core) against independent references.

* contact law, STEP and Adams mu(v) against the formulas written out here (docs/theory.md §4-5);
* the Dormand-Prince tableau, its error weights and dense output (order conditions);
* a second method: the same physics (docs/theory.md §1, §3-6) written separately below in plain
  Python, integrated with scipy's DOP853 at rtol 1e-10;
* energy: E_kin + V conserved for the elastic mesh with smooth (extended) tables, not for the
  rigid tables; the energy balance of the quadratures; friction power <= 0;
* status codes of runs that must fail;
* the seed case in steady state against statics and kinematics.

Units: mm, N, s, t, rad (docs/theory.md §1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from gearcli.core import layout
from gearcli.core.contact import impact_force, impact_potential
from gearcli.core.dopri5 import P_DENSE, dense
from gearcli.core.dopri5 import A as RK_A
from gearcli.core.dopri5 import B as RK_B
from gearcli.core.dopri5 import C as RK_C
from gearcli.core.dopri5 import E as RK_E
from gearcli.core.friction import adams_mu
from gearcli.core.gaptable import hermite
from gearcli.core.integrate import kernel_model, kernel_out, simulate
from gearcli.core.stepfunc import step
from gearcli.core.timeloop import new_work, run
from gearcli.model.timefunction import PiecewisePolynomial as PP

# --- seed-like pair (docs/theory.md §9) -----------------------------------------------------------
Z1, Z2 = 17, 25
R_B1, R_B2 = 79.874, 117.462  # base radii [mm]
P_B = 29.5213  # base pitch [mm]
G_ALPHA = 46.1485  # length of path of contact [mm]
EPS_ALPHA = G_ALPHA / P_B  # 1.5632
T1T2 = 210.0 * math.sin(math.radians(20.0))  # a sin(alpha) [mm]
T1A = T1T2 - math.sqrt(135.0**2 - R_B2**2)  # [mm]
OMEGA1 = 52.36  # 3000 deg/s [rad/s]
T_LOAD = 4.5e5  # 450 N*m [N*mm]


def disc_inertia(d_mm: float, b_mm: float = 100.0, rho: float = 7.85e-9) -> float:
    """Solid disc: m = rho pi d^2 b / 4 [t], J = m d^2 / 8 [t*mm^2]."""
    return rho * math.pi * d_mm**2 / 4.0 * b_mm * d_mm**2 / 8.0


J1, J2 = disc_inertia(170.0), disc_inertia(250.0)
MESH_PERIOD = P_B / (R_B1 * OMEGA1)  # [s]

BASE = dict(
    r_b1=R_B1, r_b2=R_B2, J1=J1, J2=J2, z1=Z1, z2=Z2, p_b=P_B, T1A=T1A, T1T2=T1T2,
    k_contact=1e5, exponent=1.5, c_max=100.0, d_max=0.1,
)


def adams_step(x, x0, h0, x1, h1):
    """Adams STEP written out (docs/theory.md §4)."""
    if x <= x0:
        return h0
    if x >= x1:
        return h1
    d = (x - x0) / (x1 - x0)
    return h0 + (h1 - h0) * d * d * (3.0 - 2.0 * d)


def mu_reference(v, mu_s, mu_d, v_s, v_d):
    """Adams friction coefficient, docs/theory.md §5, case by case."""
    if abs(v) >= v_d:
        return -math.copysign(mu_d, v)
    if abs(v) >= v_s:
        return -math.copysign(adams_step(abs(v), v_s, mu_s, v_d, mu_d), v)
    return adams_step(v, -v_s, mu_s, v_s, -mu_s)


# --- tables ---------------------------------------------------------------------------------
def rigid_tables():
    """engagement: rigid - zero gap on [0, g_alpha], nothing outside."""
    return np.zeros((4, 2, 2)), 0.0, G_ALPHA


H_GRID = G_ALPHA / 40.0  # grid spacing: 0 and g_alpha are grid points
EXT = 6  # grid points beyond each end of the path
C_G1, C_G2 = 0.02, 0.03  # curvature of the synthetic gaps outside the path [1/mm]


def synthetic_gap(c, x):
    """G = c x^2 before A, 0 on the path, c (x - g_alpha)^2 beyond E; and its slope."""
    x = np.asarray(x, float)
    below, above = np.minimum(x, 0.0), np.maximum(x - G_ALPHA, 0.0)
    return c * (below**2 + above**2), 2.0 * c * (below + above)


def extended_tables():
    """Synthetic extended tables; piecewise quadratic with knots on the grid, so the kernel's
    cubic Hermite interpolant reproduces them exactly."""
    x_lo, x_hi = -EXT * H_GRID, G_ALPHA + EXT * H_GRID
    x = np.linspace(x_lo, x_hi, 41 + 2 * EXT)
    tables = np.empty((4, 2, x.size))
    for k, c in enumerate((C_G1, C_G2, C_G2, C_G1)):  # coast tables differ from drive ones
        tables[k] = synthetic_gap(c, x)
    return tables, x_lo, x_hi


def n_slots(x_lo, x_hi):
    return math.ceil((x_hi - x_lo) / P_B) + 1


def pp_arrays(pp):
    return pp.to_arrays()


# --- 1. contact law, friction law, interpolation, tableau ----------------------------------
@pytest.mark.parametrize("pen", [-0.01, 0.0, 1e-4, 0.03, 0.0999, 0.1, 0.2])
@pytest.mark.parametrize("rate", [-500.0, -5.0, 0.0, 3.0, 400.0])
def test_impact_force_matches_adams_impact(pen, rate):
    k, e, c_max, d_max = 1e5, 1.5, 100.0, 0.1
    force, elastic = impact_force(pen, rate, k, e, c_max, d_max)
    if pen <= 0.0:
        assert force == 0.0 and elastic == 0.0
        return
    expected = max(0.0, k * pen**e + adams_step(pen, 0.0, 0.0, d_max, c_max) * rate)
    assert force == pytest.approx(expected, rel=1e-13, abs=1e-9)
    assert elastic == pytest.approx(k * pen**e, rel=1e-13)


def test_impact_potential_is_the_antiderivative_of_the_elastic_force():
    k, e = 1e5, 1.5
    for p in (1e-3, 0.02, 0.11):
        h = 1e-7
        slope = (impact_potential(p + h, k, e) - impact_potential(p - h, k, e)) / (2 * h)
        assert slope == pytest.approx(k * p**e, rel=1e-7)
        assert impact_potential(p, k, e) == pytest.approx(k * p ** (e + 1) / (e + 1), rel=1e-13)
    assert impact_potential(-0.1, k, e) == 0.0


def test_step_matches_formula():
    for x in np.linspace(-1.0, 3.0, 41):
        assert step(x, 0.5, -2.0, 2.0, 7.0) == pytest.approx(adams_step(x, 0.5, -2.0, 2.0, 7.0))


def test_adams_mu_matches_model_and_never_drives():
    args = (0.08, 0.05, 0.01, 0.1)
    vs = np.concatenate([np.linspace(-0.3, 0.3, 601), [-0.1, -0.01, 0.0, 0.01, 0.1, 1e3, -1e3]])
    for v in vs:
        mu = adams_mu(v, *args)
        assert mu == pytest.approx(mu_reference(v, *args), abs=1e-15)
        assert mu * v <= 0.0
        assert adams_mu(-v, *args) == pytest.approx(-mu, abs=1e-15)
    assert adams_mu(0.0, *args) == 0.0


def test_hermite_reproduces_a_cubic_and_its_slope():
    x_lo, x_hi, n = -2.0, 3.0, 11
    x = np.linspace(x_lo, x_hi, n)
    f = lambda s: 0.3 * s**3 - s**2 + 0.5 * s + 2.0  # noqa: E731
    df = lambda s: 0.9 * s**2 - 2.0 * s + 0.5  # noqa: E731
    tables = np.zeros((4, 2, n))
    tables[1] = f(x), df(x)
    h = (x_hi - x_lo) / (n - 1)
    for s in np.linspace(x_lo, x_hi, 37):
        inside, value, slope = hermite(tables, 1, x_lo, x_hi, h, 1.0 / h, s)
        assert inside
        assert value == pytest.approx(f(s), abs=1e-12)
        assert slope == pytest.approx(df(s), abs=1e-11)
    assert not hermite(tables, 1, x_lo, x_hi, h, 1.0 / h, x_hi + 1e-9)[0]
    assert not hermite(tables, 1, x_lo, x_hi, h, 1.0 / h, x_lo - 1e-9)[0]


def test_dormand_prince_tableau_order_conditions_and_dense_output():
    assert np.allclose(RK_A.sum(axis=1), RK_C)  # row sums = nodes
    assert RK_B.sum() == pytest.approx(1.0)
    for q in range(1, 6):  # quadrature conditions of order 5: sum b_i c_i^(q-1) = 1/q
        assert RK_B @ RK_C ** (q - 1) == pytest.approx(1.0 / q, rel=1e-13)
    assert RK_E.sum() == pytest.approx(0.0, abs=1e-15)  # both weights integrate constants
    b4 = np.append(RK_B, 0.0) - RK_E  # the embedded 4th-order weights
    for q in range(1, 5):
        assert b4 @ np.append(RK_C, 1.0) ** (q - 1) == pytest.approx(1.0 / q, rel=1e-12)
    assert np.allclose(P_DENSE.sum(axis=1)[:6], RK_B) and abs(P_DENSE[6].sum()) < 1e-14
    # the continuous extension interpolates y' = t^3 exactly enough (4th order)
    h, K = 0.1, np.zeros((7, 1))
    for s, c in enumerate(np.append(RK_C, 1.0)):
        K[s, 0] = (c * h) ** 3
    out = np.zeros(1)
    for x in (0.25, 0.5, 1.0):
        dense(np.zeros(1), K, h, x, out)
        assert out[0] == pytest.approx((x * h) ** 4 / 4.0, rel=1e-12)


def test_make_params_names_and_layout_guard():
    with pytest.raises(KeyError, match="unknown"):
        layout.make_params(**BASE, drive_mode=0, t_end=1, x_lo=0, x_hi=1, n_slots=2, bogus=1)
    with pytest.raises(KeyError, match="missing.*J2"):
        layout.make_params(**{k: v for k, v in BASE.items() if k != "J2"})
    assert len(set(layout.PARAM_NAMES)) == layout.N_PARAMS
    assert layout.P.r_b2 == layout.PARAM_NAMES.index("r_b2")


# --- 2. second method -------------------------------------------------------------------------
class Reference:
    """The model of docs/theory.md §1, §3-6 in plain Python (scalar loops, analytic gap functions).

    ``drive``: "speed" (state delta, deltadot; pinion prescribed) or "torque" (state s1, v1,
    delta, deltadot with T_drive = 0). Positions from A; slot j of the drive flank at
    x1 = x_lo + ((s1 - s1_0) mod p_b) + j p_b, gear position x1 - delta; coast slots mirrored.
    """

    def __init__(self, p, gap, tooth_offsets, speed_pp=None, load_pp=None, shaft=False):
        self.p, self.gap, self.off = p, gap, tooth_offsets
        self.speed_pp, self.load_pp, self.shaft = speed_pp, load_pp, shaft
        if speed_pp is not None:
            self.angle_pp = speed_pp.antiderivative(0.0)
            self.accel_pp = speed_pp.derivative()

    def gap_of(self, k, x):
        p = self.p
        if not (p["x_lo"] <= x <= p["x_hi"]):
            return None
        return self.gap(k, x)

    def mesh(self, s1, v1, delta, deltadot):
        """Generalized forces on s1, s2 [N], friction torques [N*mm], total forces [N]."""
        p = self.p
        s2, v2 = s1 - delta, v1 - deltadot
        th1, th2, w1, w2 = s1 / p["r_b1"], s2 / p["r_b2"], v1 / p["r_b1"], v2 / p["r_b2"]
        q1 = q2 = m1 = m2 = 0.0
        totals = [0.0, 0.0]
        fric_power = 0.0
        for coast in (False, True):
            if coast and not p["coast_flanks"]:
                continue
            if not coast:
                r, jn, tabs, rows = s1 - p["s1_0"], 0.0, (0, 1), (0, 1)
                ph1, ph2, k1, k2 = p["phase1"], p["phase2"], p["tooth_k1"], p["tooth_k2"]
            else:
                r, jn, tabs, rows = -s1 - p["s1c_0"], p["backlash_n"], (2, 3), (2, 3)
                ph1, ph2 = p["phase1_coast"], p["phase2_coast"]
                k1, k2 = p["tooth_k1_coast"], p["tooth_k2_coast"]
            n = math.floor(r / p["p_b"])
            u = r - n * p["p_b"]
            for j in range(p["n_slots"]):
                x1 = p["x_lo"] + u + j * p["p_b"]
                x2 = x1 + delta if coast else x1 - delta
                g1, g2 = self.gap_of(tabs[0], x1), self.gap_of(tabs[1], x2)
                if g1 is None or g2 is None:
                    continue
                # the physical pair keeps its teeth when the slots renumber (see rhs.py)
                i1 = int((k1 - n + j) % Z1 if coast else (k1 + n - j) % Z1)
                i2 = int((k2 - n + j) % Z2 if coast else (k2 + n - j) % Z2)
                e1 = p["ecc1"] * math.sin(th1 + ph1)
                e2 = p["ecc2"] * math.sin(th2 + ph2)
                errors = e1 + e2 + self.off[rows[0], i1] + self.off[rows[1], i2]
                de1 = p["ecc1"] * math.cos(th1 + ph1) / p["r_b1"]
                de2 = p["ecc2"] * math.cos(th2 + ph2) / p["r_b2"]
                if not coast:  # p = delta - G1(x1) - G2(x2) - errors, dx1/ds1 = 1, dx2/ds2 = 1
                    pen = delta - g1[0] - g2[0] - errors
                    dp1, dp2 = 1.0 - g1[1] - de1, -1.0 - g2[1] - de2
                else:  # p = -delta - j_n - G1c(x1c) - G2c(x2c) - errors, dx/ds = -1
                    pen = -delta - jn - g1[0] - g2[0] - errors
                    dp1, dp2 = -1.0 + g1[1] - de1, 1.0 + g2[1] - de2
                if pen <= 0.0:
                    continue
                rate = dp1 * v1 + dp2 * v2
                force = p["k_contact"] * pen ** p["exponent"] \
                    + adams_step(pen, 0.0, 0.0, p["d_max"], p["c_max"]) * rate
                force = max(force, 0.0)
                q1 -= force * dp1
                q2 -= force * dp2
                totals[coast] += force
                rho1 = p["T1A"] + x1
                rho2 = p["T1T2"] - rho1
                vs = w1 * rho1 - w2 * rho2
                f = mu_reference(vs, p["mu_s"], p["mu_d"], p["v_s"], p["v_d"]) * force \
                    if p["mu_d"] else 0.0
                m1 += f * rho1
                m2 -= f * rho2
                fric_power += f * vs
        return q1, q2, m1, m2, totals, fric_power

    def fun(self, t, y):
        p = self.p
        if self.speed_pp is not None and not self.shaft:
            s1 = p["r_b1"] * (self.angle_pp(t) + p["theta1_init"])
            v1, a1 = p["r_b1"] * self.speed_pp(t), p["r_b1"] * self.accel_pp(t)
            delta, deltadot = y
        else:
            s1, v1, delta, deltadot = y
        q1, q2, m1, m2, _, _ = self.mesh(s1, v1, delta, deltadot)
        load = self.load_pp(t) if self.load_pp is not None else 0.0
        alpha2 = (p["r_b2"] * q2 + m2 - load) / p["J2"]
        if self.speed_pp is None or self.shaft:
            torque = 0.0
            if self.shaft:  # motor angle and speed prescribed, torsional shaft to the pinion
                torque = p["shaft_k"] * (self.angle_pp(t) + p["theta1_init"] - s1 / p["r_b1"]) \
                    + p["shaft_c"] * (self.speed_pp(t) - v1 / p["r_b1"])
            a1 = p["r_b1"] * (torque + p["r_b1"] * q1 + m1) / p["J1"]
            return [v1, a1, deltadot, a1 - p["r_b2"] * alpha2]
        return [deltadot, a1 - p["r_b2"] * alpha2]


def _case(kind):
    """Parameters, kernel inputs and reference of one comparison case."""
    ramp = 0.02
    speed, load = PP.step(0.0, 0.0, ramp, OMEGA1), PP.step(0.0, 0.0, ramp, T_LOAD)
    if kind == "rigid":
        tables, x_lo, x_hi = rigid_tables()
        gap = lambda k, x: (0.0, 0.0)  # noqa: E731
    else:
        tables, x_lo, x_hi = extended_tables()
        cs = (C_G1, C_G2, C_G2, C_G1)
        gap = lambda k, x: tuple(float(v) for v in synthetic_gap(cs[k], x))  # noqa: E731
    offsets = np.zeros((4, Z2))
    extra = {}
    if kind != "rigid":
        rng = np.random.default_rng(7)
        offsets[:, :] = rng.uniform(-4e-3, 4e-3, offsets.shape)  # pitch deviations [mm]
        extra = dict(ecc1=5e-3, phase1=0.3, ecc2=8e-3, phase2=-1.1, phase1_coast=1.0,
                     phase2_coast=0.2, tooth_k1=3, tooth_k2=11, tooth_k1_coast=5,
                     tooth_k2_coast=2, s1_0=7.0, s1c_0=-3.0)
    values = dict(BASE, x_lo=x_lo, x_hi=x_hi, n_slots=n_slots(x_lo, x_hi), mu_s=0.08,
                  mu_d=0.05, v_s=0.01, v_d=0.1, backlash_n=0.05, coast_flanks=1, **extra)
    if kind == "rattle":  # free pinion, no torques: impacts on both flanks across the backlash
        values.update(drive_mode=layout.DRIVE_TORQUE, t_end=0.04, omega1_init=OMEGA1,
                      delta_init=-0.025, deltadot_init=60.0, c_max=10.0)
        speed, load = PP.constant(0.0), PP.constant(0.0)
    elif kind == "shaft":  # motor -> shaft (about 400 Hz with the pinion) -> pinion
        values.update(drive_mode=layout.DRIVE_SHAFT, t_end=ramp + 10 * MESH_PERIOD,
                      shaft_k=4e8, shaft_c=2e4)
    else:
        values.update(drive_mode=layout.DRIVE_SPEED, t_end=ramp + 20 * MESH_PERIOD)
    # tighter than the reference (rtol 1e-10), so the comparison measures the reference's error
    values.update(rtol=1e-12, atol_delta=1e-12, atol_deltadot=1e-9)
    prm = layout.make_params(**values)
    ref_p = layout.params_dict(prm)
    ref_p.update(n_slots=int(ref_p["n_slots"]), coast_flanks=bool(ref_p["coast_flanks"]))
    return values, prm, tables, offsets, speed, load, Reference(
        ref_p, gap, offsets, speed if kind != "rattle" else None, load, shaft=kind == "shaft")


@pytest.mark.parametrize("kind", ["rigid", "extended", "rattle", "shaft"])
def test_kernel_agrees_with_independent_reference(kind):
    values, prm, tables, offsets, speed, load, ref = _case(kind)
    t_end = values["t_end"]
    t_out = np.linspace(0.0, t_end, 400)
    res = simulate(prm, tables, t_out=t_out, drive_pp=pp_arrays(speed), load_pp=pp_arrays(load),
                   drive_angle_pp=pp_arrays(speed.antiderivative(0.0)), tooth_offsets=offsets)
    assert res.ok, res.message
    if kind == "rattle":
        y0 = [0.0, R_B1 * OMEGA1, values["delta_init"], values["deltadot_init"]]
    elif kind == "shaft":
        y0 = [0.0, 0.0, 0.0, 0.0]
    else:
        y0 = [0.0, 0.0]
    sol = solve_ivp(ref.fun, (0.0, t_end), y0, method="DOP853", t_eval=t_out, rtol=1e-10,
                    atol=1e-12, max_step=MESH_PERIOD / 20)
    assert sol.success
    delta_ref = sol.y[-2]
    scale = np.abs(delta_ref).max()
    err = np.abs(res.column("delta_mm") - delta_ref).max()
    # measured: 3e-9 (rigid), 2e-9 (extended), 2e-8 mm (rattle); both converge to each other
    assert err <= 1e-6 * scale, f"DTE differs by {err:.2e} mm (scale {scale:.3f} mm)"
    # total force and friction power from the reference state at the samples
    if kind in ("rattle", "shaft"):
        states = [(s1, v1, d, dd) for s1, v1, d, dd in sol.y.T]
    else:
        s1 = R_B1 * np.array([ref.angle_pp(t) for t in t_out])
        v1 = R_B1 * np.array([speed(t) for t in t_out])
        states = list(zip(s1, v1, sol.y[0], sol.y[1], strict=True))
    mesh = [ref.mesh(*s) for s in states]
    f_ref = np.array([m[4][0] for m in mesh])
    fc_ref = np.array([m[4][1] for m in mesh])
    f_scale = max(np.abs(f_ref).max(), np.abs(fc_ref).max())
    assert np.abs(res.column("force_total_N") - f_ref).max() <= 1e-4 * f_scale
    assert np.abs(res.column("force_coast_N") - fc_ref).max() <= 1e-4 * f_scale
    if kind == "rattle":
        assert fc_ref.max() > 100.0 and f_ref.max() > 100.0  # both flanks were hit
    assert np.all(res.column("friction_power_mW") <= 0.0)
    assert np.any(res.column("friction_power_mW") < 0.0)


# --- 3. energy --------------------------------------------------------------------------------
def _free_run(tables, x_lo, x_hi, t_end, **extra):
    """Free pinion and gear, no drive or load torque, rattling across the backlash."""
    values = dict(BASE, x_lo=x_lo, x_hi=x_hi, n_slots=n_slots(x_lo, x_hi),
                  drive_mode=layout.DRIVE_TORQUE, t_end=t_end, omega1_init=OMEGA1,
                  delta_init=0.02, deltadot_init=40.0, backlash_n=0.05, c_max=0.0,
                  ecc1=5e-3, phase1=0.4, ecc2=8e-3, phase2=1.3, phase1_coast=-0.3,
                  phase2_coast=2.0, tooth_k1=2, tooth_k2=9, s1_0=4.0, s1c_0=11.0,
                  rtol=1e-10, atol_delta=1e-10, atol_deltadot=1e-7)
    values.update(extra)
    offsets = np.random.default_rng(3).uniform(-3e-3, 3e-3, (4, Z2))
    zero = pp_arrays(PP.constant(0.0))
    t_out = np.linspace(0.0, t_end, 2001)
    res = simulate(layout.make_params(**values), tables, t_out=t_out, drive_pp=zero,
                   load_pp=zero, tooth_offsets=offsets)
    assert res.ok, res.message
    energy = res.column("kinetic_energy_mJ") + res.column("contact_energy_mJ")
    return res, energy


def test_energy_is_conserved_with_extended_tables():
    res, energy = _free_run(*extended_tables(), t_end=30 * MESH_PERIOD)
    assert res.column("force_total_N").max() > 500 and res.column("force_coast_N").max() > 500
    drift = np.abs(energy - energy[0]).max()
    # measured 9e-9 of the total (rotation dominates) and 1.5e-4 of the largest contact energy;
    # both shrink with the tolerances (2e-6 of the contact energy at 1e-12)
    assert drift < 1e-6 * energy[0], f"relative energy drift {drift / energy[0]:.2e}"
    assert drift < 1e-3 * res.column("contact_energy_mJ").max()
    assert res.extremum("energy_initial_mJ") == pytest.approx(energy[0], rel=1e-12)


def test_rigid_tables_are_not_conservative():
    """Regression: in the rigid model a pair enters with the full deflection, so the contact
    energy jumps at every loaded entry (docs/theory.md §3)."""
    res, energy = _free_run(*rigid_tables(), t_end=30 * MESH_PERIOD)
    # measured: jumps of 0.87 times the largest contact energy (5e-4 of the total)
    assert np.abs(energy - energy[0]).max() > 0.1 * res.column("contact_energy_mJ").max()


@pytest.mark.parametrize("mode", [layout.DRIVE_SPEED, layout.DRIVE_SHAFT, layout.DRIVE_TORQUE])
def test_energy_balance_with_damping_friction_and_load(mode):
    tables, x_lo, x_hi = extended_tables()
    speed, load = PP.step(0.0, 0.0, 0.02, OMEGA1), PP.step(0.0, 0.0, 0.02, T_LOAD)
    if mode == layout.DRIVE_TORQUE:  # 2 T_load, linear motor curve down to zero at 60 rad/s
        speed = PP.step(0.0, 0.0, 0.02, 2.0 * T_LOAD * R_B1 / R_B2)
    prm = layout.make_params(**BASE, x_lo=x_lo, x_hi=x_hi, n_slots=n_slots(x_lo, x_hi),
                             drive_mode=mode, t_end=0.06, mu_s=0.08, mu_d=0.05,
                             c1=50.0, c2=80.0, load_cv=100.0, load_cq=2.0, shaft_k=4e8,
                             shaft_c=2e4, motor_omega0=60.0, rtol=1e-9,
                             atol_delta=1e-9, atol_deltadot=1e-6)
    t_out = np.linspace(0.0, 0.06, 601)
    res = simulate(prm, tables, t_out=t_out, drive_pp=pp_arrays(speed), load_pp=pp_arrays(load),
                   drive_angle_pp=pp_arrays(speed.antiderivative()))
    assert res.ok, res.message
    c = res.column
    stored = c("kinetic_energy_mJ") + c("contact_energy_mJ") - res.extremum("energy_initial_mJ")
    budget = c("work_in_mJ") - c("work_load_mJ") - c("loss_bearing_mJ") \
        - c("loss_damping_mJ") - c("loss_friction_mJ")
    assert np.abs(stored - budget).max() <= 1e-6 * np.abs(c("work_in_mJ")).max()
    for loss in ("loss_bearing_mJ", "loss_damping_mJ", "loss_friction_mJ"):
        assert np.all(np.diff(c(loss)) >= -1e-9) and c(loss)[-1] > 0.0
    assert np.all(c("friction_power_mW") <= 0.0)
    if mode == layout.DRIVE_TORQUE:  # the motor curve: T (1 - omega1/omega0)
        t = c("t_s")
        expected = np.array([speed(x) for x in t]) * (1.0 - c("omega1_rad_s") / 60.0)
        assert np.allclose(c("drive_torque_Nmm"), expected, rtol=1e-12, atol=1e-6)


# --- 4. status codes --------------------------------------------------------------------------
def _seed_inputs(t_end=0.05, **extra):
    tables, x_lo, x_hi = rigid_tables()
    speed, load = PP.step(0.0, 0.0, 0.02, OMEGA1), PP.step(0.0, 0.0, 0.02, T_LOAD)
    values = dict(BASE, x_lo=x_lo, x_hi=x_hi, n_slots=n_slots(x_lo, x_hi),
                  drive_mode=layout.DRIVE_SPEED, t_end=t_end)
    values.update(extra)
    return (layout.make_params(**values), tables), dict(
        t_out=np.linspace(values.get("t_start", 0.0), t_end, 101), drive_pp=pp_arrays(speed),
        load_pp=pp_arrays(load), drive_angle_pp=pp_arrays(speed.antiderivative()))


def _assert_failed_cleanly(res, status):
    assert res.status == status and not res.ok
    assert res.n_valid < res.series.shape[0]
    assert np.all(np.isnan(res.series[res.n_valid:]))
    assert np.all(np.isfinite(res.series[: res.n_valid]))


def test_status_max_steps():
    args, kw = _seed_inputs(max_steps=20)
    _assert_failed_cleanly(simulate(*args, **kw), layout.STATUS_MAX_STEPS)


def test_status_runaway_penetration_with_negative_inertia():
    args, kw = _seed_inputs(J2=-J2, penetration_limit=1.0)
    res = simulate(*args, **kw)
    _assert_failed_cleanly(res, layout.STATUS_RUNAWAY_PENETRATION)
    assert res.extremum("penetration_max_mm") > 1.0


def test_status_nan_from_the_inputs():
    args, kw = _seed_inputs()
    breaks, coefs, origins = kw["load_pp"]
    coefs = coefs.copy()
    coefs[-1, 0] = np.nan  # the load torque becomes NaN after its ramp
    res = simulate(*args, **{**kw, "load_pp": (breaks, coefs, origins)})
    _assert_failed_cleanly(res, layout.STATUS_NAN)


def test_status_step_too_small():
    # at t = 1e13 s the resolution of time (2 ms) is far above the mesh's time scale
    args, kw = _seed_inputs(t_start=1e13, t_end=1e13 + 1.0)
    _assert_failed_cleanly(simulate(*args, **kw), layout.STATUS_STEP_TOO_SMALL)


def test_stale_compiled_layout_is_refused():
    (prm, tables), kw = _seed_inputs()
    t_out = kw.pop("t_out")
    model = kernel_model(prm, tables, **kw)
    out = kernel_out(model, t_out)
    assert run(model, new_work(model.prm), out, layout.LAYOUT_KEY + 1, 0)[0] \
        == layout.STATUS_STALE_CACHE
    assert np.isnan(out.series).all()  # nothing was integrated


# --- 5. seed case, steady state ----------------------------------------------------------------
def test_seed_steady_state_statics_and_kinematics():
    ramp, n_cycles = 0.05, 10
    t_end = 0.3
    t0 = t_end - n_cycles * MESH_PERIOD
    t_out = np.concatenate([np.linspace(0.0, t0, 50, endpoint=False),
                            t0 + np.arange(n_cycles * 1000 + 1) * MESH_PERIOD / 1000])
    speed, load = PP.step(0.0, 0.0, ramp, OMEGA1), PP.step(0.0, 0.0, ramp, T_LOAD)
    tables, x_lo, x_hi = rigid_tables()
    prm = layout.make_params(**BASE, x_lo=x_lo, x_hi=x_hi, n_slots=n_slots(x_lo, x_hi),
                             drive_mode=layout.DRIVE_SPEED, t_end=t_end, extrema_t_start=t0)
    res = simulate(prm, tables, t_out=t_out, drive_pp=pp_arrays(speed), load_pp=pp_arrays(load),
                   drive_angle_pp=pp_arrays(speed.antiderivative()))
    assert res.ok, res.message
    steady = res.column("t_s") >= t0

    def mean(name):  # trapezoid mean over whole mesh cycles
        v = res.column(name)[steady]
        return (v[1:] + v[:-1]).sum() / (2.0 * (v.size - 1))

    assert mean("force_total_N") == pytest.approx(T_LOAD / R_B2, rel=5e-3)
    assert mean("omega2_rad_s") == pytest.approx(OMEGA1 * Z1 / Z2, rel=1e-4)
    # rigid: in contact while x1 <= g_alpha and x2 = x1 - delta >= 0, a path g_alpha - delta
    pairs = mean("pairs_in_contact")  # a step function: sampling resolves it to 2/1000
    assert pairs == pytest.approx(EPS_ALPHA, abs=0.01)
    assert pairs == pytest.approx((G_ALPHA - mean("delta_mm")) / P_B, abs=2.5e-3)
    # true extrema come from the solver's steps: never below the sampled ones
    f = res.column("force_total_N")[steady]
    assert res.extremum("force_total_max_N") >= f.max()
    assert res.extremum("force_total_min_N") <= f.min()
    assert np.all(res.slot_extremum("force_max_N") >= res.slot_force[steady].max(axis=0))
    assert res.extremum("force_total_max_t_s") >= t0
