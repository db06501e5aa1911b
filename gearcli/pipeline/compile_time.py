"""How long compiling the solver will take here: a measured estimate for the first-run notice.

The compile is one long single-threaded job (numba/LLVM), so its wall time follows the speed
one core gives a process now (the machine and its load). Measured here, not assumed:

* after a run that compiled, its wall time is recorded in the user cache
  (``<cache>/gearcli/timing/compile.json``) with a short speed probe taken at that time;
* the estimate is that recorded time scaled by the ratio of a probe now to the probe then (a
  busier machine now: a longer estimate);
* without a record, the CPU time of a compile on the development machine
  (:data:`REFERENCE_COMPILE_CPU_S`) times the wall time of the probe now over the probe's CPU
  time there (:data:`REFERENCE_PROBE_CPU_S`): a slower core or a busy machine (the probe waits
  for the core as the compile will) gives a longer estimate.

The probe is a fixed pure-Python loop (~10 ms of CPU, the median of five); the estimate is
rough (a factor of ~2 on a machine whose load changes) and is said so ("~"). Measured on the
development machine (2-core VM, load average 6-8 from other jobs): the compile took 122 s
wall for 17.8 s of CPU; the probe took 9 ms of CPU and 28-45 ms wall.
"""

from __future__ import annotations

import json
import time

#: CPU time [s] (user) of the seed's first run that compiled the solver (0.05 s simulated), and
#: the CPU time [s] of the probe, on the development machine.
REFERENCE_COMPILE_CPU_S = 18.0
REFERENCE_PROBE_CPU_S = 0.009
#: Iterations of the probe loop.
PROBE_LOOPS = 200_000


def probe_s() -> float:
    """The median wall time [s] of five runs of a fixed pure-Python loop: what a core gives
    this process now (its speed and the machine's load)."""
    times = []
    for _ in range(5):
        t0 = time.perf_counter()
        x = 0
        for i in range(PROBE_LOOPS):
            x += (i * 7) % 13
        times.append(time.perf_counter() - t0)
    return sorted(times)[2]


def _record_path():
    from gearcli.usercache import folder

    where = folder("timing")
    return None if where is None else where / "compile.json"


def estimate() -> tuple[float, str]:
    """(estimated compile time [s], how it was estimated)."""
    now = probe_s()
    path = _record_path()
    try:
        rec = json.loads(path.read_text()) if path is not None and path.is_file() else None
        wall, then = float(rec["wall_s"]), float(rec["probe_s"])
    except (OSError, ValueError, KeyError, TypeError):
        rec = None
    if rec is not None and wall > 0.0 and then > 0.0:
        return wall * now / then, f"the last compile here took {wall:.0f} s"
    return (REFERENCE_COMPILE_CPU_S * now / REFERENCE_PROBE_CPU_S,
            "estimated from a speed probe of this machine now")


def record(wall_s: float) -> None:
    """Record the wall time [s] of a run that compiled (nothing when the cache is not
    writable)."""
    path = _record_path()
    if path is None:
        return
    try:
        path.write_text(json.dumps({"wall_s": float(wall_s), "probe_s": probe_s()}) + "\n")
    except OSError:
        pass


def notice_text() -> str:
    """The first-run notice: the estimate and where it comes from."""
    seconds, how = estimate()
    return (f"compiling the solver once, ~{seconds:.0f} s ({how}; later runs load it from the "
            "cache)")
