"""Constants of a run, computed once before the time loop from the parameters and the tables.

Reciprocals of geometry and inertia (layout.D) save divisions in the right-hand side; per flank
family (layout.F) the slot phase, the backlash offset, the tooth indices and runout phases of
its line of action, bounds on the overlap its pairs can reach, and the zero runs of its gap
tables. These bounds let the right-hand side skip work that cannot change a result
(tests/physics/test_kernel_fastpaths.py).
"""

import math

import numpy as np

from gearcli.core.gaptable import table_floors
from gearcli.core.layout import (
    FAMILY_PARAMS,
    FLANK_FAMILIES,
    GEAR,
    N_FAMILIES,
    N_GEARS,
    PINION,
    TABLE_GAP,
    TABLE_SLOPE,
    D,
    F,
    P,
)
from gearcli.core.nrt import jit_noalloc_inline


@jit_noalloc_inline
def table_of(family, gear):
    """Gap-table (and tooth-offset) row of one flank family and gear (layout.N_TABLES)."""
    return family * N_GEARS + gear


def error_bound(prm, tooth_offsets, t1, t2) -> float:
    """Largest overlap [mm] runout and tooth offsets can add on one flank family.

    ``|ecc1| + |ecc2| + max_i(-Ft1[i]) + max_i(-Ft2[i])`` (rows ``t1``, ``t2`` of the offsets).
    """
    bound = abs(prm[P.ecc1]) + abs(prm[P.ecc2])
    for row, z in ((t1, int(prm[P.z1])), (t2, int(prm[P.z2]))):
        bound += np.max(-tooth_offsets[row, :z]) if z > 0 else -math.inf
    return float(bound)


def overlap_bound(prm, floors, tooth_offsets, t1, t2) -> float:
    """Upper bound [mm] of ``-G1(x1) - G2(x2) - e1 - e2 - Ft1 - Ft2`` of one flank family
    (tables and offset rows ``t1``, ``t2``; ``floors``: gaptable.table_floors).

    A pair of the family can only touch when ``sigma delta - offset`` exceeds minus this.
    """
    return float(-floors[t1] - floors[t2] + error_bound(prm, tooth_offsets, t1, t2))


def profile_bound(profile_gaps, z, t) -> float:
    """Largest material [mm] the profile deviations (Model.tooth_profile_gap, linear between
    its columns, so extreme on them) add to one tooth of row ``t`` (``z`` teeth): ``max(-P)``;
    0 without profile deviations."""
    if profile_gaps.size == 0 or z <= 0:
        return 0.0
    return float(np.max(-profile_gaps[t, :z]))


def end_gap_bound(tables, g1, g2, floors) -> float:
    """Lower bound [mm] of ``G1(x1) + G2(x2)`` when either position sits on a table end.

    ``min(G1(x_lo), G1(x_hi)) + min G2`` or the same with the tables swapped (``min G``:
    ``floors`` from :func:`gearcli.core.gaptable.table_floors`). A pair crossing a table end
    overlaps by at most ``sigma delta - offset`` minus this (events.py); extended tables open a
    gap of about the tabulation cap there, so no crossing of theirs is loaded.
    """
    end1 = min(tables[g1, TABLE_GAP, 0], tables[g1, TABLE_GAP, -1]) + floors[g2]
    end2 = min(tables[g2, TABLE_GAP, 0], tables[g2, TABLE_GAP, -1]) + floors[g1]
    return float(min(end1, end2))


def zero_run(tables, k) -> tuple[int, int]:
    """First and last grid index of the longest run of grid points of table ``k`` where the
    value and the slope are both zero (the first of equally long ones; ``(0, -1)`` if none):
    the Hermite cubic vanishes identically between them."""
    zero = (tables[k, TABLE_GAP] == 0.0) & (tables[k, TABLE_SLOPE] == 0.0)
    if not zero.any():
        return 0, -1
    edges = np.diff(np.concatenate(([0], zero.astype(np.int8), [0])))
    starts = np.flatnonzero(edges == 1)
    lasts = np.flatnonzero(edges == -1) - 1
    j = int(np.argmax(lasts - starts))  # the first longest
    return int(starts[j]), int(lasts[j])


