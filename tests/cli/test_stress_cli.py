"""`gearcli stress`: quasi-static runs against the static ISO values, outputs, bad input.

Quasi-static runs: the seed pair at 60 deg/s (f_z = 2.8 Hz against a mesh mode of ~850 Hz),
speed and load ramped in 0.05 s, no friction, no errors, linear contact (e = 1, k = 4e5 N/mm:
equal pairs share the load equally, the static deflection is 0.01 mm so the extended contact
outside the path is short), c_max = 5 N·s/mm reached at 1 µm (ζ ≈ 0.03). 0.5 s cover every
part of the path (> 1 mesh cycle in the window); the ramps are excluded with --window 0.1 0.5.
"""

import json
import math
import shutil

import numpy as np
import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.io.results import read_run
from tests.conftest import SEED
from tests.physics.simrun import write_run

runner = CliRunner()

QUASI_STATIC = ["drive.speed=STEP(time, 0, 0, 0.05, 60)",
                "load.torque=STEP(time, 0, 0, 0.05, 4.5e5)",
                "friction.enabled=false", "contact.max_damping=5",
                "contact.penetration_depth=0.001", "contact.exponent=1",
                "contact.stiffness=4e5", "run.end_time=0.5", "run.output_rate=20000"]
WINDOW = ("--window", "0.1", "0.5")
K_LINEAR = 4e5  # N/mm
LIMITS = ["material.contact_fatigue_limit=1500", "material.bending_fatigue_limit=430"]


@pytest.fixture(scope="module")
def plain_dir(tmp_path_factory):
    """Quasi-static, unmodified teeth."""
    return write_run(tmp_path_factory.mktemp("qs") / "plain", QUASI_STATIC)


@pytest.fixture(scope="module")
def relieved_dir(tmp_path_factory):
    """Quasi-static with the design-load tip relief on both gears: C_a = F/k over the length
    g_α − p_b of each double-contact zone. The transmission error is then constant and the load
    passes linearly from pair to pair, the assumption behind ISO 6336-2's rating at B (and
    material limits, for the safety factors)."""
    from gearcli.case.load import load_case
    from gearcli.pipeline.geometry import run_geometry

    geo = run_geometry(load_case(SEED)).geometry
    c_a = 450e3 / geo.gear.r_b_mm / K_LINEAR
    length = geo.g_alpha_mm - geo.p_b_mm
    relief = [f"modifications.tip_relief.{g}.{k}={v!r}" for g in ("pinion", "gear")
              for k, v in (("amount", c_a), ("length", length))]
    return write_run(tmp_path_factory.mktemp("qs") / "relieved", QUASI_STATIC + relief + LIMITS)


def _stress(folder, *args):
    """stress with --force: these tests rerun it on shared folders on purpose."""
    return runner.invoke(app, ["stress", str(folder), "--force", *args])


def _json(folder, *args):
    result = _stress(folder, "--json", *WINDOW, *args)
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


def _along_path(folder):
    """(x from A [mm], σ_H, σ_F pinion, σ_F gear) of every loaded slot sample in the window."""
    run = read_run(folder)
    stress = np.genfromtxt(folder / "stress.csv", delimiter=",", names=True)
    t = run.column("t_s")
    sel = (t >= 0.1) & (t <= 0.5)
    out = [[], [], [], []]
    for j in range(int(run.summary.slots)):
        on = sel & (run.column(f"force_slot{j}_N") > 0.0)
        for k, name in enumerate((f"sigma_H_slot{j}_MPa", f"sigma_F_pinion_slot{j}_MPa",
                                  f"sigma_F_gear_slot{j}_MPa")):
            out[k + 1].append(stress[name][on])
        out[0].append(run.column(f"x_slot{j}_mm")[on])
    return [np.concatenate(v) for v in out]


def _points(doc_folder):
    from gearcli.case.load import load_case_text
    from gearcli.pipeline.geometry import run_geometry

    run = read_run(doc_folder)
    return run_geometry(load_case_text(json.dumps(run.manifest["resolved_case"]))).geometry


