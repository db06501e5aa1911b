"""The ISO 6336 rating through the case file: schema_rating (the `rating:` section),
pipeline/rating.py (case → RatingInput → RatingResult, duty cycle, inspection dimensions).

Anchor: cases/nrel5mw_sun_planet.yaml, the sun–planet mesh of the KISSsoft 03/2017 ISO
6336:2006 printout of the NREL 5 MW planetary stage (tests/data/kisssoft_nrel5mw_stage02.txt);
the printed values and their tolerances are those of tests/unit/test_iso6336_anchor.py, which
checks the model from hand-written inputs. Here the same numbers must come out of the case
file: S_H 1.21/1.38, S_F 2.82/2.04, Z_H 2.25, Z_E 189.81, Z_ε 0.936, Z_B 1.08, Y_F 1.47/1.38,
Y_S 2.04/2.18, Y_M 1.000/0.700, σ_HG 1295.42/1368.61, σ_FG 589.60/429.38, W_k 165.869/296.803,
M_dK 466.306/836.492, ...
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import pytest
import yaml

from gearcli.case.load import load_case, load_case_text
from gearcli.errors import CaseError
from gearcli.pipeline.rating import (
    CaseRating,
    SimulatedLoad,
    case_inspection,
    rate_case,
    rating_input,
)
from tests.unit.test_iso6336_anchor import (
    GEAR_CASES,
    PAIR_ROWS,
    make_input,
    printed,
    within_print,
)

NREL = Path(__file__).resolve().parents[2] / "cases" / "nrel5mw_sun_planet.yaml"
ISO_PAIR = NREL.parent / "iso_pair.yaml"
LIMITS = ["material.contact_fatigue_limit=1500", "material.bending_fatigue_limit=430"]


@pytest.fixture(scope="module")
def rated() -> CaseRating:
    return rate_case(NREL)


def test_the_case_maps_to_the_anchor_input(rated):
    """The RatingInput built from the case equals the anchor's hand-written one (the printout's
    inputs): the speed 246.77511 rpm is written to 8 digits (rel. 5e-8), the planet's tip
    diameter 815.6625 mm from the geometry is printed 815.663 (rel. 1e-6); the rest exactly
    or to rounding of the written profile shift and load (1e-12)."""
    ours, ref = rated.rating_input, make_input()
    assert ours.pinion_speed_rpm == pytest.approx(ref.pinion_speed_rpm, rel=5e-8)
    assert ours.pinion_torque_Nm == pytest.approx(ref.pinion_torque_Nm, rel=1e-12)
    for name in ("module_mm", "life_h", "pressure_angle_deg", "centre_distance_mm",
                 "application_factor", "load_sharing_factor", "dynamic_factor",
                 "face_load_factor", "mesh_stiffness_N_mm_um", "viscosity_40_mm2_s",
                 "minimum_safety_pitting", "minimum_safety_bending",
                 "addendum_coefficient", "dedendum_coefficient", "root_radius_coefficient"):
        assert getattr(ours, name) == pytest.approx(getattr(ref, name), rel=1e-12), name
    assert ours.edition == ref.edition == "2006"
    for mine, theirs in ((ours.pinion, ref.pinion), (ours.gear, ref.gear)):
        for f in dataclasses.fields(theirs):
            a, b = getattr(mine, f.name), getattr(theirs, f.name)
            if f.name == "tip_diameter_mm":
                assert a == pytest.approx(b, rel=1e-6)
            elif isinstance(b, float):
                assert a == pytest.approx(b, rel=1e-12, abs=1e-12), f.name
            elif isinstance(b, tuple):
                assert a == pytest.approx(b, rel=1e-12), f.name
            else:
                assert a == b, f.name


@pytest.mark.parametrize(("tag", "col", "symbol", "text", "extra"), PAIR_ROWS)
def test_pair_factors_through_the_case(rated, tag, col, symbol, text, extra):
    assert printed(tag)[col] == text
    assert within_print(rated.iso.factor(symbol).value, text, extra), symbol


@pytest.mark.parametrize(("tag", "col", "symbol", "text", "extra"), GEAR_CASES)
def test_gear_factors_through_the_case(rated, tag, col, symbol, text, extra):
    """Every row of the anchor's printout table (Z_B … S_F, both gears), from the case."""
    side = (rated.iso.pinion, rated.iso.gear)[col]
    assert within_print(side.factor(symbol).value, text, extra), (tag, side.name, symbol, text)


