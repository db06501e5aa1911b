"""analyze, report and stress never replace earlier outputs in a results folder without
--force, like simulate and run (issue 19); the earlier files stay as they were."""

from __future__ import annotations

from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import SEED

runner = CliRunner()
SHORT = ["--set", "run.end_time=0.4", "--set", "drive.speed=STEP(time, 0, 0, 0.1, 3000)",
         "--set", "load.torque=STEP(time, 0, 0, 0.1, 4.5e5)"]


def test_second_analyze_report_stress_need_force(tmp_path):
    run = tmp_path / "run"
    assert runner.invoke(app, ["simulate", str(SEED), "-o", str(run), "-q", *SHORT]).exit_code == 0
    for cmd, extra, name in (("analyze", ["-q"], "analysis.json"),
                             ("report", ["--format", "md"], "report.md"),
                             ("stress", [], "stress.json")):
        first = runner.invoke(app, [cmd, str(run), *extra])
        assert first.exit_code in (0, 4), (cmd, first.output)
        before = (run / name).read_bytes()
        again = runner.invoke(app, [cmd, str(run), *extra])
        assert again.exit_code == 1, (cmd, again.output)
        assert "--force" in again.output and again.output.startswith("error: ")
        assert (run / name).read_bytes() == before
        forced = runner.invoke(app, [cmd, str(run), *extra, "--force"])
        assert forced.exit_code in (0, 4), (cmd, forced.output)