# --- quasi-static: dynamic stresses equal the static ISO values ---------------------------------
def test_relieved_quasi_static_path_maximum_is_the_iso_value_at_B(relieved_dir):
    doc = _json(relieved_dir)
    geo = _points(relieved_dir)
    x, s_h, s_f1, s_f2 = _along_path(relieved_dir)
    st = doc["static"]
    at_b = st["pinion"]["sigma_H_at_B_MPa"]  # M1 σ_H0: Hertz at B, full static load
    # the ISO value has Z_ε (ISO 6336-2 eq. 4): Z_B Z_ε σ_H0
    assert st["pinion"]["sigma_H_iso_MPa"] == pytest.approx(
        st["pinion"]["Z_B"] * st["Z_eps"] * st["sigma_H0_MPa"], rel=1e-12)
    assert s_h.max() == pytest.approx(at_b, rel=0.01)
    assert x[np.argmax(s_h)] == pytest.approx(geo.B_mm - geo.A_mm, abs=0.5)
    # the Hertz peak at B over the ISO value: 1/Z_ε (Z_B = M1 here, M1 > 1)
    assert doc["pinion"]["ratio_sigma_H_to_static"] == pytest.approx(1.0 / st["Z_eps"],
                                                                     rel=0.01)
    # root stresses: pinion loaded at D, gear at B, the Method B load points
    assert s_f1.max() == pytest.approx(st["pinion"]["sigma_F0_MPa"], rel=0.01)
    assert x[np.argmax(s_f1)] == pytest.approx(geo.D_mm - geo.A_mm, abs=0.5)
    assert s_f2.max() == pytest.approx(st["gear"]["sigma_F0_MPa"], rel=0.01)
    assert x[np.argmax(s_f2)] == pytest.approx(geo.B_mm - geo.A_mm, abs=0.5)
    assert doc["gear"]["ratio_sigma_F_to_static"] == pytest.approx(1.0, abs=0.01)


def test_unrelieved_quasi_static_single_zone_and_entry(plain_dir):
    doc = _json(plain_dir)
    geo = _points(plain_dir)
    x, s_h, _, _ = _along_path(plain_dir)
    st = doc["static"]
    single = (x >= geo.B_mm - geo.A_mm) & (x <= geo.D_mm - geo.A_mm)
    assert s_h[single].max() == pytest.approx(st["pinion"]["sigma_H_at_B_MPa"], rel=0.01)
    # Without relief two equal pairs share the load from A on: half the load on the smallest
    # ρ_red of the path gives 1.25 × the B value for the seed pair; the path maximum is there.
    rho_a1, rho_a2 = geo.A_mm, geo.T1T2_mm - geo.A_mm
    e_star = st["E_star_MPa"]
    half_at_a = math.sqrt(0.5 * st["force_normal_N"] * e_star * (1 / rho_a1 + 1 / rho_a2)
                          / (math.pi * st["contact_face_width_mm"]))
    assert half_at_a / st["pinion"]["sigma_H_at_B_MPa"] == pytest.approx(1.247, abs=0.001)
    assert s_h.max() == pytest.approx(half_at_a, rel=0.01)
    assert abs(x[np.argmax(s_h)]) < 0.5
    assert doc["pinion"]["peak_sigma_H"]["MPa"] == pytest.approx(s_h.max(), rel=1e-9)


# --- outputs ----------------------------------------------------------------------------------
def test_table_files_and_plot(plain_dir, tmp_path):
    png = tmp_path / "stress.png"
    result = _stress(plain_dir, *WINDOW, "--plot", str(png))
    assert result.exit_code == 0, result.output
    for text in ("pinion (z = 17)", "gear (z = 25)", "peak dynamic σ_H", "σ_F0"):
        assert text in result.stdout
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    header = (plain_dir / "stress.csv").read_text().splitlines()[0].split(",")
    slots = read_run(plain_dir).summary.slots
    assert header[:2] == ["t_s", "mesh_cycle"] and len(header) == 2 + 3 * slots
    assert "sigma_F_gear_slot0_MPa" in header
    doc = json.loads((plain_dir / "stress.json").read_text())
    assert len(doc["pinion"]["sigma_H_max_per_tooth_MPa"]) == 17
    assert len(doc["gear"]["sigma_F_max_per_tooth_MPa"]) == 25
    assert doc["window_s"] == [0.1, 0.5]


