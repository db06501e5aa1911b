"""Study files: designs, units, the virtual mesh_frequency parameter, and every bad input."""

import json
import math

import pytest

from gearcli.case.schema import Case
from gearcli.errors import CaseError
from gearcli.pipeline.sweep.study import MAX_POINTS, load_study
from tests.conftest import ROOT
from tests.unit.sweep_helpers import write_study


def test_grid_with_units_and_ranges(tmp_path):
    s = load_study(write_study(tmp_path, """parameters:
  gears.face_width: {linspace: ["80 mm", "12 cm"], num: 3}
  contact.max_damping: {logspace: [1, 100], num: 3}
"""))
    assert len(s.points) == 9
    # a range's bare ends are in the key's case-file unit, which names the column (as a list's)
    assert s.parameter_columns == ["gears.face_width [mm]", "contact.max_damping [N*s/mm]"]
    assert [p.values["gears.face_width [mm]"] for p in s.points[::3]] == [80.0, 100.0, 120.0]
    assert [p.values["contact.max_damping [N*s/mm]"] for p in s.points[:3]] == [1.0, 10.0,
                                                                                100.0]
    assert s.points[4].overrides == ["gears.face_width=100 mm", "contact.max_damping=10 N*s/mm"]
    assert len({p.case_hash for p in s.points}) == 9


def test_zip_lhs_and_one_at_a_time(tmp_path):
    z = load_study(write_study(tmp_path, """design: zip
parameters:
  gears.face_width: ["80 mm", "100 mm"]
  gears.module: [9, 11]
"""))
    assert [p.overrides for p in z.points] == [["gears.face_width=80 mm", "gears.module=9"],
                                               ["gears.face_width=100 mm", "gears.module=11"]]
    text = """design: lhs
samples: 8
seed: 3
parameters:
  gears.face_width: {linspace: ["80 mm", "120 mm"]}
  contact.max_damping: {logspace: ["1 N*s/mm", "100 N*s/mm"]}
"""
    a = load_study(write_study(tmp_path, text, "a.yaml"))
    b = load_study(write_study(tmp_path, text, "b.yaml"))
    assert [p.case_hash for p in a.points] == [p.case_hash for p in b.points]  # seeded
    widths = sorted(p.values["gears.face_width [mm]"] for p in a.points)
    assert 80 <= widths[0] and widths[-1] <= 120
    # Latin hypercube: exactly one sample in each of the 8 equal strata
    assert sorted(int((w - 80) / 5) for w in widths) == list(range(8))
    o = load_study(write_study(tmp_path, """design: one_at_a_time
parameters:
  gears.face_width: ["80 mm", "120 mm"]
  gears.module: [9, 11, 12]
"""))
    assert len(o.points) == 1 + 2 + 3 and o.points[0].overrides == []
    # bare numbers are in the key's case-file unit, which names the column as for "80 mm"
    assert o.points[1].values == {"gears.face_width [mm]": 80.0, "gears.module [mm]": 10.0}


def test_a_list_mixes_bare_numbers_and_units_as_a_case_file_does(tmp_path):
    # ["80 mm", 120] failed with "wrong unit", [80, "120 mm"] with "a value in ''"
    for widths in ('["80 mm", 120]', '[80, "120 mm"]', '[80, "0.12 m"]'):
        s = load_study(write_study(tmp_path, f"parameters:\n  gears.face_width: {widths}\n"))
        values = next(iter(s.points[0].values))  # the column: the first written unit, or mm
        factor = 1e-3 if values.endswith("[m]") else 1.0
        assert [p.values[values] for p in s.points] == pytest.approx([80 * factor,
                                                                      120 * factor])


def test_mesh_frequency_sets_the_drive_speed(tmp_path):
    s = load_study(write_study(tmp_path, """parameters:
  mesh_frequency: ["170 Hz"]
  gears.pinion.teeth: [17, 20]
"""))
    # f_z = z1 n1: 170 Hz with 17 teeth -> 10 rev/s = 3600 deg/s; with 20 teeth 3060 deg/s
    assert s.points[0].overrides[0] == "drive.speed=STEP(time,0,0,0.1,3600)"
    assert s.points[1].overrides[0] == "drive.speed=STEP(time,0,0,0.1,3060)"


def test_with_overrides_take_the_value(tmp_path):
    s = load_study(write_study(tmp_path, """parameters:
  modifications.tip_relief.pinion.amount:
    values: ["0.005 mm"]
    with: {modifications.tip_relief.pinion.length: 8 mm,
           modifications.tip_relief.gear.amount: "{value}",
           modifications.tip_relief.gear.length: 8 mm}
"""))
    assert "modifications.tip_relief.gear.amount=0.005 mm" in s.points[0].overrides


def _error(tmp_path, body: str) -> str:
    with pytest.raises(CaseError) as exc:
        load_study(write_study(tmp_path, body))
    text = str(exc.value)
    assert str(tmp_path / "study.yaml") in text.splitlines()[0]
    return text


def test_unknown_key_path_is_located(tmp_path):
    text = _error(tmp_path, "parameters:\n  gears.modul: [9, 11]\n")
    assert "study.yaml:8: parameters.gears.modul" in text
    assert "did you mean 'module'" in text


