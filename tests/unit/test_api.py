"""The Python API (gearcli/api.py, issue 17): light and side-effect-free import, the same
numbers as the command line's files, the command line's error messages, the examples run."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from typer.testing import CliRunner

import gearcli
from gearcli.cli import app
from gearcli.errors import CaseError
from tests.conftest import ROOT, SEED

runner = CliRunner()
SHORT = {"run.end_time": "0.6 s", "drive.speed": "STEP(time, 0, 0, 0.2, 3000)",
         "load.torque": "STEP(time, 0, 0, 0.2, 4.5e5)"}
SHORT_SET = [a for k, v in SHORT.items() for a in ("--set", f"{k}={v}")]


def test_import_is_light_and_changes_nothing():
    code = """
import os, sys, warnings
env = dict(os.environ); filters = list(warnings.filters)
import gearcli
assert dict(os.environ) == env, set(os.environ) ^ set(env)
assert warnings.filters == filters
heavy = [m for m in ("numpy", "pandas", "numba", "matplotlib", "scipy", "pydantic")
         if m in sys.modules]
assert not heavy, heavy
assert callable(gearcli.simulate) and "simulate" in dir(gearcli)
print("ok")
"""
    env = {k: v for k, v in __import__("os").environ.items()
           if not k.endswith("_NUM_THREADS")}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, env=env, cwd=ROOT)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


def test_simulate_returns_the_numbers_of_the_cli_files(tmp_path):
    sim = gearcli.simulate(SEED, set=SHORT)
    res = runner.invoke(app, ["simulate", str(SEED), "-o", str(tmp_path / "run"), "-q",
                              *SHORT_SET])
    assert res.exit_code == 0, res.output
    scalars = json.loads((tmp_path / "run" / "summary.json").read_text())["scalars"]
    s = sim.summary
    for name in ("dynamic_factor", "force_max_N", "dte_peak_to_peak_mm", "force_static_N",
                 "mesh_natural_frequency_Hz", "contact_loss_fraction"):
        assert getattr(s, name) == pytest.approx(scalars[name], rel=1e-12), name
    assert sim.status == "ok" and isinstance(sim.warnings, list)
    df = sim.series
    assert df.index.name == "t_s" and "force_total_N" in df.columns
    assert df["force_total_N"].max() <= s.force_max_N * (1 + 1e-12)
    assert s.to_dict()["dynamic_factor"] == s.dynamic_factor
    assert sim.plot("force").axes and sim.plot("dte").axes
    saved = sim.save(tmp_path / "api_run")
    assert (saved / "timeseries.csv").is_file()
    with pytest.raises(gearcli.errors.OutputError, match="--force"):
        sim.save(tmp_path / "api_run")


def test_analyze_a_simulation_equals_analyze_of_the_cli_folder(tmp_path):
    sim = gearcli.simulate(SEED, set=SHORT)
    from_api = gearcli.analyze(sim)
    sim.save(tmp_path / "run")
    from_folder = gearcli.analyze(tmp_path / "run")
    assert isinstance(from_api.metrics, gearcli.AnalysisMetrics)
    api_metrics, folder_metrics = from_api.metrics.to_dict(), from_folder.metrics.to_dict()
    assert api_metrics.keys() == folder_metrics.keys()
    for key, value in folder_metrics.items():
        if isinstance(value, float):
            assert api_metrics[key] == pytest.approx(value, rel=1e-9, nan_ok=True), key
    # the typed metrics are analysis.json's metrics, field by field
    for key, value in from_folder.document()["metrics"].items():
        if isinstance(value, float):
            assert folder_metrics[key] == value, key
    assert from_api.passed == from_folder.passed and from_api.checks
    spectra = gearcli.spectra_frame(from_api)
    assert spectra.index.name == "frequency_Hz" and len(spectra.columns) >= 2
    assert from_api.spectra.equals(spectra)
    assert repr(from_api).startswith("<Analysis seed: ")
    # stress: typed per-gear peaks equal stress.json's
    st = gearcli.stress(tmp_path / "run")
    doc = st.document()
    assert st.pinion.teeth == 17 and st.gear.teeth == 25
    assert st.pinion.sigma_H_peak_MPa == doc["pinion"]["peak_sigma_H"]["MPa"]
    assert st.gear.sigma_F_peak_MPa == doc["gear"]["peak_sigma_F"]["MPa"]
    assert repr(st).startswith("<Stress seed: σ_H peak ")


def test_modal_returns_typed_modes_equal_to_the_cli_json():
    m = gearcli.modal(SEED)
    res = runner.invoke(app, ["modal", str(SEED), "--json"])
    assert res.exit_code in (0, 4), res.output
    doc = json.loads(res.output)
    assert [x.natural_frequency_Hz for x in m.modes] == \
        [x["natural_frequency_Hz"] for x in doc["modes"]]
    assert all(isinstance(x, gearcli.Mode) for x in m.modes)
    assert m.passed == doc["passed"] and m.plot().axes


def test_load_case_from_a_mapping_with_overrides_and_the_cli_error_messages(tmp_path):
    import yaml

    data = yaml.safe_load(SEED.read_text())
    case = gearcli.load_case(data, set={"gears.face_width": "80 mm"})
    assert case.case.gears.face_width == pytest.approx(80.0)
    with pytest.raises(CaseError) as api_err:
        gearcli.load_case(SEED, set={"gears.modul": 9})
    res = runner.invoke(app, ["simulate", str(SEED), "-o", str(tmp_path / "x"), "--set",
                              "gears.modul=9"])
    assert res.exit_code == 1
    assert str(api_err.value).splitlines()[0] in res.output
    geo = gearcli.geometry(case)
    assert geo.geometry.pinion.teeth == 17


@pytest.mark.slow
@pytest.mark.parametrize("script", ["seed_study.py", "module_loop.py",
                                    "spectra_postprocessing.py", "fault_metrics.py"])
def test_examples_run(tmp_path, script):
    args = [str(tmp_path / "out")] if script != "spectra_postprocessing.py" else []
    if script in ("module_loop.py", "fault_metrics.py"):  # a figure, not docs/'s
        args = [str(tmp_path / "figure.png")]
    out = subprocess.run([sys.executable, str(ROOT / "examples" / script), *args],
                         capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "Traceback" not in out.stderr
    if script == "fault_metrics.py":
        assert (tmp_path / "figure.png").stat().st_size > 0


def test_documents_carry_the_schema_version_and_the_results_schema_validates_one(tmp_path):
    res = runner.invoke(app, ["simulate", str(SEED), "-o", str(tmp_path / "run"), "-q",
                              *SHORT_SET])
    assert res.exit_code == 0, res.output
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["schema_version"] == gearcli.SCHEMA_VERSION == 1
    res = runner.invoke(app, ["analyze", str(tmp_path / "run"), "--json"])
    assert res.exit_code in (0, 4), res.output  # 4: the seed's checks (test_analyze_cli)
    analysis = json.loads((tmp_path / "run" / "analysis.json").read_text())
    assert analysis["schema_version"] == 1
    res = runner.invoke(app, ["schema", "--results"])
    assert res.exit_code == 0

    def strict(text):  # JSON as other parsers read it: no NaN or Infinity
        return json.loads(text, parse_constant=lambda c: pytest.fail(f"{c} in the schema"))

    schema = strict(res.output)
    res = runner.invoke(app, ["schema", "--results", "--kind", "analysis"])
    assert res.exit_code == 0
    a_schema = strict(res.output)
    assert set(a_schema["required"]) <= set(analysis)
    for key in a_schema["properties"]["metrics"]["properties"]:
        assert key in analysis["metrics"], key
    for kind in ("stress", "modal"):
        res = runner.invoke(app, ["schema", "--results", "--kind", kind])
        assert res.exit_code == 0 and strict(res.output)["title"]
    bad = runner.invoke(app, ["schema", "--results", "--kind", "spectra"])
    assert bad.exit_code == 1 and "--kind spectra" in bad.output
    from pydantic import TypeAdapter  # noqa: F401  (pydantic is a dependency; jsonschema is not)

    # the schema's required keys and every scalar it names are in a real summary.json
    assert set(schema["required"]) <= set(summary)
    for key in schema["properties"]["scalars"]["properties"]:
        assert key in summary["scalars"], key
    assert gearcli.geometry(SEED).to_dict()["pinion"]["z"] == 17


def test_metric_labels_and_units_come_from_one_registry():
    """gearcli/results/metrics.py is the one place of a metric's label and display unit: the
    typed Summary, the report's results table and the CLI tables read it (issue 17)."""
    import dataclasses

    from gearcli.results import PLACES, AnalysisMetrics, shown
    from gearcli.results.metrics import METRICS

    for f in dataclasses.fields(gearcli.Summary):
        if f.name in METRICS:
            assert f.metadata["label"] == METRICS[f.name].label, f.name
            assert f.metadata["unit"] == METRICS[f.name].unit, f.name
    for place in PLACES:  # every shown metric has the registry's label and unit
        for cls in (gearcli.Summary, AnalysisMetrics):
            assert set(shown(cls, place)) <= set(METRICS), (place, cls)


