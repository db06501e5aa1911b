"""Mesh contact: the forces of all pair slots of one flank family (docs/theory.md §3-5).

Coordinates and slots are described in :mod:`gearcli.core.rhs`; this module evaluates, for one
flank family f (layout.DRIVE_FLANKS: sigma = +1, layout.COAST_FLANKS: sigma = -1), every pair
slot's penetration from the gap tables, runout and tooth offsets, its contact force (Adams
IMPACT, docs/theory.md §4), the generalized forces on the roll distances and the friction moments
(Adams contact friction, docs/theory.md §5).

A new per-pair or per-tooth quantity (a stiffness table, a fault) is read here from a field of
:class:`gearcli.core.bundles.Model`; the per-family constants come from ``model.family``
(layout.F, :mod:`gearcli.core.derive`).
"""

import math
from typing import NamedTuple

import numpy as np

from gearcli.core.contact import impact_force
from gearcli.core.derive import table_of
from gearcli.core.friction import adams_mu
from gearcli.core.gaptable import hermite
from gearcli.core.jit import jit
from gearcli.core.layout import DRIVE_FLANKS, GEAR, LAW_TOOTH, PINION, SC, D, F, P
from gearcli.core.nrt import jit_noalloc_inline


class Kinematics(NamedTuple):
    """Rigid-body motion of the pair at one instant (both flank families see the same)."""

    s1: float  #: pinion roll distance r_b1 theta1 [mm]
    v1: float  #: its rate [mm/s]
    delta: float  #: DTE s1 - s2 [mm]
    deltadot: float  #: its rate [mm/s]
    v2: float  #: gear roll rate [mm/s]
    omega1: float  #: [rad/s]
    omega2: float  #: [rad/s]
    theta1: float  #: [rad]
    theta2: float  #: [rad]


class Approach(NamedTuple):
    """Lateral model: the gear centres' relative motion seen by one flank family (0 in the
    torsional model; model/structure.py)."""

    along: float  #: approach (u1 - u2) . n along this family's line of action [mm]
    rate: float  #: its rate [mm/s]
    slide: float  #: relative speed (u1' - u2') . t across it [mm/s] (sliding speed)


class FlankForces(NamedTuple):
    """What one flank family contributes to the equations of motion and the outputs."""

    q1: float  #: generalized mesh force on s1 [N]
    q2: float  #: on s2 [N]
    m1f: float  #: friction torque on the pinion [N*mm]
    m2f: float  #: on the gear [N*mm]
    force: float  #: sum of the normal forces [N]
    n_contact: int  #: pairs with F > 0
    friction_force: float  #: signed sum of friction forces mu(v_j) F_j [N]
    friction_power: float  #: sum f_j v_j [N*mm/s], <= 0
    damping_power: float  #: contact damping dissipation rate [N*mm/s], >= 0
    potential: float  #: contact potential sum k p^(e+1)/(e+1) [N*mm]
    pen_max: float  #: largest penetration [mm] (0 if none)


@jit
def runout(ecc, phase, theta, inv_r_b):
    """Runout gap ``ecc sin(theta + phase)`` [mm] and its derivative by the roll distance,
    ``ecc cos(theta + phase) / r_b`` [-] (``inv_r_b = 1/r_b`` [1/mm])."""
    if ecc == 0.0:
        return 0.0, 0.0
    return ecc * math.sin(theta + phase), ecc * math.cos(theta + phase) * inv_r_b


@jit_noalloc_inline
def _friction(prm, x1, omega1, omega2, slide, force, mu_s, mu_d):
    """Adams contact friction of one pair (docs/theory.md §5): friction force f = mu(v) F [N],
    its moments about O1, O2 [N*mm] (arms rho1 = T1A + x1, rho2 = T1T2 - rho1 [mm]) and its
    power f v [N*mm/s] (<= 0), v = omega1 rho1 - omega2 rho2 + slide the sliding speed."""
    rho1 = prm[P.T1A] + x1
    rho2 = prm[P.T1T2] - rho1
    vs = omega1 * rho1 - omega2 * rho2 + slide
    fr = adams_mu(vs, mu_s, mu_d, prm[P.v_s], prm[P.v_d]) * force
    return fr, fr * rho1, fr * rho2, fr * vs


