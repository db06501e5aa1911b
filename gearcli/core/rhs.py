"""Right-hand side of the spur-pair model (model.md §1, §3-6; model/structure.py).

Coordinates [mm]: roll distances s1 = r_b1 theta1, s2 = r_b2 theta2 and the DTE
delta = s1 - s2 (> 0 compresses the drive flanks). Integrated state: see layout.STATE_NAMES.

Pair slots (model.md §3). Drive flank, slot j = 0 .. N-1:
    r = s1 - s1_0,  n = floor(r / p_b),  u = r - n p_b in [0, p_b)
    x1_j = x_lo + u + j p_b        pinion roll position, measured from A [mm]
    x2_j = x1_j - delta            gear roll position [mm]
    p_j = delta - G1(x1_j) - G2(x2_j) - e1 - e2 - Ft1[i1_j] - Ft2[i2_j]
    i1_j = (k1 + n - j) mod z1,  i2_j = (k2 + n - j) mod z2
Slot 0 holds the pair that entered last. When u wraps from p_b to 0, n grows by one and the pair
of slot j moves to slot j + 1 at the same position, so its tooth index must not change:
(k1 + n - j) is invariant under (n, j) -> (n + 1, j + 1). (With "+ j" every wrap would swap the
teeth in contact, make the flank offsets jump and break energy conservation.)

Coast flank: the same construction in the mirrored coordinates s' = -s, delta' = -delta (the
coast flanks are the drive flanks of the reversed motion; the coast LoA is the mirror image of
the drive LoA about the line of centres):
    r = -s1 - s1c_0,  x1c_j = x_lo + u + j p_b,  x2c_j = x1c_j + delta
    pc_j = -delta - j_n - G1c(x1c_j) - G2c(x2c_j) - e1c - e2c - Ft1c[i1c_j] - Ft2c[i2c_j]
    i1c_j = (k1c - n + j) mod z1, ...
Both flanks are written once with sigma = +1 (drive) or -1 (coast): x1 moves as sigma s1, x2 as
sigma s2, and
    dp/ds1 = sigma (1 - G1'(x1)) - de1/ds1,   dp/ds2 = -sigma (1 + G2'(x2)) - de2/ds2.
Runout on a flank: e_i = ecc_i sin(theta_i + phase_i) (phase_i_coast on the coast LoA; the
projection of the same rotating eccentricity on the mirrored LoA differs only in phase).

Forces (model.md §4): F_j = IMPACT(p_j, pdot_j), pdot_j = dp/ds1 v1 + dp/ds2 v2 (chain rule);
generalized forces Q_s1 = -F dp/ds1, Q_s2 = -F dp/ds2 [N]: the gradient of the potential
sum k p^(e+1)/(e+1) plus the damping part, so the elastic mesh conserves energy exactly.
Torques r_b1 Q_s1 on the pinion, r_b2 Q_s2 on the gear [N*mm].

Friction (model.md §5), both flanks: rho1 = T1A + x1_j, rho2 = T1T2 - rho1 [mm],
v = omega1 rho1 - omega2 rho2 [mm/s], f = mu(v) F [N]; pinion torque += f rho1, gear torque
-= f rho2. Power f (omega1 rho1 - omega2 rho2) = mu(v) F v <= 0. Coast mirrored: in mirrored
coordinates v' = -v, mu(v') = -mu(v), f' = -f and the mirrored torques +f' rho1, -f' rho2 map
back with one more sign change to +f rho1, -f rho2: the same formulas in the real coordinates
(with the coast contact point's rho1 = T1A + x1c_j; the coast path has the drive path's length
for the symmetric teeth this assumes). The contact point is taken on the LoA also outside the
nominal path (extended contact): an approximation of the tip-contact arms of model.md §3.

Equations of motion (model.md §6), M1, M2 the mesh + friction torques:
    J1 alpha1 = T_drive + M1 - c1 omega1
    J2 alpha2 = M2 - T_load(t) - cv omega2 - cq omega2 |omega2| - c2 omega2
    s1'' = r_b1 alpha1,  delta'' = r_b1 alpha1 - r_b2 alpha2.
Drive (inputs from drive.forcing): speed - theta1(t) = theta1_init + Theta(t) - Theta(t_start)
with Theta the antiderivative of omega1(t), alpha1 = omega1'(t); T_drive = J1 alpha1 - M1 +
c1 omega1 is the torque needed (reported). Shaft - the motor angle theta_m(t) is built the same
way; T_drive = k_s (theta_m - theta1) + c_s (omega_m - omega1). Torque - T_drive = T(t)
(1 - omega1/omega0), the factor only when omega0 > 0.

Optional bodies (model/structure.py; states after N_STATE_BASE, integrated only when present):
- motor inertia J_m (torque drive through the drive shaft), twist tw_m = theta_m - theta1:
      J_m alpha_m = T(t) (1 - omega_m/omega0) - T_s,   T_s = k_s tw_m + c_s tw_m'
  and T_s replaces T_drive on the pinion; tw_m'' = alpha_m - alpha1.
- load inertia J_L on the load shaft, twist tw_l = theta2 - theta_L:
      J_L alpha_L = T_L - T_load(t) - (cv + cq |omega_L|) omega_L,   T_L = k_L tw_l + c_L tw_l'
  and the gear sees -T_L instead of the load terms; tw_l'' = alpha2 - alpha_L.
- lateral-torsional model: the centres u_i = (x_i, y_i) move on bearings (k, c per direction),
      m_i u_i'' = F_mesh,i - K_i u_i - C_i u_i',
  the approach (u1 - u2) . n adds to every pair's penetration on the flank family with line
  of action n (n_d, n_c), its rate to pdot, (u1' - u2') . t to the sliding speed; the mesh
  force on the pinion centre is -F_d n_d - F_c n_c + f_d t_d + f_c t_c, the gear gets the
  opposite (Kahraman & Singh, J. Sound Vib. 146(1), 1991: the 6-DOF spur-pair model).
Energy: shafts and bearings store sum k q^2/2 (aux spring_energy), their dampers and the load
terms dissipate into loss_bearing, so the energy balance closes for every model.
"""

