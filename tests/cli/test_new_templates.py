"""`gearcli new --template pair|seed|drivetrain` (issue 29): the default is a neutral pair in
engineering units that runs clean; every template runs; bundled copies equal cases/."""

import pytest
from typer.testing import CliRunner

from gearcli.case.load import load_case
from gearcli.case.starter import TEMPLATES, starter_text
from gearcli.cli import app
from tests.conftest import ROOT

runner = CliRunner()


@pytest.mark.parametrize("name", ["seed", "drivetrain"])
def test_bundled_templates_are_the_repository_cases(name):
    assert starter_text(name) == (ROOT / "cases" / f"{name}.yaml").read_text()


def test_the_default_is_the_engineering_pair(tmp_path):
    target = tmp_path / "my_pair.yaml"
    res = runner.invoke(app, ["new", str(target)])
    assert res.exit_code == 0, res.output
    assert target.read_text() == starter_text("pair")
    loaded = load_case(target)
    assert loaded.case.units == "engineering"
    assert loaded.name == "my_pair"  # no name in the template: results are titled by the file
    assert loaded.case.contact.law == "tooth" and 0.03 <= loaded.case.contact.damping_ratio <= 0.1
    assert "units: engineering" in target.read_text().splitlines()[7]  # declared at the top


def test_the_pair_runs_clean(tmp_path):
    """Exit 0 and not one warning: no contact loss, no coast-flank impacts, no overdamping."""
    target = tmp_path / "pair.yaml"
    assert runner.invoke(app, ["new", str(target)]).exit_code == 0
    res = runner.invoke(app, ["simulate", str(target), "-o", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    assert "warning" not in res.stderr, res.stderr


@pytest.mark.parametrize("name", [n for n in TEMPLATES if n != "pair"])
def test_every_other_template_simulates(name, tmp_path):
    target = tmp_path / f"{name}.yaml"
    assert runner.invoke(app, ["new", "--template", name, str(target)]).exit_code == 0
    res = runner.invoke(app, ["simulate", str(target), "-o", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output


def test_unknown_template_names_the_allowed_ones(tmp_path):
    res = runner.invoke(app, ["new", "--template", "helical", str(tmp_path / "c.yaml")])
    assert res.exit_code == 1
    assert res.stderr.strip() == "error: --template helical: expected one of: pair, seed, " \
        "drivetrain"
    assert not (tmp_path / "c.yaml").exists()
