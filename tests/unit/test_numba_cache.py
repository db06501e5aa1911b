"""numba's cache goes to gearcli's user folder whichever core module is imported first."""

import subprocess
import sys
from pathlib import Path

import pytest

CORE = sorted(p.stem for p in (Path(__file__).resolve().parents[2] / "gearcli" / "core").glob(
    "[a-z]*.py"))


@pytest.mark.parametrize("module", CORE)
def test_cache_folder_set_before_numba_is_imported(module, tmp_path):
    code = (f"import os, sys, gearcli.core.{module}\n"
            "if 'numba' not in sys.modules: print(True)\n"  # no numba yet: nothing to check
            "else:\n import numba.core.config as c\n"
            " print(c.CACHE_DIR == os.environ.get('NUMBA_CACHE_DIR', '') != '')")
    env = {"XDG_CACHE_HOME": str(tmp_path), "PATH": "/usr/bin:/bin",
           "PYTHONPATH": str(Path(__file__).resolve().parents[2])}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert out.stdout.strip() == "True", (module, out.stderr[-300:])
