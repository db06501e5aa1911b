"""Case loading: the seed case, unit-string equivalence, time functions, the resolved dump."""

import json
import math

import pytest

from gearcli.case.load import load_case, load_case_text
from tests.conftest import SEED

# The seed case written in SI / explicit unit strings: must load to identical internals.
SEED_SI = """
name: seed
gears:
  module: "0.01 m"
  pressure_angle: "0.3490658503988659 rad"
  face_width: "10 cm"
  pinion: {teeth: 17}
  gear: {teeth: 25}
material:
  density: "7850 kg/m^3"
  youngs_modulus: "207 GPa"
  poisson_ratio: 0.29
contact:
  law: impact
  stiffness: "3.1622776601683795e9 N/m^1.5"  # 1e5 * 1000^1.5
  exponent: 1.5
  max_damping: "1e5 N*s/m"
  penetration_depth: "1e-4 m"
friction:
  static_coefficient: 0.08
  dynamic_coefficient: 0.05
  stiction_velocity: "1e-5 m/s"
  transition_velocity: "1e-4 m/s"
drive:
  type: speed
  speed: {function: "STEP(time, 0, 0, 1, 3000)", unit: "deg/s"}
load:
  applied_to: gear
  torque: {function: "STEP(time, 0, 0, 1, 450)", unit: "N*m"}
run:
  end_time: "5000 ms"
"""


def _resolved(case) -> dict:
    return json.loads(case.model_dump_json())


def test_seed_loads_with_article_values():
    c = load_case(SEED).case
    assert c.gears.module == 10.0
    assert c.gears.pressure_angle == pytest.approx(math.radians(20), rel=1e-15)
    assert c.contact.stiffness == 1e5 and c.contact.exponent == 1.5
    assert c.material.density == pytest.approx(7.85e-9, rel=1e-15)  # t/mm^3
    assert c.drive.speed.pp(0.5) == pytest.approx(math.radians(1500), rel=1e-14)
    assert c.drive.speed.pp.final_value() == pytest.approx(math.radians(3000), rel=1e-14)
    assert c.load.torque.pp(3.0) == pytest.approx(4.5e5)  # N*mm
    assert c.run.end_time == 5.0


def test_si_strings_load_to_identical_internals():
    a = load_case(SEED).case
    b = load_case_text(SEED_SI).case
    ra, rb = _resolved(a), _resolved(b)
    ra.pop("description"), rb.pop("description")
    # Time functions are kept as written (expression + unit): compare their values instead.
    for r in (ra, rb):
        r["drive"].pop("speed"), r["load"].pop("torque")

    def close(x, y, path=""):
        if isinstance(x, dict):
            assert x.keys() == y.keys(), path
            for k in x:
                close(x[k], y[k], f"{path}.{k}")
        elif isinstance(x, str) and " " in x:
            vx, ux = x.split(" ", 1)
            vy, uy = y.split(" ", 1)
            assert ux == uy, path
            assert float(vx) == pytest.approx(float(vy), rel=1e-12), path
        elif isinstance(x, float):
            assert x == pytest.approx(y, rel=1e-12), path
        else:
            assert x == y, path

    close(ra, rb)
    for t in (0.0, 0.3, 0.7, 1.0, 4.0):
        assert a.drive.speed.pp(t) == pytest.approx(b.drive.speed.pp(t), rel=1e-14)
        assert a.load.torque.pp(t) == pytest.approx(b.load.torque.pp(t), rel=1e-14)


def test_resolved_case_round_trips():
    a = load_case(SEED).case
    text = json.dumps(_resolved(a))  # JSON is YAML
    b = load_case_text(text).case
    assert _resolved(b) == _resolved(a)


def test_a_constant_in_a_mapping_takes_its_unit_and_round_trips():
    # {function: "450", unit: "N*m"} was read as 450 N*mm, and every sweep that wrote a case
    # with a constant speed back ({function: "52.36", unit: "rad/s"}) ran it at 52.36 deg/s
    text = SEED.read_text()
    plain = load_case_text(text.replace("speed: STEP(time, 0, 0, 1, 3000)", "speed: 500 rpm")
                           ).case
    mapped = load_case_text(text.replace("speed: STEP(time, 0, 0, 1, 3000)",
                                         'speed: {function: "500", unit: rpm}')).case
    assert mapped.drive.speed.pp(1.0) == pytest.approx(plain.drive.speed.pp(1.0), rel=1e-15)
    for number in ("1e3*0.5", "(500)"):  # numbers too, not "carries its own unit"
        other = load_case_text(text.replace("speed: STEP(time, 0, 0, 1, 3000)",
                                            f'speed: {{function: "{number}", unit: rpm}}')).case
        assert other.drive.speed.pp(1.0) == pytest.approx(plain.drive.speed.pp(1.0), rel=1e-15)
    assert plain.drive.speed.pp(1.0) == pytest.approx(math.radians(3000.0), rel=1e-12)  # rad/s
    again = load_case_text(json.dumps(_resolved(plain))).case
    assert again.drive.speed.pp(1.0) == plain.drive.speed.pp(1.0)
    with pytest.raises(Exception, match="carries its own unit"):
        load_case_text(text.replace("speed: STEP(time, 0, 0, 1, 3000)",
                                    'speed: {function: "500 rpm", unit: rpm}'))
