"""The rigid tip-corner gap outside the path of contact, computed a second time from first
principles, and the line load w* below which a high-contact-ratio pair keeps a single-pair zone
(docs/theory.md §3.3 and §4b, "Corner contact").

The reference (first section of this file) uses numpy and math only, from the raw numbers of a
standard unmodified pair (z1, z2, m, α; zero profile shift, zero backlash, h_a* = 1, sharp tip
corners): two involutes drawn point by point, rigid rotations, the signed distance of the tip
corner to the mate's involute by a brute-force closest-point search, and the deflection that
closes it by bisection. It never calls gearcli's geometry, profile or gap code and never uses
the polar-angle closed form r_b (ψ_Q − ψ_flank(R_Q)) of gearcli/model/gap.py.

Frame: O1 = (0, 0), O2 = (a, 0), the line of action (LoA) from T1 = r_b1 (cos α, sin α) in the
direction d = (sin α, −cos α) to T2 = O2 − r_b2 (cos α, sin α). An involute of base radius
r_b about O, unwound from polar angle γ0, is P(t) = O + r_b (cos γ + t sin γ, sin γ − t cos γ),
γ = γ0 + t (t the roll angle); its normal at P(t) is the base tangent (−sin γ, cos γ). With
γ0,1 = α − L1/r_b1 the pinion's drive involute crosses the LoA at distance L1 from T1; with
γ0,2 = α + π − L2/r_b2 the gear's crosses it at distance L2 from T2 (towards T1). Rigid
conjugate meshing is L1 + L2 = |T1T2|; the mesh deflection along the LoA is
δ = L1 + L2 − |T1T2| (δ > 0: the gear lags, r_b2 times its lag angle when the pinion is held).
The roll position of a pair is x = L1 − |T1A| (gearcli's x, from the start of active contact A).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.case.load import load_case
from gearcli.core.gaptable import hermite_many
from gearcli.core.layout import TABLE_G1, TABLE_G2
from gearcli.pipeline.geometry import run_geometry
from gearcli.pipeline.kernel_input import case_gap_tables
from gearcli.pipeline.mesh import run_mesh
from gearcli.pipeline.mesh_input import case_mesh, tooth_stiffness
from tests.conftest import SEED
from tests.unit.test_modal_no_single_zone import ISO_PAIR, PAIR_62


# --- the independent reference: numpy and math only ------------------------------------------
class StandardPair:
    """A standard spur pair from its raw numbers [mm, deg] (ISO 21771 standard quantities)."""

    def __init__(self, z1: int, z2: int, m: float, alpha_deg: float):
        self.alpha = math.radians(alpha_deg)
        self.r_b = (0.5 * m * z1 * math.cos(self.alpha), 0.5 * m * z2 * math.cos(self.alpha))
        self.r_a = (0.5 * m * z1 + m, 0.5 * m * z2 + m)  # h_a* = 1, no shift
        self.a = 0.5 * m * (z1 + z2)  # zero backlash: operating α = α
        self.centre = (np.zeros(2), np.array([self.a, 0.0]))
        self.T1T2 = self.a * math.sin(self.alpha)
        self.T1E = math.sqrt(self.r_a[0] ** 2 - self.r_b[0] ** 2)  # pinion tip on the LoA
        self.T2A = math.sqrt(self.r_a[1] ** 2 - self.r_b[1] ** 2)  # gear tip on the LoA
        self.T1A = self.T1T2 - self.T2A
        self.g_alpha = self.T1E - self.T1A
        self.p_b = math.pi * m * math.cos(self.alpha)

    def tip_roll(self, gear: int) -> float:
        """Roll angle t of the tip corner on the drive involute of ``gear`` (0 pinion, 1 gear)."""
        return math.sqrt((self.r_a[gear] / self.r_b[gear]) ** 2 - 1.0)

    def gamma0(self, gear: int, roll_mm: float) -> float:
        """γ0 of the drive involute of ``gear`` crossing the LoA ``roll_mm`` from its own T."""
        if gear == 0:
            return self.alpha - roll_mm / self.r_b[0]
        return self.alpha + math.pi - roll_mm / self.r_b[1]


def involute_point(centre, r_b: float, gamma0: float, t):
    """P(t) = O + r_b (cos γ + t sin γ, sin γ − t cos γ), γ = γ0 + t, shape (2,) or (2, n)."""
    g = gamma0 + np.asarray(t, float)
    v = r_b * np.array([np.cos(g) + t * np.sin(g), np.sin(g) - t * np.cos(g)])
    return v + (centre[:, None] if v.ndim == 2 else centre)


def signed_distance(pair: StandardPair, q, mate: int, gamma0: float) -> tuple[float, float]:
    """(distance [mm] of point q from the mate's drive involute, > 0 free, < 0 inside the
    mate's tooth; roll angle t of the closest point). The closest point is found by brute force
    (4001 samples up to 1.5 times the tip's roll angle), then refined by bisection on the
    foot-of-perpendicular condition (q − P(t))·P'(t) = 0, P'(t) = r_b t (cos γ, sin γ). The
    mate's outward normal at P(t) is −(−sin γ, cos γ) for both gears in this frame."""
    c, rb = pair.centre[mate], pair.r_b[mate]
    t = np.linspace(0.0, 1.5 * pair.tip_roll(mate), 4001)
    pts = involute_point(c, rb, gamma0, t)
    i = int(np.argmin(np.hypot(q[0] - pts[0], q[1] - pts[1])))
    lo, hi = float(t[max(i - 1, 0)]), float(t[min(i + 1, t.size - 1)])

    def foot(tt: float) -> float:
        d = q - involute_point(c, rb, gamma0, tt)
        return d[0] * math.cos(gamma0 + tt) + d[1] * math.sin(gamma0 + tt)

    f_lo = foot(lo)
    assert f_lo * foot(hi) < 0.0, "the closest point is not inside the sampled range"
    for _ in range(100):  # to the last bit of t (~1e-16 rad, 1e-14 mm on the flank)
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        f_mid = foot(mid)
        if (f_mid > 0.0) == (f_lo > 0.0):
            lo, f_lo = mid, f_mid
        else:
            hi = mid
    tt = 0.5 * (lo + hi)
    g = gamma0 + tt
    d = q - involute_point(c, rb, gamma0, tt)
    return -(-d[0] * math.sin(g) + d[1] * math.cos(g)), tt


def corner_distance(pair: StandardPair, L1: float, L2: float, approach: bool
                    ) -> tuple[float, float]:
    """Signed distance [mm] of a tip corner to the mate's flank and the roll angle of its foot
    on the mate, the pinion's flank crossing the LoA L1 from T1 and the gear's L2 from T2:
    ``approach`` (before A) the gear's corner against the pinion's involute, else (after E)
    the pinion's corner against the gear's."""
    g01, g02 = pair.gamma0(0, L1), pair.gamma0(1, L2)
    if approach:
        q = involute_point(pair.centre[1], pair.r_b[1], g02, pair.tip_roll(1))
        return signed_distance(pair, q, 0, g01)
    q = involute_point(pair.centre[0], pair.r_b[0], g01, pair.tip_roll(0))
    return signed_distance(pair, q, 1, g02)


def touch_deflection(pair: StandardPair, x_mm: float, hold: str = "pinion") -> float:
    """The mesh deflection δ [mm] that brings the tip corner of a pair at roll position x
    (outside the path) into contact with the mate's flank, by bisection on the signed distance
    (to 1e-15 mm). ``hold`` "pinion": the pinion stays at x and the gear lags, δ = r_b2 Δφ2
    (what a loaded mesh does at a given pinion angle); "corner": the gear that carries the
    corner stays at x and the mate turns (δ = r_b,mate Δφ, the gap along the mate's involute
    normal)."""
    L = pair.T1A + x_mm
    approach = x_mm < 0.0  # before A the corner is the gear's, after E the pinion's

    def dist(d: float) -> float:
        if approach and hold == "corner":  # the gear held, the pinion advances by d
            return corner_distance(pair, L + d, pair.T1T2 - L, approach)[0]
        return corner_distance(pair, L, pair.T1T2 - L + d, approach)[0]  # the gear lags by d

    lo, hi = 0.0, 1e-3
    assert dist(lo) > 0.0, "the corner is not free at zero deflection"
    while dist(hi) > 0.0:
        lo, hi = hi, 2.0 * hi
    while hi - lo > 1e-15:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (mid, hi) if dist(mid) > 0.0 else (lo, mid)
    return 0.5 * (lo + hi)


def quadratic_coefficient(pair: StandardPair, end: str) -> float:
    """Leading-order closed form [1/mm] of the tip gap g ≈ c s² at a distance s outside the
    path. At roll x outside the path the two (extended) involutes touch on the LoA at P, with
    radii of curvature ρ1 = |T1P|, ρ2 = |T2P| (an involute's radius of curvature is its roll
    length); two convex curves touching at P separate as h = ½ (1/ρ1 + 1/ρ2) σ² at arc
    distance σ from P (the gap of two non-conforming bodies, K. L. Johnson, Contact
    Mechanics, CUP 1985, §4.1). The real tooth ends at its tip corner, an arc σ from P along its
    own involute: the arc length of an involute between roll lengths u_a, u_b is
    (u_b² − u_a²)/(2 r_b) (ds = r_b t dt), so σ = s (2 u_tip + s)/(2 r_b) ≈ s tan α_a.
    Hence c = ½ tan² α_a (1/ρ1 + 1/ρ2) with α_a the corner's pressure angle and ρ at A (gear
    corner: tan α_a2 = |T2A|/r_b2, ρ1 = |T1A|, ρ2 = |T2A|) or at E (pinion corner)."""
    if end == "approach":
        tan_a, rho1, rho2 = pair.T2A / pair.r_b[1], pair.T1A, pair.T2A
    else:
        tan_a, rho1, rho2 = pair.T1E / pair.r_b[0], pair.T1E, pair.T1T2 - pair.T1E
    return 0.5 * tan_a**2 * (1.0 / rho1 + 1.0 / rho2)


# --- the pairs: raw numbers for the reference, the case (loader) for gearcli -----------------
PAIR_28 = ["gears.module=3.175 mm", "gears.face_width=6.35 mm", "gears.pinion.teeth=28",
           "gears.gear.teeth=28", "gears.pinion.profile_shift=0", "gears.gear.profile_shift=0",
           'load.torque={function: "STEP(time, 0, 0, 0.2, 53)", unit: N*m}']  # ~200 N/mm
PAIRS = {
    "62/62 m 2": ((62, 62, 2.0, 20.0), ISO_PAIR, PAIR_62),
    "seed 17/25 m 10": ((17, 25, 10.0, 20.0), SEED, None),
    "28/28 m 3.175": ((28, 28, 3.175, 20.0), ISO_PAIR, PAIR_28),
}
OUTSIDE_MM = (0.2, 0.4, 0.62, 0.9, 1.2)  # distance s outside the path [mm]

#: Reference vs gearcli [mm]. Reference: bisection to 1e-15 mm, coordinates of ~100 mm
#: rounded at ~1e-14 mm. gearcli: cubic Hermite on a grid of p_b/1500 (h = 3.9 µm on 62/62,
#: 19.7 µm on the seed), error ≤ h⁴/384 max|G''''| (Burden & Faires §3.4): G ≈ c s²
#: (ρ1/(ρ1 − s)) near the narrow end gives G'''' ≈ 24 c ρ1²/(ρ1 − s)⁵ ≈ 0.1 /mm³ on the seed
#: 1.2 mm before A (ρ1 = |T1A| = 5.3 mm), so ≤ 4e-11 mm; the table slopes' central
#: differences (step 1e-5 mm) add ≤ (4/27) h 2 ε_G / 1e-5 ≈ 1e-12 mm. Bound 1e-9 mm, ten
#: times the sum. Measured: ≤ 3.1e-11 mm (seed), ≤ 1.0e-12 mm (62/62, 28/28).
GAP_TOL_MM = 1e-9


@pytest.fixture(scope="module", params=list(PAIRS), ids=list(PAIRS))
def pair_tables(request):
    raw, source, overrides = PAIRS[request.param]
    loaded = load_case(source, overrides)
    geo = run_geometry(loaded)
    tables, _ = case_gap_tables(loaded.case, geo, case_mesh(loaded.case, geo))
    return StandardPair(*raw), tables, geo.geometry


def _table(tables, k: int, x_mm: float) -> float:
    """gearcli's gap G_k(x) [mm]: the kernel's interpolant of the case's tables."""
    value, slope = np.empty(1), np.empty(1)
    hermite_many(tables.tables, k, tables.x_lo, tables.x_hi, np.array([x_mm]), value, slope)
    return float(value[0])


def _ltca_touch(tables, x_mm: float) -> float:
    """δ [mm] at which gearcli's pair at pinion roll x touches: the root of
    δ = G1(x) + G2(x − δ) (model/ltca.py, equation (1) with p = 0), by fixed-point iteration
    (|G2'| ≤ 0.1 outside the path here: a contraction)."""
    g1, d = _table(tables, TABLE_G1, x_mm), 0.0
    for _ in range(100):
        d_new = g1 + _table(tables, TABLE_G2, x_mm - d)
        if abs(d_new - d) < 1e-16:
            break
        d = d_new
    return d_new


def test_reference_phasing_closes_at_the_path_ends():
    """The reference's own check of its phasing: in the rigid configuration at A (E) the
    gear's (pinion's) corner lies on the mate's involute (distance at round-off, < 1e-11 mm)
    and the flanks are tangent there (the foot is the LoA point, roll |T1A| on the pinion,
    |T2E| on the gear); 1 µm of roll outside the path the corner is free, for all three
    pairs."""
    for raw, _, _ in PAIRS.values():
        p = StandardPair(*raw)
        for L1, approach, mate, u in ((p.T1A, True, 0, p.T1A),
                                      (p.T1E, False, 1, p.T1T2 - p.T1E)):
            dist, t_foot = corner_distance(p, L1, p.T1T2 - L1, approach)
            assert abs(dist) < 1e-11
            assert p.r_b[mate] * t_foot == pytest.approx(u, abs=1e-6)
            step = -1e-3 if approach else 1e-3
            assert corner_distance(p, L1 + step, p.T1T2 - L1 - step, approach)[0] > 0.0


@pytest.mark.parametrize("s", OUTSIDE_MM)
def test_corner_gap_independent_against_gearcli(pair_tables, s):
    """The deflection at which a corner s outside the path touches, reference vs gearcli,
    both ends, two definitions: with the pinion held (the loaded contact's, model/ltca.py)
    and with the corner's own gear held (the table value G(x) itself, docs/theory.md §3.2).
    Measured [µm] on 62/62 m 2 (approach pinion-held / corner-held; recess both):
    s = 0.2: 0.4213 / 0.4196, 0.4196; 0.4: 1.7081 / 1.6935, 1.6935; 0.62: 4.1651 / 4.1089,
    4.1089; 0.9: 8.9453 / 8.7667, 8.7667; 1.2: 16.2334 / 15.7918, 15.7918 — gearcli equal to
    ≤ 1e-12 mm. The foot of the contact lies on the mate's active flank (between A's radius
    and the tip), so the involute model of the mate is the real flank there."""
    p, tables, g = pair_tables
    assert p.T1A == pytest.approx(g.A_mm, abs=1e-9)
    assert p.g_alpha == pytest.approx(g.g_alpha_mm, abs=1e-9)
    for x in (-s, p.g_alpha + s):
        ref_ltca = touch_deflection(p, x, "pinion")
        ref_table = touch_deflection(p, x, "corner")
        k_table = TABLE_G2 if x < 0.0 else TABLE_G1
        assert _ltca_touch(tables, x) == pytest.approx(ref_ltca, abs=GAP_TOL_MM), (x, "ltca")
        assert _table(tables, k_table, x) == pytest.approx(ref_table, abs=GAP_TOL_MM), x
        # the contact point is on the mate's active flank: roll length between the start of
        # active profile (A on the pinion, E on the gear) and the tip
        L = p.T1A + x
        _, t_foot = corner_distance(p, L, p.T1T2 - L + ref_ltca, x < 0.0)
        mate = 0 if x < 0.0 else 1
        u_start = p.T1A if mate == 0 else p.T1T2 - p.T1E
        assert u_start < p.r_b[mate] * t_foot < p.r_b[mate] * p.tip_roll(mate)


def test_leading_order_closed_form_of_the_corner_gap():
    """The reference's gap over s² tends to the closed form ½ tan² α_a (1/ρ1 + 1/ρ2) as s → 0
    (:func:`quadratic_coefficient`), at both ends of the three pairs. Richardson's linear
    extrapolation from s = 5 and 10 µm leaves a term of order (s/ρ1)² ≤ 4e-6 times a
    coefficient of order 1 to 10 (measured: ≤ 1.7e-5 on the seed's approach, ≤ 4e-7
    elsewhere); the reference's round-off is 1e-14 mm on gaps of > 1e-7 mm. Bound 1e-4.
    The leading order alone at the distances above (reference, pinion held): 62/62 within
    0.3 % (s = 0.2 mm) … 2.6 % (1.2 mm), 28/28 within 1 … 14 %, seed recess 1 … 5 %, seed
    approach 8 … 47 % (ρ1 = |T1A| = 5.3 mm is short: the pinion's involute curvature changes
    fast near its base circle), so the closed form checks the reference's scale, not its
    values at 0.62 mm."""
    for raw, _, _ in PAIRS.values():
        p = StandardPair(*raw)
        for end, x_end, sign in (("approach", 0.0, -1.0), ("recess", p.g_alpha, 1.0)):
            for hold in ("pinion", "corner"):
                q1 = touch_deflection(p, x_end + sign * 0.005, hold) / 0.005**2
                q2 = touch_deflection(p, x_end + sign * 0.010, hold) / 0.010**2
                assert 2.0 * q1 - q2 == pytest.approx(quadratic_coefficient(p, end), rel=1e-4)


def test_single_pair_zone_exists_only_below_the_threshold_load():
    """62/62 m 2 b 20 (ε_α 1.79). In the middle of the single-pair zone (x = g_α/2) the
    neighbours are p_b − g_α/2 = 0.62 mm outside the path; the loaded pair alone deflects
    δ = w b / k(g_α/2), k the tooth law's pair stiffness at that load (a secant, §4b). The
    neighbours stay free while δ is below the smaller of their touch deflections (reference,
    pinion held: 4.117 µm leaving, 4.173 µm entering), so the single-pair zone exists only
    below w* = g_mid k(g_α/2, w*) / b. That onset does not depend on the corner's own
    stiffness (a corner touches at zero force whatever its stiffness; a soft corner only
    takes less load once touching). Measured: w* = 47.4 N/mm (0.237 of 200 N/mm), k = 230.5
    N/µm (11.5 N/(mm·µm)); gearcli's LTCA: single-pair share 0.06 / 0.035 / 0.01 / 0.005 at
    0.5 / 0.7 / 0.9 / 0.99 w* (200 points per cycle), 0 from 1.01 w* on. Asserted: share > 0
    at 0.7 and 0.9 w*, = 0 at 1.1 and 1.5 w* (400 points per cycle: at 0.9 w* the zone is
    ~0.06 mm wide, four grid points), and w* below half the nominal load."""
    loaded = load_case(ISO_PAIR, PAIR_62)
    geo = run_geometry(loaded)
    p = StandardPair(62, 62, 2.0, 20.0)
    b = 20.0
    out = p.p_b - 0.5 * p.g_alpha
    g_mid = min(touch_deflection(p, -out), touch_deflection(p, p.g_alpha + out))
    w = 200.0
    for _ in range(50):
        k = float(tooth_stiffness(loaded.case, geo, [0.5 * p.g_alpha], w * b).k_N_mm[0])
        w, w_old = g_mid * k / b, w
        if abs(w - w_old) < 1e-9 * w:
            break
    assert w < 0.5 * 200.0
    for frac, single in ((0.7, True), (0.9, True), (1.1, False), (1.5, False)):
        res = run_mesh(loaded, load_N=frac * w * b, cycles=1, points_per_cycle=400)
        share = float(np.mean(res.loaded.pairs_in_contact == 1))
        assert (share > 0.0) == single, (frac, share)