def test_mesh_returns_a_typed_summary_equal_to_the_cli_json():
    m = gearcli.mesh(ROOT / "cases" / "iso_pair.yaml")
    res = runner.invoke(app, ["mesh", str(ROOT / "cases" / "iso_pair.yaml"), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    assert isinstance(m.summary, gearcli.MeshSummary)
    assert m.summary.to_dict() == doc  # the typed document is the JSON
    assert m.summary.ste.peak_to_peak_um == doc["ste"]["peak_to_peak_um"]
    assert m.summary.stiffness.mesh_mean_N_mm == doc["stiffness"]["mesh_mean_N_mm"]
    assert m.summary.iso6336_method_b.k_v == doc["iso6336_method_b"]["k_v"]
    table = m.table
    assert table.index.name == "roll_mm" and "ste_um" in table.columns
    assert table["ste_um"].max() - table["ste_um"].min() == pytest.approx(
        m.summary.ste.peak_to_peak_um, rel=1e-9)
    schema = json.loads(runner.invoke(app, ["schema", "--results", "--kind", "mesh"]).output)
    for group in ("ste", "stiffness", "iso6336_method_b"):
        for key in schema["properties"][group]["properties"]:
            assert key in doc[group], (group, key)


@pytest.mark.parametrize("source", [None, 123, b"cases/seed.yaml", ["cases/seed.yaml"]])
def test_load_case_refuses_what_is_no_case_with_a_gearcli_error(source):
    from gearcli.errors import CaseError

    with pytest.raises(CaseError, match="expected the path of a case file"):
        gearcli.load_case(source)


def test_one_override_text_is_one_override():
    # a str was iterated character by character ("--set 'r': expected key.path=value")
    case = gearcli.load_case(SEED, set="run.end_time=0.3")
    assert case.case.run.end_time == 0.3


def test_analyze_takes_a_window_with_units_and_refuses_a_bad_one(tmp_path):
    sim = gearcli.simulate(SEED, set={"run.end_time": 0.8})
    a = gearcli.analyze(sim, window=("0.2 s", "800 ms"))  # the spectra need >= 0.353 s
    assert a.document()["window_s"] == pytest.approx([0.2, 0.8])
    with pytest.raises(CaseError, match="no number in front"):
        gearcli.analyze(sim, window=("s", 0.8))


@pytest.mark.parametrize("jobs", [0, -1, "2", 1.5, True])
def test_sweep_refuses_a_bad_worker_count(jobs):
    with pytest.raises(CaseError, match="expected a whole number of worker processes"):
        gearcli.sweep(ROOT / "cases" / "seed.yaml", jobs=jobs)


def test_sweep_refuses_what_is_no_study():
    with pytest.raises(CaseError, match="expected the path of a study file"):
        gearcli.sweep({"parameters": {"gears.module": [10]}})


@pytest.mark.parametrize("call, match", [
    # each raised a raw TypeError/ValueError from deep inside (third adversarial run)
    (lambda: gearcli.mesh(SEED, load_N=True), "load_N=True: expected a value"),
    (lambda: gearcli.mesh(SEED, load_N="5 mm"), "load_N '5 mm'"),
    (lambda: gearcli.mesh(SEED, harris="no"), "harris='no': expected True or False"),
    (lambda: gearcli.modal(SEED, speed_range_deg_s=600.0), "expected 2 values"),
    (lambda: gearcli.analyze(123), "run=123: expected a Simulation or the path"),
    (lambda: gearcli.stress("somewhere", window=(None, None)), "window"),
    (lambda: gearcli.analyze("somewhere", window=0.2), "window=0.2: expected 2 values"),
    (lambda: gearcli.geometry(SEED, set=1), "set=1: expected a mapping"),
    (lambda: gearcli.load_case(SEED, set={"run.end_time": object()}),
     r"set\['run.end_time'\]: got <object"),
    (lambda: gearcli.load_case(SEED, set={"run.end_time": float("nan")}),
     r"set\['run.end_time'\]: got nan"),
])
def test_api_bad_arguments_are_case_errors(call, match):
    with pytest.raises(CaseError, match=match):
        call()


def test_api_takes_quantities_with_units_like_the_command_line():
    m = gearcli.mesh(SEED, load_N="2 kN")
    assert m.summary.force_N == pytest.approx(2000.0)
    modal = gearcli.modal(SEED, speed_range_deg_s=("0 rpm", "6000 rpm"))
    assert modal.speed_range_deg_s == pytest.approx((0.0, 36000.0))
    with pytest.raises(CaseError, match="progress=1: expected a callable"):
        gearcli.simulate(SEED, progress=1)
    with pytest.raises(CaseError, match="progress=1: expected a callable"):
        gearcli.sweep(ROOT / "cases" / "studies" / "table5.yaml", progress=1)
    import numpy as np  # numpy scalars are numbers (np.int64 from a DataFrame, say)

    case = gearcli.load_case(SEED, set={"gears.pinion.teeth": np.int64(18),
                                        "run.end_time": np.float32(0.5)}).case
    assert case.gears.pinion.teeth == 18 and case.run.end_time == 0.5