@jit_noalloc_inline
def flank(f, kin, app, model, slot_force, scratch, full):
    """Forces of all pair slots of flank family ``f``.

    Parameters
    ----------
    f : int
        layout.DRIVE_FLANKS or layout.COAST_FLANKS (sigma = +1 or -1).
    kin : Kinematics
    app : Approach
        The centres' approach along this family's line of action (lateral model).
    model : gearcli.core.bundles.Model
    slot_force : ndarray, shape (N_FAMILIES, n_slots)
        Row ``f`` written when ``full``: the force of every slot [N] (0 out of contact).
    scratch : ndarray, shape (N_SCRATCH, n_slots)
        Work space of the tooth law (layout.SC): its first pass keeps every pair in contact.
    full : bool
        False at the inner Runge-Kutta stages, where only the derivatives are used.

    Fast paths that leave every result unchanged (tests/physics/test_kernel_fastpaths.py,
    bench/RESULTS.md): with ``sigma delta - offset + overlap <= 0`` (``model.family[f,
    F.overlap]``, derive.overlap_bound) no slot can touch and the slot loop is skipped;
    inside a table's zero run (``F.zero_lo1 .. F.zero_hi1``, and 2 for the gear) the gap and
    its slope are exactly 0 and the table is not read; without per-tooth offsets
    (``derived[D.tooth_offsets_used] == 0``) the tooth indices are not tracked.

    Contact laws (``prm[P.contact_law]``):

    * layout.LAW_IMPACT (docs/theory.md §4): F_j = max(0, k p^e + STEP(p, 0, 0, d_max, c_max)
      pdot) in one pass; potential k p^(e+1)/(e+1).
    * layout.LAW_TOOTH (§4b, §4c): the pair stiffness k_j = k(x1_j) is read from
      ``model.pair_stiffness[f]`` (cubic Hermite on the gap tables' grid) and the mesh damping
      c_m (``prm[P.mesh_damping]``) acts on the mesh deflection rate v = sigma delta' + the
      centres' approach rate, not on the gap-closure rate, shared by the pairs in contact in
      proportion to their elastic forces F_el,j = k_j p_j:
      F_j = max(0, F_el,j (1 + c_m v / max(sum_i F_el,i, F_ref))), F_ref =
      ``prm[P.damping_force_ref]`` (the static force). Loaded (sum F_el >= F_ref) the pairs
      share c_m v, in proportion to their stiffness where their deflections are equal; at
      light contact the damping is c_m v F_el,j / F_ref, Hunt & Crossley's form lambda p p'
      (J. Appl. Mech. 42, 1975), so a pair's force rises from zero at first touch
      (docs/theory.md §4c). A first pass finds the pairs in contact (``scratch``), a second
      computes their forces.
      Potential V_j = k_j p_j^2 / 2 with k_j depending on x1_j: the generalized forces are
      -dV/ds, Q_s1 = -(F_j dp/ds1 + p_j^2/2 dk/dx sigma), Q_s2 = -F_j dp/ds2 (dx1/ds1 = sigma),
      so the elastic mesh conserves energy with a position-dependent stiffness. The damping
      part F_j - F_el,j acts along the mesh deflection (generalized forces -F_d sigma on s1,
      +F_d sigma on s2), so its dissipation F_d v >= 0 (a pair clamped at F_j = 0: its
      damping cancels F_el,j along p_j, dissipating -F_el,j pdot_j).

    Returns
    -------
    FlankForces
    """
    prm = model.prm
    derived = model.derived
    fam = model.family
    tables = model.tables
    tooth_offsets = model.tooth_offsets
    sigma = 1.0 if f == DRIVE_FLANKS else -1.0
    if full:
        for j in range(slot_force.shape[1]):
            slot_force[f, j] = 0.0
    offset = fam[f, F.offset]
    lat = app.along
    if sigma * kin.delta + lat - offset + fam[f, F.overlap] <= 0.0:  # no slot can touch
        return FlankForces(0.0, 0.0, 0.0, 0.0, 0.0, 0, 0.0, 0.0, 0.0, 0.0, 0.0)
    delta = kin.delta
    v1 = kin.v1
    v2 = kin.v2
    omega1 = kin.omega1
    omega2 = kin.omega2
    lat_rate = app.rate
    slide = app.slide
    e1, de1 = runout(prm[P.ecc1], fam[f, F.phase1], kin.theta1, derived[D.inv_r_b1])
    e2, de2 = runout(prm[P.ecc2], fam[f, F.phase2], kin.theta2, derived[D.inv_r_b2])
    g1 = table_of(f, PINION)  # gap tables, and the rows of the tooth offsets
    g2 = table_of(f, GEAR)
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
    tooth_law = prm[P.contact_law] == LAW_TOOTH
    n_touch = 0  # tooth law: pairs in contact kept in the scratch
    fel_sum = 0.0  # tooth law: their elastic force sum [N]
    use_friction = mu_s != 0.0 or mu_d != 0.0
    r = sigma * kin.s1 - fam[f, F.phase0]
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
    # tooth indices of slot 0; slot j holds teeth (k + sigma (n - j)) mod z (rhs.py docstring)
    use_offsets = derived[D.tooth_offsets_used] != 0.0
    use_factors = derived[D.tooth_factors_used] != 0.0
    track = derived[D.teeth_tracked] != 0.0
    zlo1 = fam[f, F.zero_lo1]
    zhi1 = fam[f, F.zero_hi1]
    zlo2 = fam[f, F.zero_lo2]
    zhi2 = fam[f, F.zero_hi2]
    i1 = 0
    i2 = 0
    if track:
        i1 = (int(fam[f, F.tooth_k1]) + isig * n) % z1
        i2 = (int(fam[f, F.tooth_k2]) + isig * n) % z2
    for j in range(slot_force.shape[1]):
        if j > 0 and track:
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
            pen -= tooth_offsets[g1, i1] + tooth_offsets[g2, i2]
        if pen <= 0.0:
            continue
        if pen > pen_max:
            pen_max = pen
        dp1 = sigma * (1.0 - dgap1) - de1  # dp/ds1 [-]
        dp2 = -sigma * (1.0 + dgap2) - de2  # dp/ds2 [-]
        pdot = dp1 * v1 + dp2 * v2 + lat_rate
        if tooth_law:
            # int(f): the family as a run-time int, one compiled hermite for every call
            _, kj, dkj = hermite(model.pair_stiffness, int(f), x_lo, x_hi, h_grid, inv_h, x1)
            if use_factors:  # this pair's teeth: the factor is constant along its path
                fac = model.tooth_stiffness_factor[PINION, i1] \
                    * model.tooth_stiffness_factor[GEAR, i2]
                kj *= fac
                dkj *= fac
            scratch[SC.slot, n_touch] = j
            scratch[SC.x1, n_touch] = x1
            scratch[SC.pen, n_touch] = pen
            scratch[SC.pdot, n_touch] = pdot
            scratch[SC.dp1, n_touch] = dp1
            scratch[SC.dp2, n_touch] = dp2
            scratch[SC.k, n_touch] = kj
            scratch[SC.dk, n_touch] = dkj
            n_touch += 1
            fel_sum += kj * pen
            continue
        force, fel = impact_force(pen, pdot, k, ex, c_max, d_max)
        pot += fel * pen * inv_e1  # k p^(e+1)/(e+1), contact.impact_potential
        # damping dissipation rate (F - k p^e) pdot >= 0, also when the max() clips F to 0
        pdamp += (force - fel) * pdot
        if force <= 0.0:
            continue
        if full:
            slot_force[f, j] = force
        f_sum += force
        n_contact += 1
        q1 -= force * dp1
        q2 -= force * dp2
        if use_friction:
            fr, fm1, fm2, fp = _friction(prm, x1, omega1, omega2, slide, force, mu_s, mu_d)
            m1f += fm1
            m2f -= fm2
            ff_sum += fr
            fpow += fp
    if n_touch > 0:  # tooth law, second pass: damping shared by elastic force (docstring)
        v_mesh = sigma * kin.deltadot + lat_rate  # the mesh deflection rate [mm/s]
        # damping force per unit elastic force [-]
        damp = prm[P.mesh_damping] * v_mesh / max(fel_sum, prm[P.damping_force_ref])
        for m in range(n_touch):
            pen = scratch[SC.pen, m]
            fel = scratch[SC.k, m] * pen
            force = max(0.0, fel + fel * damp)
            pot += 0.5 * fel * pen
            # the position-dependent stiffness's generalized force, dV/dx1 dx1/ds1
            q1 -= 0.5 * pen * pen * scratch[SC.dk, m] * sigma
            if force <= 0.0:  # clamped: the damping cancels the elastic force along p
                pdamp -= fel * scratch[SC.pdot, m]
                continue
            # the damping part acts along the mesh deflection (d(sigma delta)/ds1 = sigma,
            # /ds2 = -sigma), the coordinate whose rate it opposes: it dissipates
            # F_d v_mesh = c_m v_mesh^2 w_j >= 0 (on the pair's own rate, which holds its gap
            # closure under relief, extended contact or errors, it could also feed energy in)
            fd = force - fel
            pdamp += fd * v_mesh
            if full:
                slot_force[f, int(scratch[SC.slot, m])] = force
            f_sum += force
            n_contact += 1
            q1 -= fel * scratch[SC.dp1, m] + fd * sigma
            q2 -= fel * scratch[SC.dp2, m] - fd * sigma
            if use_friction:
                fr, fm1, fm2, fp = _friction(prm, scratch[SC.x1, m], omega1, omega2, slide,
                                             force, mu_s, mu_d)
                m1f += fm1
                m2f -= fm2
                ff_sum += fr
                fpow += fp
    return FlankForces(q1, q2, m1f, m2f, f_sum, n_contact, ff_sum, fpow, pdamp, pot, pen_max)
