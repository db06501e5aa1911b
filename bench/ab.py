"""Kernel A/B against another revision: the solver's time on a few cases, alternating rounds.

Run from the repository root with the project's venv:

    .venv/bin/python bench/ab.py [--base REV] [--rounds 3] [--runs 9] [--head REV]
                                 [--cases seed,iso_pair]

Exports ``REV`` (default ``HEAD``) with ``git archive`` into a temporary folder and times
``SimulationResult.wall_time_s`` (the compiled kernel call with its set-up) of the same cases
with that tree and with the working tree (or the revision ``--head``, exported the same
way: the working tree may then change while the rounds run), one child process per side and
round, alternating, so that a noisy neighbour slows both alike: median and minimum of
``--runs`` runs after one warm-up (which compiles when the cache has no code for that tree
yet). Prints a table and the ratios' median and range over the rounds only; copy what you
measured into bench/RESULTS.md. Times are host- and load-dependent, so they belong here,
never in tests.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: (label, case file, overrides): the seed (IMPACT, extended engagement, friction), the seed
#: with rigid engagement (event hops), the tooth law at two speeds.
CASES = (
    ("seed", "cases/seed.yaml", []),
    ("seed rigid", "cases/seed.yaml", ["contact.engagement=rigid"]),
    ("seed rigid, no friction", "cases/seed.yaml",
     ["contact.engagement=rigid", "friction.enabled=false"]),
    ("iso_pair", "cases/iso_pair.yaml", []),
    ("iso_pair 2500 rpm", "cases/iso_pair.yaml", ["drive.speed=2500 rpm"]),
)

_CHILD = """
import json, os, random, statistics, sys, time
if os.environ.get("GEARCLI_AB_LAYOUT"):  # a heap layout of its own (--layouts)
    rng = random.Random(int(os.environ["GEARCLI_AB_LAYOUT"]))
    _pads = [bytearray(rng.randrange(520, 9000)) for _ in range(rng.randrange(8, 64))]
import gearcli.core.integrate as integrate
from gearcli.pipeline.simulate import run_simulation
runs, cases, clock = int(sys.argv[1]), json.loads(sys.argv[2]), sys.argv[3]
kernel, cpu = integrate.simulate, []

def timed(*args, **kwargs):  # the same call as wall_time_s, on this thread's CPU clock
    t0 = time.thread_time()
    try:
        return kernel(*args, **kwargs)
    finally:
        cpu.append(time.thread_time() - t0)

integrate.simulate = timed
out = {}
for label, path, overrides in cases:
    wall = [run_simulation(path, overrides, zoom=False, notice=None).wall_time_s
            for _ in range(runs + 1)][1:]
    times = wall if clock == "wall" else cpu[-runs:]
    out[label] = [statistics.median(times), min(times)]
print(json.dumps(out))
"""


def side(tree: Path, runs: int, labels: list[str], clock: str = "wall",
         layout: int | None = None) -> dict:
    cases = [(label, str(ROOT / path), overrides) for label, path, overrides in CASES
             if label in labels]
    env = {**os.environ, "PYTHONPATH": str(tree)}
    if layout is not None:
        env["GEARCLI_AB_LAYOUT"] = str(layout)
    done = subprocess.run([sys.executable, "-c", _CHILD, str(runs), json.dumps(cases), clock],
                          env=env, cwd=tree, capture_output=True, text=True, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--base", default="HEAD", help="revision to compare with (git rev)")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--runs", type=int, default=9, help="timed runs per case and round")
    ap.add_argument("--head", default=None,
                    help="revision to time instead of the working tree (git rev)")
    ap.add_argument("--cases", default=None,
                    help="comma-separated labels of CASES (default: all; seed rigid as "
                         "seed_rigid etc.: spaces and commas as underscores)")
    ap.add_argument("--clock", choices=("wall", "cpu"), default="wall",
                    help="wall: SimulationResult.wall_time_s; cpu: the thread's CPU time of "
                         "the same kernel call (time.thread_time: time spent waiting for a "
                         "core on a loaded machine is not counted)")
    ap.add_argument("--layouts", action="store_true",
                    help="each round in another heap layout: before importing gearcli, both "
                         "sides' processes of round r allocate the same random padding "
                         "(seeded by r), so the ratio's spread over the rounds includes where "
                         "the heap puts the kernel's arrays (5-11 %% on this VM, "
                         "bench/RESULTS.md), not one layout per revision")
    args = ap.parse_args()
    labels = [label for label, _, _ in CASES]
    if args.cases:
        wanted = args.cases.split(",")
        labels = [label for label in labels if _key(label) in wanted]
    with tempfile.TemporaryDirectory(prefix="gearcli-ab-") as tmp:
        base = _export(args.base, Path(tmp, "base"))
        head = _export(args.head, Path(tmp, "head")) if args.head else ROOT
        rows: dict[str, list[str]] = {label: [] for label in labels}
        ratios: dict[str, list[float]] = {label: [] for label in labels}
        ratios_min: dict[str, list[float]] = {label: [] for label in labels}
        for r in range(args.rounds):
            layout = r + 1 if args.layouts else None
            before = side(base, args.runs, labels, args.clock, layout)
            after = side(head, args.runs, labels, args.clock, layout)
            for label in rows:
                (b, b_min), (a, a_min) = before[label], after[label]
                ratios[label].append(a / b)
                ratios_min[label].append(a_min / b_min)
                rows[label].append(f"{1e3 * b:.2f} / {1e3 * a:.2f} ({100 * (a / b - 1):+.1f} %)")
    print(f"kernel A/B ({args.clock} clock), median of {args.runs} runs in ms: {args.base} / "
          f"{args.head or 'working tree'}")
    print("| case | " + " | ".join(f"round {i + 1}" for i in range(args.rounds)) + " |")
    print("|---|" + "---|" * args.rounds)
    for label, cells in rows.items():
        print(f"| {label} | " + " | ".join(cells) + " |")
    print("ratio after/before per case, median [min, max] over the rounds: of the medians; "
          "of the minima (less sensitive to a loaded machine)")
    for label, r in ratios.items():
        m = ratios_min[label]
        print(f"  {label}: {statistics.median(r):.3f} [{min(r):.3f}, {max(r):.3f}]; "
              f"{statistics.median(m):.3f} [{min(m):.3f}, {max(m):.3f}]")


def _key(label: str) -> str:
    return label.replace(", ", "_").replace(" ", "_")


def _export(rev: str, into: Path) -> Path:
    """The package ``gearcli`` of revision ``rev`` in folder ``into`` (git archive)."""
    into.mkdir(parents=True)
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", rev, "gearcli"],
                             capture_output=True, check=True).stdout
    subprocess.run(["tar", "-x", "-C", str(into)], input=archive, check=True)
    return into


if __name__ == "__main__":
    main()
