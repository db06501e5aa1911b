"""Drivetrain bodies around the mesh: drive side, load side, gear centres on their bearings.

Equations (docs/theory.md §6; model/structure.py), with M1, M2 the mesh + friction torques on pinion
and gear [N*mm] from :mod:`gearcli.core.flank`:

Drive (inputs from drive.forcing):
- speed: theta1(t) prescribed; T_drive = J1 alpha1 - M1 + c1 omega1 is the torque needed.
- shaft: a prescribed motor angle theta_m(t) through a torsional shaft,
  T_drive = k_s (theta_m - theta1) + c_s (omega_m - omega1).
- torque: T_drive = T(t) (1 - omega/omega0), the factor only when omega0 > 0; with a motor
  inertia J_m behind the drive shaft (twist tw_m = theta_m - theta1):
  J_m alpha_m = T(t) (1 - omega_m/omega0) - T_s, T_s = k_s tw_m + c_s tw_m', and T_s drives
  the pinion. Free pinion: J1 alpha1 = T_pinion + M1 - c1 omega1.
Load: J2 alpha2 = M2 - T_load(t) - cv omega2 - cq omega2 |omega2| - c2 omega2, or with a load
inertia J_L on a load shaft (twist tw_l = theta2 - theta_L):
J_L alpha_L = T_L - T_load(t) - (cv + cq |omega_L|) omega_L, T_L = k_L tw_l + c_L tw_l', and
the gear sees -T_L instead of the load terms.
Lateral-torsional model: the centres u_i = (x_i, y_i) move on bearings (k, c per direction),
m_i u_i'' = F_mesh,i - K_i u_i - C_i u_i' with the mesh force on the pinion centre
-F_d n_d - F_c n_c + f_d t_d + f_c t_c, n_d = (sin a_w, cos a_w), n_c = (sin a_w, -cos a_w),
t_d = (-cos a_w, sin a_w), t_c = (cos a_w, sin a_w); the gear gets the opposite (Kahraman &
Singh, J. Sound Vib. 144(3), 469-506, 1991: the 6-DOF spur-pair model).

Every body returns its dissipation rate (dampers, load terms) [N*mm/s] and its spring energy
sum k q^2 / 2 [N*mm], so the energy balance closes for every model.
"""

from typing import NamedTuple

from gearcli.core.flank import Approach
from gearcli.core.layout import DRIVE_SHAFT, DRIVE_SPEED, D, P, S
from gearcli.core.nrt import jit_noalloc_inline


class LoadSide(NamedTuple):
    alpha2: float  #: gear angular acceleration [rad/s^2]
    alpha_l: float  #: load inertia's [rad/s^2] (0 without one)
    omega_l: float  #: load speed [rad/s] (omega2 without a load inertia)
    shaft_torque: float  #: torque the load shaft takes from the gear [N*mm]
    loss: float  #: dissipation rate [N*mm/s]
    spring: float  #: load-shaft spring energy [N*mm]
    work_rate: float  #: T_load times the speed it acts on [N*mm/s]


class DriveSide(NamedTuple):
    a1: float  #: pinion roll acceleration r_b1 alpha1 [mm/s^2]
    torque: float  #: T_drive, into the system (speed drive: the torque needed) [N*mm]
    omega_m: float  #: motor speed [rad/s] (omega1 without a motor)
    shaft_torque: float  #: torque the drive shaft applies to the pinion [N*mm]
    loss: float  #: drive-shaft damper dissipation rate [N*mm/s]
    spring: float  #: drive-shaft spring energy [N*mm]
    work_rate: float  #: input power at the system's boundary [N*mm/s]


class Bearings(NamedTuple):
    fx1: float  #: force of the pinion on its bearings, k x + c x' [N]
    fy1: float
    fx2: float  #: of the gear
    fy2: float
    loss: float  #: bearing damper dissipation rate [N*mm/s]
    spring: float  #: bearing spring energy [N*mm]


@jit_noalloc_inline
def approaches(prm, y, lateral):
    """The centres' approach along the drive and the coast line of action (flank.Approach)."""
    if not lateral:
        return Approach(0.0, 0.0, 0.0), Approach(0.0, 0.0, 0.0)
    sa = prm[P.sin_aw]
    ca = prm[P.cos_aw]
    dxc = y[S.x1] - y[S.x2]
    dyc = y[S.y1] - y[S.y2]
    dvx = y[S.vx1] - y[S.vx2]
    dvy = y[S.vy1] - y[S.vy2]
    return (Approach(dxc * sa + dyc * ca, dvx * sa + dvy * ca, -dvx * ca + dvy * sa),
            Approach(dxc * sa - dyc * ca, dvx * sa - dvy * ca, dvx * ca + dvy * sa))


