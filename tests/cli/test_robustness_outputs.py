"""Issue 18, outputs: `run` all or nothing, signals clean up, folders follow the umask, the
manifest hashes what was parsed, bad output paths and hand-edited results folders are exit 1."""

from __future__ import annotations

import json
import os
import shutil
import signal
import time

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import SEED

runner = CliRunner()
SHORT = ["--set", "run.end_time=0.5"]


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def no_internal_error(r) -> None:
    assert "internal error" not in r.stderr and "Traceback" not in r.stderr, r.stderr


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """A complete `gearcli run` folder (results, analysis, report)."""
    out = tmp_path_factory.mktemp("run") / "seed"
    r = invoke("run", SEED, "-o", out, "-q", *SHORT)
    assert r.exit_code in (0, 4), r.stderr
    return out


def _copy(finished, tmp_path):
    dst = tmp_path / "copy"
    shutil.copytree(finished, dst)
    return dst


def _leftovers(folder):
    return [p.name for p in folder.iterdir()  # the lock files stay (io.owner.lock_path)
            if p.name.startswith(".") and not p.name.endswith(".lock")]


# --- run: all or nothing ---------------------------------------------------------------------
def test_run_keeps_earlier_results_when_the_report_fails(finished, tmp_path, monkeypatch):
    out = _copy(finished, tmp_path)
    before = sorted(p.name for p in out.rglob("*"))
    manifest = (out / "manifest.json").read_text()

    def broken(*args, **kwargs):
        raise RuntimeError("report failed")

    monkeypatch.setattr("gearcli.report.build_report", broken)
    r = invoke("run", SEED, "-o", out, "-q", "--force", "--set", "run.end_time=0.4")
    assert r.exit_code == 3  # a bug (here: injected), but nothing lost
    assert sorted(p.name for p in out.rglob("*")) == before
    assert (out / "manifest.json").read_text() == manifest
    assert _leftovers(tmp_path) == []


def test_sigterm_during_run_leaves_no_temporary_folder(finished, tmp_path, monkeypatch):
    out = _copy(finished, tmp_path)
    manifest = (out / "manifest.json").read_text()
    from gearcli.pipeline import analysis_io

    real = analysis_io.write_analysis

    def terminated(res):
        doc = real(res)
        os.kill(os.getpid(), signal.SIGTERM)  # arrives while the new folder is half written
        return doc

    monkeypatch.setattr(analysis_io, "write_analysis", terminated)
    r = invoke("run", SEED, "-o", out, "-q", "--force", "--set", "run.end_time=0.4")
    assert r.exit_code == 128 + signal.SIGTERM
    assert "terminated" in r.stderr
    assert (out / "manifest.json").read_text() == manifest
    assert _leftovers(tmp_path) == []


def test_result_folders_follow_the_umask(tmp_path):
    old = os.umask(0o022)
    try:
        from gearcli.io import files

        files.umask.cache_clear()
        out = tmp_path / "res"
        r = invoke("simulate", SEED, "-o", out, "-q", *SHORT)
        assert r.exit_code == 0, r.stderr
        assert out.stat().st_mode & 0o777 == 0o755
        assert (out / "summary.json").stat().st_mode & 0o777 == 0o644
    finally:
        os.umask(old)
        files.umask.cache_clear()


def test_manifest_hashes_the_bytes_that_were_parsed(tmp_path, monkeypatch):
    import hashlib

    from gearcli.pipeline import simulate as sim

    case = tmp_path / "case.yaml"
    raw = SEED.read_bytes()
    case.write_bytes(raw)
    real = sim.run_simulation

    def then_edit(*args, **kwargs):
        res = real(*args, **kwargs)
        case.write_text("edited while running\n")  # the file changes during the run
        return res

    monkeypatch.setattr(sim, "run_simulation", then_edit)
    out = tmp_path / "res"
    r = invoke("simulate", case, "-o", out, "-q", *SHORT)
    assert r.exit_code == 0, r.stderr
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["case_sha256"] == hashlib.sha256(raw).hexdigest()


def test_case_deleted_during_the_run_keeps_the_results(tmp_path, monkeypatch):
    from gearcli.pipeline import simulate as sim

    case = tmp_path / "case.yaml"
    case.write_bytes(SEED.read_bytes())
    real = sim.run_simulation

    def then_delete(*args, **kwargs):
        res = real(*args, **kwargs)
        case.unlink()
        return res

    monkeypatch.setattr(sim, "run_simulation", then_delete)
    r = invoke("simulate", case, "-o", tmp_path / "res", "-q", *SHORT)
    assert r.exit_code == 0, r.stderr
    assert (tmp_path / "res" / "timeseries.csv").is_file()