import math

import numpy as np

from gearcli.core.contact import impact_force
from gearcli.core.friction import adams_mu
from gearcli.core.gaptable import (
    TABLE_G1,
    TABLE_G1_COAST,
    TABLE_G2,
    TABLE_G2_COAST,
    hermite,
    table_floor,
)
from gearcli.core.jit import jit
from gearcli.core.layout import DRIVE_SHAFT, DRIVE_SPEED, N_STATE_BASE, A, D, P, S
from gearcli.core.nrt import jit_noalloc, jit_noalloc_inline


@jit_noalloc_inline
def flank(sigma, s1, v1, delta, v2, omega1, omega2, e1, de1, e2, de2, phase0, offset,
          lat, lat_rate, slide, k1, k2, t1, t2, g1, g2, overlap_max, prm, derived, tables,
          tooth_offsets, slot_force, full):
    """Forces of all pair slots of one flank family (drive: sigma = +1, coast: sigma = -1).

    Parameters
    ----------
    sigma : float
        +1 drive flanks, -1 coast flanks.
    s1, v1 : float
        Pinion roll distance [mm] and rate [mm/s].
    delta, v2 : float
        DTE [mm] and gear roll rate [mm/s].
    omega1, omega2 : float
        Angular speeds [rad/s] (friction).
    e1, de1, e2, de2 : float
        Runout gaps on this flank's LoA [mm] and their derivatives de1/ds1, de2/ds2 [-].
    phase0 : float
        s1_0 or s1c_0 [mm].
    offset : float
        0 (drive) or the normal backlash j_n (coast) [mm].
    lat, lat_rate, slide : float
        Lateral model: approach (u1 - u2) . n of the gear centres along this flank's line of
        action [mm], its rate [mm/s], and their relative speed (u1' - u2') . t across it
        [mm/s], added to the sliding speed (model/structure.py); 0 in the torsional model.
    k1, k2 : int
        Tooth index offsets; t1, t2 rows of ``tooth_offsets`` (per-tooth flank offsets [mm]).
    g1, g2 : int
        Gap tables of the pinion and gear roll positions.
    overlap_max : float
        Upper bound of ``-G1 - G2 - e1 - e2 - Ft1 - Ft2`` over all positions [mm]
        (:func:`overlap_bound`); with ``sigma delta - offset + overlap_max <= 0`` no slot can
        touch and the slot loop is skipped.

    Fast paths that leave every result unchanged (tests/physics/test_kernel_fastpaths.py,
    bench/RESULTS.md): inside a table's zero run (``derived[D.zero_lo + k] ..
    derived[D.zero_hi + k]``, :func:`derive`) the gap and its slope are exactly 0 and the
    table is not read (most slots of the seed case: the mid-path of extended tables, all of
    the rigid ones); without per-tooth offsets (``derived[D.tooth_offsets_used] == 0``) the
    tooth indices are not tracked.
    prm, derived : ndarray
        Parameter vector (layout.P) and derived constants (layout.D).
    tables, tooth_offsets : ndarray
        See :func:`rhs`.
    slot_force : ndarray, shape (N,)
        Written when ``full``: the force of every slot [N] (0 out of contact).
    full : bool
        False at the inner Runge-Kutta stages, where only the derivatives are used.

    Returns
    -------
    tuple
        (Q1, Q2, M1f, M2f, F_sum, n_contact, f_sum, friction_power, damping_power, V, pen_max):
        generalized mesh forces on s1, s2 [N]; friction torques on pinion, gear [N*mm];
        sum of normal forces [N]; pairs with F > 0; signed friction force sum [N]; sum f v
        [N*mm/s] (<= 0); damping dissipation rate [N*mm/s] (>= 0); contact potential [N*mm];
        largest penetration [mm].
    """
    if full:
        for j in range(slot_force.shape[0]):
            slot_force[j] = 0.0
    if sigma * delta + lat - offset + overlap_max <= 0.0:  # no slot can touch
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0, 0.0, 0.0, 0.0, 0.0, 0.0
    p_b = prm[P.p_b]
    x_lo = prm[P.x_lo]
    x_hi = prm[P.x_hi]
    h_grid = derived[D.grid_step]
    inv_h = derived[D.inv_grid_step]
    z1 = int(prm[P.z1])
    z2 = int(prm[P.z2])
    k = prm[P.k_contact]
    ex = prm[P.exponent]
    c_max = prm[P.c_max]
    d_max = prm[P.d_max]
    mu_s = prm[P.mu_s]
    mu_d = prm[P.mu_d]
    inv_e1 = derived[D.inv_exponent_plus_1]
    use_friction = mu_s != 0.0 or mu_d != 0.0
    r = sigma * s1 - phase0
    nf = np.floor(r * derived[D.inv_p_b])  # a float: math.floor's int costs two conversions
    u = r - nf * p_b
    if u >= p_b:  # rounding of r - floor(r/p) p
        u -= p_b
        nf += 1.0
    elif u < 0.0:
        u += p_b
        nf -= 1.0
    n = int(nf)
    isig = 1 if sigma > 0.0 else -1
    q1 = 0.0
    q2 = 0.0
    m1f = 0.0
    m2f = 0.0
    f_sum = 0.0
    n_contact = 0
    ff_sum = 0.0
    fpow = 0.0
    pdamp = 0.0
    pot = 0.0
    pen_max = 0.0
    # tooth indices of slot 0; slot j holds teeth (k + sigma (n - j)) mod z (module docstring)
    use_offsets = derived[D.tooth_offsets_used] != 0.0
    zlo1 = derived[D.zero_lo + g1]
    zhi1 = derived[D.zero_hi + g1]
    zlo2 = derived[D.zero_lo + g2]
    zhi2 = derived[D.zero_hi + g2]
    i1 = 0
    i2 = 0
    if use_offsets:
        i1 = (k1 + isig * n) % z1
        i2 = (k2 + isig * n) % z2
    for j in range(slot_force.shape[0]):
        if j > 0 and use_offsets:
            i1 -= isig
            i2 -= isig
            if i1 < 0:
                i1 += z1
            elif i1 >= z1:
                i1 -= z1
            if i2 < 0:
                i2 += z2
            elif i2 >= z2:
                i2 -= z2
        x1 = x_lo + u + j * p_b
        x2 = x1 - sigma * delta
        # x1 >= x_lo always (u >= 0); NaN fails every comparison and ends the loop
        if not x1 <= x_hi:
            break  # x1 grows with j: every further slot is beyond the table too
        if not (x2 >= x_lo and x2 <= x_hi):
            continue
        # inside a table's zero run the Hermite cubic is exactly 0 (values and slopes 0)
        if x1 >= zlo1 and x1 <= zhi1:
            gap1 = 0.0
            dgap1 = 0.0
        else:
            _, gap1, dgap1 = hermite(tables, g1, x_lo, x_hi, h_grid, inv_h, x1)
        if x2 >= zlo2 and x2 <= zhi2:
            gap2 = 0.0
            dgap2 = 0.0
        else:
            _, gap2, dgap2 = hermite(tables, g2, x_lo, x_hi, h_grid, inv_h, x2)
        pen = sigma * delta + lat - offset - gap1 - gap2 - e1 - e2
        if use_offsets:
            pen -= tooth_offsets[t1, i1] + tooth_offsets[t2, i2]
        if pen <= 0.0:
            continue
        if pen > pen_max:
            pen_max = pen
        dp1 = sigma * (1.0 - dgap1) - de1  # dp/ds1 [-]
        dp2 = -sigma * (1.0 + dgap2) - de2  # dp/ds2 [-]
        pdot = dp1 * v1 + dp2 * v2 + lat_rate
        force, fel = impact_force(pen, pdot, k, ex, c_max, d_max)
        pot += fel * pen * inv_e1  # k p^(e+1)/(e+1), contact.impact_potential
        # damping dissipation rate (F - k p^e) pdot >= 0, also when the max() clips F to 0
        pdamp += (force - fel) * pdot
        if force <= 0.0:
            continue
        if full:
            slot_force[j] = force
        f_sum += force
        n_contact += 1
        q1 -= force * dp1
        q2 -= force * dp2
        if use_friction:
            rho1 = prm[P.T1A] + x1
            rho2 = prm[P.T1T2] - rho1
            vs = omega1 * rho1 - omega2 * rho2 + slide
            f = adams_mu(vs, mu_s, mu_d, prm[P.v_s], prm[P.v_d]) * force
            m1f += f * rho1
            m2f -= f * rho2
            ff_sum += f
            fpow += f * vs
    return q1, q2, m1f, m2f, f_sum, n_contact, ff_sum, fpow, pdamp, pot, pen_max


