"""The opt-out of gearcli's two compile-time fixes of numba (gearcli/numba_inline.py, the IR
inliner's copies; gearcli/numba_ssa.py, the SSA rewrite): with ``GEARCLI_NUMBA_PATCHES=0`` the
first compilation in the process leaves numba's functions as they were; without it the same
compilation installs both. Either way the compiled kernel function computes the same numbers.

Each case runs in a fresh interpreter (the fixes are process-wide and installed once) with an
empty numba cache folder of its own, so the kernel function is compiled, not loaded: a cache
hit raises no compile event and would install nothing either way. The function is
``core.flank._factors``, which inlines ``gaptable.linear`` twice (numba IR inlining, then SSA
reconstruction: both fixes act on its compilation), small enough to compile in about a second.
"""

import json
import os
import subprocess
import sys

import pytest

from gearcli import numba_inline

_SCRIPT = r"""
import json
import numpy as np
import gearcli.core.jit  # what every kernel module imports: the fixes' listener, unless opted out
from numba.core import inline_closurecall as ic, ssa
from gearcli import numba_inline, numba_ssa

def numba_functions():
    return (ic.copy, ic.InlineWorker.inline_ir, ic.InlineWorker.inline_function,
            ssa._run_ssa, ssa._run_block_rewrite)

before = numba_functions()
known_shape = (numba_inline._inliner_has_known_shape(ic)  # before the fixes replace them
               and numba_inline._inline_function_has_known_shape(ic)
               and numba_ssa._has_known_shape(ssa))
from gearcli.core.flank import _factors

table = (np.arange(2 * 3 * 5, dtype=np.float64).reshape(2, 3, 5) + 1.0) ** 1.5
values = [_factors(table, 0, 1, i, 2 - i, 0.25, 2.5, x) for i in range(3) for x in (0.3, 1.7)]
print(json.dumps({
    "compiled": len(_factors.stats.cache_misses) > 0,
    "originals": [a is b for a, b in zip(before, numba_functions())],
    "known_shape": known_shape,
    "values": [[float(v).hex() for v in pair] for pair in values],
}))
"""


def _compile_in_fresh_process(tmp_path, name, opt_out):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / name))  # empty: a real compilation
    env.pop(numba_inline.OPT_OUT_VARIABLE, None)
    if opt_out is not None:
        env[numba_inline.OPT_OUT_VARIABLE] = opt_out
    out = subprocess.run([sys.executable, "-c", _SCRIPT], capture_output=True, text=True,
                         env=env, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    result = json.loads(out.stdout.splitlines()[-1])
    assert result["compiled"], "the kernel function came from a cache: nothing was compiled"
    return result


def test_opt_out_leaves_numba_untouched_and_the_results_the_same(tmp_path):
    off = _compile_in_fresh_process(tmp_path, "off", "0")
    assert off["originals"] == [True] * 5  # copy module, inline_ir, inline_function, SSA x2
    on = _compile_in_fresh_process(tmp_path, "on", None)
    if not on["known_shape"]:
        pytest.skip("numba's inliner or SSA module changed shape: the fixes are not installed")
    assert on["originals"] == [False] * 5  # both fixes installed by the first compilation
    assert on["values"] == off["values"]  # bit for bit: the fixes change compile time only


@pytest.mark.parametrize("value, enabled", [(None, True), ("1", True), ("", True),
                                            ("0", False), ("off", False), (" False ", False),
                                            ("no", False)])
def test_which_values_opt_out(monkeypatch, value, enabled):
    if value is None:
        monkeypatch.delenv(numba_inline.OPT_OUT_VARIABLE, raising=False)
    else:
        monkeypatch.setenv(numba_inline.OPT_OUT_VARIABLE, value)
    assert numba_inline.patches_enabled() is enabled
