"""`--svg` of `gearcli run` and `gearcli report` (issue 29): the report's figures are PNG only
unless SVG is asked for; a report without --svg removes the SVGs of an earlier one."""

from __future__ import annotations

from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import SEED

runner = CliRunner()
SHORT = ["--set", "run.end_time=0.3", "--set", "drive.speed=STEP(time, 0, 0, 0.1, 3000)",
         "--set", "load.torque=STEP(time, 0, 0, 0.1, 4.5e5)"]


def test_run_svg_then_report_without_it(tmp_path):
    out = tmp_path / "run"
    res = runner.invoke(app, ["run", str(SEED), "-o", str(out), "-q", "--svg", *SHORT])
    assert res.exit_code in (0, 4), res.output
    figures = out / "figures"
    pngs = sorted(p.stem for p in figures.glob("*.png"))
    assert pngs and pngs == sorted(p.stem for p in figures.glob("*.svg"))
    res = runner.invoke(app, ["report", str(out), "--force", "-q"])
    assert res.exit_code == 0, res.output
    assert sorted(p.stem for p in figures.glob("*.png")) == pngs
    assert not list(figures.glob("*.svg"))