@jit_noalloc
def error_bound(prm, tooth_offsets, t1, t2):
    """Largest overlap [mm] runout and tooth offsets can add on one flank family.

    ``|ecc1| + |ecc2| + max_i(-Ft1[i]) + max_i(-Ft2[i])`` (rows ``t1``, ``t2`` of the offsets).
    """
    bound = abs(prm[P.ecc1]) + abs(prm[P.ecc2])
    for row, z in ((t1, int(prm[P.z1])), (t2, int(prm[P.z2]))):
        worst = -math.inf
        for i in range(z):
            worst = max(worst, -tooth_offsets[row, i])
        bound += worst
    return bound


@jit_noalloc
def overlap_bound(prm, tables, tooth_offsets, g1, g2, t1, t2):
    """Upper bound [mm] of ``-G1(x1) - G2(x2) - e1 - e2 - Ft1 - Ft2`` of one flank family.

    A pair of the family can only touch when ``sigma delta - offset`` exceeds minus this.
    """
    h = (prm[P.x_hi] - prm[P.x_lo]) / (tables.shape[2] - 1)
    return -table_floor(tables, g1, h) - table_floor(tables, g2, h) \
        + error_bound(prm, tooth_offsets, t1, t2)


@jit_noalloc
def end_gap_bound(tables, g1, g2, h):
    """Lower bound [mm] of ``G1(x1) + G2(x2)`` when either position sits on a table end.

    ``min(G1(x_lo), G1(x_hi)) + min G2`` or the same with the tables swapped (``min G`` from
    :func:`gearcli.core.gaptable.table_floor`). A pair crossing a table end overlaps by at most
    ``sigma delta - offset`` minus this (events.py); extended tables open a gap of about the
    tabulation cap there, so no crossing of theirs is loaded.
    """
    n = tables.shape[2]
    end1 = min(tables[g1, 0, 0], tables[g1, 0, n - 1]) + table_floor(tables, g2, h)
    end2 = min(tables[g2, 0, 0], tables[g2, 0, n - 1]) + table_floor(tables, g1, h)
    return min(end1, end2)


