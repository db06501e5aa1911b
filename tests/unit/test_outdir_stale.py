"""Temporary result folders left by a killed gearcli (kill -9 cannot clean up) are removed by
the next write to the same target (issue 18); those of running processes are kept."""

from __future__ import annotations

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