def test_safeties_and_verdict_of_the_printout(rated):
    """S_H 1.21/1.38 against S_H,min 1.25 (the sun fails, as printed), S_F 2.82/2.04 against
    1.56; K_v given (1.06): σ_H ∝ √K_v, so S_H carries half K_v's rounding, S_F all of it."""
    kv = 0.005 / 1.06
    p, g = rated.iso.pinion, rated.iso.gear
    assert within_print(p.S_H, "1.21", kv / 2) and within_print(g.S_H, "1.38", kv / 2)
    assert within_print(p.S_F, "2.82", kv) and within_print(g.S_F, "2.04", kv)
    assert not p.pitting_ok and g.pitting_ok and p.bending_ok and g.bending_ok
    assert not rated.ok and rated.to_dict()["verdict"] == "fail"
    assert rated.dynamic_factor_source == "given" and rated.iso.edition == "2006"


def test_edition_2019_only_changes_the_idlers_mean_stress_factor(rated):
    r19 = rate_case(NREL, ["rating.edition=2019"])
    assert r19.iso.edition == "2019"
    assert r19.iso.gear.factor("Y_M").value == pytest.approx(0.69999, abs=1e-5)
    assert r19.iso.pinion.S_F == rated.iso.pinion.S_F and r19.iso.gear.S_H == rated.iso.gear.S_H
    assert r19.iso.gear.S_F / rated.iso.gear.S_F == pytest.approx(
        r19.iso.gear.factor("Y_M").value / 0.7, rel=1e-12)


def test_inspection_dimensions_of_the_case():
    """W_k, M_dK at the nominal thickness and at the printed allowances (As.e/i)."""
    ins = case_inspection(NREL)
    assert ins.allowances_mm == ((-0.130, -0.190), (-0.175, -0.255))
    assert (ins.pinion.span_teeth, ins.gear.span_teeth) == (3, 5)
    wk = printed("Wk")[:2] + printed("Wk.e/i")[:4]
    mdk = printed("MdK")[:2] + printed("MdK.e/i")[:4]
    assert wk == ["165.869", "296.803", "165.747", "165.690", "296.638", "296.563"]
    assert mdk == ["466.306", "836.492", "466.079", "465.974", "836.128", "835.961"]
    for dims, texts in ((ins.pinion.span_mm, wk[0:1] + wk[2:4]),
                        (ins.gear.span_mm, wk[1:2] + wk[4:6]),
                        (ins.pinion.over_balls_mm, mdk[0:1] + mdk[2:4]),
                        (ins.gear.over_balls_mm, mdk[1:2] + mdk[4:6])):
        for value, text in zip(dims, texts, strict=True):
            assert within_print(value, text), (value, text)
    assert (ins.pinion.ball_mm, ins.gear.ball_mm) == (45.0, 40.0)
    doc = ins.to_dict()
    assert doc["pinion"]["thickness_allowances_mm"] == [-0.13, -0.19]
    json.dumps(doc)


def test_inspection_allowances_default_to_the_thickness_allowance():
    """Without rating.<gear>.thickness_allowances both allowances are −thickness_allowance;
    W_k then shifts by A_sn cos α (hand value)."""
    ins = case_inspection(NREL, overrides=["rating.pinion.thickness_allowances=null"])
    assert ins.allowances_mm[0] == (-0.16, -0.16)
    shift = ins.pinion.span_mm[1] - ins.pinion.span_mm[0]
    assert shift == pytest.approx(-0.16 * math.cos(math.radians(20.0)), rel=1e-9)


def test_torque_times_four_halves_S_H(rated):
    """σ_H ∝ √F_t with every load factor given or load independent here (K_Hα stays at its
    lower limit 1), σ_F ∝ F_t: S_H halves, S_F quarters; the strengths do not change."""
    four = rate_case(NREL, ["load.torque=STEP(time, 0, 0, 0.2, 432281.462256)"])
    for a, b in ((four.iso.pinion, rated.iso.pinion), (four.iso.gear, rated.iso.gear)):
        assert a.S_H == pytest.approx(b.S_H / 2.0, rel=1e-12)
        assert a.S_F == pytest.approx(b.S_F / 4.0, rel=1e-12)
        assert a.sigma_HG_MPa == b.sigma_HG_MPa


