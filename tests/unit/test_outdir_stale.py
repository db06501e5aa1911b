"""Temporary result folders left by a killed gearcli (kill -9 cannot clean up) are removed by
the next write to the same target (issue 18); those of running processes are kept."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from gearcli.io.outdir import atomic_dir, remove_stale


def test_folder_of_a_sigkilled_writer_is_removed_by_the_next_write(tmp_path):
    target = tmp_path / "run"
    script = (f"import os, signal; from gearcli.io.outdir import atomic_dir\n"
              f"with atomic_dir({str(target)!r}, False) as tmp:\n"
              f"    (tmp / 'timeseries.csv').write_text('t_s\\n0\\n')\n"
              f"    os.kill(os.getpid(), signal.SIGKILL)\n")
    proc = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, timeout=120)
    assert proc.returncode == -9
    left = list(tmp_path.glob(".run.*.tmp"))
    assert len(left) == 1 and not target.exists()  # what kill -9 leaves
    with atomic_dir(target, False) as tmp:
        (tmp / "manifest.json").write_text("{}")
    assert not list(tmp_path.glob(".run.*.tmp*"))
    assert (target / "manifest.json").is_file()


def test_folders_of_live_processes_and_foreign_names_are_kept(tmp_path):
    mine = tmp_path / f".run.{os.getpid()}.abc.tmp"
    foreign = tmp_path / ".run.notapid.tmp"
    other = tmp_path / ".runner.1.x.tmp"  # another target's name
    for d in (mine, foreign, other):
        d.mkdir()
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    gone = tmp_path / f".run.{dead.pid}.xyz.tmp.old"
    gone.mkdir()
    assert remove_stale(tmp_path, "run") == [gone]
    assert mine.is_dir() and foreign.is_dir() and other.is_dir()


def _dead_pid() -> int:
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    return dead.pid


def test_a_dotted_target_name_is_not_mistaken_for_a_pid(tmp_path):
    """``.out.2024.PID.X.tmp`` belongs to the target ``out.2024``: a write to ``out`` must
    not read 2024 as a dead process and delete another run's live folder."""
    live = tmp_path / f".out.2024.{os.getpid()}.abc.tmp"
    live.mkdir()
    assert remove_stale(tmp_path, "out") == []
    assert live.is_dir()


def test_a_stale_folder_holding_user_files_is_kept(tmp_path):
    """After a swap, the earlier folder holds the user's files until they are moved: a kill
    in between must not lose them to the next write's clean-up."""
    old = tmp_path / f".run.{_dead_pid()}.xyz.tmp"
    old.mkdir()
    (old / "summary.json").write_text("{}")
    (old / "notes.txt").write_text("mine")
    assert remove_stale(tmp_path, "run") == []
    assert (old / "notes.txt").read_text() == "mine"


def test_replacing_keeps_the_folder_mode_and_moves_read_only_user_folders(tmp_path):
    target = tmp_path / "run"
    with atomic_dir(target, False) as tmp:
        (tmp / "manifest.json").write_text("{}")
        (tmp / "stress.json").write_text("{}")
    (target / "ro").mkdir()
    (target / "ro" / "data").write_text("k")
    os.chmod(target / "ro", 0o555)
    os.chmod(target, 0o750)
    inode = (target / "ro").stat().st_ino
    try:
        with atomic_dir(target, True) as tmp:
            (tmp / "manifest.json").write_text('{"new": 1}')
        assert json.loads((target / "manifest.json").read_text())["new"] == 1  # + outputs
        assert not (target / "stress.json").exists()  # the earlier run's result goes
        assert (target / "ro").stat().st_ino == inode  # moved, not copied
        assert (target / "ro" / "data").read_text() == "k"
        assert target.stat().st_mode & 0o777 == 0o750
        assert not list(tmp_path.glob(".run.*.tmp*"))  # (.run.lock, the lock file, stays)
    finally:
        os.chmod(target / "ro", 0o755)


def test_files_stranded_by_a_killed_force_write_block_the_next_write(tmp_path):
    """A --force write killed between the swap and the moves leaves the user's files in the
    swapped-out folder: the next write to that target names it instead of going on."""
    import pytest

    from gearcli.errors import OutputError
    from gearcli.io.outdir import check_target

    target = tmp_path / "run"
    with atomic_dir(target, False) as tmp:
        (tmp / "manifest.json").write_text("{}")
    old = tmp_path / f".run.{_dead_pid()}.xyz.tmp"
    old.mkdir()
    (old / "notes.txt").write_text("mine")
    with pytest.raises(OutputError, match=r"\.run\..*\.xyz\.tmp beside it holds your files"):
        check_target(target, True)
    (old / "notes.txt").rename(target / "notes.txt")  # the user deals with it
    check_target(target, True)


def test_a_read_only_results_folder_gets_its_mode_after_the_moves(tmp_path):
    target = tmp_path / "run"
    with atomic_dir(target, False) as tmp:
        (tmp / "manifest.json").write_text("{}")
    (target / "notes.txt").write_text("mine")
    os.chmod(target, 0o555)
    try:
        with atomic_dir(target, True) as tmp:
            (tmp / "manifest.json").write_text('{"new": 1}')
        assert (target / "notes.txt").read_text() == "mine"
        assert target.stat().st_mode & 0o777 == 0o555
    finally:
        os.chmod(target, 0o755)
    assert not list(tmp_path.glob(".run.*.tmp*"))  # (.run.lock, the lock file, stays)


def test_a_killed_write_with_a_half_written_result_is_not_taken_for_user_files(tmp_path):
    """io.files.write_atomic's ``.analysis.json.XXXXXXXX.tmp`` inside a killed write's folder
    is gearcli's: the folder is cleaned up, not reported as holding the user's files."""
    from gearcli.io.outdir import stranded

    old = tmp_path / f".run.{_dead_pid()}.xyz.tmp"
    old.mkdir()
    (old / "manifest.json").write_text("{}")
    (old / ".analysis.json.k2j4h5g6.tmp").write_text("{")
    assert stranded(tmp_path, "run") == []
    assert remove_stale(tmp_path, "run") == [old]