def test_unknown_key_in_set(tmp_path):
    body = "parameters:\n  gears.module: [9]\n"
    path = write_study(tmp_path, body)
    path.write_text(path.read_text().replace("contact.max_damping", "contact.max_dampin"))
    with pytest.raises(CaseError, match=r"study.yaml:6: set.contact.max_dampin: unknown key"):
        load_study(path)


def test_empty_list(tmp_path):
    assert "empty list" in _error(tmp_path, "parameters:\n  gears.module: []\n")


def test_wrong_unit(tmp_path):
    text = _error(tmp_path, "parameters:\n  gears.face_width: [\"80 s\"]\n")
    assert "parameters.gears.face_width" in text and "not a length" in text
    text = _error(tmp_path, "parameters:\n  gears.face_width: {linspace: [\"80 mm\", \"1 s\"], "
                  "num: 3}\n")
    assert "wrong or inconsistent units" in text


def test_grid_too_large_needs_yes(tmp_path):
    body = ("parameters:\n  gears.face_width: {linspace: [80, 120], num: 40}\n"
            "  contact.max_damping: {linspace: [1, 100], num: 30}\n")
    text = _error(tmp_path, body)
    assert f"1200 points (> {MAX_POINTS}); pass --yes" in text
    assert len(load_study(write_study(tmp_path, body), allow_large=True).points) == 1200


def test_base_case_invalid(tmp_path):
    path = write_study(tmp_path, "parameters:\n  gears.module: [9]\n")
    path.write_text(path.read_text().replace("0.4 s", "-1 s"))
    with pytest.raises(CaseError, match="the base case is invalid: .*run.end_time"):
        load_study(path)
    path.write_text(path.read_text().replace("base: /", "base: /nonexistent/"))
    with pytest.raises(CaseError, match="not found"):
        load_study(path)


def test_other_bad_inputs(tmp_path):
    assert "unknown key" in _error(tmp_path, "parameter:\n  gears.module: [9]\n")
    assert "unknown metric" in _error(tmp_path, "parameters:\n  gears.module: [9]\n"
                                      "metrics: [force_max]\n")
    assert "needs 'samples'" in _error(tmp_path, "design: lhs\nparameters:\n  gears.module: [9]\n")
    assert "needs 'num'" in _error(tmp_path, "parameters:\n  gears.module: {linspace: [9, 11]}\n")
    assert "one length" in _error(tmp_path, "design: zip\nparameters:\n  gears.module: [9, 11]\n"
                                  "  gears.face_width: [80]\n")


@pytest.mark.parametrize("speed, unit, final", [
    ('{function: "STEP(time, 0, 0, 0.1, 3000)", unit: deg/s}', "deg/s", "3600"),
    ('{function: "STEP5(time, 0, 0, 0.1, 50)", unit: rad/s}', "rad/s", "62.8318530718"),
    ('{function: "RAMP(time, 0, 0, 0.1, 500)", unit: rpm}', "rpm", "600"),
])
def test_mesh_frequency_keeps_a_mapping_ramp(tmp_path, speed, unit, final):
    """A drive speed written as {function: STEP(...), unit: ...} keeps its ramp, in its unit
    (it became a constant speed: the ramp was lost); 170 Hz with 17 teeth = 10 rev/s."""
    path = write_study(tmp_path, "parameters:\n  mesh_frequency: [\"170 Hz\"]\n")
    path.write_text(path.read_text().replace("drive.speed: STEP(time, 0, 0, 0.1, 3000)",
                                             f"drive.speed: {speed}"))
    s = load_study(path)
    name = speed.split('"')[1].split("(")[0]
    assert s.points[0].overrides[0] == json.dumps(
        {"function": f"{name}(time,0,0,0.1,{final})", "unit": unit}).join(["drive.speed=", ""])
    drive = json.loads(s.points[0].case_json)["drive"]["speed"]
    assert drive["function"].startswith(name)  # a ramp, not a constant
    rad_s = Case.model_validate(json.loads(s.points[0].case_json)).drive.speed.pp
    assert rad_s(0.0) == 0.0
    assert rad_s(0.3) == pytest.approx(20.0 * math.pi, rel=1e-11)  # 10 rev/s, 12 digits kept


def test_mesh_frequency_ramp_in_a_declared_unit_system(tmp_path):
    """A bare "STEP(...)" in a case declaring ``units:`` is in that system's unit of angular
    velocity: the ramp's final value is written in it (it was written in deg/s, so 90 Hz of
    the 18-tooth sun became 1800 rpm, six times the speed)."""
    path = tmp_path / "study.yaml"
    path.write_text(f"""base: {ROOT / "cases" / "nrel5mw_sun_planet.yaml"}
set:
  drive.speed: STEP(time, 0, 0, 0.2, 246)
parameters:
  mesh_frequency: ["90 Hz"]
""")
    s = load_study(path)
    assert s.points[0].overrides[0] == "drive.speed=STEP(time,0,0,0.2,300)"  # rpm: 5 rev/s
    rad_s = Case.model_validate(json.loads(s.points[0].case_json)).drive.speed.pp
    assert rad_s(0.5) == pytest.approx(10.0 * math.pi, rel=1e-11)
