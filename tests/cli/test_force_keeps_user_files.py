"""--force replaces gearcli's results, never the user's files (io/outdir.py): whatever else an
earlier results folder holds moves into the new one; and the list of what gearcli
writes (outdir.RESULT_NAMES) covers every file the commands write, so that no stale result is
moved over as if it were the user's."""

from __future__ import annotations

import os

from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.io.outdir import RESULT_NAMES, user_entries
from tests.conftest import SEED

runner = CliRunner()
SHORT = ["--set", "run.end_time=0.4", "--set", "drive.speed=STEP(time, 0, 0, 0.1, 3000)",
         "--set", "load.torque=STEP(time, 0, 0, 0.1, 4.5e5)"]


def _ok(args):
    res = runner.invoke(app, args)
    assert res.exit_code in (0, 4), (args, res.output)
    return res


def test_every_file_the_commands_write_is_a_result_name(tmp_path):
    run, parquet, mesh = tmp_path / "run", tmp_path / "parquet", tmp_path / "mesh"
    _ok(["run", str(SEED), "-o", str(run), "-q", *SHORT])
    _ok(["stress", str(run)])
    _ok(["report", str(run), "--format", "md", "--force"])  # beside the html of run
    _ok(["simulate", str(SEED), "-o", str(parquet), "-q", "--format", "parquet", *SHORT])
    _ok(["mesh", str(SEED), "-o", str(mesh), "-q"])
    for folder in (run, parquet, mesh):
        assert user_entries(folder) == [], folder
    written = {q.name for folder in (run, parquet, mesh) for q in folder.iterdir()}
    assert {"report.html", "report.md", "stress.json", "analysis.json", "timeseries.parquet",
            "zoom.csv", "mesh.json", "figures"} <= written
    assert written <= RESULT_NAMES


def test_force_keeps_the_users_files_and_drops_stale_results(tmp_path):
    run = tmp_path / "run"
    _ok(["simulate", str(SEED), "-o", str(run), "-q", *SHORT])
    _ok(["stress", str(run)])  # a result of the earlier run, stale once it is replaced
    (run / "notes.txt").write_text("bearing supplier said 20 um runout\n")
    (run / "mine").mkdir()
    (run / "mine" / "fit.py").write_text("print(1)\n")
    os.symlink("notes.txt", run / "notes-link")
    again = runner.invoke(app, ["simulate", str(SEED), "-o", str(run), "-q", *SHORT])
    assert again.exit_code == 1 and "--force" in again.output  # never without --force
    _ok(["simulate", str(SEED), "-o", str(run), "-q", "--force", *SHORT])
    assert (run / "notes.txt").read_text() == "bearing supplier said 20 um runout\n"
    assert (run / "mine" / "fit.py").read_text() == "print(1)\n"
    assert os.readlink(run / "notes-link") == "notes.txt"
    assert not (run / "stress.json").exists()  # the earlier run's, not the new one's
    assert (run / "summary.json").is_file() and (run / "timeseries.csv").is_file()
    assert not [q for q in tmp_path.iterdir() if q.name.startswith(".")
                and not q.name.endswith(".lock")]  # no temporary left (lock files stay)
