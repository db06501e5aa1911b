"""ISO 6336 rating (gearcli/model/iso6336) against the KISSsoft 03/2017 ISO 6336:2006 Method B
printout of the NREL 5 MW spur planetary stage (tests/data/kisssoft_nrel5mw_stage02.txt, from
github.com/gfsReboucas/Drivetrain, @NREL_5MW/stage_02.rtf): the sun–planet mesh, every printed
factor to its printed digits. The other tests/unit/test_iso6336_*.py files import
:func:`make_input` and :func:`printed` from here.

Inputs as printed: z 18/36, m_n 21, α 20°, a 584, b 550, x1 0.3890, x2 = Σx − x1 with Σx from
the centre distance (printed 0.8929 and 0.5039), d_a 432.838/815.663 (tip shortening included),
basic rack 1.25/0.38/1.0, case-hardened 18CrNiMo7-6 with σ_Hlim 1500, σ_Flim 430 (KISSsoft's
values, given), E 206000, ν 0.3, R_zH 4.8, R_zF 20, ν40 220 mm²/s, K_A 1.25, K_γ 1.10,
K_v 1.06, K_Hβ 2.06 (user), c_γα 15.640, f_pb 16.90/17.90 µm, S_Hmin 1.25, S_Fmin 1.56, life
175200 h, thickness allowances −0.130/−0.190 and −0.175/−0.255 mm. The sun is the pinion
(three contacts per revolution), the planet an idler. Load per planet: F_t = 285900.438 N
(printed), i.e. T1 = F_t d1/2000. Speed relative to the carrier: n1 = N_L/(60 L_h 3) with the
printed N_L = 7782.3·10⁶ (246.775 min⁻¹; the printed 294.5 − 47.8 = 246.7 carries the speeds'
rounding to 0.1 min⁻¹).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from gearcli.model.iso6336 import bending as b3
from gearcli.model.iso6336 import pitting as p2
from gearcli.model.iso6336.common import Edition, involute
from gearcli.model.iso6336.factors import bending_face_load_factor, running_in_profile
from gearcli.model.iso6336.inputs import GearInput, RatingInput
from gearcli.model.iso6336.inspection import chordal_height, chordal_thickness
from gearcli.model.iso6336.life import bending_life_curve, pitting_life_curve
from gearcli.model.iso6336.material import MaterialKind, Quality
from gearcli.model.iso6336.rate import pair_geometry, rate

PRINTOUT = Path(__file__).resolve().parents[1] / "data" / "kisssoft_nrel5mw_stage02.txt"
F_T_N = 285900.438
LIFE_H = 175200.0
N_L_SUN = 7782.3e6
SPEED_SUN_RPM = N_L_SUN / (60.0 * LIFE_H * 3.0)
ALPHA = math.radians(20.0)
# Σx from a = 584: inv α_w = inv α + 2 Σx tan α/(z1 + z2), cos α_w = 567 cos α/584.
SUM_X = ((involute(math.acos(567.0 * math.cos(ALPHA) / 584.0)) - involute(ALPHA)) * 54.0
         / (2.0 * math.tan(ALPHA)))
X1 = 0.389
X2 = SUM_X - X1


def printed(tag: str) -> list[str]:
    """The numbers printed after ``[tag]`` on its first line of the printout, as strings."""
    for line in PRINTOUT.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):
            continue
        key = f"[{tag}]"
        if key in line:
            return re.findall(r"-?\d+\.\d+(?:e[+-]?\d+)?|-?\d+(?:e[+-]?\d+)?",
                              line.split(key, 1)[1])
    raise KeyError(tag)


def within_print(value: float, text: str, extra_rel: float = 0.0) -> bool:
    """True when ``value`` rounds to the printed ``text`` (half a unit of its last digit, plus
    ``extra_rel`` × value where a test states why)."""
    decimals = len(text.split(".")[1]) if "." in text else 0
    return abs(value - float(text)) <= 0.5 * 10.0 ** -decimals * (1 + 1e-9) + extra_rel * abs(value)


def make_input(edition: Edition = Edition.ISO2006, **changes) -> RatingInput:
    common = {"face_width_mm": 550.0, "material": MaterialKind.CASE_HARDENED,
              "quality": Quality.MQ, "sigma_h_lim_MPa": 1500.0, "sigma_f_lim_MPa": 430.0,
              "youngs_MPa": 206000.0, "poisson": 0.3, "flank_roughness_rz_um": 4.8,
              "root_roughness_rz_um": 20.0, "accuracy_grade": 6}
    sun = GearInput(teeth=18, profile_shift=X1, tip_diameter_mm=432.838,
                    base_pitch_deviation_um=16.90, contacts_per_revolution=3.0,
                    thickness_allowances_mm=(-0.130, -0.190), **common)
    planet = GearInput(teeth=36, profile_shift=X2, tip_diameter_mm=815.663,
                       base_pitch_deviation_um=17.90, idler=True,
                       thickness_allowances_mm=(-0.175, -0.255), **common)
    fields = {"module_mm": 21.0, "pinion": sun, "gear": planet,
              "pinion_torque_Nm": F_T_N * 378.0 / 2000.0, "pinion_speed_rpm": SPEED_SUN_RPM,
              "life_h": LIFE_H, "pressure_angle_deg": 20.0, "centre_distance_mm": 584.0,
              "application_factor": 1.25, "load_sharing_factor": 1.10, "dynamic_factor": 1.06,
              "face_load_factor": 2.06, "mesh_stiffness_N_mm_um": 15.640,
              "viscosity_40_mm2_s": 220.0, "minimum_safety_pitting": 1.25,
              "minimum_safety_bending": 1.56, "edition": edition}
    fields.update(changes)
    return RatingInput(**fields)


#: Half the printed K_v's last digit, relative: 0.005/1.06. σ_F ∝ K_v, σ_H ∝ √K_v.
KV_REL = 0.005 / 1.06

# Printout columns: 0 the sun, 1 the planet in the sun mesh. Extra tolerances (zero unless
# stated):
#   σ_H0: 2e-5 — ours 573.3946; KISSsoft's ε_α differs from ours by ~5e-5 (printed 1.370), which
#         moves Z_ε by 1e-5;
#   σ_HG, σ_HP: 1e-5 — Z_v from v: the printed speeds are rounded to 0.1 min⁻¹ (v from 246.7 or
#         246.775 min⁻¹ moves Z_v by 7e-6);
#   σ_H, S_H: KV_REL/2; σ_F, S_F: KV_REL — K_v is given as the printed 1.06.
#: tag in the printout ; rating-document symbol(s) ; printed sun ; printed planet ; extra
#: relative tolerance (0, 1e-5, kv/2 = KV_REL/2, kv = KV_REL).
SUN_PLANET_TABLE = """
ZB,ZD             ; Z_B|Z_D ;    1.08 ;    1.00 ; 0
sigHB, sigHD      ; σ_H     ; 1071.17 ;  994.13 ; kv/2
ZNT               ; Z_NT    ;   0.857 ;   0.905 ; 0
ZL                ; Z_L     ;   1.020 ;   1.020 ; 0
ZV                ; Z_v     ;   0.982 ;   0.982 ; 0
ZR                ; Z_R     ;   1.007 ;   1.007 ; 0
ZW                ; Z_W     ;   1.000 ;   1.000 ; 0
ZX                ; Z_X     ;   1.000 ;   1.000 ; 0
sigHG             ; σ_HG    ; 1295.42 ; 1368.61 ; 1e-5
sigHP=sigHG/SHmin ; σ_HP    ; 1036.34 ; 1094.89 ; 1e-5
SHBD=sigHG/sigHBD ; S_H     ;    1.21 ;    1.38 ; kv/2
YF                ; Y_F     ;    1.47 ;    1.38 ; 0
YS                ; Y_S     ;    2.04 ;    2.18 ; 0
hF                ; h_Fe    ;   24.33 ;   25.73 ; 0
alfFen            ; α_Fen   ;   25.74 ;   24.68 ; 0
sFn               ; s_Fn    ;   44.78 ;   47.70 ; 0
roF               ; ρ_F     ;    9.52 ;    8.69 ; 0
Ybet              ; Y_β     ;    1.00 ;    1.00 ; 0
YDT               ; Y_DT    ;    1.00 ;    1.00 ; 0
YB                ; Y_B     ;    1.00 ;    1.00 ; 0
sigF0             ; σ_F0    ;   73.95 ;   74.21 ; 0
sigF              ; σ_F     ;  209.38 ;  210.14 ; kv
YdrelT            ; Y_δrelT ;   0.999 ;   1.002 ; 0
YRrelT            ; Y_RrelT ;   0.957 ;   0.957 ; 0
YX                ; Y_X     ;   0.840 ;   0.840 ; 0
YNT               ; Y_NT    ;   0.854 ;   0.886 ; 0
YM                ; Y_M     ;   1.000 ;   0.700 ; 0
Yst               ; Y_ST    ;    2.00 ;       - ; 0
sigFG             ; σ_FG    ;  589.60 ;  429.38 ; 0
sigFP=sigFG/SFmin ; σ_FP    ;  377.95 ;  275.24 ; 0
SF=sigFG/sigF     ; S_F     ;    2.82 ;    2.04 ; kv
"""
_EXTRA = {"0": 0.0, "1e-5": 1e-5, "kv/2": KV_REL / 2, "kv": KV_REL}
SUN_PLANET_ROWS = [tuple(c.strip() for c in line.split(";"))
                   for line in SUN_PLANET_TABLE.strip().splitlines()]


PAIR_ROWS = [  # (tag, column, symbol, printed, extra relative tolerance; see above)
    ("ZH", 0, "Z_H", "2.25", 0.0), ("ZE", 0, "Z_E", "189.81", 0.0),
    ("Zeps", 0, "Z_ε", "0.936", 0.0), ("Zbet", 0, "Z_β", "1.000", 0.0),
    ("sigH0", 0, "σ_H0", "573.40", 2e-5), ("Ft", 0, "F_t", "285900.438", 0.0),
    ("KFb", 0, "K_Fβ", "1.94", 0.0), ("KHa", 0, "K_Hα", "1.00", 0.0),
    ("KFa", 0, "K_Fα", "1.00", 0.0),
    ("eps_a", 0, "ε_α", "1.370", 0.0), ("alfwt", 0, "α_wt", "24.169", 0.0),
    ("v", 0, "v", "4.88", 0.0),
]


@pytest.fixture(scope="module")
def rated():
    return rate(make_input())


@pytest.mark.parametrize(("tag", "col", "symbol", "text", "extra"), PAIR_ROWS)
def test_pair_factor_against_printout(rated, tag, col, symbol, text, extra):
    assert printed(tag)[col] == text  # the literal quoted here is the printout's
    value = rated.factor(symbol).value
    assert within_print(value, text, extra), (symbol, value, text)


GEAR_CASES = [(tag, col, symbol.split("|")[col] if "|" in symbol else symbol, text, _EXTRA[extra])
              for tag, symbol, *texts, extra in SUN_PLANET_ROWS
              for col, text in enumerate(texts) if text != "-"]


@pytest.mark.parametrize(("tag", "col", "symbol", "text", "extra"), GEAR_CASES)
def test_gear_factor_against_printout(rated, tag, col, symbol, text, extra):
    assert printed(tag)[col] == text
    gear = rated.pinion if col == 0 else rated.gear
    value = gear.factor(symbol).value
    assert within_print(value, text, extra), (gear.name, symbol, value, text)


def test_minimum_safeties_and_verdicts(rated):
    assert printed("SHmin")[0] == "1.25" and printed("SFmin")[0] == "1.56"
    # S_H 1.21 (sun) < 1.25: the printout's sun flank fails its required safety; the rest pass.
    assert not rated.pinion.pitting_ok and rated.gear.pitting_ok
    assert rated.pinion.bending_ok and rated.gear.bending_ok and not rated.ok
    assert rated.to_dict()["verdict"] == "fail"


def test_load_cycles_contacts_and_speed():
    """N_L (in millions) 7782.3 (sun, 3 contacts per revolution) and 1297.1 (planet): the ratio
    is 3 × u = 6; the speed that gives 7782.3e6 lies within the printed speeds' rounding."""
    assert printed("NL")[:2] == ["7782.3", "1297.1"]
    r = rate(make_input())
    assert within_print(r.pinion.load_cycles / 1e6, "7782.3")
    assert within_print(r.gear.load_cycles / 1e6, "1297.1")
    assert abs(SPEED_SUN_RPM - (294.5 - 47.8)) < 0.1
    assert printed("nSteg")[0] == "47.8" and printed("n")[0] == "294.5"


