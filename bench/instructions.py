"""Instructions executed by the compiled time loop: a load-independent A/B of the kernel.

Run from the repository root with the project's venv (needs ``valgrind`` with its headers,
``valgrind/callgrind.h``, and ``gcc``):

    .venv/bin/python bench/instructions.py [--rev REV ...] [--tree] [--runs 2]
                                           [--cases seed,seed_rigid,iso_pair]
                                           [--region run|simulate] [--branch-sim]

Why instructions. Wall and CPU times on a shared machine move by 5-15 % between rounds
(bench/RESULTS.md, session 11); the number of instructions a deterministic run executes
does not. Hardware counters (``perf stat -e instructions:u``) would be the obvious source,
but this VM has no PMU ("PMU not available due to virtualization": perf reports
``<not supported>``), so the count is valgrind's: ``callgrind``'s ``Ir`` (instructions
executed, user space, exact and repeatable; the run is ~50 times slower under it).

What is counted. Each tree (``--rev REV``: the package ``gearcli`` of a revision, exported
with ``git archive`` like bench/ab.py; ``--tree``: the working tree) runs in one child process
under ``valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no``. The child imports
gearcli, runs each case once as a warm-up (loads the compiled code from numba's cache), then
``--runs`` times with collection switched on only inside the compiled ``timeloop.run`` calls
(``--region run``, default: the kernel proper, every chunk summed) or inside the whole
``integrate.simulate`` call that bench/ab.py times (``--region simulate``: with its Python
set-up), through callgrind's client requests (a 10-line C helper compiled with gcc, called
with ctypes; the few hundred instructions of the ctypes call itself are counted too). One
callgrind dump per run; its ``Ir`` total is the run's count. Printed: instructions per run
(the runs agree to a few instructions), per right-hand-side evaluation (the kernel's
``rhs_evaluations + output_evaluations`` counters) and per accepted step, and the ratio of
each tree to the first.

The code that is counted. Under valgrind the CPU reports fewer features than the host (no
AVX-512 on this znver4 host: valgrind cannot execute it), and numba compiles for the
features it detects, so code compiled natively would not run there and code compiled under
valgrind would differ from the host's. Both the warm-up compile (a native child, so it takes
native time) and the counted child therefore compile for the host's CPU name with the
feature set valgrind reports (``NUMBA_CPU_NAME``, ``NUMBA_CPU_FEATURES``; numba keys its cache
by them, so the valgrind child only loads). That is a close proxy of the production code (the
same scheduling model, no 512-bit instructions), not the same machine code: confirm a
finding with bench/ab.py's CPU clock. ``--branch-sim`` adds callgrind's simulated branch
predictor (``Bc``/``Bcm``, ``Bi``/``Bim``: conditional and indirect branches, mispredicted);
cycles and stalls are not available here.

Times are host-dependent and counts compiler-dependent, so they belong in bench/RESULTS.md,
never in tests.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
from ab import CASES, _export, _key  # noqa: E402  (the same cases and export as the A/B)

_HELPER_C = r"""
#include <valgrind/callgrind.h>
void cg_instrument(void) { CALLGRIND_START_INSTRUMENTATION; }
void cg_zero(void) { CALLGRIND_ZERO_STATS; }
void cg_toggle(void) { CALLGRIND_TOGGLE_COLLECT; }
void cg_dump(const char *label) { CALLGRIND_DUMP_STATS_AT(label); }
"""

_CPU_QUERY = """
import llvmlite.binding as ll
print(ll.get_host_cpu_name()); print(ll.get_host_cpu_features().flatten())
"""

_CHILD = """
import ctypes, json, sys
import gearcli.core.integrate as integrate
from gearcli.pipeline.simulate import run_simulation
helper, runs, region = ctypes.CDLL(sys.argv[1]), int(sys.argv[2]), sys.argv[4]
cases = json.loads(sys.argv[3])
counting = False
run, simulate = integrate.run, integrate.simulate

def counted(inner, whole):
    def call(*args, **kwargs):
        if not counting:
            return inner(*args, **kwargs)
        if whole:
            helper.cg_zero()
        helper.cg_toggle()
        try:
            return inner(*args, **kwargs)
        finally:
            helper.cg_toggle()
    return call

integrate.run = counted(run, False) if region == "run" else run
integrate.simulate = counted(simulate, True) if region == "simulate" else simulate
if region == "run":  # zero once per simulate call, count every chunk's run
    def zeroed(*args, **kwargs):
        if counting:
            helper.cg_zero()
        return simulate(*args, **kwargs)
    integrate.simulate = zeroed
out = {}
for label, path, overrides in cases:
    res = run_simulation(path, overrides, zoom=False, notice=None)  # warm-up: the cache
    helper.cg_instrument()
    counting = True
    for i in range(runs):
        res = run_simulation(path, overrides, zoom=False, notice=None)
        helper.cg_dump(f"{label}#{i}".encode())
    counting = False
    c = res.kernel.counters
    out[label] = {"rhs": c["rhs_evaluations"] + c["output_evaluations"],
                  "steps": c["accepted_steps"], "rejected": c["rejected_steps"]}