@jit_noalloc
def zero_run(tables, k):
    """First and last grid index of the longest run of grid points of table ``k`` where the
    value and the slope are both zero (``(0, -1)`` if none): the Hermite cubic vanishes
    identically between them."""
    best_lo = 0
    best_hi = -1
    start = -1
    n = tables.shape[2]
    for i in range(n + 1):
        zero = i < n and tables[k, 0, i] == 0.0 and tables[k, 1, i] == 0.0
        if zero:
            if start < 0:
                start = i
        elif start >= 0:
            if i - 1 - start > best_hi - best_lo:
                best_lo = start
                best_hi = i - 1
            start = -1
    return best_lo, best_hi


@jit_noalloc
def derive(prm, tables, tooth_offsets, derived):
    """Fill ``derived`` (layout.D) with the constants of a run: overlap bounds, grid step and
    reciprocals of the geometry and inertia parameters."""
    h = (prm[P.x_hi] - prm[P.x_lo]) / (tables.shape[2] - 1)
    derived[D.overlap_drive] = overlap_bound(prm, tables, tooth_offsets, TABLE_G1, TABLE_G2, 0, 1)
    derived[D.overlap_coast] = overlap_bound(prm, tables, tooth_offsets, TABLE_G1_COAST,
                                             TABLE_G2_COAST, 2, 3)
    derived[D.error_bound] = max(error_bound(prm, tooth_offsets, 0, 1),
                                 error_bound(prm, tooth_offsets, 2, 3))
    used = 0.0
    for row in range(tooth_offsets.shape[0]):
        for i in range(tooth_offsets.shape[1]):
            if tooth_offsets[row, i] != 0.0:
                used = 1.0
    derived[D.tooth_offsets_used] = used
    for k in range(tables.shape[0]):
        lo, hi = zero_run(tables, k)
        if hi - lo >= 2:
            # one grid step in from the run's ends: a position there falls in an interval of
            # the run whatever the rounding of its grid index, and the cubic is exactly 0
            derived[D.zero_lo + k] = prm[P.x_lo] + (lo + 1) * h
            derived[D.zero_hi + k] = prm[P.x_lo] + (hi - 1) * h
        else:  # no zero run: an empty interval
            derived[D.zero_lo + k] = math.inf
            derived[D.zero_hi + k] = -math.inf
    derived[D.inv_exponent_plus_1] = 1.0 / (prm[P.exponent] + 1.0)
    derived[D.end_gap_drive] = end_gap_bound(tables, TABLE_G1, TABLE_G2, h)
    derived[D.end_gap_coast] = end_gap_bound(tables, TABLE_G1_COAST, TABLE_G2_COAST, h)
    derived[D.grid_step] = h
    derived[D.inv_grid_step] = 1.0 / h
    derived[D.inv_p_b] = 1.0 / prm[P.p_b]
    derived[D.inv_r_b1] = 1.0 / prm[P.r_b1]
    derived[D.inv_r_b2] = 1.0 / prm[P.r_b2]
    derived[D.inv_J1] = 1.0 / prm[P.J1]
    derived[D.inv_J2] = 1.0 / prm[P.J2]