def test_running_in_and_face_load_factor_for_bending():
    """y_α = 0.075 f_pb (Eh) with the planet's f_pb 17.90 µm: 1.342 µm; K_Fβ = 2.06^N_F,
    b/h = 550/45.5 (h = h_a + h_f = 27.419 + 18.081)."""
    assert printed("ya")[0] == "1.342" and printed("fpbT")[:2] == ["16.90", "17.90"]
    assert within_print(running_in_profile(MaterialKind.CASE_HARDENED, 1500.0, 17.90, 4.88),
                        "1.342")
    geo = pair_geometry(make_input())
    assert geo.tooth_height[0] == pytest.approx(27.419 + 18.081, abs=1e-3)
    assert within_print(bending_face_load_factor(2.06, 550.0, geo.tooth_height[0]), "1.94")
    assert printed("KHb")[0] == "2.06"
    assert printed("Summexi")[0] == "0.8929" and within_print(SUM_X, "0.8929")


def _check_with_allowances(tag, nominal, at_allowances, sun, planet):
    """Printed [tag] (sun, planet) and [tag.e/i] (sun e, i, planet e, i) against the
    (nominal, upper, lower) triples of the two gears."""
    assert printed(tag)[:2] == nominal
    assert printed(f"{tag}.e/i")[:4] == at_allowances
    texts = (nominal[0], *at_allowances[:2], nominal[1], *at_allowances[2:])
    for got, text in zip((*sun, *planet), texts, strict=True):
        assert within_print(got, text), (tag, got, text)