print(json.dumps(out))
"""

_EVENTS = ("Ir", "Bc", "Bcm", "Bi", "Bim")


def helper_library(into: Path) -> Path:
    """The callgrind client-request helper as a shared library (gcc)."""
    src, lib = into / "cg_helper.c", into / "cg_helper.so"
    src.write_text(_HELPER_C)
    subprocess.run(["gcc", "-O1", "-shared", "-fPIC", "-o", str(lib), str(src)], check=True)
    return lib


def target_env(tree: Path) -> dict:
    """Environment of both children: the tree on the path, the host's CPU name with the
    features valgrind reports (see the module docstring)."""
    env = {**os.environ, "PYTHONPATH": str(tree), "PYTHONHASHSEED": "0"}
    native = _query(env, []).splitlines()
    under = _query(env, ["valgrind", "-q", "--tool=none"]).splitlines()
    env.update(NUMBA_CPU_NAME=native[0], NUMBA_CPU_FEATURES=under[1])
    return env


def _query(env: dict, prefix: list[str]) -> str:
    return subprocess.run(prefix + [sys.executable, "-c", _CPU_QUERY], env=env,
                          capture_output=True, text=True, check=True).stdout


def _options(args) -> list[str]:
    return (["--branch-sim=yes"] if args.branch_sim else []) \
        + (["--dump-instr=yes"] if args.dump_instr else [])


def count(tree: Path, lib: Path, cases: list, runs: int, region: str, options: list[str],
          work: Path) -> dict:
    """Per case: the counters and the callgrind totals of every counted run of ``tree``."""
    env = target_env(tree)
    warm = [sys.executable, "-c", _CHILD, str(lib), "0", json.dumps(cases), region]
    subprocess.run(warm, env=env, cwd=tree, capture_output=True, text=True, check=True)
    out_dir = Path(tempfile.mkdtemp(prefix=f"cg-{tree.name}-", dir=work))
    vg = ["valgrind", "--tool=callgrind", "--instr-atstart=no", "--collect-atstart=no",
          f"--callgrind-out-file={out_dir}/callgrind.out", *options]
    done = subprocess.run(vg + [sys.executable, "-c", _CHILD, str(lib), str(runs),
                                json.dumps(cases), region],
                          env=env, cwd=tree, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(done.stderr[-3000:])
    result = json.loads(done.stdout.strip().splitlines()[-1])
    for label in result:
        result[label]["totals"] = []
    for dump in sorted(out_dir.glob("callgrind.out.*"), key=lambda p: int(p.suffix[1:])):
        label, totals = _read_dump(dump)
        if label is not None:
            result[label.rsplit("#", 1)[0]]["totals"].append(totals)
    return result


def _read_dump(path: Path) -> tuple[str | None, dict]:
    label, events, totals = None, [], {}
    for line in path.read_text(errors="replace").splitlines():
        if line.startswith("desc: Trigger: Client Request: "):
            label = line.split("Client Request: ", 1)[1].strip()
        elif line.startswith("events:"):
            events = line.split()[1:]
        elif line.startswith(("summary:", "totals:")):
            totals = dict(zip(events, (int(v) for v in line.split()[1:]), strict=False))
    return label, totals


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rev", action="append", default=[], help="revision to count (repeat)")
    ap.add_argument("--tree", action="store_true", help="count the working tree too")
    ap.add_argument("--runs", type=int, default=2, help="counted runs per case")
    ap.add_argument("--cases", default="seed,seed_rigid,seed_rigid_no_friction,iso_pair",
                    help="comma-separated labels of bench/ab.py's CASES (spaces and commas "
                         "as underscores)")
    ap.add_argument("--region", choices=("run", "simulate"), default="run")
    ap.add_argument("--branch-sim", action="store_true")
    ap.add_argument("--json", default=None, help="also write the raw counts to this file")
    ap.add_argument("--keep", default=None,
                    help="keep the exported trees and callgrind dumps in this folder "
                         "(callgrind_annotate; default: a temporary folder)")
    ap.add_argument("--dump-instr", action="store_true",
                    help="callgrind --dump-instr=yes: counts per machine instruction")
    args = ap.parse_args()
    wanted = args.cases.split(",")
    cases = [(label, str(ROOT / path), ov) for label, path, ov in CASES if _key(label) in wanted]
    names = args.rev + (["working tree"] if args.tree or not args.rev else [])
    results = {}
    with tempfile.TemporaryDirectory(prefix="gearcli-instr-") as tmp:
        work = Path(args.keep or tmp)
        work.mkdir(parents=True, exist_ok=True)
        lib = helper_library(work)
        for i, name in enumerate(names):
            tree = ROOT if name == "working tree" else _export(name, work / f"tree{i}")
            results[name] = count(tree, lib, cases, args.runs, args.region,
                                  _options(args), work)
            print(f"counted {name}", file=sys.stderr, flush=True)
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1))
    _print(results, names, [c[0] for c in cases])


def _print(results: dict, names: list[str], labels: list[str]) -> None:
    print("instructions (callgrind Ir) per kernel run, min over the counted runs; "
          "per RHS evaluation; per accepted step; ratio to the first tree")
    print("| case | tree | Ir per run | spread | RHS evals | Ir / RHS | Ir / step | ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for label in labels:
        first = None
        for name in names:
            r = results[name][label]
            irs = [t.get("Ir", 0) for t in r["totals"]]
            ir = min(irs)
            first = first or ir
            extra = "".join(f", {e} {min(t.get(e, 0) for t in r['totals'])}"
                            for e in _EVENTS[1:] if e in r["totals"][0])
            print(f"| {label} | {name} | {ir:,} | {max(irs) - ir:,} | {r['rhs']} | "
                  f"{ir / r['rhs']:.1f} | {ir / r['steps']:.1f} | {ir / first:.4f} |{extra}")


if __name__ == "__main__":
    main()
