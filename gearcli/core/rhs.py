"""Right-hand side of the spur-pair model (docs/theory.md §1, §3-6; model/structure.py).

Coordinates [mm]: roll distances s1 = r_b1 theta1, s2 = r_b2 theta2 and the DTE
delta = s1 - s2 (> 0 compresses the drive flanks). Integrated state: see layout.STATE_NAMES.

Pair slots (docs/theory.md §3). Drive flank, slot j = 0 .. N-1:
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

Forces (docs/theory.md §4): F_j = IMPACT(p_j, pdot_j), pdot_j = dp/ds1 v1 + dp/ds2 v2 (chain rule);
generalized forces Q_s1 = -F dp/ds1, Q_s2 = -F dp/ds2 [N]: the gradient of the potential
sum k p^(e+1)/(e+1) plus the damping part, so the elastic mesh conserves energy exactly.
Torques r_b1 Q_s1 on the pinion, r_b2 Q_s2 on the gear [N*mm].

Friction (docs/theory.md §5), both flanks: rho1 = T1A + x1_j, rho2 = T1T2 - rho1 [mm],
v = omega1 rho1 - omega2 rho2 [mm/s], f = mu(v) F [N]; pinion torque += f rho1, gear torque
-= f rho2. Power f (omega1 rho1 - omega2 rho2) = mu(v) F v <= 0. Coast mirrored: in mirrored
coordinates v' = -v, mu(v') = -mu(v), f' = -f and the mirrored torques +f' rho1, -f' rho2 map
back with one more sign change to +f rho1, -f rho2: the same formulas in the real coordinates
(with the coast contact point's rho1 = T1A + x1c_j; the coast path has the drive path's length
for the symmetric teeth this assumes). The contact point is taken on the LoA also outside the
nominal path (extended contact): an approximation of the tip-contact arms of docs/theory.md §3.

Equations of motion (docs/theory.md §6; the bodies in :mod:`gearcli.core.bodies`), M1, M2 the mesh +
friction torques:
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
  opposite (Kahraman & Singh, J. Sound Vib. 144(3), 469-506, 1991: the 6-DOF spur-pair
  model).
Energy: shafts and bearings store sum k q^2/2 (aux spring_energy), their dampers and the load
terms dissipate into loss_bearing, so the energy balance closes for every model.
"""

from gearcli.core.bodies import approaches, bearings, drive_side, load_side
from gearcli.core.flank import Kinematics, flank
from gearcli.core.layout import COAST_FLANKS, DRIVE_FLANKS, DRIVE_SPEED, N_STATE_BASE, A, D, P, S
from gearcli.core.nrt import jit_noalloc_inline