def test_harder_material_raises_S_H():
    """σ_Hlim from ISO 6336-5 (through-hardened alloy, MQ: 1.313 HV + 373) instead of given
    limits: 300 → 350 HV raises σ_Hlim from 766.9 to 832.55 N/mm² and S_H with it."""
    base = ["rating.pinion.material={kind: through_hardened_alloy, hardness: %s, "
            "proof_stress: 850}",
            "rating.gear.material={kind: through_hardened_alloy, hardness: %s, "
            "proof_stress: 850}"]
    r = [rate_case(ISO_PAIR, [b % hv for b in base]) for hv in (300, 350)]
    lim = [x.iso.pinion.factor("σ_Hlim").value for x in r]
    assert lim == pytest.approx([1.313 * 300 + 373, 1.313 * 350 + 373], rel=1e-12)
    assert r[0].iso.pinion.factor("σ_Hlim").clause == "ISO 6336-5:2016 Table 1"
    # σ_Hlim also enters the running-in allowance y_β = 320/σ_Hlim F_βx (V), so K_Hβ (Method
    # C) rises a little (1.0203 → 1.0214): S_H rises by the limits' ratio times √(K ratio)
    kh = [x.iso.factor("K_Hβ").value * x.iso.factor("K_Hα").value for x in r]
    assert r[1].iso.pinion.S_H / r[0].iso.pinion.S_H == pytest.approx(
        lim[1] / lim[0] * math.sqrt(kh[0] / kh[1]), rel=1e-9)


def _one_bin(torque: str, speed: str) -> list[str]:
    return [f"rating.duty_cycle=[{{torque: {torque}, speed: {speed}, time_share: 1}}]"]


def test_duty_cycle_of_one_bin_equals_the_single_load_rating(rated):
    """One bin at the case's load torque and speed: the Miner damage is L_h/L_h(S_min), the
    single rating's (the sun flank's 2.88: its life at S_H,min 1.25 is 60 783 h; the others'
    are infinite, damage 0)."""
    one = rate_case(NREL, _one_bin("108070.365564", "246.77511"))
    for d, g in ((one.duty_cycle.pinion, rated.iso.pinion), (one.duty_cycle.gear,
                                                             rated.iso.gear)):
        assert d.pitting == pytest.approx(g.damage_pitting, rel=1e-9)
        assert d.bending == pytest.approx(g.damage_bending, rel=1e-9, abs=0.0)
    assert one.duty_cycle.pinion.pitting == pytest.approx(175200.0 / 60782.94, rel=1e-5)
    assert not one.ok and one.to_dict()["duty_cycle"]["pinion"]["pitting"] > 1.0


def test_duty_cycle_torque_is_the_load_torque_of_the_case():
    """A bin's torque means what load.torque means (on the gear, here the planet): half the
    case's torque in a single bin gives the damage of the case rated at half its load."""
    half = "54035.182782"
    by_bin = rate_case(NREL, _one_bin(half, "246.77511"))
    by_load = rate_case(NREL, [f"load.torque=STEP(time, 0, 0, 0.2, {half})"])
    assert by_bin.duty_cycle.pinion.pitting == pytest.approx(by_load.iso.pinion.damage_pitting,
                                                             rel=1e-9)


def test_simulated_dynamic_factor_needs_a_run_and_takes_the_runs():
    with pytest.raises(CaseError, match="rating.dynamic_factor.*simulation run"):
        rate_case(NREL, ["rating.dynamic_factor=simulated"])
    r = rate_case(NREL, ["rating.dynamic_factor=simulated"],
                  simulated=SimulatedLoad(1.3, sigma_H_peak_MPa=(1100.0, 1000.0)))
    assert r.iso.factor("K_v").value != 1.3  # the ISO column: Method B
    assert r.simulated.factor("K_v").value == 1.3
    assert r.simulated.factor("K_v").clause.startswith("simulated")
    ratio = math.sqrt(r.iso.factor("K_v").value / 1.3)
    assert r.simulated.pinion.S_H == pytest.approx(r.iso.pinion.S_H * ratio, rel=1e-12)
    # the peak carries the dynamics, not K_A 1.25, K_γ 1.10, K_Hβ 2.06 (the case's, as printed):
    # σ_H,sim = 1100 √(1.25 × 1.10 × 2.06) = 1851.30 N/mm²
    assert r.simulated_peaks["pinion"].sigma_H_MPa == pytest.approx(1851.30, abs=0.005)
    assert r.simulated_peaks["pinion"].S_H == pytest.approx(
        r.simulated.pinion.sigma_HG_MPa / (1100.0 * math.sqrt(1.25 * 1.10 * 2.06)), rel=1e-12)
    json.dumps(r.to_dict())