def test_inspection_dimensions_against_printout(rated):
    sun, planet = rated.pinion.inspection, rated.gear.inspection
    assert printed("k")[:2] == ["3.000", "5.000"]
    assert (sun.span_teeth, planet.span_teeth) == (3, 5)
    _check_with_allowances("Wk", ["165.869", "296.803"], ["165.747", "165.690", "296.638",
                                                          "296.563"], sun.span_mm, planet.span_mm)
    assert printed("DM")[:2] == ["41.072", "38.726"]
    assert within_print(sun.ball_theoretical_mm, "41.072")
    assert within_print(planet.ball_theoretical_mm, "38.726")
    assert printed("DMeff")[:2] == ["45.000", "40.000"]
    assert (sun.ball_mm, planet.ball_mm) == (45.0, 40.0)
    _check_with_allowances("MdK", ["466.306", "836.492"], ["466.079", "465.974", "836.128",
                                                           "835.961"],
                           sun.over_balls_mm, planet.over_balls_mm)
    assert printed("sc")[:2] == ["38.864", "40.670"]
    assert within_print(sun.chordal_thickness_mm[0], "38.864")
    assert within_print(planet.chordal_thickness_mm[0], "40.670")
    sc_ei = printed("sc.e/i")[:4]
    assert sc_ei == ["38.734", "38.674", "40.495", "40.415"]
    assert within_print(planet.chordal_thickness_mm[1], "40.495")
    assert within_print(planet.chordal_thickness_mm[2], "40.415")
    # The sun's at the allowances: ours (the exact chord of the thinned tooth) 38.7352/38.6755,
    # 1.2e-3 and 1.5e-3 above the print. KISSsoft prints s_c + A_sn, the nominal chord plus the
    # allowance (38.864 - 0.130, 38.864 - 0.190), which the exact chord exceeds by ~A_sn s²/(2d²)
    # more than that at m_n 21 (docs/theory.md "ISO 6336 rating" §6): checked as printed, and
    # ours within 2e-3 mm, less than a tenth of the allowance band.
    assert within_print(38.864 - 0.130, sc_ei[0]) and within_print(38.864 - 0.190, sc_ei[1])
    assert sun.chordal_thickness_mm[1] == pytest.approx(38.734, abs=2e-3)
    assert sun.chordal_thickness_mm[2] == pytest.approx(38.674, abs=2e-3)


