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


def test_analyze_orders_draws_the_run_up_order_map(tmp_path):
    """`analyze --orders FILE` (issue 19): the order map of the run-up; an existing FILE only
    with --force; the report of a run-up gains the same figure."""
    run = tmp_path / "run"
    assert runner.invoke(app, ["simulate", str(SEED), "-o", str(run), "-q", *SHORT]).exit_code == 0
    fig = tmp_path / "orders.png"
    res = runner.invoke(app, ["analyze", str(run), "-q", "--orders", str(fig)])
    assert res.exit_code in (0, 4), res.output
    assert fig.stat().st_size > 20_000
    res = runner.invoke(app, ["analyze", str(run), "-q", "--force", "--orders", str(fig)])
    assert res.exit_code in (0, 4)  # --force covers both the analysis and the figure
    res = runner.invoke(app, ["analyze", str(run), "-q", "--force", "--orders",
                              str(tmp_path / "orders.txt")])
    assert res.exit_code == 1 and ".png, .svg or .pdf" in res.output
    assert runner.invoke(app, ["report", str(run)]).exit_code == 0
    assert (run / "figures" / "orders.png").is_file()
