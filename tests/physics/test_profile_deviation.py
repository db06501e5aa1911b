"""Per-tooth profile slope deviations f_Hα (issue 31; docs/theory.md §3.5): the kernel adds to
each tooth's gap the linear ramp of its mean profile line, positive f_Hα = more material at the
tip (ISO 1328-1 profile diagram); ``accuracy:`` fills them from the grade's draws.

The closed forms use the kernel's own gap computation (core/flank.flank) at a fixed mesh
deflection: with rigid engagement (zero gap inside the path) the no-load transmission error is
the largest material any pair in contact carries, max_j e_j (docs/theory.md §3.5)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.case.load import load_case
from gearcli.core.flank import Approach, Kinematics, flank
from gearcli.core.integrate import kernel_model, simulate
from gearcli.core.layout import (
    DRIVE_FLANKS,
    N_FAMILIES,
    N_SCRATCH,
    TABLE_G1,
    TABLE_G1_COAST,
    TABLE_G2,
    TABLE_G2_COAST,
    F,
    P,
)
from gearcli.model.accuracy import draw_deviations
from gearcli.model.errors import profile_slope_gaps
from gearcli.pipeline.geometry import run_geometry
from gearcli.pipeline.kernel_input import build_kernel_input
from tests.conftest import ROOT
from tests.unit.test_accuracy_grade import STUDY as GRADED_STUDY

SEED = ROOT / "cases" / "seed.yaml"
ISO_PAIR = ROOT / "cases" / "iso_pair.yaml"
F_HA_MM = 0.010  #: 10 µm, a grade-8 size deviation of the seed pair
DEFLECTION_MM = 0.02  #: a mesh deflection above every material the deviation adds (5 µm)


def _rigid_input(overrides):
    loaded = load_case(SEED, ["contact.engagement=rigid", "friction.enabled=false",
                              *overrides])
    geo = run_geometry(loaded)
    return geo.geometry, build_kernel_input(loaded.case, geo)


def _model(ki):
    return kernel_model(ki.params, ki.tables.tables, drive_pp=ki.drive_pp, load_pp=ki.load_pp,
                        drive_angle_pp=ki.drive_angle_pp, **ki.arrays)


def _no_load_te_mm(model, s1_mm: float) -> float:
    """The largest material [mm] of the pairs in contact at pinion roll s1 (the rigid, unloaded
    transmission error, positive = gear ahead): the kernel's largest penetration at a mesh
    deflection D less D."""
    n_slots = int(model.prm[P.n_slots])
    kin = Kinematics(s1_mm, 0.0, DEFLECTION_MM, 0.0, 0.0, 0.0, 0.0,
                     s1_mm / model.prm[P.r_b1], 0.0)
    res = flank(DRIVE_FLANKS, kin, Approach(0.0, 0.0, 0.0), model,
                np.zeros((N_FAMILIES, n_slots)), np.zeros((N_SCRATCH, n_slots)), True)
    return res.pen_max - DEFLECTION_MM


def _expected_te_mm(model, s1_mm: float, pinion_ramp, tooth: int) -> float:
    """Closed form: the slots' positions x_j = x_lo + u + j p_b with slot j holding pinion tooth
    (k1 + n − j) mod z1 (docs/theory.md §3.1); a pair touches when x_j ≤ x_hi and its gear
    position x_j − D ≥ x_lo. Every pair carries 0 but the deviating tooth, which carries
    ``pinion_ramp(x)``; the TE is the largest."""
    prm, fam = model.prm, model.family
    p_b, x_lo, x_hi, z1 = prm[P.p_b], prm[P.x_lo], prm[P.x_hi], int(prm[P.z1])
    r = s1_mm - fam[DRIVE_FLANKS, F.phase0]
    n = math.floor(r / p_b)
    u = r - n * p_b
    carried = []
    for j in range(int(prm[P.n_slots])):
        x = x_lo + u + j * p_b
        if x <= x_hi and x - DEFLECTION_MM >= x_lo:
            held = (int(fam[DRIVE_FLANKS, F.tooth_k1]) + n - j) % z1
            carried.append(pinion_ramp(x) if held == tooth else 0.0)
    return max(carried)


def test_one_tooth_profile_slope_gives_the_linear_ramp_of_the_rigid_transmission_error():
    tooth = 3
    values = [0.0] * 17
    values[tooth] = F_HA_MM
    g, ki = _rigid_input([f"errors.profile_slope_deviation.pinion={values}"])
    model = _model(ki)
    g_a = g.g_alpha_mm
    assert (model.prm[P.x_lo], model.prm[P.x_hi]) == pytest.approx((0.0, g_a), abs=1e-12)

    def ramp(x):  # e = f_Hα (ρ − L_α/2)/L_α, the pinion's ρ = x, L_α = g_α
        return F_HA_MM * (x - 0.5 * g_a) / g_a

    s1 = np.linspace(0.0, 17 * g.p_b_mm, 3401)  # one pinion revolution, 200 points a pitch
    te = np.array([_no_load_te_mm(model, s) for s in s1])
    expected = np.array([_expected_te_mm(model, s, ramp, tooth) for s in s1])
    # both are sums of a few doubles of size 1e-2 mm: round-off 1e-15 mm
    assert np.max(np.abs(te - expected)) < 1e-12
    # the ramp is seen once per revolution: positive over the tooth's tip half, where it leads
    # (up to f_Hα/2 at E), negative only in its single-pair zone (from g_α − p_b: the other
    # pairs carry 0 in the double zones), zero elsewhere
    # (sampling: 1/200 pitch moves the ramp by < 0.1 % of f_Hα; 1 % allowed)
    assert te.max() == pytest.approx(ramp(g_a), abs=F_HA_MM * 0.01)
    single_from = g_a - g.p_b_mm
    assert te.min() == pytest.approx(ramp(single_from), abs=F_HA_MM * 0.01)
    # the tooth is in contact over g_α of the 17 p_b of a revolution, non-zero on part of it
    assert 0 < np.count_nonzero(te) <= math.ceil(g.eps_alpha / 17 * s1.size) + 2


def test_positive_profile_slope_deviation_means_more_material_at_the_tip():
    """ISO 1328-1: the profile slope deviation is positive when the mean profile line rises
    toward the tip in the profile diagram (material plus upward, roll length toward the tip):
    the gap (material missing) falls toward each gear's tip — the pinion's at E (x = g_α), the
    gear's at A (x = 0) — and the pair touches earlier there."""
    g_a = 20.0
    table = profile_slope_gaps([F_HA_MM], [F_HA_MM], 0.0, g_a, g_a)
    for row in (TABLE_G1, TABLE_G1_COAST):  # pinion: tip at x_hi
        assert table[row, 0].tolist() == pytest.approx([0.5 * F_HA_MM, -0.5 * F_HA_MM])
    for row in (TABLE_G2, TABLE_G2_COAST):  # gear: tip at x_lo
        assert table[row, 0].tolist() == pytest.approx([-0.5 * F_HA_MM, 0.5 * F_HA_MM])
    # in the kernel: a gear tooth with positive f_Hα leads (TE > 0) when its tip is in
    # contact, at the start of the path A, and lags at its root end E if it is alone there
    values = [0.0] * 25
    values[0] = F_HA_MM
    g, ki = _rigid_input([f"errors.profile_slope_deviation.gear={values}"])
    model = _model(ki)
    s1 = np.linspace(0.0, 25 * g.p_b_mm, 5001)
    te = np.array([_no_load_te_mm(model, s) for s in s1])
    # the gear tooth leads most where it enters, its tip at A (gear position x2 = x1 − D = 0):
    # material f_Hα/2; it lags most at its root end alone in contact (single-pair zone)
    assert te.max() == pytest.approx(0.5 * F_HA_MM, abs=F_HA_MM * 0.01)
    # (the next pair touches from x1 = p_b + D: the lone gear tooth's last x2 = p_b)
    assert te.min() == pytest.approx(-F_HA_MM * (g.p_b_mm - 0.5 * g.g_alpha_mm)
                                     / g.g_alpha_mm, abs=F_HA_MM * 0.01)


