"""Mesh contact: the forces of all pair slots of one flank family (docs/theory.md §3-5).

Coordinates and slots are described in :mod:`gearcli.core.rhs`; this module evaluates, for one
flank family f (layout.DRIVE_FLANKS: sigma = +1, layout.COAST_FLANKS: sigma = -1), every pair
slot's penetration from the gap tables, runout and tooth offsets, its stiffness (the tooth
law's table, the per-tooth, per-position stiffness factors, docs/theory.md §4b.2), its contact
force under the run's contact law (:mod:`gearcli.core.laws`, docs/theory.md §4, §4b, §4c), the
generalized forces on the roll distances and the friction moments (Adams contact friction,
docs/theory.md §5).

A new per-pair or per-tooth quantity (a stiffness table, a fault) is read here from a field of
:class:`gearcli.core.bundles.Model`; the per-family constants come from ``model.family``
(layout.F, :mod:`gearcli.core.derive`). A new contact law is a function of
:mod:`gearcli.core.laws`, not code here.
"""

import math
from typing import NamedTuple

import numpy as np

from gearcli.core.derive import table_of
from gearcli.core.friction import adams_mu
from gearcli.core.gaptable import hermite, linear
from gearcli.core.jit import jit
from gearcli.core.laws import law_constants, pair_force
from gearcli.core.layout import DRIVE_FLANKS, GEAR, PINION, SC, D, F, P
from gearcli.core.nrt import jit_noalloc, jit_noalloc_inline


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


@jit
def _slot_phase(r, p_b, inv_p_b):
    """Position ``u`` of slot 0 within its base pitch, ``0 <= u < p_b`` [mm], and the pitch
    count ``n`` of ``r = u + n p_b`` (``r``: the family's roll distance less its phase)."""
    nf = np.floor(r * inv_p_b)  # a float: math.floor's int costs two conversions
    u = r - nf * p_b
    if u >= p_b:  # rounding of r - floor(r/p) p
        u -= p_b
        nf += 1.0
    elif u < 0.0:
        u += p_b
        nf -= 1.0
    return u, int(nf)


@jit
def _previous_tooth(i, isig, z):
    """The tooth of the next slot: ``(i - isig) mod z`` for ``0 <= i < z``."""
    i -= isig
    if i < 0:
        i += z
    elif i >= z:
        i -= z
    return i


@jit_noalloc_inline
def _gap(tables, g, x, zero_lo, zero_hi, grid):
    """Gap [mm] and slope [-] of table ``g`` at ``x`` [mm]; inside the table's zero run
    ``zero_lo .. zero_hi`` the Hermite cubic is exactly 0 (values and slopes 0) and the table
    is not read. ``grid = (x_lo, x_hi, h, inv_h)`` of the gap tables."""
    if x >= zero_lo and x <= zero_hi:
        return 0.0, 0.0
    x_lo, x_hi, h, inv_h = grid
    _, gap, dgap = hermite(tables, g, x_lo, x_hi, h, inv_h, x)
    return gap, dgap


@jit_noalloc
def _factors(table, g1, g2, i1, i2, x_lo, inv_hf, x1):
    """The pair's stiffness factor f_P(i1, x1) f_G(i2, x1) [-] and its slope by x1 [1/mm]
    (docs/theory.md §4b.2) from rows ``g1``, ``g2`` (the flank family's pinion and gear rows,
    derive.table_of): a call, not inlined (read only in runs with factors)."""
    fp, dfp = linear(table, g1, i1, x_lo, inv_hf, x1)
    fg, dfg = linear(table, g2, i2, x_lo, inv_hf, x1)
    return fp * fg, dfp * fg + fp * dfg


@jit_noalloc
def _profile_gaps(table, rows, x_lo, inv_h, xs, gaps):
    """The pair's gaps and slopes ``gaps = (G1, G1', G2, G2')`` plus the per-tooth profile
    deviation gaps (docs/theory.md §3.5) of pinion tooth i1 at x1 and gear tooth i2 at x2
    (``rows = (g1, g2, i1, i2)``, ``xs = (x1, x2)`` [mm]; ``table``: Model.tooth_profile_gap
    [mm], linear on its grid over [x_lo, x_hi]): a call, not inlined (read only in runs with
    profile deviations)."""
    g1, g2, i1, i2 = rows
    p1, dp1 = linear(table, g1, i1, x_lo, inv_h, xs[0])
    p2, dp2 = linear(table, g2, i2, x_lo, inv_h, xs[1])
    return gaps[0] + p1, gaps[1] + dp1, gaps[2] + p2, gaps[3] + dp2


