"""Where the first run's compilation goes: numba compile events per function, in process.

Run from the repository root with the project's venv (~15 s):

    .venv/bin/python bench/compile_profile.py [CASE] [--set key=value ...]

Points ``XDG_CACHE_HOME`` and ``NUMBA_CACHE_DIR`` at fresh temporary folders (an empty cache,
whatever is installed), runs ``run_simulation`` on the case (default: the seed, 0.05 s), and
prints numba's ``numba:compile`` events per function: exclusive and inclusive seconds, how often
it was compiled, and every function compiled more than once with its signatures (a literal
argument type, an array layout or an int/float mix compiles a callee again: issue 16). Prints
only; copy what you measured into bench/RESULTS.md.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case", nargs="?", default=str(ROOT / "cases" / "seed.yaml"))
    ap.add_argument("--set", dest="overrides", action="append", default=None,
                    help="case override key=value (default: run.end_time=0.05)")
    ap.add_argument("--top", type=int, default=25, help="functions listed")
    ap.add_argument("--clock", choices=("wall", "cpu"), default="wall",
                    help="wall: time.perf_counter; cpu: this thread's CPU time "
                         "(time.thread_time, where numba compiles: waiting for a core on a "
                         "loaded machine is not counted)")
    args = ap.parse_args()
    clock = time.perf_counter if args.clock == "wall" else time.thread_time
    os.environ["XDG_CACHE_HOME"] = tempfile.mkdtemp(prefix="gearcli-compile-")
    os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="gearcli-compile-numba-")

    from numba.core import event

    exclusive: dict[str, float] = defaultdict(float)
    inclusive: dict[str, float] = defaultdict(float)
    dispatchers: dict[str, object] = {}
    stack: list[list] = []

    class Listener(event.Listener):
        def on_start(self, ev):
            dispatcher = ev.data["dispatcher"]
            name = f"{dispatcher.py_func.__module__}.{dispatcher.py_func.__qualname__}"
            dispatchers[name] = dispatcher
            stack.append([name, clock(), 0.0])

        def on_end(self, ev):
            name, start, children = stack.pop()
            seconds = clock() - start
            inclusive[name] += seconds
            exclusive[name] += seconds - children
            if stack:
                stack[-1][2] += seconds

    event.register("numba:compile", Listener())
    t0 = clock()
    from gearcli.pipeline.simulate import run_simulation

    run_simulation(args.case, args.overrides or ["run.end_time=0.05"], notice=None)
    total = clock() - t0
    print(f"{args.case} ({args.clock} clock): {total:.1f} s in process (imports, set-up, "
          "compilation, run), "
          f"{sum(exclusive.values()):.1f} s compiling {len(exclusive)} functions")
    print(f"{'function':58s} {'excl s':>7s} {'incl s':>7s} {'times':>5s}")
    for name, seconds in sorted(exclusive.items(), key=lambda kv: -kv[1])[:args.top]:
        count = len(dispatchers[name].signatures)
        print(f"{name:58s} {seconds:7.2f} {inclusive[name]:7.2f} {count:5d}")
    again = {name: d for name, d in dispatchers.items() if len(d.signatures) > 1}
    print("compiled more than once:", "none" if not again else "")
    for name, dispatcher in again.items():
        print(f"  {name}: " + "; ".join(str(s) for s in dispatcher.signatures))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