@jit_noalloc_inline
def rhs(t, y, dy, aux, slot_force, scratch, model, forcing, full):
    """Time derivative of the state and auxiliary results at time ``t`` [s].

    Parameters
    ----------
    t : float
        Time [s] (only through ``forcing``; kept for clarity of the call sites).
    y : ndarray, shape (n_state,)
        State (layout.S); in speed mode ``y[S.s1]``, ``y[S.v1]`` are ignored.
    dy : ndarray, shape (n_state,)
        Written: dy/dt.
    aux : ndarray, shape (N_AUX,)
        Written when ``full``: auxiliary results (layout.A).
    slot_force : ndarray, shape (N_FAMILIES, n_slots)
        Written when ``full``: force per drive / coast slot [N].
    scratch : ndarray, shape (N_SCRATCH, n_slots)
        Work space of the flank loops (flank.flank).
    model : gearcli.core.bundles.Model
    forcing : gearcli.core.drive.Forcing
        Drive and load inputs at ``t`` (:func:`gearcli.core.drive.forcing`).
    full : bool
        Write ``aux`` and the slot forces; False at the inner Runge-Kutta stages of a step,
        whose only use is ``dy`` (the accepted step's last stage and the samples are full).
    """
    prm = model.prm
    derived = model.derived
    mode = int(prm[P.drive_mode])
    r_b1 = prm[P.r_b1]
    r_b2 = prm[P.r_b2]
    inv_r_b1 = derived[D.inv_r_b1]
    inv_r_b2 = derived[D.inv_r_b2]
    a1 = 0.0
    if mode == DRIVE_SPEED:
        s1 = r_b1 * forcing.angle
        v1 = r_b1 * forcing.value
        a1 = r_b1 * forcing.rate
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
    kin = Kinematics(s1, v1, delta, deltadot, v2, omega1, omega2, theta1, theta2)
    lateral = prm[P.lateral] != 0.0
    app_d, app_c = approaches(prm, y, lateral)

    fl = flank(DRIVE_FLANKS, kin, app_d, model, slot_force, scratch, full)
    q1 = fl.q1
    q2 = fl.q2
    m1f = fl.m1f
    m2f = fl.m2f
    fd = fl.force
    ffd = fl.friction_force
    fpd = fl.friction_power
    pdd = fl.damping_power
    potd = fl.potential
    pend = fl.pen_max
    fc = 0.0
    nc = 0
    ffc = 0.0
    if prm[P.coast_flanks] != 0.0:
        co = flank(COAST_FLANKS, kin, app_c, model, slot_force, scratch, full)
        q1 += co.q1
        q2 += co.q2
        m1f += co.m1f
        m2f += co.m2f
        fc = co.force
        nc = co.n_contact
        ffc = co.friction_force
        ffd += ffc
        fpd += co.friction_power
        pdd += co.damping_power
        potd += co.potential
        if co.pen_max > pend:
            pend = co.pen_max
    elif full:
        for j in range(slot_force.shape[1]):
            slot_force[COAST_FLANKS, j] = 0.0

    m1 = r_b1 * q1 + m1f  # mesh + friction torque on the pinion [N*mm]
    m2 = r_b2 * q2 + m2f  # on the gear
    c1w = prm[P.c1] * omega1
    loss = c1w * omega1  # dissipation rate of bearings, shafts and load terms [N*mm/s]
    spring = 0.0  # potential of shafts and bearings [N*mm]
    ld = load_side(prm, derived, y, omega2, m2, forcing.load)
    loss += ld.loss
    spring += ld.spring
    dr = drive_side(prm, derived, y, mode, a1, omega1, theta1, m1, c1w, forcing)
    loss += dr.loss
    spring += dr.spring
    a1 = dr.a1

    dy[S.s1] = v1
    dy[S.v1] = a1
    dy[S.delta] = deltadot
    dy[S.deltadot] = a1 - r_b2 * ld.alpha2
    if y.shape[0] > N_STATE_BASE:  # optional degrees of freedom
        motor_J = prm[P.motor_J]
        if motor_J > 0.0:
            dy[S.tw_m] = y[S.tw_m_dot]
            dy[S.tw_m_dot] = (dr.torque - dr.shaft_torque) / motor_J - a1 * inv_r_b1
        else:
            dy[S.tw_m] = 0.0
            dy[S.tw_m_dot] = 0.0
        if prm[P.load_J] > 0.0:
            dy[S.tw_l] = y[S.tw_l_dot]
            dy[S.tw_l_dot] = ld.alpha2 - ld.alpha_l
        else:
            dy[S.tw_l] = 0.0
            dy[S.tw_l_dot] = 0.0
        if lateral:
            br = bearings(prm, y, dy, fd, fc, fl.friction_force, ffc)
            loss += br.loss
            spring += br.spring
            if full:
                aux[A.bearing_fx1] = br.fx1
                aux[A.bearing_fy1] = br.fy1
                aux[A.bearing_fx2] = br.fx2
                aux[A.bearing_fy2] = br.fy2
        else:
            for i in range(S.x1, S.vy2 + 1):
                dy[i] = 0.0
            if full:
                aux[A.bearing_fx1] = 0.0
                aux[A.bearing_fy1] = 0.0
                aux[A.bearing_fx2] = 0.0
                aux[A.bearing_fy2] = 0.0
    dy[S.work_in] = dr.work_rate
    dy[S.work_load] = ld.work_rate
    dy[S.loss_bearing] = loss
    dy[S.loss_damping] = pdd
    dy[S.loss_friction] = -fpd

    if not full:
        return
    aux[A.s1] = s1
    aux[A.v1] = v1
    aux[A.force_drive] = fd
    aux[A.force_coast] = fc
    aux[A.n_drive] = fl.n_contact
    aux[A.n_coast] = nc
    aux[A.friction_force] = ffd
    aux[A.friction_power] = fpd
    aux[A.drive_torque] = dr.torque
    aux[A.load_torque] = forcing.load
    aux[A.contact_energy] = potd
    aux[A.max_penetration] = pend
    aux[A.spring_energy] = spring
    aux[A.motor_speed] = dr.omega_m
    aux[A.drive_shaft_torque] = dr.shaft_torque
    aux[A.load_speed] = ld.omega_l
    aux[A.load_shaft_torque] = ld.shaft_torque