@jit_noalloc_inline
def _gather(f, sigma, kin, app, model, scratch):
    """First pass over the slots of flank family ``f``: every pair in contact (p > 0) into
    ``scratch`` (layout.SC: slot, x1, p, p', dp/ds1, dp/ds2, k, dk/dx1). Returns their count,
    the sum of k p over them [N] and the largest penetration [mm] (0 if none).

    The stiffness k_j [N/mm^e] of the pair at pinion roll position x1 [mm] holding pinion
    tooth i1 and gear tooth i2, and dk_j/dx1 [N/mm^(e+1)] (docs/theory.md §4b.2): with a
    ``model.pair_stiffness`` table (the tooth law) k(x1) and its slope (cubic Hermite on the
    gap tables' grid), else the constant ``prm[P.k_contact]``; with stiffness factors times
    f_P(i1, x1) f_G(i2, x1) (:func:`_factors`), k_j' = k' f_P f_G + k (f_P f_G)'. Without
    factors nothing is multiplied. With ``model.tooth_profile_gap`` the gaps of the pair's
    teeth gain their profile deviations (:func:`_profile_gaps`)."""
    prm = model.prm
    derived = model.derived
    fam = model.family
    tables = model.tables
    tooth_offsets = model.tooth_offsets
    delta = kin.delta
    v1 = kin.v1
    v2 = kin.v2
    lat = app.along
    lat_rate = app.rate
    offset = fam[f, F.offset]
    e1, de1 = runout(prm[P.ecc1], fam[f, F.phase1], kin.theta1, derived[D.inv_r_b1])
    e2, de2 = runout(prm[P.ecc2], fam[f, F.phase2], kin.theta2, derived[D.inv_r_b2])
    g1 = table_of(f, PINION)  # gap tables, and the rows of the tooth offsets
    g2 = table_of(f, GEAR)
    p_b = prm[P.p_b]
    x_lo = prm[P.x_lo]
    x_hi = prm[P.x_hi]
    grid = (x_lo, x_hi, derived[D.grid_step], derived[D.inv_grid_step])
    k = prm[P.k_contact]
    factors = derived[D.tooth_factors_used] != 0.0
    inv_hf = 0.0
    if factors:
        inv_hf = (model.tooth_stiffness_factor.shape[2] - 1) / (x_hi - x_lo)
    table = model.pair_stiffness.size != 0
    profiles = model.tooth_profile_gap.size != 0
    inv_hp = 0.0
    if profiles:
        inv_hp = (model.tooth_profile_gap.shape[2] - 1) / (x_hi - x_lo)
    u, n = _slot_phase(sigma * kin.s1 - fam[f, F.phase0], p_b, derived[D.inv_p_b])
    # tooth indices of slot 0; slot j holds teeth (k + sigma (n - j)) mod z (rhs.py docstring)
    use_offsets = derived[D.tooth_offsets_used] != 0.0
    track = derived[D.teeth_tracked] != 0.0
    zlo1 = fam[f, F.zero_lo1]
    zhi1 = fam[f, F.zero_hi1]
    zlo2 = fam[f, F.zero_lo2]
    zhi2 = fam[f, F.zero_hi2]
    # +1 / -1 typed int64, not a literal: one compiled _previous_tooth for both families
    isig = int(math.copysign(1.0, sigma))
    z1 = int(prm[P.z1])
    z2 = int(prm[P.z2])
    i1 = 0
    i2 = 0
    if track:
        i1 = (int(fam[f, F.tooth_k1]) + isig * n) % z1
        i2 = (int(fam[f, F.tooth_k2]) + isig * n) % z2
    n_touch = 0
    fel_sum = 0.0
    pen_max = 0.0
    for j in range(scratch.shape[1]):
        if j > 0 and track:
            i1 = _previous_tooth(i1, isig, z1)
            i2 = _previous_tooth(i2, isig, z2)
        x1 = x_lo + u + j * p_b
        x2 = x1 - sigma * delta
        # x1 >= x_lo always (u >= 0); NaN fails every comparison and ends the loop
        if not x1 <= x_hi:
            break  # x1 grows with j: every further slot is beyond the table too
        if not (x2 >= x_lo and x2 <= x_hi):
            continue
        gap1, dgap1 = _gap(tables, g1, x1, zlo1, zhi1, grid)
        gap2, dgap2 = _gap(tables, g2, x2, zlo2, zhi2, grid)
        if profiles:  # per-tooth profile deviations (docs/theory.md §3.5)
            gap1, dgap1, gap2, dgap2 = _profile_gaps(model.tooth_profile_gap, (g1, g2, i1, i2),
                                                     x_lo, inv_hp, (x1, x2),
                                                     (gap1, dgap1, gap2, dgap2))
        pen = sigma * delta + lat - offset - gap1 - gap2 - e1 - e2
        if use_offsets:
            pen -= tooth_offsets[g1, i1] + tooth_offsets[g2, i2]
        if pen <= 0.0:
            continue
        if pen > pen_max:
            pen_max = pen
        dp1 = sigma * (1.0 - dgap1) - de1  # dp/ds1 [-]
        dp2 = -sigma * (1.0 + dgap2) - de2  # dp/ds2 [-]
        kj = k
        dkj = 0.0
        if table:
            # int(f): the family as a run-time int, one compiled hermite for every call
            _, kj, dkj = hermite(model.pair_stiffness, int(f), x_lo, x_hi, grid[2], grid[3], x1)
        if factors:
            fac, dfac = _factors(model.tooth_stiffness_factor, g1, g2, i1, i2, x_lo, inv_hf,
                                 x1)
            dkj = dkj * fac + kj * dfac
            kj *= fac
        scratch[SC.slot, n_touch] = j
        scratch[SC.x1, n_touch] = x1
        scratch[SC.pen, n_touch] = pen
        scratch[SC.pdot, n_touch] = dp1 * v1 + dp2 * v2 + lat_rate
        scratch[SC.dp1, n_touch] = dp1
        scratch[SC.dp2, n_touch] = dp2
        scratch[SC.k, n_touch] = kj
        scratch[SC.dk, n_touch] = dkj
        n_touch += 1
        fel_sum += kj * pen
    return n_touch, fel_sum, pen_max


