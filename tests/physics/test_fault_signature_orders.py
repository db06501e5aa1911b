"""The fault's signature repeats once per revolution of its gear (issue 30, Tests): a root
crack on a pinion tooth puts sidebands at the pinion's shaft order around the mesh harmonics of
the pinion's TSA, one on a gear tooth at the gear's order in the gear's TSA (docs/theory.md,
"Condition-monitoring signals" §3; `gearcli monitor`'s ``sidebands``).

Case: cases/iso_pair.yaml (21/43 teeth, 1500 rpm, 300 N*m), ramps shortened to 0.05 s, 0.4 s
run (steady window: 8 pinion and 4 gear revolutions); crack depth 4 mm at 45° (7 % of the mesh
stiffness, docs/theory.md "Tooth faults"). Signal: the TE from the shaft angles, no noise.
"""

from __future__ import annotations

import numpy as np
import pytest

from gearcli import api
from tests.conftest import ROOT

FAST = ["run.end_time=0.4",
        "drive.speed={function: 'STEP(time, 0, 0, 0.05, 1500)', unit: rpm}",
        "load.torque={function: 'STEP(time, 0, 0, 0.05, 300)', unit: N*m}"]
CRACK = "faults=[{{kind: root_crack, gear: {gear}, tooth: 2, depth: 4 mm, angle: 45 deg}}]"


@pytest.fixture(scope="module")
def sidebands(tmp_path_factory):
    """{run: {shaft: A_{z−1} + A_{z+1} of its TSA}} for healthy, pinion-cracked, gear-cracked."""
    out = {}
    for name, extra in (("healthy", []), ("pinion", [CRACK.format(gear="pinion")]),
                        ("gear", [CRACK.format(gear="gear")])):
        folder = tmp_path_factory.mktemp(name) / "run"
        api.simulate(ROOT / "cases" / "iso_pair.yaml", FAST + extra).save(folder)
        doc = api.monitor(folder)
        out[name] = {s.shaft: s.sidebands[0].amplitudes[2] + s.sidebands[0].amplitudes[4]
                     for s in doc.shafts}
        out[name]["doc"] = doc
    return out


@pytest.mark.parametrize("faulted, other", [("pinion", "gear"), ("gear", None)])
def test_sidebands_at_the_faulted_shafts_order(sidebands, faulted, other):
    healthy, cracked = sidebands["healthy"], sidebands[faulted]
    doc = cracked["doc"]
    shaft = next(s for s in doc.shafts if s.shaft == faulted)
    assert shaft.faulted_teeth == (2,) and shaft.n_revolutions >= 2
    row = shaft.sidebands[0]
    assert row.order == shaft.teeth and len(row.amplitudes) == 7
    # healthy: the ±1 sidebands are the discretisation's floor (~1e-4 of the mesh line); the
    # crack raises them by more than an order of magnitude on its own shaft
    growth = cracked[faulted] / healthy[faulted]
    assert growth > 10.0, (faulted, growth)
    # in the gear's orders the pinion's once-per-revolution signature sits at ±k z2/z1 =
    # ±2.05 k around the mesh harmonic, never near ±1: the gear's ±1 sidebands hardly move
    # (measured 1.9x against the pinion's 53x). The converse is not tested: in the pinion's
    # orders the gear's signature sits at ±k z1/z2 = ±0.488 k, and its second harmonic,
    # ±0.977, is so near ±1 that 8 revolutions pass it almost whole (monitoring §2:
    # |sin(8π·0.023)/(8 sin(0.023π))| = 0.98; measured: pinion 85x, gear 97x)
    if other is not None:
        assert cracked[other] / healthy[other] < growth / 4.0, (other, cracked[other]
                                                               / healthy[other])
    assert np.isfinite(shaft.value("fm4"))