def _zero_interval(prm, tables, k, h) -> tuple[float, float]:
    """[lo, hi] [mm] inside table ``k``'s zero run, one grid step in from its ends (a position
    there falls in an interval of the run whatever the rounding of its grid index, and the
    cubic is exactly 0); an empty interval when there is no run of at least 3 points."""
    lo, hi = zero_run(tables, k)
    if hi - lo >= 2:
        return prm[P.x_lo] + (lo + 1) * h, prm[P.x_lo] + (hi - 1) * h
    return math.inf, -math.inf


def derive_tables(prm, tables, tooth_offsets, tooth_factors, derived, family,
                  profile_gaps=None) -> None:
    """The table- and offset-dependent constants: ``derived`` entries error_bound,
    tooth_offsets_used, tooth_factors_used, teeth_tracked, grid_step and reciprocals;
    ``family`` columns overlap, end_gap and the zero runs. Profile deviations
    (``profile_gaps``: Model.tooth_profile_gap) raise the overlap and error bounds and lower
    the end gaps by the material they can add (:func:`profile_bound`).

    Plain numpy, run once per run: compiled, these seven small functions cost the first run
    ~1.1 s of compilation and every later run a cache load (bench/RESULTS.md, session 9)."""
    if profile_gaps is None:
        profile_gaps = np.zeros((0, 0, 0))
    h = (prm[P.x_hi] - prm[P.x_lo]) / (tables.shape[2] - 1)
    floors = table_floors(tables, h)
    bound = -math.inf
    for f in range(N_FAMILIES):
        t1 = f * N_GEARS + PINION  # table_of(f, PINION), uncompiled
        t2 = f * N_GEARS + GEAR
        family[f, F.overlap] = overlap_bound(prm, floors, tooth_offsets, t1, t2)
        family[f, F.end_gap] = end_gap_bound(tables, t1, t2, floors)
        family[f, F.zero_lo1], family[f, F.zero_hi1] = _zero_interval(prm, tables, t1, h)
        family[f, F.zero_lo2], family[f, F.zero_hi2] = _zero_interval(prm, tables, t2, h)
        err = error_bound(prm, tooth_offsets, t1, t2)
        if profile_gaps.size:
            extra = (profile_bound(profile_gaps, int(prm[P.z1]), t1)
                     + profile_bound(profile_gaps, int(prm[P.z2]), t2))
            family[f, F.overlap] += extra
            family[f, F.end_gap] -= extra
            err += extra
        bound = max(bound, err)
    derived[D.error_bound] = bound
    used = 1.0 if np.any(tooth_offsets != 0.0) else 0.0
    derived[D.tooth_offsets_used] = used
    derived[D.tooth_factors_used] = 1.0 if tooth_factors.size > 0 else 0.0
    derived[D.teeth_tracked] = max(used, derived[D.tooth_factors_used],
                                   1.0 if profile_gaps.size else 0.0)
    derived[D.inv_exponent_plus_1] = 1.0 / (prm[P.exponent] + 1.0)
    derived[D.grid_step] = h
    derived[D.inv_grid_step] = 1.0 / h
    derived[D.inv_p_b] = 1.0 / prm[P.p_b]
    derived[D.inv_r_b1] = 1.0 / prm[P.r_b1]
    derived[D.inv_r_b2] = 1.0 / prm[P.r_b2]
    derived[D.inv_J1] = 1.0 / prm[P.J1]
    derived[D.inv_J2] = 1.0 / prm[P.J2]


def derive(prm, tables, tooth_offsets, derived, family, tooth_factors=None,
           profile_gaps=None) -> None:
    """Fill ``derived`` (layout.D) and ``family`` (layout.F) for a run: the parameters each
    flank family reads (layout.FAMILY_PARAMS) and :func:`derive_tables` (``tooth_factors``,
    ``profile_gaps``: the Model's tooth_stiffness_factor and tooth_profile_gap, absent by
    default)."""
    if tooth_factors is None:
        tooth_factors = np.zeros((0, 0))
    for f, name in enumerate(FLANK_FAMILIES):
        for column, source in FAMILY_PARAMS[name]:
            family[f, F._fields.index(column)] = 0.0 if source is None \
                else prm[P._fields.index(source)]
    derive_tables(prm, tables, tooth_offsets, tooth_factors, derived, family, profile_gaps)