def test_chordal_height_from_the_mean_tip_diameter():
    """"Reference chordal height from da.m": d_a,m = mean of d_a.e/i (432.838/432.828 and
    815.663/815.653). KISSsoft prints h_a + s²/(4d), the first term of the exact
    (d_a − d)/2 + d/2 (1 − cos(s/d)), which is lower by d (s/d)⁴/48 (0.9e-3 mm for the sun,
    0.3e-3 mm for the planet; docs/theory.md "ISO 6336 rating" §6): the print is checked
    against that approximation, and ours against the print less that term."""
    assert printed("ha")[:2] == ["28.419", "30.376"]
    assert printed("da.e/i")[:4] == ["432.838", "432.828", "815.663", "815.653"]
    for z, x, d_am, h_print in ((18, X1, 0.5 * (432.838 + 432.828), "28.419"),
                                (36, X2, 0.5 * (815.663 + 815.653), "30.376")):
        d = 21.0 * z
        s = 21.0 * (0.5 * math.pi + 2.0 * x * math.tan(ALPHA))  # arc thickness s_n
        assert within_print(0.5 * (d_am - d) + s * s / (4.0 * d), h_print)
        assert within_print(chordal_height(z, x, 21.0, ALPHA, d_am) + d * (s / d) ** 4 / 48.0,
                            h_print)
    assert printed("sn")[:2] == ["38.933", "40.689"]
    assert within_print(chordal_thickness(18, X1, 21.0, ALPHA), "38.864")