@jit
def runout(ecc, phase, theta, inv_r_b):
    """Runout gap ``ecc sin(theta + phase)`` [mm] and its derivative by the roll distance,
    ``ecc cos(theta + phase) / r_b`` [-] (``inv_r_b = 1/r_b`` [1/mm])."""
    if ecc == 0.0:
        return 0.0, 0.0
    return ecc * math.sin(theta + phase), ecc * math.cos(theta + phase) * inv_r_b


@jit_noalloc_inline
def rhs(t, y, dy, aux, slot_force, slot_force_coast, prm, derived, tables, tooth_offsets,
        drive_angle, drive_value, drive_rate, load_torque, full):
    """Time derivative of the state and auxiliary results at time ``t`` [s].

    Parameters
    ----------
    t : float
        Time [s] (only through the inputs below; kept for clarity of the call sites).
    y : ndarray, shape (N_STATE,)
        State (layout.S); in speed mode ``y[S.s1]``, ``y[S.v1]`` are ignored.
    dy : ndarray, shape (N_STATE,)
        Written: dy/dt.
    aux : ndarray, shape (N_AUX,)
        Written: auxiliary results (layout.A).
    slot_force, slot_force_coast : ndarray, shape (N,)
        Written: force per drive / coast slot [N].
    prm : ndarray
        Parameter vector (layout.P).
    derived : ndarray, shape (N_DERIVED,)
        Constants from :func:`derive` (layout.D).
    tables : ndarray, shape (4, 2, n)
        Gap tables (gaptable.py).
    tooth_offsets : ndarray, shape (4, max(z1, z2))
        Rows Ft1, Ft2, Ft1c, Ft2c: flank offset of each tooth [mm], positive = material missing.
    drive_angle, drive_value, drive_rate, load_torque : float
        From :func:`gearcli.core.drive.forcing` at ``t``: prescribed angle [rad], drive speed
        [rad/s] or torque [N*mm], its rate [rad/s^2], load torque [N*mm].
    full : bool
        Write ``aux`` and the slot forces; False at the inner Runge-Kutta stages of a step,
        whose only use is ``dy`` (the accepted step's last stage and the samples are full).
    """
    mode = int(prm[P.drive_mode])
    r_b1 = prm[P.r_b1]
    r_b2 = prm[P.r_b2]
    J1 = prm[P.J1]
    inv_r_b1 = derived[D.inv_r_b1]
    inv_r_b2 = derived[D.inv_r_b2]
    a1 = 0.0
    if mode == DRIVE_SPEED:
        s1 = r_b1 * drive_angle
        v1 = r_b1 * drive_value
        a1 = r_b1 * drive_rate
    else:
        s1 = y[S.s1]
        v1 = y[S.v1]
    delta = y[S.delta]
    deltadot = y[S.deltadot]
    v2 = v1 - deltadot
    theta1 = s1 * inv_r_b1
    theta2 = (s1 - delta) * inv_r_b2
    omega1 = v1 * inv_r_b1
    omega2 = v2 * inv_r_b2

    lateral = prm[P.lateral] != 0.0
    lat_d = 0.0  # approach of the gear centres along the drive / coast LoA [mm]
    lat_c = 0.0
    lat_d_rate = 0.0
    lat_c_rate = 0.0
    slide_d = 0.0  # their relative speed across the LoA [mm/s] (friction)
    slide_c = 0.0
    sa = prm[P.sin_aw]
    ca = prm[P.cos_aw]
    if lateral:  # n_d = (sa, ca), n_c = (sa, -ca), t_d = (-ca, sa), t_c = (ca, sa)
        dxc = y[S.x1] - y[S.x2]
        dyc = y[S.y1] - y[S.y2]
        dvx = y[S.vx1] - y[S.vx2]
        dvy = y[S.vy1] - y[S.vy2]
        lat_d = dxc * sa + dyc * ca
        lat_c = dxc * sa - dyc * ca
        lat_d_rate = dvx * sa + dvy * ca
        lat_c_rate = dvx * sa - dvy * ca
        slide_d = -dvx * ca + dvy * sa
        slide_c = dvx * ca + dvy * sa

    e1, de1 = runout(prm[P.ecc1], prm[P.phase1], theta1, inv_r_b1)
    e2, de2 = runout(prm[P.ecc2], prm[P.phase2], theta2, inv_r_b2)
    q1, q2, m1f, m2f, fd, nd, ffd, fpd, pdd, potd, pend = flank(
        1.0, s1, v1, delta, v2, omega1, omega2, e1, de1, e2, de2, prm[P.s1_0], 0.0,
        lat_d, lat_d_rate, slide_d, int(prm[P.tooth_k1]), int(prm[P.tooth_k2]), 0, 1,
        TABLE_G1, TABLE_G2, derived[D.overlap_drive], prm, derived, tables, tooth_offsets,
        slot_force, full)
    fc = 0.0
    nc = 0
    ffc = 0.0
    ff_drive = ffd
    if prm[P.coast_flanks] != 0.0:
        e1, de1 = runout(prm[P.ecc1], prm[P.phase1_coast], theta1, inv_r_b1)
        e2, de2 = runout(prm[P.ecc2], prm[P.phase2_coast], theta2, inv_r_b2)
        q1c, q2c, m1c, m2c, fc, nc, ffc, fpc, pdc, potc, penc = flank(
            -1.0, s1, v1, delta, v2, omega1, omega2, e1, de1, e2, de2, prm[P.s1c_0],
            prm[P.backlash_n], lat_c, lat_c_rate, slide_c, int(prm[P.tooth_k1_coast]),
            int(prm[P.tooth_k2_coast]), 2, 3, TABLE_G1_COAST, TABLE_G2_COAST,
            derived[D.overlap_coast], prm, derived, tables, tooth_offsets, slot_force_coast,
            full)
        q1 += q1c
        q2 += q2c
        m1f += m1c
        m2f += m2c
        ffd += ffc
        fpd += fpc
        pdd += pdc
        potd += potc
        if penc > pend:
            pend = penc
    elif full:
        for j in range(slot_force_coast.shape[0]):
            slot_force_coast[j] = 0.0

    m1 = r_b1 * q1 + m1f  # mesh + friction torque on the pinion [N*mm]
    m2 = r_b2 * q2 + m2f  # on the gear
    t_load = load_torque
    c1w = prm[P.c1] * omega1
    loss = c1w * omega1  # dissipation rate of bearings, shafts and load terms [N*mm/s]
    spring = 0.0  # potential of shafts and bearings [N*mm]

    # load side: the load terms act on the load inertia behind the load shaft, or on the gear
    load_J = prm[P.load_J]
    alpha_l = 0.0
    if load_J > 0.0:
        tw_l = y[S.tw_l]
        tw_l_dot = y[S.tw_l_dot]
        omega_l = omega2 - tw_l_dot
        t_lshaft = prm[P.load_k] * tw_l + prm[P.load_c] * tw_l_dot  # taken from the gear
        load_terms = (prm[P.load_cv] + prm[P.load_cq] * abs(omega_l)) * omega_l
        alpha_l = (t_lshaft - t_load - load_terms) / load_J
        c2w = prm[P.c2] * omega2
        alpha2 = (m2 - t_lshaft - c2w) * derived[D.inv_J2]
        loss += load_terms * omega_l + c2w * omega2 + prm[P.load_c] * tw_l_dot * tw_l_dot
        spring += 0.5 * prm[P.load_k] * tw_l * tw_l
        work_load_rate = t_load * omega_l
    else:
        omega_l = omega2
        t_lshaft = 0.0
        gear_loss = (prm[P.load_cv] + prm[P.c2] + prm[P.load_cq] * abs(omega2)) * omega2
        alpha2 = (m2 - t_load - gear_loss) * derived[D.inv_J2]
        loss += gear_loss * omega2
        work_load_rate = t_load * omega2

    # drive side
    motor_J = prm[P.motor_J]
    omega_m = omega1
    t_dshaft = 0.0
    t_pinion = 0.0
    if mode == DRIVE_SPEED:
        t_drive = J1 * a1 * inv_r_b1 - m1 + c1w
        work_in_rate = t_drive * omega1
    else:
        if mode == DRIVE_SHAFT:  # prescribed motor angle and speed
            omega_m = drive_value
            t_dshaft = prm[P.shaft_k] * (drive_angle - theta1) \
                + prm[P.shaft_c] * (drive_value - omega1)
            t_drive = t_dshaft
            t_pinion = t_dshaft
        elif motor_J > 0.0:  # torque on the motor inertia, drive shaft to the pinion
            tw_m = y[S.tw_m]
            tw_m_dot = y[S.tw_m_dot]
            omega_m = omega1 + tw_m_dot
            t_drive = drive_value
            if prm[P.motor_omega0] > 0.0:
                t_drive *= 1.0 - omega_m / prm[P.motor_omega0]
            t_dshaft = prm[P.shaft_k] * tw_m + prm[P.shaft_c] * tw_m_dot
            t_pinion = t_dshaft
            loss += prm[P.shaft_c] * tw_m_dot * tw_m_dot
            spring += 0.5 * prm[P.shaft_k] * tw_m * tw_m
        else:
            t_drive = drive_value
            if prm[P.motor_omega0] > 0.0:
                t_drive *= 1.0 - omega1 / prm[P.motor_omega0]
            t_pinion = t_drive
        a1 = r_b1 * (t_pinion + m1 - c1w) * derived[D.inv_J1]
        # the system's boundary: the motor inertia if modelled, else the pinion (a prescribed
        # motor's shaft is outside: its torque is the input, its spring energy not counted)
        work_in_rate = t_drive * (omega_m if motor_J > 0.0 else omega1)

    dy[S.s1] = v1
    dy[S.v1] = a1
    dy[S.delta] = deltadot
    dy[S.deltadot] = a1 - r_b2 * alpha2
    if y.shape[0] > N_STATE_BASE:  # optional degrees of freedom
        if motor_J > 0.0:
            dy[S.tw_m] = y[S.tw_m_dot]
            dy[S.tw_m_dot] = (t_drive - t_dshaft) / motor_J - a1 * inv_r_b1
        else:
            dy[S.tw_m] = 0.0
            dy[S.tw_m_dot] = 0.0
        if load_J > 0.0:
            dy[S.tw_l] = y[S.tw_l_dot]
            dy[S.tw_l_dot] = alpha2 - alpha_l
        else:
            dy[S.tw_l] = 0.0
            dy[S.tw_l_dot] = 0.0
        bfx1 = 0.0
        bfy1 = 0.0
        bfx2 = 0.0
        bfy2 = 0.0
        if lateral:
            # mesh force on the pinion centre: -F_d n_d - F_c n_c + f_d t_d + f_c t_c
            fx1 = -(fd + fc) * sa + (ffc - ff_drive) * ca
            fy1 = (fc - fd) * ca + (ff_drive + ffc) * sa
            x1 = y[S.x1]
            y1 = y[S.y1]
            x2 = y[S.x2]
            y2 = y[S.y2]
            vx1 = y[S.vx1]
            vy1 = y[S.vy1]
            vx2 = y[S.vx2]
            vy2 = y[S.vy2]
            bfx1 = prm[P.kx1] * x1 + prm[P.cx1] * vx1
            bfy1 = prm[P.ky1] * y1 + prm[P.cy1] * vy1
            bfx2 = prm[P.kx2] * x2 + prm[P.cx2] * vx2
            bfy2 = prm[P.ky2] * y2 + prm[P.cy2] * vy2
            dy[S.x1] = vx1
            dy[S.y1] = vy1
            dy[S.x2] = vx2
            dy[S.y2] = vy2
            dy[S.vx1] = (fx1 - bfx1) / prm[P.m1]
            dy[S.vy1] = (fy1 - bfy1) / prm[P.m1]
            dy[S.vx2] = (-fx1 - bfx2) / prm[P.m2]
            dy[S.vy2] = (-fy1 - bfy2) / prm[P.m2]
            loss += prm[P.cx1] * vx1 * vx1 + prm[P.cy1] * vy1 * vy1 \
                + prm[P.cx2] * vx2 * vx2 + prm[P.cy2] * vy2 * vy2
            spring += 0.5 * (prm[P.kx1] * x1 * x1 + prm[P.ky1] * y1 * y1
                             + prm[P.kx2] * x2 * x2 + prm[P.ky2] * y2 * y2)
        else:
            for i in range(S.x1, S.vy2 + 1):
                dy[i] = 0.0
        if full:
            aux[A.bearing_fx1] = bfx1
            aux[A.bearing_fy1] = bfy1
            aux[A.bearing_fx2] = bfx2
            aux[A.bearing_fy2] = bfy2
    dy[S.work_in] = work_in_rate
    dy[S.work_load] = work_load_rate
    dy[S.loss_bearing] = loss
    dy[S.loss_damping] = pdd
    dy[S.loss_friction] = -fpd

    if not full:
        return
    aux[A.s1] = s1
    aux[A.v1] = v1
    aux[A.force_drive] = fd
    aux[A.force_coast] = fc
    aux[A.n_drive] = nd
    aux[A.n_coast] = nc
    aux[A.friction_force] = ffd
    aux[A.friction_power] = fpd
    aux[A.drive_torque] = t_drive
    aux[A.load_torque] = t_load
    aux[A.contact_energy] = potd
    aux[A.max_penetration] = pend
    aux[A.spring_energy] = spring
    aux[A.motor_speed] = omega_m
    aux[A.drive_shaft_torque] = t_dshaft
    aux[A.load_speed] = omega_l
    aux[A.load_shaft_torque] = t_lshaft
