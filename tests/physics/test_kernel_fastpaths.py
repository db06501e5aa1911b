"""Shortcuts of the compiled kernel that must not change a result (bench/RESULTS.md).

* inside a gap table's zero run (values and slopes 0 at consecutive grid points) the Hermite
  cubic is exactly zero, so the right-hand side skips the table lookup there;
* a flank family whose tables open a gap at their ends (extended engagement) cannot have a
  loaded table-end crossing, so the event search skips it;
* without per-tooth offsets the tooth indices are not tracked.
"""

from __future__ import annotations

import numpy as np
import pytest

from gearcli.core import layout
from gearcli.core.derive import derive, end_gap_bound, zero_run
from gearcli.core.gaptable import hermite, table_floors
from gearcli.core.layout import COAST_FLANKS, DRIVE_FLANKS, D, F, P


def _tables(values: np.ndarray, slopes: np.ndarray) -> np.ndarray:
    t = np.zeros((4, 2, values.size))
    t[:, 0, :] = values
    t[:, 1, :] = slopes
    return t


def test_zero_run_is_the_longest_run_and_the_cubic_vanishes_on_it():
    x = np.linspace(-2.0, 6.0, 81)
    g = np.where(x < 0.0, x**2, 0.0) + np.where(x > 4.0, 0.5 * (x - 4.0) ** 2, 0.0)
    dg = np.where(x < 0.0, 2.0 * x, 0.0) + np.where(x > 4.0, x - 4.0, 0.0)
    g[70] = 0.0  # a shorter zero run elsewhere (value only: slope non-zero) is not taken
    tables = _tables(g, dg)
    lo, hi = zero_run(tables, 0)
    assert (lo, hi) == (20, 60)  # x = 0 .. 4
    h = x[1] - x[0]
    for q in np.linspace(x[lo + 1], x[hi - 1], 57):  # derive's shortcut interval
        inside, value, slope = hermite(tables, 0, x[0], x[-1], h, 1.0 / h, q)
        assert inside and value == 0.0 and slope == 0.0
    assert zero_run(_tables(np.ones(5), np.zeros(5)), 1) == (0, -1)  # no zero run


def test_derive_zero_runs_end_gaps_and_offset_flag():
    x = np.linspace(-1.0, 5.0, 61)
    g = np.where(x < 0.0, x**2, 0.0) + np.where(x > 4.0, (x - 4.0) ** 2, 0.0)
    dg = np.where(x < 0.0, 2.0 * x, 0.0) + np.where(x > 4.0, 2.0 * (x - 4.0), 0.0)
    tables = _tables(g, dg)
    prm = layout.make_params(t_end=1.0, r_b1=80.0, r_b2=117.0, J1=60.0, J2=300.0, z1=17,
                             z2=25, p_b=29.5, T1A=5.0, T1T2=72.0, x_lo=-1.0, x_hi=5.0,
                             n_slots=2, k_contact=1e5, exponent=1.5, c_max=100.0, d_max=0.1,
                             drive_mode=0)
    offsets = np.zeros((layout.N_TABLES, 25))
    derived = np.zeros(layout.N_DERIVED)
    family = np.zeros((layout.N_FAMILIES, layout.N_FAMILY))
    derive(prm, tables, offsets, derived, family)
    h = derived[D.grid_step]
    for f in (DRIVE_FLANKS, COAST_FLANKS):  # every table of every family has its own run
        for lo, hi in ((F.zero_lo1, F.zero_hi1), (F.zero_lo2, F.zero_hi2)):
            assert family[f, lo] == pytest.approx(0.0 + h, abs=1e-12)  # one step inside
            assert family[f, hi] == pytest.approx(4.0 - h, abs=1e-12)
    assert derived[D.tooth_offsets_used] == 0.0
    # table ends at x = -1 (G = 1) and x = 5 (G = 1); the floor of the Hermite cubic <= 0
    floors = table_floors(tables, h)
    expected = 1.0 + floors[1]
    assert family[DRIVE_FLANKS, F.end_gap] == pytest.approx(expected)
    assert end_gap_bound(tables, 0, 1, floors) == pytest.approx(expected)
    assert derived[D.inv_exponent_plus_1] == pytest.approx(1.0 / 2.5)
    offsets[1, 3] = 1e-3
    derive(prm, tables, offsets, derived, family)
    assert derived[D.tooth_offsets_used] == 1.0
    # rigid tables (all zero): the whole grid is one zero run, and the ends are loaded
    derive(prm, np.zeros_like(tables), offsets, derived, family)
    assert family[COAST_FLANKS, F.zero_lo2] == pytest.approx(prm[P.x_lo] + h)
    assert family[COAST_FLANKS, F.zero_hi2] == pytest.approx(prm[P.x_hi] - h)
    assert family[DRIVE_FLANKS, F.end_gap] == 0.0


