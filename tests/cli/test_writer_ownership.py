"""Issue 32, the output side: one writer that refuses links out of the results folder, a results
folder that belongs to one producer (--force replaces only gearcli's own files), a lock that
keeps analyze from mixing two runs, short writes to stdout as exit 1, refusals before the work
(docs/theory.md §8, "Writing results")."""

from __future__ import annotations

import contextlib
import errno
import fcntl
import json
import os
import resource
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.errors import OutputError
from gearcli.io import files, owner
from tests.conftest import ROOT, SEED
from tests.unit.sweep_helpers import write_study

runner = CliRunner()
SHORT = ["--set", "run.end_time=0.4", "--set", "drive.speed=STEP(time, 0, 0, 0.1, 3000)",
         "--set", "load.torque=STEP(time, 0, 0, 0.1, 4.5e5)"]
ONE_POINT = "name: a\nparameters:\n  contact.max_damping: ['5 N*s/mm']\n"


def _invoke(args, code=(0, 4)):
    res = runner.invoke(app, [str(a) for a in args])
    assert res.exit_code in code, (args, res.exit_code, res.output)
    return res


@pytest.fixture(scope="module")
def run_folder(tmp_path_factory) -> Path:
    """A short simulated run (0.4 s) to copy from."""
    out = tmp_path_factory.mktemp("runs") / "run"
    _invoke(["simulate", SEED, "-o", out, "-q", *SHORT])
    return out


@pytest.fixture(scope="module")
def analyzed_folder(run_folder, tmp_path_factory) -> Path:
    """The short run, analysed (a report needs it)."""
    out = _copy_run(run_folder, tmp_path_factory.mktemp("analyzed") / "run")
    _invoke(["analyze", out, "-q"])
    return out


def _copy_run(src: Path, dest: Path) -> Path:
    import shutil

    shutil.copytree(src, dest)
    return dest


# --- the writer ------------------------------------------------------------------------------
def test_writer_refuses_a_link_target_and_a_link_on_the_way(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "precious.txt").write_text("keep\n")
    folder = tmp_path / "results"
    folder.mkdir()
    os.symlink(outside / "precious.txt", folder / "trends.md")
    with pytest.raises(OutputError, match="symbolic link"):
        files.write_atomic(folder / "trends.md", "x")
    os.symlink(outside, folder / "figures")
    with pytest.raises(OutputError, match="symbolic link"):
        files.write_atomic(folder / "figures" / "a.png", b"x", folder)
    with pytest.raises(OutputError, match="symbolic link"):
        files.make_folder(folder / "figures", folder)
    assert (outside / "precious.txt").read_text() == "keep\n"
    assert sorted(q.name for q in outside.iterdir()) == ["precious.txt"]


