"""Issue 32: every user-supplied name (case, study, --set name=) is printed and drawn as plain
text. Before: "x[/bold]" crashed geometry, modal, mesh, stress (rich markup) and "$\\frac{1$"
crashed run, sweep and speed curves after all the computation (matplotlib mathtext), exit 3;
a non-UTF-8 byte in --set or a Latin-1 case-file name was exit 3 too."""

from __future__ import annotations

import json
import os

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import ROOT
from tests.unit.sweep_helpers import write_study

runner = CliRunner()
SEED = str(ROOT / "cases" / "seed.yaml")
#: both hazards at once: a rich closing tag and an unbalanced mathtext fraction
NAME = "x[/bold] $\\frac{1$"


@pytest.mark.parametrize("command", ["geometry", "modal", "mesh"])
def test_a_markup_and_mathtext_name_is_plain_text(tmp_path, command):
    fig = tmp_path / "f.png"
    r = runner.invoke(app, [command, SEED, "--set", f"name={NAME}", "--plot", str(fig)])
    assert r.exit_code == 0, r.output
    assert NAME in r.stdout  # printed as written, not read as markup
    assert fig.stat().st_size > 0  # the title drawn, not parsed as mathtext


@pytest.fixture(scope="module")
def run_folder(tmp_path_factory):
    out = tmp_path_factory.mktemp("names") / "run"
    r = runner.invoke(app, ["run", SEED, "-o", str(out), "--set", f"name={NAME}",
                            "--set", "run.end_time=0.6"])
    assert r.exit_code in (0, 4), r.output  # 4: a check of the short run; never 3
    return out


def test_run_with_the_name_writes_its_report_and_figures(run_folder):
    assert (run_folder / "report.html").stat().st_size > 0
    assert json.loads((run_folder / "summary.json").read_text())["case"] == NAME


def test_stress_prints_and_draws_the_name(run_folder, tmp_path):
    fig = tmp_path / "s.png"
    r = runner.invoke(app, ["stress", str(run_folder), "--plot", str(fig)])
    assert r.exit_code == 0, r.output
    assert NAME in r.stdout and fig.stat().st_size > 0


@pytest.mark.parametrize("design", ["grid", "speed_curve"])
def test_sweep_with_the_name_finishes(tmp_path, design):
    body = (f"name: '{NAME}'\n" + ("design: speed_curve\nparameters:\n  mesh_frequency: "
                                    "['300 Hz', '400 Hz']\n" if design == "speed_curve" else
                                    "parameters:\n  gears.face_width: ['80 mm', '90 mm']\n"))
    path = write_study(tmp_path, body)
    r = runner.invoke(app, ["sweep", str(path), "-o", str(tmp_path / "o"), "-j", "1"])
    assert r.exit_code == 0, r.output
    png = "speed_curve.png" if design == "speed_curve" else "trend_gears_face_width__mm.png"
    assert (tmp_path / "o" / png).stat().st_size > 0


@pytest.mark.parametrize("command", ["geometry", "modal", "mesh"])
def test_non_utf8_bytes_in_set_are_a_one_line_error(command):
    # how Python hands a command-line byte 0xff to the program (surrogateescape)
    r = runner.invoke(app, [command, SEED, "--set", "name=x\udcff"])
    assert r.exit_code == 1, r.output
    assert "not UTF-8 text" in r.stderr and "x\\xff" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_a_latin1_case_file_name_works(tmp_path):
    path = tmp_path / os.fsdecode(b"caf\xe9.yaml")  # a Latin-1 'e acute' in the file name
    text = (ROOT / "cases" / "seed.yaml").read_text().replace("name: seed\n", "")
    path.write_text(text)
    r = runner.invoke(app, ["geometry", str(path), "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["case"] == "caf\ufffd"  # the undecodable byte as U+FFFD
    out = tmp_path / "run"
    r = runner.invoke(app, ["run", str(path), "-o", str(out), "--set", "run.end_time=0.6"])
    assert r.exit_code in (0, 4), r.output
    assert "caf\ufffd" in (out / "report.html").read_text(encoding="utf-8")