def test_flank_life_and_damage_of_the_sun():
    """Tooth flank service life of the sun 59646 h (5.965e+004) at S_H,min = 1.25 and damage
    293.74 % of the required 175200 h; roots and the planet flank: > 10⁶ h (printed 1e+006).

    The life is the stress's 32.6th power (the Z_NT line beyond 5·10⁷ cycles), so it needs K_v
    beyond the printed 1.06: K_v = (σ_Hw/σ_H0)²/(K_A K_γ K_Hβ) from the printed σ_Hw = 994.13,
    σ_H0 = 573.40. Their print resolution (5e-6 relative) and our σ_H0 (9e-6 below the print)
    leave ~2e-5 in σ_H, i.e. ~0.07 % in life: tolerance 0.2 %."""
    assert printed("HHatt")[:3] == ["5.965e+004", "1e+006", "1e+006"]
    assert printed("HFatt")[:3] == ["1e+006", "1e+006", "1e+006"]
    text = PRINTOUT.read_text(encoding="utf-8").split("Damage calculated on the basis of the "
                                                       "required service life")[1]
    damage = text.splitlines()[2].split()
    assert damage == ["0.00", "0.00", "0.00", "293.74", "0.00", "0.00"]
    assert "[Hatt]\t     59646" in PRINTOUT.read_text(encoding="utf-8")
    k_v = (994.13 / 573.40) ** 2 / (1.25 * 1.10 * 2.06)
    r = rate(make_input(dynamic_factor=k_v))
    assert r.pinion.life_pitting_h == pytest.approx(59646.0, rel=2e-3)
    assert 100.0 * r.pinion.damage_pitting == pytest.approx(293.74, rel=2e-3)
    for life in (r.gear.life_pitting_h, r.pinion.life_bending_h, r.gear.life_bending_h):
        assert life > 1e6
    assert r.gear.damage_pitting == r.pinion.damage_bending == r.gear.damage_bending == 0.0


