"""Contact laws of a tooth pair: one compiled function per law, one dispatch point.

:func:`gearcli.core.flank.flank` finds the pairs of a flank family in contact (penetration
p > 0) and keeps, per pair, its penetration p [mm] and rate p' [mm/s], the derivatives
dp/ds1, dp/ds2 [-] of p by the roll distances, and its stiffness k [N/mm^e] with the
derivative dk/dx1 [N/mm^(e+1)] by the pinion roll position (the tooth law's table k(x1) times
the per-tooth stiffness factors, docs/theory.md §4b.2; the constant k of the IMPACT law). It
then calls :func:`pair_force` once per pair in contact. A law turns one pair into

* its normal force F [N] (0 when it does not push),
* its share of the generalized forces on s1, s2 [N] (subtracted from the running sums
  ``q1``, ``q2``), derived from the pair's potential V(p, k) so that the elastic mesh conserves
  energy: the elastic part of Q_s = -dV/ds includes -dV/dk dk/dx1 sigma on s1 (dx1/ds1 =
  sigma) when k varies with the position,
* its potential V [N*mm] and its damping dissipation rate [N*mm/s] (>= 0), added to ``pot``
  and ``pdamp``.

Adding a law: one function here with the signature of :func:`impact_law`, one named integer
next to layout.LAW_IMPACT, one branch in :func:`pair_force`, its entry in :data:`KNOWN_LAWS`,
its closed form in docs/theory.md and a test (tests/unit/test_contact_laws.py); a constant the
law needs from the run's vectors is a field of :class:`LawConstants`.

Each law is a compiled function of scalars only (numba tuples of floats), so the call passes
registers, not arrays, and LLVM inlines it where it is used; numba compiles it once, not once
per flank family (bench/RESULTS.md, session 13: the first compile). Arguments of every law:

* ``consts``: :class:`LawConstants`, read from the run's parameter and derived vectors
  (layout.P, layout.D) once per flank family and evaluation (:func:`law_constants`);
* ``pair = (p, p', dp/ds1, dp/ds2, k, dk/dx1)``;
* ``shared = (sigma, v, sum_k_p)``: the flank family's sign (+1 drive, -1 coast), its mesh
  deflection rate v = sigma delta' + the centres' approach rate [mm/s], and the sum of k p
  over its pairs in contact [N] (known before the first force: laws that share something
  between the pairs, like the tooth law's damping, read it);
* ``acc = (q1, q2, pot, pdamp)``: the running sums; the law returns ``(F, q1, q2, pot, pdamp)``.

Each law updates each sum in one fixed order, the order of the code before the laws were split
out (gearcli 0.1.0), so results are bit for bit those of that code.
"""

from typing import NamedTuple

from gearcli.core.contact import elastic_force, impact_force
from gearcli.core.layout import LAW_IMPACT, LAW_TOOTH, D, P
from gearcli.core.nrt import jit_noalloc, jit_noalloc_inline


class LawConstants(NamedTuple):
    """The run's constants every law may read, taken from ``prm``/``derived`` once per flank
    family and evaluation (:func:`law_constants`), not re-read per pair."""

    k_contact: float  #: IMPACT stiffness k [N/mm^e] (the plain law's; factors scale it)
    c_max: float  #: IMPACT maximum damping [N*s/mm]
    exponent: float  #: IMPACT force exponent e [-]
    d_max: float  #: IMPACT full-damping penetration [mm]
    inv_exponent_plus_1: float  #: 1/(e + 1) [-]
    mesh_damping: float  #: tooth law's mesh damping c_m [N*s/mm]
    damping_force_ref: float  #: tooth law's reference force F_ref [N]
    #: 1 in runs with stiffness factors (a pair's k may differ from k_contact), else 0
    stiffness_factors: float


@jit_noalloc_inline
def law_constants(prm, derived):
    """:class:`LawConstants` of a run's parameter and derived vectors (layout.P, layout.D)."""
    return LawConstants(prm[P.k_contact], prm[P.c_max], prm[P.exponent], prm[P.d_max],
                        derived[D.inv_exponent_plus_1], prm[P.mesh_damping],
                        prm[P.damping_force_ref], derived[D.tooth_factors_used])


#: Every contact law the kernel knows (layout.P.contact_law); integrate.kernel_model refuses
#: other values.
KNOWN_LAWS = (LAW_IMPACT, LAW_TOOTH)