def _simulate(ki, **extra):
    return simulate(ki.params, ki.tables.tables, t_out=ki.t_out, drive_pp=ki.drive_pp,
                    load_pp=ki.load_pp, drive_angle_pp=ki.drive_angle_pp, **ki.arrays, **extra)


def test_zero_profile_deviations_reproduce_a_tooth_law_run_bit_for_bit():
    """The tooth law (cases/iso_pair.yaml, extended engagement) through the profile path with
    a table of zeros: the same run, bit for bit; a deviation changes it."""
    loaded = load_case(ISO_PAIR, ["run.end_time=0.05"])
    ki = build_kernel_input(loaded.case, run_geometry(loaded))
    z_max = loaded.case.gears.gear.teeth
    plain = _simulate(ki)
    explicit = _simulate(ki, tooth_profile_gap=np.zeros((2, z_max, 2)))
    assert np.array_equal(plain.series, explicit.series, equal_nan=True)
    table = np.zeros((2, z_max, 2))
    table[0, 0] = (F_HA_MM / 2, -F_HA_MM / 2)  # pinion tooth 0, both flank families
    assert not np.array_equal(plain.series, _simulate(ki, tooth_profile_gap=table).series,
                              equal_nan=True)


def test_zero_profile_deviations_reproduce_the_run_bit_for_bit():
    _, ki = _rigid_input(["run.end_time=0.05"])
    _, zero = _rigid_input(["run.end_time=0.05",
                            f"errors.profile_slope_deviation.pinion={[0.0] * 17}"])
    assert "tooth_profile_gap" not in zero.arrays  # zeros: the kernel's path without them

    def run(**extra):
        return _simulate(ki, **extra)

    plain = run()
    z_max = 25
    explicit = run(tooth_profile_gap=np.zeros((4, z_max, 2)))  # the profile path, adding 0
    assert np.array_equal(plain.series, explicit.series, equal_nan=True)
    assert np.array_equal(plain.counters, explicit.counters)
    # a non-zero deviation does change the run (the test can fail)
    values = [0.0] * 17
    values[0] = F_HA_MM
    _, dev = _rigid_input(["run.end_time=0.05",
                           f"errors.profile_slope_deviation.pinion={values}"])
    changed = run(tooth_profile_gap=dev.arrays["tooth_profile_gap"])
    assert not np.array_equal(plain.series, changed.series, equal_nan=True)


