"""What the time loop keeps: output rows at the sample times and extrema at the solver's steps.

Pure bookkeeping on the arrays of :mod:`gearcli.core.layout`; no physics beyond the kinetic
energy sum 1/2 J omega^2 + 1/2 m v^2 of the bodies [t*mm^2/s^2 = N*mm = mJ].
"""

import math

import numpy as np

from gearcli.core.layout import DRIVE_FLANKS, N_FAMILIES, N_STATE_BASE, SX, A, C, P, S, X
from gearcli.core.nrt import jit_noalloc


@jit_noalloc
def kinetic_energy(prm, s1dot, y):
    """Kinetic energy [N*mm] of every body from the pinion roll rate [mm/s] and the state."""
    omega1 = s1dot / prm[P.r_b1]
    omega2 = (s1dot - y[S.deltadot]) / prm[P.r_b2]
    e = 0.5 * prm[P.J1] * omega1 * omega1 + 0.5 * prm[P.J2] * omega2 * omega2
    if y.shape[0] > N_STATE_BASE:
        if prm[P.lateral] != 0.0:
            e += 0.5 * prm[P.m1] * (y[S.vx1] ** 2 + y[S.vy1] ** 2) \
                + 0.5 * prm[P.m2] * (y[S.vx2] ** 2 + y[S.vy2] ** 2)
        if prm[P.motor_J] > 0.0:
            e += 0.5 * prm[P.motor_J] * (omega1 + y[S.tw_m_dot]) ** 2
        if prm[P.load_J] > 0.0:
            e += 0.5 * prm[P.load_J] * (omega2 - y[S.tw_l_dot]) ** 2
    return e


@jit_noalloc
def write_row(series, slot_series, i, t, y, aux, slot_force, prm):
    """Fill output row ``i`` of ``series`` and ``slot_series`` (bundles.Out) at time ``t`` [s]
    from the state and one full RHS evaluation there (``aux``, ``slot_force`` of shape
    (N_FAMILIES, n_slots)). Takes the two output arrays, not the Out bundle: numba passes a
    bundle as all its arrays, and this runs once per output row."""
    r_b1 = prm[P.r_b1]
    r_b2 = prm[P.r_b2]
    s1 = aux[A.s1]
    v1 = aux[A.v1]
    delta = y[S.delta]
    deltadot = y[S.deltadot]
    row = series[i]
    row[C.t_s] = t
    row[C.theta1_rad] = s1 / r_b1
    row[C.omega1_rad_s] = v1 / r_b1
    row[C.theta2_rad] = (s1 - delta) / r_b2
    row[C.omega2_rad_s] = (v1 - deltadot) / r_b2
    row[C.delta_mm] = delta
    row[C.deltadot_mm_s] = deltadot
    row[C.force_total_N] = aux[A.force_drive]
    row[C.force_coast_N] = aux[A.force_coast]
    row[C.pairs_in_contact] = aux[A.n_drive]
    row[C.pairs_in_contact_coast] = aux[A.n_coast]
    row[C.friction_force_N] = aux[A.friction_force]
    row[C.friction_power_mW] = aux[A.friction_power]
    row[C.drive_torque_Nmm] = aux[A.drive_torque]
    row[C.load_torque_Nmm] = aux[A.load_torque]
    row[C.kinetic_energy_mJ] = kinetic_energy(prm, v1, y)
    row[C.contact_energy_mJ] = aux[A.contact_energy]
    row[C.spring_energy_mJ] = aux[A.spring_energy]
    row[C.work_in_mJ] = y[S.work_in]
    row[C.work_load_mJ] = y[S.work_load]
    row[C.loss_bearing_mJ] = y[S.loss_bearing]
    row[C.loss_damping_mJ] = y[S.loss_damping]
    row[C.loss_friction_mJ] = y[S.loss_friction]
    lateral = prm[P.lateral] != 0.0
    row[C.x1_mm] = y[S.x1] if lateral else 0.0
    row[C.y1_mm] = y[S.y1] if lateral else 0.0
    row[C.x2_mm] = y[S.x2] if lateral else 0.0
    row[C.y2_mm] = y[S.y2] if lateral else 0.0
    row[C.bearing_force_x1_N] = aux[A.bearing_fx1] if lateral else 0.0
    row[C.bearing_force_y1_N] = aux[A.bearing_fy1] if lateral else 0.0
    row[C.bearing_force_x2_N] = aux[A.bearing_fx2] if lateral else 0.0
    row[C.bearing_force_y2_N] = aux[A.bearing_fy2] if lateral else 0.0
    row[C.omega_motor_rad_s] = aux[A.motor_speed]
    row[C.drive_shaft_torque_Nmm] = aux[A.drive_shaft_torque]
    row[C.omega_load_rad_s] = aux[A.load_speed]
    row[C.load_shaft_torque_Nmm] = aux[A.load_shaft_torque]
    for f in range(N_FAMILIES):
        for j in range(slot_force.shape[1]):
            slot_series[f, i, j] = slot_force[f, j]