def test_family_constants_come_from_their_parameters():
    """Each flank family reads its own phase, backlash offset, tooth indices and runout phases
    (layout.FAMILY_PARAMS): the coast family the coast parameters, the drive family none."""
    tables = _tables(np.zeros(11), np.zeros(11))
    prm = layout.make_params(t_end=1.0, r_b1=80.0, r_b2=117.0, J1=60.0, J2=300.0, z1=17,
                             z2=25, p_b=29.5, T1A=5.0, T1T2=72.0, x_lo=-1.0, x_hi=5.0,
                             n_slots=2, k_contact=1e5, exponent=1.5, drive_mode=0,
                             s1_0=1.0, s1c_0=2.0, backlash_n=0.3, tooth_k1=3, tooth_k2=4,
                             tooth_k1_coast=5, tooth_k2_coast=6, phase1=0.1, phase2=0.2,
                             phase1_coast=0.3, phase2_coast=0.4)
    family = np.zeros((layout.N_FAMILIES, layout.N_FAMILY))
    derive(prm, tables, np.zeros((layout.N_TABLES, 25)), np.zeros(layout.N_DERIVED), family)
    names = ("phase0", "offset", "tooth_k1", "tooth_k2", "phase1", "phase2")
    assert [family[DRIVE_FLANKS, F._fields.index(n)] for n in names] == [1.0, 0.0, 3, 4, 0.1, 0.2]
    assert [family[COAST_FLANKS, F._fields.index(n)] for n in names] == [2.0, 0.3, 5, 6, 0.3, 0.4]


def test_layout_sizes_come_from_one_constant_each():
    """The gap tables and the per-family constants are sized from the flank families and gears
    (no fixed number of slots a further table could overwrite)."""
    assert layout.N_TABLES == len(layout.FLANK_FAMILIES) * len(layout.GEARS)
    rows = {layout.TABLE_G1, layout.TABLE_G2, layout.TABLE_G1_COAST, layout.TABLE_G2_COAST}
    assert rows == set(range(layout.N_TABLES))
    assert len(set(layout.FAMILY_NAMES)) == layout.N_FAMILY == len(layout.F)


def test_kernel_model_refuses_an_array_it_has_no_field_for():
    """Optional model arrays are passed by their Model field name; a name the kernel does not
    know is a programming error, never silently dropped."""
    from gearcli.core.integrate import kernel_model

    prm = layout.make_params(t_end=1.0, r_b1=80.0, r_b2=117.0, J1=60.0, J2=300.0, z1=17,
                             z2=25, p_b=29.5, T1A=5.0, T1T2=72.0, x_lo=-1.0, x_hi=5.0,
                             n_slots=2, k_contact=1e5, exponent=1.5, drive_mode=2)
    pp = (np.zeros(0), np.zeros((1, 1)), np.zeros(1))
    tables = _tables(np.zeros(11), np.zeros(11))
    model = kernel_model(prm, tables, drive_pp=pp, load_pp=pp)
    assert model.family.shape == (layout.N_FAMILIES, layout.N_FAMILY)
    with pytest.raises(ValueError, match="pair_stiffnes"):
        kernel_model(prm, tables, drive_pp=pp, load_pp=pp, pair_stiffnes=np.ones((2, 11)))