def test_deterministic(plain_dir):
    first = _stress(plain_dir, "--json", *WINDOW).stdout
    data = (plain_dir / "stress.csv").read_bytes()
    assert _stress(plain_dir, "--json", *WINDOW).stdout == first
    assert (plain_dir / "stress.csv").read_bytes() == data


def test_safety_factors_against_the_peaks(relieved_dir):
    doc = _json(relieved_dir, "--safety")
    for which in ("pinion", "gear"):
        g = doc[which]
        sf = g["safety"]
        assert sf["S_H"] == pytest.approx(1500 / g["peak_sigma_H"]["MPa"], rel=1e-12)
        assert sf["S_F"] == pytest.approx(430 * 2.0 / g["peak_sigma_F"]["MPa"], rel=1e-12)


# --- bad input --------------------------------------------------------------------------------
def _one_line_error(result):
    assert result.exit_code == 1, result.output
    assert result.stderr.startswith("error: ") and "Traceback" not in result.output
    assert len(result.stderr.strip().splitlines()) == 1
    return result.stderr


def test_missing_material_limits_for_safety_factors(plain_dir):
    err = _one_line_error(_stress(plain_dir, "--safety"))
    assert "material.contact_fatigue_limit" in err and "missing" in err
    assert _json(plain_dir)["pinion"]["safety"] is None  # without --safety: no factors


def test_folder_without_per_pair_forces(plain_dir, tmp_path):
    old = tmp_path / "old"
    shutil.copytree(plain_dir, old)
    lines = (old / "timeseries.csv").read_text().splitlines()
    names = lines[0].split(",")
    keep = [i for i, n in enumerate(names) if not n.startswith(("force_slot", "x_slot"))]
    rows = [",".join(r.split(",")[i] for i in keep) for r in lines]
    (old / "timeseries.csv").write_text("\n".join(rows) + "\n")
    err = _one_line_error(_stress(old))
    assert "force_slot0_N" in err and "rerun gearcli simulate" in err


@pytest.mark.parametrize("args, fragment", [
    (("--window", "0.4", "9"), "outside the run"),
    (("--plot", "out.jpg"), ".png, .svg or .pdf"),
])
def test_bad_options(plain_dir, args, fragment):
    assert fragment in _one_line_error(_stress(plain_dir, *args))


def test_not_a_results_folder(tmp_path):
    assert "not found" in _one_line_error(_stress(tmp_path / "nope"))


def test_report_gains_a_stress_section(relieved_dir):
    assert _stress(relieved_dir, *WINDOW, "--safety").exit_code == 0
    assert runner.invoke(app, ["analyze", str(relieved_dir)]).exit_code \
        in (0, 4)
    result = runner.invoke(app, ["report", str(relieved_dir), "--format", "md", "--force"])
    assert result.exit_code == 0, result.output
    text = (relieved_dir / "report.md").read_text()
    assert "## Stress" in text and "contact σ\\_H" in text


def test_report_says_when_the_stress_window_is_not_the_analysis_window(tmp_path):
    # the stress table said "peak dynamic stress in the window" with peaks outside the window
    # the analysis tables above it used (third adversarial run)
    from typer.testing import CliRunner

    from gearcli.cli import app
    from tests.conftest import ROOT

    run, out = CliRunner(), tmp_path / "r"
    assert run.invoke(app, ["simulate", str(ROOT / "cases" / "iso_pair.yaml"), "-o", str(out),
                            "-q", "--set", "run.end_time=0.6"]).exit_code == 0
    assert run.invoke(app, ["analyze", str(out), "--window", "0.3", "0.5"]).exit_code in (0, 4)
    assert run.invoke(app, ["stress", str(out)]).exit_code in (0, 4)
    assert run.invoke(app, ["report", str(out), "--format", "md"]).exit_code in (0, 4)
    text = (out / "report.md").read_text()
    assert "of gearcli stress (" in text and "not the analysis window 0.3-0.5 s" in text
