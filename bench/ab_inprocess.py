"""Kernel A/B of two revisions in ONE process, both allocation orders: native time, layout-fair.

Run from the repository root with the project's venv:

    .venv/bin/python bench/ab_inprocess.py --base REV [--head REV] [--runs 40]
                                           [--cases seed,seed_rigid,iso_pair]

Why. bench/ab.py times each side in its own process. On this 2-vCPU VM that mixes two
things with the code's speed: the load of the other vCPU (CPU time grows when a neighbour runs
on the sibling thread) and where the heap puts the kernel's arrays. The second is not small:
the same revision against itself, both copies in one process with their calls alternated,
ran 6-7 % slower for whichever copy allocated its model second (bench/RESULTS.md, session 12),
so the A/B of two revisions in two processes can move by that much from memory layout alone.

How. The package ``gearcli`` of ``--base`` is exported (``git archive``, as bench/ab.py) and
imported as ``gearcli``; ``--head`` (or the working tree) is exported a second time with every
``gearcli`` in its Python files renamed to ``gearclib`` and imported as that, so both live in
one process with their own compiled code. For each case the child runs the case once per side
through ``run_simulation`` (compiling or loading each side's code) and keeps the arguments of
the kernel call (``integrate.simulate``), then calls the two kernels alternately ``--runs``
times each on fresh copies of those arguments, timed with ``time.perf_counter`` (the two
calls of a pair are ~10-30 ms apart, so both see the same neighbours). This is done twice,
once with the base's model allocated first and once with the head's first; the printed ratio
head/base is the geometric mean of the two orders (of the minima, and of the medians), which
cancels the allocation-order effect (the same revision on both sides gives 1.000 that way).
Prints only; copy what you measured into bench/RESULTS.md, never into tests.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
from ab import CASES, _export, _key  # noqa: E402  (the same cases and export as the A/B)

_CHILD = """
import copy, json, statistics, sys, time
cases, runs, head_first = json.loads(sys.argv[1]), int(sys.argv[2]), sys.argv[3] == "1"
sys.path.insert(0, sys.argv[4])  # bench/
from kernel_call import kernel_call
import gearcli.core.integrate as base_integrate
import gearclib.core.integrate as head_integrate
from gearcli.pipeline.simulate import run_simulation as base_run
from gearclib.pipeline.simulate import run_simulation as head_run

out = {}
for label, path, overrides in cases:
    sides = [(base_integrate, base_run), (head_integrate, head_run)]
    order = sides[::-1] if head_first else sides
    made = [kernel_call(integrate, run, path, overrides) for integrate, run in order]
    (base_sim, base_args), (head_sim, head_args) = made[::-1] if head_first else made
    times = {"base": [], "head": []}
    for i in range(runs):
        pair = [("base", base_sim, base_args), ("head", head_sim, head_args)]
        for side, simulate, call in (pair if i % 2 == 0 else pair[::-1]):
            args, kwargs = copy.deepcopy(call)
            t0 = time.perf_counter()
            simulate(*args, **kwargs)
            times[side].append(time.perf_counter() - t0)
    out[label] = {side: [min(t), statistics.median(t)] for side, t in times.items()}
print(json.dumps(out))
"""


def prepare(base: str, head: str | None, into: Path) -> Path:
    """``into`` with ``gearcli`` (revision ``base``) and ``gearclib`` (``head`` or the working
    tree, renamed)."""
    _export(base, into)
    other = into / "head"
    if head:
        _export(head, other)
    else:
        other.mkdir(parents=True)
        subprocess.run(["cp", "-r", str(ROOT / "gearcli"), str(other)], check=True)
    (other / "gearcli").rename(into / "gearclib")
    other.rmdir()
    for src in (into / "gearclib").rglob("*.py"):
        text = src.read_text()
        src.write_text(text.replace("gearcli", "gearclib").replace("gearclibb", "gearclib"))
    for cache in into.rglob("__pycache__"):
        subprocess.run(["rm", "-rf", str(cache)], check=True)
    return into


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--base", required=True, help="revision to compare with (git rev)")
    ap.add_argument("--head", default=None, help="revision to time (default: working tree)")
    ap.add_argument("--runs", type=int, default=40, help="timed kernel calls per side, order")
    ap.add_argument("--cases", default="seed,seed_rigid,seed_rigid_no_friction,iso_pair",
                    help="comma-separated labels of bench/ab.py's CASES")
    args = ap.parse_args()
    wanted = args.cases.split(",")
    cases = [(label, str(ROOT / path), ov) for label, path, ov in CASES if _key(label) in wanted]
    with tempfile.TemporaryDirectory(prefix="gearcli-abin-") as tmp:
        tree = prepare(args.base, args.head, Path(tmp) / "tree")
        env = {**os.environ, "PYTHONPATH": str(tree)}
        orders = {}
        for head_first in ("0", "1"):
            done = subprocess.run([sys.executable, "-c", _CHILD, json.dumps(cases),
                                   str(args.runs), head_first, str(ROOT / "bench")],
                                  env=env, cwd=tree, capture_output=True, text=True, check=True)
            orders[head_first] = json.loads(done.stdout.strip().splitlines()[-1])
    print(f"kernel A/B in one process ({args.runs} calls per side and order), ms, min / median: "
          f"{args.base} / {args.head or 'working tree'}")
    print("| case | base first: base | head | head first: base | head | ratio of minima "
          "(geometric mean of the orders) | of medians |")
    print("|---|---|---|---|---|---|---|")
    for label, _, _ in cases:
        a, b = orders["0"][label], orders["1"][label]
        r_min = math.sqrt(a["head"][0] / a["base"][0] * b["head"][0] / b["base"][0])
        r_med = math.sqrt(a["head"][1] / a["base"][1] * b["head"][1] / b["base"][1])
        cells = [f"{1e3 * x[0]:.2f} / {1e3 * x[1]:.2f}"
                 for x in (a["base"], a["head"], b["base"], b["head"])]
        print(f"| {label} | " + " | ".join(cells) + f" | {r_min:.3f} | {r_med:.3f} |")


if __name__ == "__main__":
    main()