@jit_noalloc_inline
def load_side(prm, derived, y, omega2, m2, t_load):
    """The gear and what loads it, from the mesh torque ``m2`` [N*mm] and T_load [N*mm]."""
    load_J = prm[P.load_J]
    if load_J > 0.0:
        tw_l = y[S.tw_l]
        tw_l_dot = y[S.tw_l_dot]
        omega_l = omega2 - tw_l_dot
        t_lshaft = prm[P.load_k] * tw_l + prm[P.load_c] * tw_l_dot  # taken from the gear
        load_terms = (prm[P.load_cv] + prm[P.load_cq] * abs(omega_l)) * omega_l
        alpha_l = (t_lshaft - t_load - load_terms) / load_J
        c2w = prm[P.c2] * omega2
        alpha2 = (m2 - t_lshaft - c2w) * derived[D.inv_J2]
        loss = load_terms * omega_l + c2w * omega2 + prm[P.load_c] * tw_l_dot * tw_l_dot
        spring = 0.5 * prm[P.load_k] * tw_l * tw_l
        return LoadSide(alpha2, alpha_l, omega_l, t_lshaft, loss, spring, t_load * omega_l)
    gear_loss = (prm[P.load_cv] + prm[P.c2] + prm[P.load_cq] * abs(omega2)) * omega2
    alpha2 = (m2 - t_load - gear_loss) * derived[D.inv_J2]
    return LoadSide(alpha2, 0.0, omega2, 0.0, gear_loss * omega2, 0.0, t_load * omega2)


@jit_noalloc_inline
def drive_side(prm, derived, y, mode, a1, omega1, theta1, m1, c1w, forcing):
    """The pinion's drive. ``a1`` [mm/s^2] is the prescribed roll acceleration in speed mode
    (else unused); ``m1`` the mesh torque on the pinion and ``c1w = c1 omega1`` [N*mm];
    ``forcing`` the drive inputs at t (:class:`gearcli.core.drive.Forcing`: the prescribed
    motor angle [rad] and the speed [rad/s] or torque [N*mm] value)."""
    drive_angle = forcing.angle
    drive_value = forcing.value
    r_b1 = prm[P.r_b1]
    inv_r_b1 = derived[D.inv_r_b1]
    if mode == DRIVE_SPEED:
        t_drive = prm[P.J1] * a1 * inv_r_b1 - m1 + c1w
        return DriveSide(a1, t_drive, omega1, 0.0, 0.0, 0.0, t_drive * omega1)
    loss = 0.0
    spring = 0.0
    omega_m = omega1
    motor_J = prm[P.motor_J]
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
        loss = prm[P.shaft_c] * tw_m_dot * tw_m_dot
        spring = 0.5 * prm[P.shaft_k] * tw_m * tw_m
    else:
        t_dshaft = 0.0
        t_drive = drive_value
        if prm[P.motor_omega0] > 0.0:
            t_drive *= 1.0 - omega1 / prm[P.motor_omega0]
        t_pinion = t_drive
    a1 = r_b1 * (t_pinion + m1 - c1w) * derived[D.inv_J1]
    # the system's boundary: the motor inertia if modelled, else the pinion (a prescribed
    # motor's shaft is outside: its torque is the input, its spring energy not counted)
    work_rate = t_drive * (omega_m if motor_J > 0.0 else omega1)
    return DriveSide(a1, t_drive, omega_m, t_dshaft, loss, spring, work_rate)


@jit_noalloc_inline
def bearings(prm, y, dy, fd, fc, ff_drive, ff_coast):
    """Rates of the gear centres on their bearings (written into ``dy``) from the normal
    forces ``fd``, ``fc`` and the friction force sums of both flank families [N]."""
    sa = prm[P.sin_aw]
    ca = prm[P.cos_aw]
    # mesh force on the pinion centre: -F_d n_d - F_c n_c + f_d t_d + f_c t_c
    fx1 = -(fd + fc) * sa + (ff_coast - ff_drive) * ca
    fy1 = (fc - fd) * ca + (ff_drive + ff_coast) * sa
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
    loss = prm[P.cx1] * vx1 * vx1 + prm[P.cy1] * vy1 * vy1 \
        + prm[P.cx2] * vx2 * vx2 + prm[P.cy2] * vy2 * vy2
    spring = 0.5 * (prm[P.kx1] * x1 * x1 + prm[P.ky1] * y1 * y1
                    + prm[P.kx2] * x2 * x2 + prm[P.ky2] * y2 * y2)
    return Bearings(bfx1, bfy1, bfx2, bfy2, loss, spring)
