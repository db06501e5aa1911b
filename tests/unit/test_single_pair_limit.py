"""The largest static force with one pair alone somewhere in the cycle (model/ltca.py
``single_pair_limit``, `gearcli mesh` ``sharing``; docs/theory.md §4b, "Corner contact").

Checked against (1) the LTCA it summarises: at 1.02 F* no roll position has one pair alone
(exact: F* is the maximum over the cycle), at 0.95 F* some have; (2) the independent
first-principles threshold of tests/physics/test_corner_gap_independent.py for 62/62 m 2
(w* = 47.4 N/mm there, from a numpy-only corner gap at the middle of the single-pair zone and
the law's stiffness); (3) a pair without a single-pair zone even unloaded (ε_α > 2, every
position has two pairs on the path): F* = 0.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.case.load import load_case
from gearcli.errors import GearcliError
from gearcli.pipeline.mesh import run_mesh
from tests.cli.test_modal_high_contact_ratio import HIGH_CONTACT
from tests.conftest import SEED
from tests.unit.test_modal_no_single_zone import ISO_PAIR, PAIR_62

CASES = {"62/62 m 2": (ISO_PAIR, PAIR_62), "seed": (SEED, None)}


def _share(loaded, force_N: float, points: int = 400) -> float:
    res = run_mesh(loaded, load_N=force_N, cycles=1, points_per_cycle=points)
    return float(np.mean(res.loaded.pairs_in_contact == 1))


@pytest.mark.parametrize("name", list(CASES))
def test_the_ltca_has_one_pair_alone_below_the_limit_and_never_above(name):
    source, overrides = CASES[name]
    loaded = load_case(source, overrides)
    res = run_mesh(loaded, cycles=1)
    f_star = res.single_pair_limit_N
    assert math.isfinite(f_star) and f_star > 0.0
    assert res.summary.sharing.single_pair_limit_N == pytest.approx(f_star, rel=1e-12)
    # above: no position can have one pair alone (F* is the maximum over every position)
    assert _share(loaded, 1.02 * f_star) == 0.0
    # below: the single-pair zone reopens (0.95: a zone several grid steps wide)
    assert _share(loaded, 0.95 * f_star) > 0.0


def test_62_62_limit_agrees_with_the_independent_threshold():
    """The independent w* of tests/physics/test_corner_gap_independent.py (corner gap from
    both involutes drawn point by point, 4.117 µm at 0.62 mm outside the path; the law's
    stiffness 230.5 N/µm of the loaded pair at the middle of the zone): 47.4 N/mm. gearcli's
    limit is the maximum over the whole zone, the reference the value at its middle, so the
    limit may exceed it slightly; 2 % covers that (the LTCA had one pair alone at 0.99 w*,
    none at 1.01 w*, on 200 points per cycle)."""
    res = run_mesh(load_case(ISO_PAIR, PAIR_62), cycles=1)
    w_star = res.summary.sharing.single_pair_limit_N_per_mm
    assert w_star == pytest.approx(47.4, rel=0.02)
    assert w_star < 0.25 * 200.0  # the pair's nominal 200 N/mm closes the zone


def test_a_pair_with_two_pairs_everywhere_has_no_single_pair_limit():
    """80/120 m 2, α 16°, rack addendum 1.35: no single-pair zone even unloaded."""
    res = run_mesh(load_case(ISO_PAIR, HIGH_CONTACT), cycles=1)
    sharing = res.summary.sharing
    assert sharing.single_pair_limit_N == 0.0
    assert sharing.single_pair_share == 0.0
    assert sharing.pairs_in_contact_min >= 2
    assert sharing.single_pair_limit_note.startswith("no load")


def test_a_limit_beyond_the_gap_tables_is_not_called_any_load():
    """A stub-toothed iso_pair (rack addendum 0.7, ε_α 1.13): at some roll positions the
    entering and the leaving neighbour both sit where the tip gap exceeds the gap tables' cap,
    so within the tables a second pair never touches (F* None). That is the contact model's
    range (cap max(0.05 m, 20 static deflections)), not "any load": the note says so and
    names the cap. With rigid engagement (no contact outside the path) "any load" is right."""
    stub = ["gears.rack={addendum: 0.7, dedendum: 1.0, root_radius: 0.25}"]
    res = run_mesh(load_case(ISO_PAIR, stub), cycles=1)
    sharing = res.summary.sharing
    assert sharing.single_pair_limit_N is None and sharing.single_pair_limit_N_per_mm is None
    assert "above the model's range" in sharing.single_pair_limit_note
    assert f"{res.tables_cap_mm:.3g} mm" in sharing.single_pair_limit_note
    assert res.tables_cap_mm >= 0.05 * 5.0  # module 5 mm
    rigid = run_mesh(load_case(ISO_PAIR, [*stub, "contact.engagement=rigid"]), cycles=1)
    assert rigid.summary.sharing.single_pair_limit_note.startswith("any load (rigid")
    finite = run_mesh(load_case(SEED), cycles=1).summary.sharing
    assert finite.single_pair_limit_N > 0.0 and finite.single_pair_limit_note == ""


def test_a_load_beyond_the_gap_tables_is_refused():
    """`gearcli mesh --load` far above the case's load: the loaded pair's penetration passes the
    gap tables' cap, so pairs whose tip gaps lie beyond it would touch but are left out (the
    seed at 10 MN reported a 21 mm STE and one pair alone on 35 % of the cycle, against its
    F* of 80 kN). Refused like a load without equilibrium."""
    loaded = load_case(SEED)
    with pytest.raises(GearcliError, match="leaves the contact tables"):
        run_mesh(loaded, load_N=1e7, cycles=1)
    res = run_mesh(loaded, load_N=1e5, cycles=1)  # above F*, inside the tables
    assert np.max(res.loaded.ste_mm - res.loaded.unloaded_te_mm) < res.tables_cap_mm
    assert not np.any(res.loaded.pairs_in_contact == 1)


def test_the_tooth_law_limit_does_not_depend_on_the_load_it_started_from():
    """With the tooth law F* is a fixed point (the contact secant depends on the load), solved
    from the law at the analysed force. Plain passes stopped at 1e-4 left the printed sixth
    digit to --load (107067 at 1e5 N, 107068 otherwise on iso_pair); solved to 1e-8 the starts
    agree to 1e-7 (the bounded search's own resolution, 1e-9 p_b in roll, is ~1e-9 in F)."""
    loaded = load_case(ISO_PAIR)
    limits = [run_mesh(loaded, load_N=f, cycles=1).single_pair_limit_N
              for f in (None, 0.01, 1e5)]
    assert limits[1] == pytest.approx(limits[0], rel=1e-7)
    assert limits[2] == pytest.approx(limits[0], rel=1e-7)


def test_harris_rows_outside_the_contact_tables_are_null_not_numbers():
    """The seed at 3e5 N is inside its gap tables (1.687 mm reach) but the Harris map's rows
    run to 2 x that load, where the mesh deflection (~2.5 mm) leaves them: those rows are
    None (null in mesh.json, a dash and a note in the table), the rows below stay numbers."""
    res = run_mesh(load_case(SEED), load_N=3e5, harris=True, cycles=1, points_per_cycle=100)
    ptp = res.summary.harris.ste_peak_to_peak_um
    assert ptp[0] is not None and ptp[-1] is None
    first_null = ptp.index(None)
    assert all(p is not None for p in ptp[:first_null])
    assert all(p is None for p in ptp[first_null:])  # deflection grows with the load
    doc = res.summary.to_dict()
    assert doc["harris"]["ste_peak_to_peak_um"][-1] is None


def test_62_62_with_tip_relief_keeps_its_single_pair_zone_and_a_rising_harris_map():
    """The design answer to extended contact (docs/theory.md §4b, "Corner contact"): tip
    relief C_a larger than the 16.5 µm the loaded pair alone deflects at 200 N/mm, here 30 µm
    over 2.5 mm of the path on both gears. The corners no longer touch, so the single-pair
    zone is back at the nominal load (measured: 58 % of the cycle, F* = 8521 N = 426 N/mm
    against the 3999 N applied) and the Harris map rises with load from 0.3 x on (below it the
    relief itself is the transmission error: the classic dip of a relieved pair, Harris 1958).
    Unmodified, the same pair has F* = 956 N (test above) and no single-pair zone."""
    relief = "{amount: 0.03 mm, length: 2.5 mm}"
    overrides = [*PAIR_62, f"modifications.tip_relief.pinion={relief}",
                 f"modifications.tip_relief.gear={relief}"]
    res = run_mesh(load_case(ISO_PAIR, overrides), harris=True)
    s = res.summary
    assert s.sharing.single_pair_share > 0.3
    assert s.sharing.single_pair_limit_N > 1.5 * s.force_N
    ptp = np.array(s.harris.ste_peak_to_peak_um)
    assert np.all(np.diff(ptp[2:]) > 0.0), ptp  # 0.3 x ... 2 x the load