def test_profile_list_length_and_bare_list_are_checked():
    with pytest.raises(Exception, match="one per tooth of the pinion"):
        load_case(SEED, ["errors.profile_slope_deviation.pinion=[0.001, 0.002]"])
    loaded = load_case(SEED, [f"errors.profile_slope_deviation.gear={['5 um'] * 25}"])
    assert loaded.case.errors.profile_slope_deviation.gear.values == pytest.approx(
        [0.005] * 25)


def test_accuracy_grade_fills_the_profile_slope_deviations_the_kernel_uses():
    loaded = load_case(ISO_PAIR, ["accuracy.grade=6", "accuracy.seed=1"])
    ps = loaded.case.errors.profile_slope_deviation
    assert (ps.pinion.iso1328_grade, ps.pinion.seed, ps.gear.seed) == (6, 1, 2)
    geo = run_geometry(loaded)
    ki = build_kernel_input(loaded.case, geo)
    g = geo.geometry
    f1 = draw_deviations(6, g.pinion.d_mm, g.module_mm, g.pinion.teeth, 1).profile_slope_um
    f2 = draw_deviations(6, g.gear.d_mm, g.module_mm, g.gear.teeth, 2).profile_slope_um
    expected = profile_slope_gaps(1e-3 * f1, 1e-3 * f2, ki.tables.x_lo, ki.tables.x_hi,
                                  g.g_alpha_mm)
    assert np.array_equal(ki.arrays["tooth_profile_gap"], expected)
    assert np.any(ki.arrays["tooth_offsets"] != 0.0)  # and the pitch deviations


#: the graded speed curve of test_accuracy_grade with seed 1, two speeds
STUDY = GRADED_STUDY.replace("accuracy.seed: 3", "accuracy.seed: 1")


def test_speed_curve_of_a_grade_runs_with_pitch_and_profile_deviations(tmp_path):
    from tests.physics.test_validity_same_everywhere import speed_curve_of

    curve = speed_curve_of(tmp_path, STUDY)
    assert not curve.errors
    assert curve.rows and all(np.isfinite(r.dynamic_factor) for r in curve.rows)
    assert curve.accuracy["grade"] == 6 and curve.accuracy["seed"] == 1
