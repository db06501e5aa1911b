"""Per-tooth, per-position stiffness factors (docs/theory.md §4b.2; core/flank.py
``_gather``, ``_factors``; core/bundles.py ``Model.tooth_stiffness_factor``) in the running kernel.

* a table of ones gives the run without a table bit for bit (both laws, through the pipeline,
  pipeline/kernel_input.py);
* statics of the synthetic pair of tests/physics/test_kernel.py on rigid tables with a constant
  pair stiffness K0 (closed forms, docs/theory.md §4b): a factor 1/2 on one pinion tooth over a
  band of roll positions doubles the single-pair deflection F/K0 inside the band and gives the
  tooth 1/3 of the load in the double-pair zone (k_w/(k_w + k) with equal penetrations); outside
  the band nothing changes;
* constant factors c_P on the pinion's teeth and c_G on the gear's scale the mesh stiffness by
  c = c_P c_G: deflections F/(c K0) and F/(2 c K0) (tooth law), (F/(c k))^(1/e) (IMPACT);
* energy: with factors that vary along the path the free, undamped mesh conserves
  E_kin + sum V_j only because the generalized forces include -dV/dk dk/dx1 (both laws).

Units: mm, N, s, t, rad (docs/theory.md §1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.case.load import load_case
from gearcli.core import layout
from gearcli.core.integrate import kernel_model, simulate
from gearcli.model.timefunction import PiecewisePolynomial as PP
from gearcli.pipeline.geometry import run_geometry
from gearcli.pipeline.kernel_input import build_kernel_input, factor_positions
from tests.conftest import ROOT
from tests.physics import test_kernel as tk

K0 = 1.4e6  # pair stiffness [N/mm] (tests/physics/test_tooth_law.py)
F_STATIC = tk.T_LOAD / tk.R_B2  # static normal force [N]
WEAK = 3  # the weakened pinion tooth
BAND = (8.0, 24.0)  # its band of roll positions x1 [mm]: double zone [0, 16.6), single beyond
N_POS = 93  # factor table columns over [0, g_alpha]: step 0.50 mm


def _run(law, factors=None, t_end=1.0, **extra):
    """Speed drive at 0.2 OMEGA1 with load ramps over 0.1 s, rigid tables on [0, g_alpha]
    (zero gap on the path), drive flanks only. Tooth law: constant k = K0 and mesh damping at
    zeta ~ 0.1 of the mesh mode; IMPACT: BASE of test_kernel.py (k = 1e5 N/mm^1.5, e = 1.5,
    c_max = 100 N s/mm).
    ``t_end`` 1 s: settled from 0.3 s, then more than one pinion revolution (0.6 s)."""
    tables, x_lo, x_hi = np.zeros((4, 2, 2)), 0.0, tk.G_ALPHA
    arrays = {} if factors is None else {"tooth_stiffness_factor": factors}
    values = dict(tk.BASE, x_lo=x_lo, x_hi=x_hi, n_slots=tk.n_slots(x_lo, x_hi),
                  drive_mode=layout.DRIVE_SPEED, t_end=t_end, coast_flanks=0.0, rtol=1e-9,
                  atol_delta=1e-10, atol_deltadot=1e-6, contact_law=law, **extra)
    if law == layout.LAW_TOOTH:
        stiffness = np.full((layout.N_FAMILIES, 2, 2), K0)
        stiffness[:, 1] = 0.0
        arrays["pair_stiffness"] = stiffness
        values["mesh_damping"] = 2.0 * 0.1 * math.sqrt(1.56 * K0 * tk.BASE["J2"] / tk.R_B2**2)
    speed, load = PP.step(0.0, 0.0, 0.1, 0.2 * tk.OMEGA1), PP.step(0.0, 0.0, 0.1, tk.T_LOAD)
    res = simulate(layout.make_params(**values), tables, t_out=np.linspace(0.0, t_end, 6001),
                   drive_pp=tk.pp_arrays(speed), load_pp=tk.pp_arrays(load),
                   drive_angle_pp=tk.pp_arrays(speed.antiderivative()), **arrays)
    assert res.ok, res.message
    return res


def _positions(res):
    """Steady samples: slot 0's roll position x1 = u [mm], its pinion tooth, pairs in contact
    (x_lo = 0, phase 0, tooth index 0: slot j holds tooth (n - j) mod z1, core/rhs.py)."""
    steady = res.column("t_s") > 0.3
    s1 = res.column("theta1_rad")[steady] * tk.R_B1
    n = np.floor(s1 / tk.P_B)
    pairs = res.column("pairs_in_contact")[steady]
    return steady, s1 - n * tk.P_B, np.mod(n.astype(int), tk.Z1), pairs


def test_a_factor_band_on_one_tooth_softens_that_tooth_there_only():
    """Factor 1/2 on pinion tooth WEAK for x1 in BAND, linearly interpolated between the grid
    points (flat between the first and last grid point inside the band). Medians (each zone
    change is a step in the mesh stiffness that rings, rigid tables), tolerance 1 % as the
    tooth law's statics (test_tooth_law.py; measured below 1e-6); the load share is exact
    (equal penetrations, damping shared in proportion to the elastic forces, docs/theory.md
    §4c) at every sample."""
    x = np.linspace(0.0, tk.G_ALPHA, N_POS)  # the columns' x1 (kernel_input.factor_positions)
    factors = np.ones((layout.N_GEARS, tk.Z2, N_POS))
    inside = (x >= BAND[0]) & (x <= BAND[1])
    factors[layout.PINION, WEAK, inside] = 0.5
    flat = (x[inside][0], x[inside][-1])
    res = _run(layout.LAW_TOOTH, factors)
    steady, u, tooth, pairs = _positions(res)
    delta = res.column("delta_mm")[steady]
    in_band = (tooth == WEAK) & (u >= flat[0]) & (u <= flat[1])
    out_band = (tooth == WEAK) & ((u < BAND[0] - 0.6) | (u > BAND[1] + 0.6))
    single, double = pairs == 1, pairs == 2
    for where, n in ((in_band & single, 20), (in_band & double, 20), (out_band & single, 20)):
        assert where.sum() > n
    # single-pair zone inside the band: the compliance doubles
    assert np.median(delta[in_band & single]) == pytest.approx(2.0 * F_STATIC / K0, rel=0.01)
    # double-pair zone inside the band: stiffness 1.5 K0, the weak tooth (slot 0) carries 1/3
    assert np.median(delta[in_band & double]) == pytest.approx(F_STATIC / (1.5 * K0), rel=0.01)
    share = res.slot_force[steady, 0] / res.column("force_total_N")[steady]
    np.testing.assert_allclose(share[in_band & double], 1.0 / 3.0, rtol=1e-9)
    others = double & (tooth != WEAK) & (tooth != (WEAK + 1) % tk.Z1)  # weak tooth in no slot
    np.testing.assert_allclose(share[others], 0.5, rtol=1e-9)
    # outside the band the weak tooth is a sound one
    assert np.median(delta[out_band & single]) == pytest.approx(F_STATIC / K0, rel=0.01)
    assert np.median(delta[single & (tooth != WEAK)]) == pytest.approx(F_STATIC / K0, rel=0.01)


def test_factor_rows_belong_to_their_flank_family():
    """Four rows (drive pinion, drive gear, coast pinion, coast gear, as the tooth offsets): a
    band of 1/2 on the coast pinion's tooth WEAK leaves a drive-only run bit for bit as it is
    without factors (its drive rows are ones); the same band on the drive pinion's row softens
    the drive run (single-pair deflection 2 F/K0 inside the band, as above)."""
    x = np.linspace(0.0, tk.G_ALPHA, N_POS)
    band = (x >= BAND[0]) & (x <= BAND[1])
    plain = _run(layout.LAW_TOOTH)
    for family in (layout.COAST_FLANKS, layout.DRIVE_FLANKS):
        factors = np.ones((layout.N_TABLES, tk.Z2, N_POS))
        factors[family * layout.N_GEARS + layout.PINION, WEAK, band] = 0.5
        res = _run(layout.LAW_TOOTH, factors)
        same = np.array_equal(plain.series, res.series)
        assert same == (family == layout.COAST_FLANKS)
    steady, u, tooth, pairs = _positions(res)
    weak = (tooth == WEAK) & (pairs == 1) & (u >= x[band][0]) & (u <= x[band][-1])
    assert weak.sum() > 20
    delta = res.column("delta_mm")[steady][weak]
    assert np.median(delta) == pytest.approx(2.0 * F_STATIC / K0, rel=0.01)


@pytest.mark.parametrize("c_pinion, c_gear", [(0.4, 1.0), (2.5, 1.0), (1.0, 0.4), (1.6, 1.6)])
def test_a_constant_factor_scales_the_mesh_stiffness(c_pinion, c_gear):
    """Every pinion tooth c_pinion, every gear tooth c_gear (a 3-D table, constant): the pair
    stiffness is K0 c_pinion c_gear, so the single- and double-pair deflections are F/(c K0)
    and F/(2 c K0) with c = c_pinion c_gear (tooth law, tolerance 1 % as above)."""
    factors = np.empty((layout.N_GEARS, tk.Z2, 5))
    factors[layout.PINION], factors[layout.GEAR] = c_pinion, c_gear
    res = _run(layout.LAW_TOOTH, factors, t_end=0.6)
    steady, _, _, pairs = _positions(res)
    delta = res.column("delta_mm")[steady]
    c = c_pinion * c_gear
    assert np.median(delta[pairs == 1]) == pytest.approx(F_STATIC / (c * K0), rel=0.01)
    assert np.median(delta[pairs == 2]) == pytest.approx(F_STATIC / (2.0 * c * K0), rel=0.01)


def test_a_constant_factor_scales_the_impact_stiffness():
    """IMPACT, F = k p^e per pair: with c on every pinion tooth (a 2-D table: constant along
    the path; the gear's ones) the single-pair deflection is (F/(c k))^(1/e), c^(-1/e) = 0.543
    times the plain run's (tolerance 1 %, overdamped contact, zeta ~ 1.5, settles within a
    mesh cycle)."""
    c, k, e = 2.5, tk.BASE["k_contact"], tk.BASE["exponent"]
    factors = np.ones((layout.N_GEARS, tk.Z2))
    factors[layout.PINION] = c
    plain = _run(layout.LAW_IMPACT, t_end=0.6)
    stiff = _run(layout.LAW_IMPACT, factors, t_end=0.6)
    medians = []
    for res in (plain, stiff):
        steady, _, _, pairs = _positions(res)
        medians.append(np.median(res.column("delta_mm")[steady][pairs == 1]))
    assert medians[0] == pytest.approx((F_STATIC / k) ** (1.0 / e), rel=0.01)
    assert medians[1] == pytest.approx((F_STATIC / (c * k)) ** (1.0 / e), rel=0.01)


@pytest.mark.parametrize("law", [layout.LAW_IMPACT, layout.LAW_TOOTH])
def test_energy_is_conserved_with_factors_along_the_path(law):
    """Free pinion and gear rattling across the backlash (no drive, load or damping, both
    flank families, extended tables), every tooth with its own factor profile 1 + 0.3 sin(...)
    along the path: E_kin + sum V_j is conserved to the bounds of the laws' own energy tests
    (test_kernel.py, test_tooth_law.py). The -dV/dk dk/dx1 force is what makes it so: measured
    drifts 5.3e-4 (IMPACT) and 5.9e-5 (tooth) of the largest contact energy; with the factors'
    slope left out of dk/dx1, 0.44 and 0.19 (and 1.9e-5, 2.9e-3 of the total)."""
    tables, x_lo, x_hi = tk.extended_tables()
    t_end = 30 * tk.MESH_PERIOD
    x = np.linspace(x_lo, x_hi, 37)
    teeth = np.arange(tk.Z2)[None, :, None]
    gears = np.arange(layout.N_GEARS)[:, None, None]
    factors = 1.0 + 0.3 * np.sin(2.0 * math.pi * x[None, None, :] / (x_hi - x_lo)
                                 * (1 + gears) + teeth)
    values = dict(tk.BASE, x_lo=x_lo, x_hi=x_hi, n_slots=tk.n_slots(x_lo, x_hi),
                  drive_mode=layout.DRIVE_TORQUE, t_end=t_end, omega1_init=tk.OMEGA1,
                  contact_law=law, c_max=0.0,
                  rtol=1e-10, atol_delta=1e-10, atol_deltadot=1e-7)
    # the initial rattle of each law's own energy test
    values.update(delta_init=0.02, deltadot_init=40.0, backlash_n=0.05)
    arrays = {"tooth_stiffness_factor": factors}
    if law == layout.LAW_TOOTH:
        values.update(delta_init=0.004, deltadot_init=10.0, backlash_n=0.01)
        stiffness = np.zeros((layout.N_FAMILIES, 2, tables.shape[2]))
        stiffness[:, 0] = K0
        arrays["pair_stiffness"] = stiffness
    zero = tk.pp_arrays(PP.constant(0.0))
    res = simulate(layout.make_params(**values), tables, t_out=np.linspace(0.0, t_end, 2001),
                   drive_pp=zero, load_pp=zero, **arrays)
    assert res.ok, res.message
    assert min(res.column("force_total_N").max(), res.column("force_coast_N").max()) > 500
    c = res.column
    energy = c("kinetic_energy_mJ") + c("contact_energy_mJ")
    drift = np.abs(energy - energy[0]).max()
    of_total, of_contact = drift / energy[0], drift / c("contact_energy_mJ").max()
    assert of_total < 1e-6 and of_contact < 1e-3, (of_total, of_contact)


@pytest.mark.parametrize("case, overrides", [
    ("iso_pair.yaml", ["run.end_time=0.02"]),
    ("seed.yaml", ["run.end_time=0.02", "drive.speed=STEP(time, 0, 0, 0.005, 3000)",
                   "load.torque=STEP(time, 0, 0, 0.005, 4.5e+05)"]),
])
def test_a_table_of_ones_is_no_table(case, overrides):
    """Through the pipeline (build_kernel_input's tooth_stiffness_factor): all ones over 7
    positions, a tooth law case and an IMPACT case, gives the run without factors bit for
    bit (the factor multiplies by exactly 1, its slope is exactly 0)."""
    loaded = load_case(ROOT / "cases" / case, overrides)
    geo = run_geometry(loaded)
    z = max(geo.geometry.pinion.teeth, geo.geometry.gear.teeth)
    runs = []
    for factors in (None, np.ones((layout.N_GEARS, z, 7))):
        ki = build_kernel_input(loaded.case, geo, tooth_stiffness_factor=factors)
        assert ("tooth_stiffness_factor" in ki.arrays) == (factors is not None)
        x = factor_positions(ki.tables, 7)  # the columns: the gap tables' range, evenly
        assert (x[0], x[-1]) == (ki.tables.x_lo, ki.tables.x_hi)
        assert np.allclose(np.diff(x), (ki.tables.x_hi - ki.tables.x_lo) / 6, rtol=1e-12)
        runs.append(simulate(ki.params, ki.tables.tables, t_out=ki.t_out, drive_pp=ki.drive_pp,
                             load_pp=ki.load_pp, drive_angle_pp=ki.drive_angle_pp,
                             **ki.arrays))
    plain, ones = runs
    assert plain.ok and ones.ok
    assert plain.column("force_total_N").max() > 100.0  # loaded contact
    np.testing.assert_array_equal(plain.series, ones.series)
    np.testing.assert_array_equal(plain.slot_force, ones.slot_force)
    assert plain.counters == ones.counters


def test_refused_factor_tables():
    loaded = load_case(ROOT / "cases" / "iso_pair.yaml")
    geo = run_geometry(loaded)
    z = max(geo.geometry.pinion.teeth, geo.geometry.gear.teeth)
    for bad, match in ((np.ones((layout.N_GEARS, z - 1, 5)), "shape"),
                       (np.ones((layout.N_GEARS, z, 1)), "shape"),
                       (np.full((layout.N_GEARS, z, 5), -0.1), ">= 0"),
                       (np.full((layout.N_GEARS, z, 5), np.nan), "finite")):
        with pytest.raises(ValueError, match=match):
            build_kernel_input(loaded.case, geo, tooth_stiffness_factor=bad)
    tables, x_lo, x_hi = tk.extended_tables()
    prm = layout.make_params(**tk.BASE, x_lo=x_lo, x_hi=x_hi, n_slots=tk.n_slots(x_lo, x_hi),
                             drive_mode=layout.DRIVE_TORQUE, t_end=0.01)
    zero = tk.pp_arrays(PP.constant(0.0))
    for bad in (np.ones((layout.N_GEARS, tk.Z2, 1)), np.ones((3, tk.Z2, 4)), np.ones(tk.Z2)):
        with pytest.raises(ValueError, match="tooth_stiffness_factor"):
            kernel_model(prm, tables, drive_pp=zero, load_pp=zero, tooth_stiffness_factor=bad)