@jit_noalloc_inline
def _pair_forces(f, kin, app, model, shared, scratch, n_touch, slot_force, full):
    """Second pass: the force of every pair kept by :func:`_gather` under the run's contact law
    (:func:`gearcli.core.laws.pair_force`, ``shared`` as there), the slot forces (row ``f`` of
    ``slot_force`` when ``full``) and the friction of the pairs that push. Returns the sums
    q1, q2, m1f, m2f, force, n_contact, friction force, friction power, damping power and
    potential (the fields of FlankForces but pen_max)."""
    prm = model.prm
    derived = model.derived
    law = int(prm[P.contact_law])
    consts = law_constants(prm, derived)
    omega1 = kin.omega1
    omega2 = kin.omega2
    slide = app.slide
    mu_s = prm[P.mu_s]
    mu_d = prm[P.mu_d]
    use_friction = mu_s != 0.0 or mu_d != 0.0
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
    for m in range(n_touch):
        pair = (scratch[SC.pen, m], scratch[SC.pdot, m], scratch[SC.dp1, m],
                scratch[SC.dp2, m], scratch[SC.k, m], scratch[SC.dk, m])
        force, q1, q2, pot, pdamp = pair_force(law, consts, pair, shared, (q1, q2, pot, pdamp))
        if force <= 0.0:
            continue
        if full:
            slot_force[f, int(scratch[SC.slot, m])] = force
        f_sum += force
        n_contact += 1
        if use_friction:
            fr, fm1, fm2, fp = _friction(prm, scratch[SC.x1, m], omega1, omega2, slide, force,
                                         mu_s, mu_d)
            m1f += fm1
            m2f -= fm2
            ff_sum += fr
            fpow += fp
    return q1, q2, m1f, m2f, f_sum, n_contact, ff_sum, fpow, pdamp, pot


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
        Work space (layout.SC): the pairs in contact between the two passes.
    full : bool
        False at the inner Runge-Kutta stages, where only the derivatives are used.

    Two passes: :func:`_gather` finds the pairs in contact with their penetration, its rate
    and derivatives and their stiffness (the tooth law's table k(x1), the per-tooth,
    per-position stiffness factors); :func:`_pair_forces` applies the contact
    law (``prm[P.contact_law]``, one call of :func:`gearcli.core.laws.pair_force` per pair;
    the laws and their closed forms are in :mod:`gearcli.core.laws`) and adds friction.

    Fast paths that leave every result unchanged (tests/physics/test_kernel_fastpaths.py,
    bench/RESULTS.md): with ``sigma delta - offset + overlap <= 0`` (``model.family[f,
    F.overlap]``, derive.overlap_bound) no slot can touch and the slot loop is skipped;
    inside a table's zero run (``F.zero_lo1 .. F.zero_hi1``, and 2 for the gear) the gap and
    its slope are exactly 0 and the table is not read; without per-tooth offsets or factors
    (``derived[D.teeth_tracked] == 0``) the tooth indices are not tracked; without factors
    (``derived[D.tooth_factors_used] == 0``) the stiffness is not multiplied.

    Returns
    -------
    FlankForces
    """
    fam = model.family
    sigma = 1.0 if f == DRIVE_FLANKS else -1.0
    if full:
        for j in range(slot_force.shape[1]):
            slot_force[f, j] = 0.0
    if sigma * kin.delta + app.along - fam[f, F.offset] + fam[f, F.overlap] <= 0.0:
        return FlankForces(0.0, 0.0, 0.0, 0.0, 0.0, 0, 0.0, 0.0, 0.0, 0.0, 0.0)  # no touch
    n_touch, fel_sum, pen_max = _gather(f, sigma, kin, app, model, scratch)
    # the mesh deflection rate [mm/s]
    shared = (sigma, sigma * kin.deltadot + app.rate, fel_sum)
    q1, q2, m1f, m2f, f_sum, n_contact, ff_sum, fpow, pdamp, pot = _pair_forces(
        f, kin, app, model, shared, scratch, n_touch, slot_force, full)
    return FlankForces(q1, q2, m1f, m2f, f_sum, n_contact, ff_sum, fpow, pdamp, pot, pen_max)
