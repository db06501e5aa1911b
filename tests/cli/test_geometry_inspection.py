"""`gearcli geometry`: the inspection dimensions section (issue 28): span W_k, balls, M_dK,
chordal thickness/height at the nominal thickness and the allowances, in the JSON and table.

Anchor: the KISSsoft 03/2017 printout of the NREL 5 MW sun–planet mesh
(tests/data/kisssoft_nrel5mw_stage02.txt, cases/nrel5mw_sun_planet.yaml): W_k 165.869/296.803
(k 3/5) and M_dK 466.306/836.492 (balls 45/40 mm), each printed to 0.001 mm: the tolerance is
half a unit of the last printed digit."""

import json
import math

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import ROOT, SEED

runner = CliRunner()
NREL = ROOT / "cases" / "nrel5mw_sun_planet.yaml"
HALF_PRINTED_DIGIT = 0.0005  # mm
# (z, x) of sun and planet, m_n 21 mm, α 20° (the printout; the planet's x = Σx − x1 from
# a = 584 mm, as the case file gives it)
SUN, PLANET, M, ALPHA = (18, 0.389), (36, 0.5038693866260261), 21.0, math.radians(20.0)


def _inv(a: float) -> float:
    return math.tan(a) - a


def _span_hand(z: int, x: float, k: int) -> float:
    """W_k = m cos α [π (k − 0.5) + z inv α] + 2 x m sin α (ISO 21771 / Niemann-Winter)."""
    return M * math.cos(ALPHA) * (math.pi * (k - 0.5) + z * _inv(ALPHA)) + 2 * x * M * math.sin(
        ALPHA)


def _over_balls_hand(z: int, x: float, ball: float) -> float:
    """inv α_K = inv α + D_M/(z m cos α) − π/(2z) + 2 x tan α / z; d_K = z m cos α / cos α_K;
    M_dK = d_K + D_M (even z), d_K cos(90°/z) + D_M (odd z) (ISO 21771, Niemann-Winter)."""
    target = _inv(ALPHA) + ball / (z * M * math.cos(ALPHA)) - math.pi / (2 * z) + (
        2 * x * math.tan(ALPHA) / z)
    lo, hi = 0.0, 1.5
    for _ in range(200):  # bisection on the monotonic inv
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _inv(mid) < target else (lo, mid)
    d_k = z * M * math.cos(ALPHA) / math.cos(0.5 * (lo + hi))
    return (d_k if z % 2 == 0 else d_k * math.cos(math.pi / (2 * z))) + ball


@pytest.fixture(scope="module")
def nrel() -> dict:
    result = runner.invoke(app, ["geometry", str(NREL), "--json"])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)["inspection"]


@pytest.mark.parametrize(("gear", "zx", "k", "w_k", "ball", "m_dk"), [
    ("pinion", SUN, 3, 165.869, 45.0, 466.306),
    ("gear", PLANET, 5, 296.803, 40.0, 836.492),
])
def test_span_and_over_balls_against_printout_and_hand(nrel, gear, zx, k, w_k, ball, m_dk):
    g = nrel[gear]
    assert g["span_teeth"] == k
    assert g["ball_mm"] == ball
    assert g["span_mm"][0] == pytest.approx(w_k, abs=HALF_PRINTED_DIGIT)
    assert g["over_balls_mm"][0] == pytest.approx(m_dk, abs=HALF_PRINTED_DIGIT)
    # closed forms written here (not the code under test), to round-off
    assert g["span_mm"][0] == pytest.approx(_span_hand(*zx, k), rel=1e-12)
    assert g["over_balls_mm"][0] == pytest.approx(_over_balls_hand(*zx, ball), rel=1e-10)


def test_allowances_thin_the_tooth(nrel):
    """A thinner tooth (allowance A_sn < 0) shortens W_k by |A_sn| cos α (span over flanks
    normal to them) and M_dK; the order nominal > upper > lower holds for every dimension."""
    for gear in ("pinion", "gear"):
        g = nrel[gear]
        upper, lower = g["thickness_allowances_mm"]
        assert g["span_mm"][1] - g["span_mm"][0] == pytest.approx(upper * math.cos(ALPHA),
                                                                  rel=1e-9)
        assert g["span_mm"][2] - g["span_mm"][0] == pytest.approx(lower * math.cos(ALPHA),
                                                                  rel=1e-9)
        for key in ("span_mm", "over_balls_mm", "chordal_thickness_mm"):
            nominal, up, low = g[key]
            assert nominal > up > low, (gear, key)
        assert g["ball_theoretical_mm"] <= g["ball_mm"]


def test_table_and_seed_json():
    table = runner.invoke(app, ["geometry", str(NREL)])
    assert table.exit_code == 0, table.output
    assert "Inspection dimensions" in table.stdout and "466.306" in table.stdout
    seed = json.loads(runner.invoke(app, ["geometry", str(SEED), "--json"]).stdout)
    ins = seed["inspection"]
    assert set(ins) == {"pinion", "gear"}
    # the seed gives no allowances: all three columns are the nominal tooth
    assert ins["pinion"]["thickness_allowances_mm"] == [0.0, 0.0]
    assert len(set(ins["gear"]["over_balls_mm"])) == 1