def test_iso_dynamic_factor_is_the_one_gearcli_mesh_prints():
    """K_v 'iso' with K_A = 1 is `gearcli mesh`'s Method B K_v of the same case."""
    from gearcli.pipeline.mesh import mesh_document, run_mesh

    r = rate_case(ISO_PAIR, LIMITS)
    mesh = mesh_document(run_mesh(load_case(ISO_PAIR, LIMITS)))
    assert r.iso.factor("K_v").value == pytest.approx(mesh.iso6336_method_b.k_v,
                                                      rel=1e-12)
    assert r.dynamic_factor_source.startswith("ISO 6336-1 Method B")
    assert r.iso.factor("K_v").clause == r.dynamic_factor_source  # the table says where from
    with_ka = rate_case(ISO_PAIR, [*LIMITS, "rating.application_factor=1.5"])
    assert with_ka.iso_dynamic.line_load_N_mm == pytest.approx(
        1.5 * r.iso_dynamic.line_load_N_mm, rel=1e-12)


def test_missing_fatigue_limits_say_what_is_missing():
    with pytest.raises(CaseError) as err:
        rate_case(ISO_PAIR)
    text = str(err.value)
    assert "contact_fatigue_limit" in text and "bending_fatigue_limit" in text
    assert "hardness" in text and "\n" not in text
    # a per-gear limit is enough for that gear; the other is still named
    with pytest.raises(CaseError, match="gear bending_fatigue_limit") as err:
        rate_case(ISO_PAIR, ["material.contact_fatigue_limit=1500",
                             "gears.pinion.material={bending_fatigue_limit: 430}"])
    assert "pinion bending" not in str(err.value)


def test_through_hardened_material_needs_its_proof_stress():
    with pytest.raises(CaseError, match="rating.gear.material.proof_stress"):
        rate_case(ISO_PAIR, [*LIMITS, "rating.gear.material.kind=through_hardened_alloy"])


def test_hardness_gives_the_iso_6336_5_limits():
    """Case-hardened MQ (ISO 6336-5 Table 1): σ_Hlim 1500, σ_Flim 425 N/mm² at any hardness
    in 600…800 HV (the anchor's KISSsoft value 430 is its database's)."""
    r = rate_case(ISO_PAIR, ["rating.pinion.material.hardness=700",
                             "rating.gear.material.hardness=700"])
    for g in (r.iso.pinion, r.iso.gear):
        assert g.factor("σ_Hlim").value == 1500.0 and g.factor("σ_Flim").value == 425.0


@pytest.mark.parametrize(("override", "key", "reason"), [
    ("rating.pinion.thickness_allowances=[-30, -40]", "rating.pinion.thickness_allowances",
     "leaves no tooth"),
    ("rating.gear.ball_diameter=400", "rating.gear.ball_diameter", "above the tip"),
    ("rating.pinion.ball_diameter=5 mm", "rating.pinion.ball_diameter", "falls between"),
])
def test_impossible_inspection_inputs_are_errors_at_their_keys(override, key, reason):
    """A thickness allowance that thins the tooth away or a ball that cannot touch both flanks
    between the base circle and the tip: a one-line error at the key (it was "rating: cannot
    rate this case: involute value ... outside 0…1")."""
    with pytest.raises(CaseError) as err:
        rate_case(NREL, [override])
    text = str(err.value)
    assert key in text and reason in text and "involute value" not in text, text


