"""Tooth faults in the running kernel (docs/theory.md "Tooth faults"; model/faults,
pipeline/kernel_input.build_kernel_input(faults=...)).

* zero-size faults give the healthy run bit for bit (both laws);
* a missing pinion tooth carries no force in any slot that holds it, the others carry;
* a root crack on a pinion tooth, and one on a gear tooth, leave a signature (the difference
  of the dynamic mesh force to the healthy run) that peaks once per revolution of the faulted
  gear, at the same angle of that gear every revolution;
* the energy balance closes with a fault to the band of healthy runs.

Case: cases/iso_pair.yaml (tooth law, 21/43 teeth, 1500 rpm, 300 N*m), ramps shortened to
0.05 s so that the steady part holds several gear revolutions. Units: mm, N, s, rad.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.case.load import load_case
from gearcli.core.integrate import simulate
from gearcli.core.layout import P
from gearcli.model.faults import ChippedTip, MissingTooth, RootCrack, Spall
from gearcli.pipeline.geometry import run_geometry
from gearcli.pipeline.kernel_input import build_kernel_input
from gearcli.pipeline.simulate import energy_balance
from tests.conftest import ROOT

FAST = ["drive.speed={function: 'STEP(time, 0, 0, 0.05, 1500)', unit: rpm}",
        "load.torque={function: 'STEP(time, 0, 0, 0.05, 300)', unit: N*m}"]
T_STEADY = 0.1  # s: ramps end at 0.05 s, the mesh mode (zeta 0.07, ~1.8 kHz) has settled


def _run(overrides, faults=None, case="iso_pair.yaml"):
    loaded = load_case(ROOT / "cases" / case, overrides)
    geo = run_geometry(loaded)
    ki = build_kernel_input(loaded.case, geo, faults=faults)
    res = simulate(ki.params, ki.tables.tables, t_out=ki.t_out, drive_pp=ki.drive_pp,
                   load_pp=ki.load_pp, drive_angle_pp=ki.drive_angle_pp, **ki.arrays)
    assert res.ok, res.message
    return res, ki, geo


VOID = [RootCrack("pinion", 3, 0.0), Spall("gear", 5, 4.0, 0.0, 0.01, diameter_mm=200.0),
        ChippedTip("pinion", 7, 0.0, width=0.5), RootCrack("gear", 1, 2.0, width=0.0)]


@pytest.mark.parametrize("case, overrides", [
    ("iso_pair.yaml", [*FAST, "run.end_time=0.03"]),
    ("seed.yaml", ["run.end_time=0.02", "drive.speed=STEP(time, 0, 0, 0.005, 3000)",
                   "load.torque=STEP(time, 0, 0, 0.005, 4.5e+05)"]),
])
def test_zero_size_faults_are_the_healthy_run_bit_for_bit(case, overrides):
    plain, ki_plain, _ = _run(overrides, None, case)
    void, ki_void, _ = _run(overrides, VOID, case)
    assert "tooth_stiffness_factor" not in ki_void.arrays
    assert plain.column("force_total_N").max() > 100.0
    np.testing.assert_array_equal(plain.series, void.series)
    np.testing.assert_array_equal(plain.slot_force, void.slot_force)
    assert plain.counters == void.counters


def _slot_teeth(res, ki, geo):
    """Pinion tooth of every drive slot at every sample: (k1 + n − j) mod z1 (core/flank.py)."""
    prm, g = ki.params, geo.geometry
    r = res.column("theta1_rad") * g.pinion.r_b_mm - prm[P.s1_0]
    n = np.floor(r / g.p_b_mm).astype(int)
    j = np.arange(res.slot_force.shape[1])
    return (int(prm[P.tooth_k1]) + n[:, None] - j[None, :]) % g.pinion.teeth


SEED_FAST = ["drive.speed=STEP(time, 0, 0, 0.02, 3000)", "load.torque=STEP(time, 0, 0, 0.02, "
             "4.5e+05)", "run.end_time=0.25"]


@pytest.mark.parametrize("case, overrides", [("iso_pair.yaml", [*FAST, "run.end_time=0.16"]),
                                             ("seed.yaml", SEED_FAST)])
def test_a_missing_tooth_carries_nothing(case, overrides):
    """Pinion tooth 4 missing: every drive slot holding it has force exactly 0 (factor 0; the
    tooth law's damping share is proportional to the elastic force, docs/theory.md §4c, the
    IMPACT law's c_max is scaled by the factor, §4b.2); every other pinion tooth carries in
    some sample of the steady part. Both contact laws: iso_pair (tooth law), seed (IMPACT)."""
    res, ki, geo = _run(overrides, [MissingTooth("pinion", 4)], case)
    teeth = _slot_teeth(res, ki, geo)
    force = res.slot_force  # drive slots
    steady = res.column("t_s") > T_STEADY
    assert np.all(force[teeth == 4] == 0.0)
    assert (teeth[steady] == 4).sum() > 100  # the tooth passed through the slots
    carried = {int(t) for t in np.unique(teeth[steady][force[steady] > 1.0])}
    assert carried == set(range(geo.geometry.pinion.teeth)) - {4}


def _signature(faults, t_end):
    healthy, ki, geo = _run([*FAST, f"run.end_time={t_end}"])
    faulty, _, _ = _run([*FAST, f"run.end_time={t_end}"], faults)
    t = healthy.column("t_s")
    diff = np.abs(faulty.column("force_total_N") - healthy.column("force_total_N"))
    return t, diff, healthy, geo


@pytest.mark.parametrize("gear, tooth, t_end", [("pinion", 6, 0.30), ("gear", 30, 0.43)])
def test_a_crack_signature_repeats_once_per_revolution_of_its_gear(gear, tooth, t_end):
    """Root crack (depth 3 mm at 45°, full width) on one tooth: |F_faulty − F_healthy| over
    the steady part, cut into revolutions of the faulted gear (by its own angle). In every
    revolution the largest difference lies within ±1.5 mesh periods of the same gear angle
    (the faulted tooth's passage, ringing included), and it is at least 3 times the largest
    difference more than 4 mesh periods away from that angle (the mesh mode, ζ = 0.07 at
    ~1.8 kHz against 525 Hz mesh, rings down to e^(−2π·0.07·1.8/0.525·4) ≈ 0.2 % in 4
    periods). Measured: peaks within 6.4° (pinion, pitch 17.1°) and 0.05° (gear, pitch 8.4°)
    of each other; ratios 22-56 (pinion), 25-46 (gear)."""
    t, diff, healthy, geo = _signature([RootCrack(gear, tooth, 3.0, 45.0)], t_end)
    g = geo.geometry
    z = g.pinion.teeth if gear == "pinion" else g.gear.teeth
    theta = healthy.column("theta1_rad") if gear == "pinion" else \
        healthy.column("theta1_rad") * g.pinion.teeth / g.gear.teeth
    steady = t > T_STEADY
    rev = np.floor(theta / (2 * math.pi)).astype(int)
    whole = [k for k in np.unique(rev[steady]) if np.all(steady[rev == k])]
    assert len(whole) >= 2
    pitch = 2 * math.pi / z
    peaks = []
    for k in whole:
        sel = rev == k
        i = np.argmax(diff[sel])
        peaks.append(float(theta[sel][i] % (2 * math.pi)))
    spread = np.angle(np.exp(1j * (np.array(peaks) - peaks[0])))
    assert np.all(np.abs(spread) < 1.5 * pitch), (np.degrees(peaks), math.degrees(pitch))
    ratios = []
    for k in whole:
        sel = rev == k
        phase = np.angle(np.exp(1j * (theta[sel] - peaks[0])))
        near, far = np.abs(phase) <= 1.5 * pitch, np.abs(phase) > 4 * pitch
        ratios.append(diff[sel][near].max() / diff[sel][far].max())
    assert min(ratios) > 3.0, ratios


def test_the_energy_balance_closes_with_faults():
    """A crack, a spall and a missing tooth at once (impacts at every passage of the missing
    tooth): the energy balance's relative residual (pipeline.simulate.energy_balance,
    docs/theory.md §6.6) stays in the band of the healthy run's order (valid runs 1e-9 …
    1e-5, pipeline/validity.py), far below the validity limit 1e-3. Measured 1.2e-6 (healthy
    1.3e-7)."""
    overrides = [*FAST, "run.end_time=0.15"]
    faults = [RootCrack("pinion", 2, 4.0), MissingTooth("gear", 11),
              Spall("pinion", 9, 3.0, 0.6, 0.01, diameter_mm=115.0)]
    healthy, _, _ = _run(overrides)
    faulty, ki, _ = _run(overrides, faults)
    assert "tooth_stiffness_factor" in ki.arrays
    base = energy_balance(healthy).relative_residual
    got = energy_balance(faulty).relative_residual
    assert got < 1e-5, (got, base)


def test_a_case_file_fault_runs_through_the_pipeline():
    """``faults:`` in the case (as `gearcli simulate --set faults=...`): run_simulation uses
    them (the kernel gets the table that build_kernel_input(faults=records) makes), the run is
    valid and its summary's energy residual in the band above."""
    from gearcli.pipeline.simulate import run_simulation

    entry = "faults=[{kind: root_crack, gear: pinion, tooth: 2, depth: 3 mm, angle: 45 deg}]"
    res = run_simulation(ROOT / "cases" / "iso_pair.yaml", [*FAST, "run.end_time=0.12", entry],
                         zoom=False)
    table = res.kernel_input.arrays["tooth_stiffness_factor"]
    loaded = load_case(ROOT / "cases" / "iso_pair.yaml", [*FAST, "run.end_time=0.12"])
    ki = build_kernel_input(loaded.case, run_geometry(loaded),
                            faults=[RootCrack("pinion", 2, 3.0, 45.0)])
    np.testing.assert_allclose(table, ki.arrays["tooth_stiffness_factor"], rtol=1e-12, atol=0)
    assert table[0, 2].min() < 0.95 and np.all(np.delete(table, 2, axis=1)[0] == 1.0)
    assert res.status == "ok", res.invalid_reason
    assert res.summary.energy_balance.relative_residual < 1e-5


def test_given_factors_multiply_the_faults():
    """build_kernel_input with a table of the caller's and faults: the product, the caller's
    two rows serving both flank families (a table of 2.0 doubles every fault factor)."""
    loaded = load_case(ROOT / "cases" / "iso_pair.yaml")
    geo = run_geometry(loaded)
    faults = [RootCrack("gear", 4, 3.0), ChippedTip("pinion", 2, 1.0, 0.5)]
    alone = build_kernel_input(loaded.case, geo, faults=faults).arrays["tooth_stiffness_factor"]
    given = np.full((2, 43, alone.shape[2]), 2.0)
    both = build_kernel_input(loaded.case, geo, tooth_stiffness_factor=given, faults=faults)
    np.testing.assert_array_equal(both.arrays["tooth_stiffness_factor"], 2.0 * alone)
    flat = build_kernel_input(loaded.case, geo, tooth_stiffness_factor=np.full((2, 43), 2.0),
                              faults=faults)
    np.testing.assert_array_equal(flat.arrays["tooth_stiffness_factor"], 2.0 * alone)