# --- output paths ------------------------------------------------------------------------------
def test_empty_output_path_is_exit_1(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = invoke("simulate", SEED, "-o", "", *SHORT)
    assert r.exit_code == 1 and "empty path" in r.stderr
    no_internal_error(r)


def test_current_folder_as_output_is_exit_1(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = invoke("simulate", SEED, "-o", ".", *SHORT)
    assert r.exit_code == 1
    no_internal_error(r)


def test_dangling_symlink_as_output_is_exit_1(tmp_path):
    link = tmp_path / "link"
    link.symlink_to(tmp_path / "nowhere" / "x")
    r = invoke("simulate", SEED, "-o", link, *SHORT)
    assert r.exit_code == 1 and "symbolic link" in r.stderr
    no_internal_error(r)


def test_plot_never_silently_overwrites(tmp_path):
    plot = tmp_path / "pair.svg"
    plot.write_text("mine")
    r = invoke("geometry", SEED, "--plot", plot)
    assert r.exit_code == 1 and "already exists" in r.stderr
    assert plot.read_text() == "mine"
    r = invoke("geometry", SEED, "--plot", plot, "--force")
    assert r.exit_code == 0 and plot.read_text() != "mine"


def test_report_into_a_folder_is_exit_1(finished, tmp_path):
    r = invoke("report", finished, "-o", tmp_path)
    assert r.exit_code == 1 and "is a folder" in r.stderr
    no_internal_error(r)


# --- nonsense refused: reverse drives --------------------------------------------------------
@pytest.mark.parametrize("setting, key", [
    ("drive.speed=STEP(time, 0, 0, 1, -3000)", "drive.speed"),
    ("drive.speed=-3000", "drive.speed"),
    ("drive.initial_speed=-10", "drive.initial_speed"),
])
def test_reverse_drive_is_refused(setting, key):
    r = invoke("simulate", SEED, "-o", "-", "--set", setting)
    assert r.exit_code == 1
    assert key in r.stderr and "reverse drive" in r.stderr
    no_internal_error(r)


# --- hand-edited results folders: exit 1 naming the file and entry -------------------------
def _edit_json(name, edit):
    def apply(folder):
        path = folder / name
        doc = json.loads(path.read_text())
        edit(doc)
        path.write_text(json.dumps(doc))
    return apply


def _drop_column(name):
    def apply(folder):
        path = folder / "timeseries.csv"
        lines = path.read_text().splitlines()
        i = lines[0].split(",").index(name)
        path.write_text("\n".join(",".join(c for j, c in enumerate(line.split(",")) if j != i)
                                  for line in lines) + "\n")
    return apply


EDITS = {
    "summary_no_window": _edit_json("summary.json", lambda d: d["scalars"].pop("window_s")),
    "summary_no_fz": _edit_json("summary.json",
                                lambda d: d["scalars"].pop("gear_mesh_frequency_Hz")),
    "summary_text_rate": _edit_json("summary.json",
                                    lambda d: d["scalars"].update(output_rate_Hz="fast")),
    "summary_rows_text": _edit_json("summary.json", lambda d: d.update(rows="many")),
    "summary_modes_text": _edit_json("summary.json",
                                     lambda d: d["scalars"].update(modes="none")),
    "manifest_no_case": _edit_json("manifest.json", lambda d: d.pop("resolved_case")),
    "manifest_case_no_gears": _edit_json("manifest.json",
                                         lambda d: d["resolved_case"].pop("gears")),
    "no_omega2_column": _drop_column("omega2_rad_s"),
    "no_force_column": _drop_column("force_total_N"),
    "summary_not_utf8": lambda f: (f / "summary.json").write_bytes(b"\xff\xfe{}"),
    "summary_is_folder": lambda f: ((f / "summary.json").unlink(),
                                    (f / "summary.json").mkdir()),
}


@pytest.mark.parametrize("edit", sorted(EDITS))
def test_hand_edited_results_are_exit_1_for_analyze(finished, tmp_path, edit):
    folder = _copy(finished, tmp_path)
    EDITS[edit](folder)
    r = invoke("analyze", folder)
    assert r.exit_code == 1, (r.exit_code, r.stderr)
    no_internal_error(r)
    assert len(r.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("edit", [
    _edit_json("analysis.json", lambda d: d.update(window_s="x")),
    _edit_json("analysis.json", lambda d: d.update(checks=[1])),
    _edit_json("analysis.json", lambda d: d["metrics"].update(force_max_N="x")),
    _edit_json("manifest.json", lambda d: d["resolved_case"].pop("gears")),
])
def test_hand_edited_results_are_exit_1_for_report(finished, tmp_path, edit):
    folder = _copy(finished, tmp_path)
    edit(folder)
    r = invoke("report", folder)
    assert r.exit_code == 1, (r.exit_code, r.stderr)
    no_internal_error(r)


def test_a_signal_wrapped_by_a_library_still_ends_as_the_signal(finished, tmp_path, monkeypatch):
    """pydantic's serializer wraps the exception a signal handler raises inside it in its own
    PydanticSerializationError: that is still SIGTERM (exit 143), not an internal error."""
    out = _copy(finished, tmp_path)
    from gearcli.pipeline import analysis_io

    real = analysis_io.write_analysis

    def wrapped(res):
        doc = real(res)
        try:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)  # the handler raises here
        except BaseException as exc:
            raise RuntimeError("serializer failed") from exc  # what a library does with it
        return doc

    monkeypatch.setattr(analysis_io, "write_analysis", wrapped)
    r = invoke("run", SEED, "-o", out, "-q", "--force", "--set", "run.end_time=0.4")
    assert r.exit_code == 128 + signal.SIGTERM, r.stderr
    assert "terminated (SIGTERM)" in r.stderr and "internal error" not in r.stderr
    assert _leftovers(tmp_path) == []