def test_a_fine_pitch_pair_is_rated_with_its_own_standard_ball():
    """Module 0.3 (an instrument pair): no ball given, the "next standard" ball must touch the
    flanks. The series began at 1 mm, twice the theoretical 0.50 mm: its contact lay above the
    tip, and the whole rating was refused at rating.gear.ball_diameter, a key the case never
    wrote (before the inspection check it rated with M_d of that impossible ball)."""
    fine = ["gears.module=0.3", "gears.face_width=3", "gears.pinion.bore_diameter=1",
            "gears.gear.bore_diameter=2", "load.torque={function: 'STEP(time, 0, 0, 0.2, 0.1)',"
            " unit: N*m}", "material.contact_fatigue_limit=1500 MPa",
            "material.bending_fatigue_limit=430 MPa"]
    rated = rate_case(ISO_PAIR, fine)
    assert rated.iso.pinion.S_H > 0.0 and rated.iso.gear.S_F > 0.0


@pytest.mark.parametrize(("override", "key"), [
    ("rating.application_factor=0", "rating.application_factor"),
    ("rating.application_factor=0.5", "rating.application_factor"),  # K_A >= 1 (ISO 6336-6)
    ("rating.load_sharing_factor=0.9", "rating.load_sharing_factor"),  # K_γ = max/mean >= 1
    ("rating.dynamic_factor=fast", "rating.dynamic_factor"),
    ("rating.edition=2010", "rating.edition"),
    ("rating.pinion.material.kind=unobtainium", "rating.pinion.material.kind"),
    ("rating.gear.material.quality=MX", "rating.gear.material.quality"),
    ("rating.life=-5 h", "rating.life"),
    ("rating.life=5 kg", "rating.life"),
    ("rating.minimum_safety.pitting=0", "rating.minimum_safety.pitting"),
    ("rating.pinion.thickness_allowances=[-0.2, -0.1]",
     "rating.pinion.thickness_allowances"),
    ("rating.duty_cycle=[{torque: 1, speed: 100, time_share: 0.5}]", "rating.duty_cycle"),
])
def test_schema_errors_name_the_key(override, key):
    with pytest.raises(CaseError) as err:
        load_case(NREL, [override])
    assert key in str(err.value), str(err.value)


def test_unknown_rating_key_is_refused_with_its_name(tmp_path):
    text = NREL.read_text().replace("  application_factor: 1.25", "  aplication_factor: 1.25")
    with pytest.raises(CaseError) as err:
        load_case_text(text, "typo.yaml")
    assert "rating.aplication_factor" in str(err.value)
    assert "application_factor" in str(err.value)  # did you mean


def test_units_of_the_rating_keys():
    """Bare numbers: life in h, roughness and deviations in µm, ν40 in mm²/s; strings with
    units convert (pint); the Dim factors are pint's."""
    from gearcli import units
    from gearcli.case.schema_rating import LIFE, ROUGHNESS, VISCOSITY

    for dim in (LIFE, ROUGHNESS, VISCOSITY):
        assert units.registry().Quantity(1.0, dim.default).to(dim.internal).magnitude == \
            pytest.approx(dim.factor, rel=1e-15)
    a = load_case(NREL, ["rating.life=175200", "rating.pinion.roughness.flank=0.0048 mm",
                         "rating.lubricant.viscosity_40=220 cSt"]).case.rating
    b = load_case(NREL).case.rating
    assert a.life == b.life == 175200.0 * 3600.0
    assert a.pinion.roughness.flank == pytest.approx(b.pinion.roughness.flank, rel=1e-12)
    assert b.pinion.roughness.flank == pytest.approx(0.0048, rel=1e-12)
    assert a.lubricant.viscosity_40 == pytest.approx(220.0, rel=1e-12)


def test_resolved_case_loads_again_with_the_same_rating(tmp_path):
    """The resolved case (manifests, sweeps) writes the rating section back in internal
    units; it loads to the identical section."""
    loaded = load_case(NREL, ["rating.duty_cycle=[{torque: 1e5, speed: 200, time_share: 1}]"])
    data = json.loads(loaded.case.model_dump_json())
    again = load_case_text(yaml.safe_dump(data), "again.yaml")
    assert again.case.rating == loaded.case.rating


def test_rating_input_reuses_a_given_geometry():
    from gearcli.pipeline.geometry import run_geometry

    loaded = load_case(NREL)
    geo = run_geometry(loaded)
    inp, source, info = rating_input(loaded, geo)
    assert source == "given" and info is None and inp.pinion.teeth == 18