def test_ring_mesh_factors_of_the_same_printout():
    """The planet–ring mesh of the printout checks the material-dependent branches the sun mesh
    does not reach: through-hardened 34CrNiMo6 ring, σ_Hlim 700, HBW 240, R_zH 8.0, internal
    mesh ρ_red = ρ1 ρ2/(ρ2 − ρ1) from the printed T1C lengths 99.372 and 256.711, v 4.88 m/s,
    N_L 1506.3·10⁶ (ring)."""
    assert printed("ZL")[2:4] == ["1.038", "1.038"] and printed("ZV")[2:4] == ["0.961", "0.961"]
    assert printed("ZR")[2:4] == ["1.026", "1.026"] and printed("ZW")[3] == "1.135"
    assert printed("YX")[2] == "0.904" and printed("YRrelT")[2] == "0.957"
    assert printed("ZNT")[2] == "0.901" and printed("YNT")[2] == "0.883"
    v = math.pi * 378.0 * SPEED_SUN_RPM / 60000.0
    assert within_print(p2.lubricant_factor(700.0, 220.0), "1.038")
    assert within_print(p2.velocity_factor(700.0, v), "0.961")
    rho_red = 99.372 * 256.711 / (256.711 - 99.372)
    assert within_print(p2.roughness_factor(700.0, 4.8, 8.0, rho_red), "1.026")
    assert within_print(p2.work_hardening_factor(240.0), "1.135")
    kind = MaterialKind.THROUGH_HARDENED_ALLOY
    assert within_print(b3.size_factor(kind, 21.0), "0.904")
    assert within_print(b3.relative_surface_factor(kind, 20.0), "0.957")
    assert within_print(pitting_life_curve(kind)(1506.3e6), "0.901")
    assert within_print(bending_life_curve(kind)(1506.3e6), "0.883")


def test_editions_differ_only_in_the_idler_mean_stress_factor():
    """Both editions for this case (the choice is documented in docs/theory.md): spur gears make
    Z_β = Y_β = 1 in both; the planet (idler) has Y_M = 0.7 in 2006 and, in 2019,
    Y_M = 1/(1 − R (1 − M)/(1 + M)) with R = −1.2 and M = 0.8 − 0.15 Y_S (case hardened):
    with Y_S = 2.1755, M = 0.4737 and Y_M = 0.69999 — the two S_F differ by 1.3e-5 relative."""
    r06, r19 = rate(make_input(Edition.ISO2006)), rate(make_input(Edition.ISO2019))
    y_s = r19.gear.factor("Y_S").value
    m = 0.8 - 0.15 * y_s
    y_m = 1.0 / (1.0 + 1.2 * (1.0 - m) / (1.0 + m))
    assert r19.gear.factor("Y_M").value == pytest.approx(y_m, rel=1e-12)
    assert y_m == pytest.approx(0.69999, abs=1e-5)
    assert r19.gear.S_F / r06.gear.S_F == pytest.approx(y_m / 0.7, rel=1e-12)
    assert r19.pinion.S_F == r06.pinion.S_F and r19.pinion.S_H == r06.pinion.S_H
    assert r19.gear.S_H == r06.gear.S_H
    assert r19.edition == "2019" and r06.to_dict()["edition"] == "2006"