def test_writer_leaves_no_temporary_file_when_the_disk_is_full(tmp_path, monkeypatch):
    def full(_fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(files.os, "fsync", full)
    with pytest.raises(OutputError, match="No space left"):
        files.write_atomic(tmp_path / "analysis.json", "{}\n")
    assert list(tmp_path.iterdir()) == []


def test_analyze_on_a_full_disk_leaves_no_temporary_file(tmp_path, run_folder, monkeypatch):
    run = _copy_run(run_folder, tmp_path / "run")
    before = sorted(q.name for q in run.iterdir())

    def full(_fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(files.os, "fsync", full)
    res = _invoke(["analyze", run, "-q"], code=(1,))
    assert "No space left" in res.output
    assert sorted(q.name for q in run.iterdir()) == before


def test_analyze_whose_disk_fills_after_analysis_json_changes_nothing(tmp_path, run_folder,
                                                                      monkeypatch):
    """Found in issue 32's closing check (a tmpfs with 40 kB free): analysis.json was written,
    spectrum.csv failed, and the message said "nothing was changed"; the three files now go
    in together or not at all."""
    run = _copy_run(run_folder, tmp_path / "run")
    before = {q.name: q.read_bytes() for q in run.iterdir()}
    real, calls = files.os.fsync, []

    def full_at_the_second(fd):
        calls.append(fd)
        if len(calls) == 2:  # analysis.json fits, spectrum.csv does not
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(fd)

    monkeypatch.setattr(files.os, "fsync", full_at_the_second)
    res = _invoke(["analyze", run, "-q"], code=(1,))
    assert "spectrum.csv" in res.output and "nothing was changed" in res.output
    assert {q.name: q.read_bytes() for q in run.iterdir()} == before


def test_report_on_a_full_disk_leaves_no_figures_folder(tmp_path, analyzed_folder,
                                                        monkeypatch):
    """Found in issue 32's closing check (a tmpfs with 40 kB free): the failed report left an
    empty figures/ that its manifest did not list, so even `report --force` refused it."""
    run = _copy_run(analyzed_folder, tmp_path / "run")
    before = sorted(q.name for q in run.iterdir())

    def full(_fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    with monkeypatch.context() as m:
        m.setattr(files.os, "fsync", full)
        res = _invoke(["report", run, "--format", "md", "-q"], code=(1,))
    assert "No space left" in res.output
    assert sorted(q.name for q in run.iterdir()) == before  # no figures/, no temporary
    _invoke(["report", run, "--format", "md", "-q"])  # room again: no --force needed
    assert (run / "report.md").is_file()


# --- links out of the results folder: sweep and report ---------------------------------------
def test_sweep_refuses_links_out_of_its_folder(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "trends.csv").write_text("mine\n")
    study = write_study(tmp_path, ONE_POINT)
    out = tmp_path / "sweep"
    out.mkdir()
    os.symlink(outside / "trends.csv", out / "trends.csv")
    res = _invoke(["sweep", study, "-o", out, "-j", "1", "-q"], code=(1,))
    assert "symbolic link" in res.output
    (out / "trends.csv").unlink()
    os.symlink(outside, out / "points")
    res = _invoke(["sweep", study, "-o", out, "-j", "1", "-q", "--keep-timeseries"], code=(1,))
    assert "symbolic link" in res.output
    assert sorted(q.name for q in outside.iterdir()) == ["trends.csv"]
    assert (outside / "trends.csv").read_text() == "mine\n"


def test_report_force_refuses_a_figures_link(tmp_path, analyzed_folder):
    run = _copy_run(analyzed_folder, tmp_path / "run")
    outside = tmp_path / "outside"
    outside.mkdir()
    _invoke(["report", run, "--format", "md", "-q"])
    import shutil

    shutil.rmtree(run / "figures")
    os.symlink(outside, run / "figures")
    res = _invoke(["report", run, "--format", "md", "-q", "--force"], code=(1,))
    assert "symbolic link" in res.output
    assert list(outside.iterdir()) == []


# --- one producer per folder -------------------------------------------------------------------
def test_a_second_study_into_the_folder_is_refused_and_the_rows_stay(tmp_path):
    a = write_study(tmp_path, ONE_POINT, "a.yaml")
    # b holds a's case too (the rows' check alone would let it in) but is another study
    b = write_study(tmp_path, "name: b\nparameters:\n  contact.max_damping: ['5 N*s/mm']\n",
                    "b.yaml")
    out = tmp_path / "sweep"
    _invoke(["sweep", a, "-o", out, "-j", "1", "-q"])
    rows = (out / "summary.csv").read_text()
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["producer"]["command"] == "sweep" and manifest["producer"]["study"]
    assert {"summary.csv", "trends.csv", "trends.md"} <= set(manifest["outputs"])
    res = _invoke(["sweep", b, "-o", out, "-j", "1", "-q"], code=(1,))
    assert "--force" in res.output and "study" in res.output
    assert (out / "summary.csv").read_text() == rows
    # the same study again resumes (nothing to run) and keeps its row
    _invoke(["sweep", a, "-o", out, "-j", "1", "-q"])
    assert (out / "summary.csv").read_text().splitlines()[1].split(",")[0] == "0"


def test_a_simulate_folder_refuses_a_sweep_and_a_sweep_folder_a_simulate(tmp_path, run_folder):
    run = _copy_run(run_folder, tmp_path / "run")
    before = sorted(q.name for q in run.iterdir())
    study = write_study(tmp_path, ONE_POINT)
    _invoke(["sweep", study, "-o", run, "-j", "1", "-q"], code=(1,))
    assert owner.read_manifest(run)["producer"] == {"command": "simulate"}
    assert sorted(q.name for q in run.iterdir()) == before
    out = tmp_path / "sweep"
    _invoke(["sweep", study, "-o", out, "-j", "1", "-q"])
    res = _invoke(["simulate", SEED, "-o", out, "-q", *SHORT], code=(1,))
    assert "--force" in res.output and (out / "summary.csv").is_file()


def test_force_keeps_the_users_files_with_result_names(tmp_path, run_folder):
    run = _copy_run(run_folder, tmp_path / "run")
    mine = {"summary.csv": "my table\n", "report.md": "# my notes\n", "mesh.png": "not a png\n"}
    for name, text in mine.items():
        (run / name).write_text(text)
    (run / "figures").mkdir()
    (run / "figures" / "sketch.txt").write_text("mine\n")
    _invoke(["simulate", SEED, "-o", run, "-q", "--force", *SHORT])
    for name, text in mine.items():
        assert (run / name).read_text() == text, name
    assert (run / "figures" / "sketch.txt").read_text() == "mine\n"
    outputs = owner.read_manifest(run)["outputs"]
    assert "report.md" not in outputs and "timeseries.csv" in outputs
    # and a report --force does not replace the user's report.md or figures either
    res = _invoke(["report", run, "--format", "md", "-q", "--force"], code=(1,))
    assert "not written by gearcli" in res.output
    assert (run / "report.md").read_text() == "# my notes\n"


def test_force_replaces_gearclis_own_report(tmp_path, analyzed_folder):
    run = _copy_run(analyzed_folder, tmp_path / "run")
    _invoke(["report", run, "--format", "md", "-q"])
    assert {"report.md", "figures"} <= set(owner.read_manifest(run)["outputs"])
    _invoke(["report", run, "--format", "md", "-q", "--force"])
    _invoke(["simulate", SEED, "-o", run, "-q", "--force", *SHORT])
    assert not (run / "report.md").exists() and not (run / "figures").exists()


# --- the lock ----------------------------------------------------------------------------------
@contextlib.contextmanager
def _held_by_another(folder: Path):
    """The lock of ``folder`` as another gearcli holds it (its own open file description)."""
    fd = os.open(owner.lock_path(folder), os.O_RDWR | os.O_CREAT)
    fcntl.flock(fd, fcntl.LOCK_EX)
    try:
        yield fd
    finally:
        fcntl.flock(fd, fcntl.LOCK_UN)
        os.close(fd)


def test_analyze_refuses_while_another_gearcli_replaces_the_folder(tmp_path, run_folder,
                                                                  monkeypatch):
    run = _copy_run(run_folder, tmp_path / "run")
    monkeypatch.setenv("GEARCLI_LOCK_WAIT_S", "0.2")
    with _held_by_another(run):
        res = _invoke(["analyze", run, "-q"], code=(1,))
    assert "another gearcli" in res.output
    assert not (run / "analysis.json").exists()


def test_simulate_force_does_not_swap_under_a_running_analyze(tmp_path, run_folder,
                                                            monkeypatch):
    run = _copy_run(run_folder, tmp_path / "run")
    before = (run / "timeseries.csv").read_bytes()
    monkeypatch.setenv("GEARCLI_LOCK_WAIT_S", "0.2")
    with _held_by_another(run):
        res = _invoke(["simulate", SEED, "-o", run, "-q", "--force", *SHORT,
                       "--set", "load.torque=STEP(time, 0, 0, 0.1, 4e5)"], code=(1,))
    assert "another gearcli" in res.output
    assert (run / "timeseries.csv").read_bytes() == before  # the earlier run, whole
    assert [q.name for q in tmp_path.iterdir() if q.name.startswith(".")] == [".run.lock"]


def test_analyze_waits_for_the_lock_then_analyses_the_folder_as_it_is(tmp_path, run_folder,
                                                                    monkeypatch):
    run = _copy_run(run_folder, tmp_path / "run")
    monkeypatch.setenv("GEARCLI_LOCK_WAIT_S", "60")
    fd = os.open(owner.lock_path(run), os.O_RDWR | os.O_CREAT)
    fcntl.flock(fd, fcntl.LOCK_EX)
    released = []

    def release():
        time.sleep(0.3)
        released.append(True)
        fcntl.flock(fd, fcntl.LOCK_UN)
        os.close(fd)

    t = threading.Thread(target=release)
    t.start()
    try:
        _invoke(["analyze", run, "-q"])
    finally:
        t.join()
    assert released and (run / "analysis.json").is_file()


def test_targets_in_one_parent_have_their_own_locks(tmp_path, run_folder, monkeypatch):
    """make -j into out/a and out/b: one holding its folder does not stop the other."""
    a = _copy_run(run_folder, tmp_path / "a")
    b = _copy_run(run_folder, tmp_path / "b")
    monkeypatch.setenv("GEARCLI_LOCK_WAIT_S", "0")  # no waiting: a shared lock would refuse
    with _held_by_another(a):
        _invoke(["analyze", b, "-q"])
        res = _invoke(["analyze", a, "-q"], code=(1,))
    assert (b / "analysis.json").is_file() and not (a / "analysis.json").exists()
    assert str(owner.lock_path(a)) in res.output  # the refusal names the lock file
    assert owner.lock_path(a) == tmp_path / ".a.lock"


@contextlib.contextmanager
def _sweep_running(monkeypatch, study: Path, out: Path):
    """A sweep of ``study`` into ``out`` in another thread, stopped inside its points' runs
    (in the middle of the study, holding its folder) until the block ends."""
    from gearcli import api
    from gearcli.pipeline.sweep import run as sweep_run

    started, release, errors = threading.Event(), threading.Event(), []

    def execute(*_args, **_kw):
        if not started.is_set():  # the first sweep's; later ones run nothing
            started.set()
            release.wait(timeout=60)  # a safety net only: the block sets it
        return iter(())

    monkeypatch.setattr(sweep_run, "execute", execute)

    def first():
        try:
            api.sweep(str(study), str(out), jobs=1)
        except Exception as exc:  # reported by the test
            errors.append(exc)

    t = threading.Thread(target=first)
    t.start()
    try:
        assert started.wait(timeout=60)
        yield
    finally:
        release.set()
        t.join()
    assert not errors


def test_a_second_sweep_into_a_running_sweeps_folder_refuses_at_once(tmp_path, monkeypatch):
    a = write_study(tmp_path, ONE_POINT, "a.yaml")
    b = write_study(tmp_path, "name: b\nparameters:\n  contact.max_damping: ['6 N*s/mm']\n",
                    "b.yaml")
    out = tmp_path / "sweep"
    monkeypatch.setenv("GEARCLI_LOCK_WAIT_S", "600")  # a study holder is not waited for
    with _sweep_running(monkeypatch, a, out):
        res = _invoke(["sweep", b, "-o", out, "-j", "1", "-q"], code=(1,))
        assert "a study is running there" in res.output
        assert str(owner.lock_path(out)) in res.output
        import gearcli.pipeline.simulate as sim

        def never(*_a, **_k):
            raise AssertionError("solved before refusing")

        monkeypatch.setattr(sim, "build_kernel_input", never)  # refused before the work
        res = _invoke(["simulate", SEED, "-o", out, "-q", "--force", *SHORT], code=(1,))
        assert "a study is running there" in res.output
        # a sweep into a neighbouring folder goes ahead (its own lock); nothing to run here
        _invoke(["sweep", b, "-o", tmp_path / "other", "-j", "1", "-q"], code=(0, 1, 4))
        assert not (tmp_path / "other" / "summary.csv").read_text().splitlines()[1:]
    assert owner.read_manifest(out)["producer"]["command"] == "sweep"


def test_a_speed_curve_refuses_a_folder_a_sweep_is_running_in(tmp_path, monkeypatch):
    from gearcli.pipeline import speed_curve

    study = write_study(tmp_path, ONE_POINT)
    out = tmp_path / "sweep"

    def never(*_a, **_k):
        raise AssertionError("the speed curve ran")

    monkeypatch.setattr(speed_curve, "run_speed_curve", never)
    with _sweep_running(monkeypatch, study, out):
        res = _invoke(["sweep", ROOT / "cases" / "studies" / "speed_curve.yaml", "-o", out,
                       "-q", "--force"], code=(1,))
    assert "a study is running there" in res.output


def test_forked_workers_do_not_keep_the_lock(tmp_path):
    """A sweep's forked workers close their copy of its lock: once the sweep lets go (or is
    killed), the folder is free although a worker still runs."""
    out = tmp_path / "sweep"
    r, w = os.pipe()
    with owner.folder_lock(out, wait_s=0, study=True):
        pid = os.fork()
        if pid == 0:  # the worker: waits until told to end
            os.close(w)
            os.read(r, 1)
            os._exit(0)
    try:
        fd = os.open(owner.lock_path(out), os.O_RDWR)
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)  # BlockingIOError if the child held it
        os.close(fd)
    finally:
        os.write(w, b"x")
        os.waitpid(pid, 0)
        os.close(r)
        os.close(w)


# --- refusals before the work ------------------------------------------------------------------
def _unwritable(tmp_path: Path) -> Path:
    """A folder this process cannot write in: a read-only one, or (as root, whom permissions
    do not stop) /sys, a read-only file system."""
    if os.geteuid() != 0:
        ro = tmp_path / "ro"
        ro.mkdir()
        ro.chmod(0o555)
        return ro
    if not Path("/sys").is_dir() or _can_write("/sys"):
        pytest.skip("no read-only folder available to this (root) process")
    return Path("/sys")


def _can_write(folder: str) -> bool:
    try:
        os.rmdir(tempfile.mkdtemp(dir=folder))
        return True
    except OSError:
        return False


@pytest.mark.parametrize("command", ["simulate", "run", "sweep", "mesh-fe", "stress"])
def test_an_unwritable_output_is_refused_before_the_work(tmp_path, run_folder, monkeypatch,
                                                         command):
    import gearcli.pipeline.simulate as sim_pipeline

    def no_work(*_a, **_k):
        raise AssertionError("the work started before the output was checked")

    monkeypatch.setattr(sim_pipeline, "run_simulation", no_work)
    monkeypatch.setattr("gearcli.api.stress", no_work)
    monkeypatch.setattr("gearcli.api.mesh", no_work)
    target = _unwritable(tmp_path) / "out"
    if command == "sweep":
        args = ["sweep", write_study(tmp_path, ONE_POINT), "-o", target, "-j", "1", "-q"]
    elif command == "mesh-fe":
        args = ["mesh", SEED, "--method", "fe", "-o", target, "-q"]
    elif command == "stress":
        run = _copy_run(run_folder, tmp_path / "run")
        if os.geteuid() == 0:  # root writes in a read-only folder: the file system refuses
            real = tempfile.mkdtemp

            def read_only_fs(*a, dir=None, **k):
                if dir is not None and Path(dir) == run:
                    raise OSError(errno.EROFS, "Read-only file system")
                return real(*a, dir=dir, **k)

            monkeypatch.setattr(tempfile, "mkdtemp", read_only_fs)
        else:
            run.chmod(0o555)
        args = ["stress", run, "-q"]
    else:
        args = [command, SEED, "-o", target, "-q", *SHORT]
    res = _invoke(args, code=(1,))
    assert "cannot" in res.output and "AssertionError" not in res.output


# --- short writes to stdout --------------------------------------------------------------------
def _limited(args: list[str], limit: int) -> tuple[int, int, str]:
    """Run gearcli with a file-size limit of ``limit`` bytes on its output file."""
    def preexec():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    # unbuffered: the text layer wrote straight to the file and dropped a short write's rest
    # (exit 0, a truncated file); no bytecode written under the limit (a truncated .pyc)
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONDONTWRITEBYTECODE": "1",
           "PYTHONUNBUFFERED": "1"}
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "out.txt"
        with open(path, "wb") as fh:
            proc = subprocess.run([sys.executable, "-m", "gearcli", *args], stdout=fh,
                                  stderr=subprocess.PIPE, env=env, preexec_fn=preexec,
                                  timeout=600)
        return proc.returncode, path.stat().st_size, proc.stderr.decode("utf-8", "replace")


@pytest.mark.parametrize("args", [
    ["schema"],
    ["modal", str(SEED), "--json"],
    ["simulate", str(SEED), "-o", "-", "-q", *SHORT],
])
def test_a_short_write_to_stdout_is_exit_1(args):
    full, size, _ = _limited(args, 1 << 30)  # warm (compiled solver cached) and the length
    assert full == 0 and size > 2048
    code, size, err = _limited(args, 2048)
    assert code == 1 and size <= 2048, (code, size, err)
    assert "error:" in err and "File too large" in err


def test_sweep_force_does_not_delete_the_users_summary(tmp_path, run_folder):
    study = write_study(tmp_path, ONE_POINT)
    plain = tmp_path / "plain"
    plain.mkdir()
    (plain / "summary.csv").write_text("my,own\n1,2\n")
    res = _invoke(["sweep", study, "-o", plain, "-j", "1", "-q", "--force"], code=(1,))
    assert "gearcli did not write" in res.output
    assert (plain / "summary.csv").read_text() == "my,own\n1,2\n"
    run = _copy_run(run_folder, tmp_path / "run")  # a simulate folder with the user's table
    (run / "summary.csv").write_text("my,own\n")
    res = _invoke(["sweep", study, "-o", run, "-j", "1", "-q", "--force"], code=(1,))
    assert "not written by gearcli" in res.output
    assert (run / "summary.csv").read_text() == "my,own\n"