@jit_noalloc
def impact_law(consts, pair, shared, acc):
    """Adams IMPACT (docs/theory.md §4.2, §4.3): F = max(0, k p^e + STEP(p, 0, 0, d_max, c_max)
    p') for p > 0 (with stiffness factors f = k/k_contact, k and c_max are both scaled by f),
    V = k p^(e+1)/(e+1), the whole force along the pair's penetration
    (Q_s1 -= F dp/ds1, Q_s2 -= F dp/ds2), dissipation (F - k p^e) p' >= 0 (also when the max
    clips F to 0). With a position-dependent k (stiffness factors), Q_s1 -= p^(e+1)/(e+1)
    dk/dx1 sigma; skipped when dk/dx1 = 0, so the constant k of the plain law runs the
    operations it always ran."""
    k = pair[4]
    c_max = consts.c_max
    k_plain = consts.k_contact  # stiffness factors f = k/k_plain (docs/theory.md §4b.2) scale
    if k != k_plain and k_plain > 0.0:  # c_max too: a missing tooth (f = 0) carries no damping
        c_max *= k / k_plain
    return _impact(consts, c_max, pair, shared, acc)


@jit_noalloc
def _impact(consts, c_max, pair, shared, acc):
    """:func:`impact_law` with its damping coefficient ``c_max`` [N*s/mm] given (the run's, or
    scaled with the pair's stiffness factor)."""
    pen, pdot, dp1, dp2, k, dk = pair
    q1, q2, pot, pdamp = acc
    force, fel = impact_force(pen, pdot, k, consts.exponent, c_max, consts.d_max)
    pot += fel * pen * consts.inv_exponent_plus_1  # k p^(e+1)/(e+1), contact.impact_potential
    # damping dissipation rate (F - k p^e) pdot >= 0, also when the max() clips F to 0
    pdamp += (force - fel) * pdot
    if dk != 0.0:  # dV/dk = p^(e+1)/(e+1) (k may be 0: a missing tooth)
        q1 -= elastic_force(pen, 1.0, consts.exponent) * pen * consts.inv_exponent_plus_1 \
            * dk * shared[0]
    if not force <= 0.0:  # (a NaN force reaches the sums, as every other NaN)
        q1 -= force * dp1
        q2 -= force * dp2
    return force, q1, q2, pot, pdamp


@jit_noalloc
def tooth_law(consts, pair, shared, acc):
    """Tooth compliance with shared mesh damping (docs/theory.md §4b, §4c): the elastic force
    F_el = k p, F = max(0, F_el (1 + c_m v / max(sum_i k_i p_i, F_ref))) (c_m =
    ``consts.mesh_damping``, F_ref = ``consts.damping_force_ref``), V = k p^2/2.

    The elastic part acts along the penetration plus the position-dependent stiffness's
    -p^2/2 dk/dx1 sigma on s1; the damping part F_d = F - F_el along the mesh deflection
    (-F_d sigma on s1, +F_d sigma on s2), dissipating F_d v >= 0. A pair clamped at F = 0: its
    damping cancels F_el along p, dissipating -F_el p'."""
    pen, pdot, dp1, dp2, k, dk = pair
    sigma, v_mesh, fel_sum = shared
    q1, q2, pot, pdamp = acc
    # damping force per unit elastic force [-]
    damp = consts.mesh_damping * v_mesh / max(fel_sum, consts.damping_force_ref)
    fel = k * pen
    force = max(0.0, fel + fel * damp)
    pot += 0.5 * fel * pen
    # the position-dependent stiffness's generalized force, dV/dx1 dx1/ds1
    q1 -= 0.5 * pen * pen * dk * sigma
    if force <= 0.0:  # clamped: the damping cancels the elastic force along p
        pdamp -= fel * pdot
        return force, q1, q2, pot, pdamp
    # the damping part acts along the mesh deflection (d(sigma delta)/ds1 = sigma, /ds2 =
    # -sigma), the coordinate whose rate it opposes: it dissipates F_d v = c_m v^2 w_j >= 0 (on
    # the pair's own rate, which holds its gap closure under relief, extended contact or
    # errors, it could also feed energy in)
    fd = force - fel
    pdamp += fd * v_mesh
    q1 -= fel * dp1 + fd * sigma
    q2 -= fel * dp2 - fd * sigma
    return force, q1, q2, pot, pdamp


@jit_noalloc_inline
def pair_force(law, consts, pair, shared, acc):
    """The force of one pair in contact under contact law ``law`` (layout.LAW_*) and the
    updated sums: ``(F, q1, q2, pot, pdamp)``; arguments as in the module docstring. The one
    place a law is chosen (inlined: a compare and a branch per pair). In a run without
    stiffness factors every pair has the run's k, so IMPACT goes without its damping scaling
    (:func:`_impact` with the run's c_max: the same numbers, no per-pair test and division,
    ~2 % of the seed's kernel time, bench/RESULTS.md session 13)."""
    if law == LAW_TOOTH:
        return tooth_law(consts, pair, shared, acc)
    if consts.stiffness_factors != 0.0:
        return impact_law(consts, pair, shared, acc)
    # without stiffness factors every pair has the run's k: no damping scaling to test for
    return _impact(consts, consts.c_max, pair, shared, acc)