def init_extrema(extrema, slot_extrema) -> None:
    """Start values: -inf for maxima, +inf for minima (NaN'ed by :func:`finish_extrema`).
    Plain numpy, like :func:`finish_extrema`: once per run, not worth a compilation."""
    extrema[:] = math.nan
    for k in (X.force_total_max_N, X.force_coast_max_N, X.delta_max_mm, X.penetration_max_mm,
              X.bearing_force_max_1_N, X.bearing_force_max_2_N):
        extrema[k] = -math.inf
    for k in (X.force_total_min_N, X.delta_min_mm):
        extrema[k] = math.inf
    slot_extrema[SX.force_max_N] = -math.inf
    slot_extrema[SX.force_max_t_s] = math.nan
    slot_extrema[SX.force_min_N] = math.inf


@jit_noalloc
def update_extrema(extrema, slot_extrema, t, y, aux, slot_force, lateral):
    """Fold the state and forces of one accepted step end (time ``t`` [s]) into ``extrema`` and
    the drive slots' ``slot_extrema`` (bundles.Out; the arrays, not the bundle, as in
    :func:`write_row`)."""
    if lateral:
        b1 = math.hypot(aux[A.bearing_fx1], aux[A.bearing_fy1])
        b2 = math.hypot(aux[A.bearing_fx2], aux[A.bearing_fy2])
        if b1 > extrema[X.bearing_force_max_1_N]:
            extrema[X.bearing_force_max_1_N] = b1
        if b2 > extrema[X.bearing_force_max_2_N]:
            extrema[X.bearing_force_max_2_N] = b2
    f = aux[A.force_drive]
    if f > extrema[X.force_total_max_N]:
        extrema[X.force_total_max_N] = f
        extrema[X.force_total_max_t_s] = t
    if f < extrema[X.force_total_min_N]:
        extrema[X.force_total_min_N] = f
        extrema[X.force_total_min_t_s] = t
    fc = aux[A.force_coast]
    if fc > extrema[X.force_coast_max_N]:
        extrema[X.force_coast_max_N] = fc
        extrema[X.force_coast_max_t_s] = t
    d = y[S.delta]
    if d > extrema[X.delta_max_mm]:
        extrema[X.delta_max_mm] = d
        extrema[X.delta_max_t_s] = t
    if d < extrema[X.delta_min_mm]:
        extrema[X.delta_min_mm] = d
        extrema[X.delta_min_t_s] = t
    pen = aux[A.max_penetration]
    if pen > extrema[X.penetration_max_mm]:
        extrema[X.penetration_max_mm] = pen
        extrema[X.penetration_max_t_s] = t
    for j in range(slot_force.shape[1]):
        fj = slot_force[DRIVE_FLANKS, j]
        if fj > slot_extrema[SX.force_max_N, j]:
            slot_extrema[SX.force_max_N, j] = fj
            slot_extrema[SX.force_max_t_s, j] = t
        if fj < slot_extrema[SX.force_min_N, j]:
            slot_extrema[SX.force_min_N, j] = fj


def finish_extrema(extrema, slot_extrema) -> None:
    """Replace the +-inf start values that no step touched by NaN."""
    extrema[np.isinf(extrema)] = math.nan
    slot_extrema[np.isinf(slot_extrema)] = math.nan
