"""`gearcli modal` works for every mesh `gearcli mesh` works for (issue 31): beyond the 62/62
pairs of tests/cli/test_modal_no_single_zone_cli.py (ε_α 1.79 and 15°), a high-contact-ratio
pair (80/120, m 2, α 16°, rack addendum 1.35: no single- and no double-pair zone, three pairs
or more in contact everywhere at its load). Both commands complete; the mesh mode is the 2-DOF
closed form of the linearised (mean) mesh stiffness with the pinion held by the speed drive,
f = √(k r_b2²/J2)/(2π) (docs/theory.md §4.4, §11.2)."""

import json
import math

from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import ROOT

runner = CliRunner()

HIGH_CONTACT = ["gears.module=2 mm", "gears.face_width=20 mm", "gears.pinion.teeth=80",
                "gears.gear.teeth=120", "gears.pinion.profile_shift=0",
                "gears.gear.profile_shift=0", "gears.pinion.bore_diameter=null",
                "gears.gear.bore_diameter=null", "gears.rack.addendum=1.35",
                "gears.rack.dedendum=1.6", "gears.rack.root_radius=0.15",
                "gears.pressure_angle=16 deg"]


def _run(command, *args):
    sets = [a for o in HIGH_CONTACT for a in ("--set", o)]
    return runner.invoke(app, [command, str(ROOT / "cases" / "iso_pair.yaml"), *sets, *args])


def test_modal_works_on_a_mesh_with_three_pairs_everywhere():
    mesh = _run("mesh", "--json")
    assert mesh.exit_code == 0, mesh.output
    r = _run("modal", "--json")
    # exit 4 is the case's resonance-margin check failing at this speed, not an error
    assert r.exit_code in (0, 4), r.output
    doc = json.loads(r.stdout)
    lin = doc["linearisation"]
    assert lin["single_pair_stiffness_N_mm"] is None  # no single-pair zone
    assert lin["double_pair_stiffness_N_mm"] is None  # nor a double-pair one
    mode = doc["modes"][0]
    assert "mesh" in mode["description"]
    # with a speed drive the pinion is held: f = √(k r_b2²/J2)/(2π), r_b2 = m z2 cos α / 2
    r_b2 = 2.0 * 120 * math.cos(math.radians(16.0)) / 2.0
    k, j2 = lin["mesh_stiffness_N_mm"], doc["bodies"]["gear_inertia_t_mm2"]
    f = math.sqrt(k * r_b2**2 / j2) / (2.0 * math.pi)
    assert abs(mode["undamped_frequency_Hz"] / f - 1.0) < 1e-9  # the same formula, round-off
    table = _run("modal")
    assert table.exit_code in (0, 4), table.output
    assert "not applicable" in " ".join(table.output.split())
