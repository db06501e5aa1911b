"""What the time loop keeps: output rows at the sample times and extrema at the solver's steps.

Pure bookkeeping on the arrays of :mod:`gearcli.core.layout`; no physics beyond the kinetic
energy 1/2 J1 omega1^2 + 1/2 J2 omega2^2 [t*mm^2/s^2 = N*mm = mJ].
"""

import math

from gearcli.core.layout import A, C, P, S, X
from gearcli.core.nrt import jit_noalloc


@jit_noalloc
def kinetic_energy(prm, s1dot, deltadot):
    """Kinetic energy [N*mm] from the pinion roll rate and the DTE rate [mm/s]."""
    omega1 = s1dot / prm[P.r_b1]
    omega2 = (s1dot - deltadot) / prm[P.r_b2]
    return 0.5 * prm[P.J1] * omega1 * omega1 + 0.5 * prm[P.J2] * omega2 * omega2


@jit_noalloc
def write_row(series, slot_out, slot_out_coast, i, t, y, aux, slot_force, slot_force_coast,
              prm):
    """Fill output row ``i`` at time ``t`` [s] from the state and one RHS evaluation there."""
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
    row[C.kinetic_energy_mJ] = kinetic_energy(prm, v1, deltadot)
    row[C.contact_energy_mJ] = aux[A.contact_energy]
    row[C.work_in_mJ] = y[S.work_in]
    row[C.work_load_mJ] = y[S.work_load]
    row[C.loss_bearing_mJ] = y[S.loss_bearing]
    row[C.loss_damping_mJ] = y[S.loss_damping]
    row[C.loss_friction_mJ] = y[S.loss_friction]
    for j in range(slot_force.shape[0]):
        slot_out[i, j] = slot_force[j]
        slot_out_coast[i, j] = slot_force_coast[j]


@jit_noalloc
def init_extrema(extrema, slot_extrema):
    """Start values: -inf for maxima, +inf for minima (NaN'ed by :func:`finish_extrema`)."""
    for k in range(extrema.shape[0]):
        extrema[k] = math.nan
    extrema[X.force_total_max_N] = -math.inf
    extrema[X.force_total_min_N] = math.inf
    extrema[X.force_coast_max_N] = -math.inf
    extrema[X.delta_max_mm] = -math.inf
    extrema[X.delta_min_mm] = math.inf
    extrema[X.penetration_max_mm] = -math.inf
    for j in range(slot_extrema.shape[1]):
        slot_extrema[0, j] = -math.inf
        slot_extrema[1, j] = math.nan
        slot_extrema[2, j] = math.inf


@jit_noalloc
def update_extrema(extrema, slot_extrema, t, y, aux, slot_force):
    """Fold the state and forces of one accepted step end (time ``t`` [s]) into the extrema."""
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
    for j in range(slot_force.shape[0]):
        fj = slot_force[j]
        if fj > slot_extrema[0, j]:
            slot_extrema[0, j] = fj
            slot_extrema[1, j] = t
        if fj < slot_extrema[2, j]:
            slot_extrema[2, j] = fj


@jit_noalloc
def finish_extrema(extrema, slot_extrema):
    """Replace the +-inf start values that no step touched by NaN."""
    for k in range(extrema.shape[0]):
        if math.isinf(extrema[k]):
            extrema[k] = math.nan
    for r in range(slot_extrema.shape[0]):
        for j in range(slot_extrema.shape[1]):
            if math.isinf(slot_extrema[r, j]):
                slot_extrema[r, j] = math.nan
