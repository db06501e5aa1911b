"""Where the compiled kernel spends its time: perf samples (cpu-clock) inside ``timeloop.run``.

Run from the repository root with the project's venv (needs ``perf`` and ``objdump``):

    .venv/bin/python bench/hotspots.py [CASE] [--set key=value ...] [--seconds 8] [--top 40]

This VM has no hardware counters (``perf stat`` cycles "not supported"), but the kernel's
software clock samples work: ``perf record -e cpu-clock`` interrupts the process at a fixed
rate and records the instruction pointer. The script runs the case once through
``run_simulation`` (compiling or loading the kernel), keeps the arguments of the kernel call
(``integrate.simulate``), starts ``perf record`` on its own process, calls the kernel again and
again for ``--seconds``, stops perf, and maps the sampled addresses into the machine code of
the compiled ``timeloop.run`` (compiled into an empty cache; its address from numba's code
library, its code and symbols from the same library's object file, disassembled with
``objdump``). Prints the share of samples inside ``run`` and its compiled callees, the
hottest code windows and instructions, so two revisions' hot loops can be compared. Prints
only; copy what you measured into bench/RESULTS.md.
"""

from __future__ import annotations

import argparse
import collections
import copy
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def compiled_functions():
    """(Python name, symbol, address, numba code library) of every compiled function of
    gearcli's modules that numba has loaded."""
    from numba.core.dispatcher import Dispatcher

    dispatchers = {id(obj): obj for module in list(sys.modules.values())
                   if module is not None and module.__name__.startswith("gearcli.")
                   for obj in list(vars(module).values()) if isinstance(obj, Dispatcher)}
    found = []
    for dispatcher in dispatchers.values():
        for cres in dispatcher.overloads.values():
            library = cres.library
            name = cres.fndesc.mangled_name
            try:
                address = library.get_pointer_to_function(name)
            except Exception:  # noqa: BLE001  (not materialised: never called)
                continue
            found.append((dispatcher.py_func.__qualname__, name, address, library))
    return found


def symbol_table(obj: Path) -> dict[str, tuple[int, int]]:
    """symbol -> (offset in its code section, size) of an object file (``objdump -t``; numba's
    large code model puts code in .ltext)."""
    out = subprocess.run(["objdump", "-t", str(obj)], capture_output=True, text=True,
                         check=True).stdout
    table = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 6 and parts[-3].startswith((".text", ".ltext")):
            table[parts[-1]] = (int(parts[0], 16), int(parts[-2], 16))
    return table


def disassembly(obj: Path) -> dict[int, str]:
    """offset in the code section -> instruction text."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "-M", "intel", str(obj)],
                         capture_output=True, text=True, check=True).stdout
    code = {}
    for line in out.splitlines():
        m = re.match(r"\s*([0-9a-f]+):\s+(.*)", line)
        if m:
            code[int(m.group(1), 16)] = m.group(2).strip()
    return code


def _short(text: str) -> str:
    """A perf symbol or an objdump jump target without numba's long mangled name."""
    return re.sub(r"_ZN\w{60,}", "<run>", text)[:70]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case", nargs="?", default=str(ROOT / "cases" / "seed.yaml"))
    ap.add_argument("--set", dest="overrides", action="append", default=[])
    ap.add_argument("--seconds", type=float, default=8.0)
    ap.add_argument("--top", type=int, default=40, help="hottest instructions listed")
    ap.add_argument("--asm", default=None,
                    help="write run's disassembly with samples per instruction to this file")
    ap.add_argument("--window", type=int, default=512, help="bytes per code window")
    ap.add_argument("--context", type=int, default=0,
                    help="instructions shown before each listed one")
    args = ap.parse_args()
    # compile into an empty cache: a library loaded from the cache keeps no object code
    os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="gearcli-hot-numba-")
    import gearcli.core.integrate as integrate
    from gearcli.pipeline.simulate import run_simulation

    sys.path.insert(0, str(ROOT / "bench"))
    from kernel_call import kernel_call

    simulate, call = kernel_call(integrate, run_simulation, args.case, args.overrides)
    a, k = copy.deepcopy(call)
    simulate(*a, **k)  # warm
    with tempfile.TemporaryDirectory(prefix="gearcli-hot-") as tmp:
        data = Path(tmp) / "perf.data"
        perf = subprocess.Popen(["perf", "record", "-q", "-e", "cpu-clock", "-F", "20000",
                                 "-p", str(os.getpid()), "-o", str(data)],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(0.5)
        calls = 0
        t_end = time.perf_counter() + args.seconds
        while time.perf_counter() < t_end:
            a, k = copy.deepcopy(call)
            simulate(*a, **k)
            calls += 1
        perf.send_signal(signal.SIGINT)
        perf.wait()
        rows = subprocess.run(["perf", "script", "-i", str(data), "-F", "ip,sym,dso"],
                              capture_output=True, text=True).stdout.splitlines()
        ips = []
        elsewhere = collections.Counter()  # outside numba's code: shared object and symbol
        for row in rows:
            parts = row.split(None, 1)
            if parts:
                ips.append(int(parts[0], 16))
                elsewhere[ips[-1]] = parts[1] if len(parts) > 1 else "?"
        functions = compiled_functions()
        ranges = []
        for qualname, name, address, library in functions:
            obj = Path(tmp) / f"{len(ranges)}.o"
            obj.write_bytes(library._get_compiled_object())  # the object the JIT loaded
            table = symbol_table(obj)
            if name not in table:
                continue
            offset, size = table[name]
            ranges.append((qualname, address, size, obj, offset))
        counts = collections.Counter()
        per_function = collections.Counter()
        for ip in ips:
            for qualname, address, size, _obj, _offset in ranges:
                if address <= ip < address + size:
                    per_function[qualname] += 1
                    counts[(qualname, ip - address)] += 1
                    break
            else:
                per_function[f"(elsewhere) {_short(elsewhere[ip])}"] += 1
        run = next((r for r in ranges if r[0] == "run"), None)
        code = disassembly(run[3]) if run is not None else {}
    total = len(ips)
    if os.environ.get("HOT_DEBUG"):
        print([(q, hex(a), s) for q, a, s, _, _ in ranges][:5], len(functions))
        print([hex(ip) for ip, _ in collections.Counter(ips).most_common(5)])
    print(f"{args.case} {args.overrides}: {calls} kernel calls, {total} samples")
    for name, n in per_function.most_common(16):
        print(f"  {name:50s} {n:7d}  {100 * n / max(total, 1):5.1f} %")
    if run is None:
        return
    qualname, address, size, obj, offset = run
    offsets = sorted(code)
    if args.asm:
        with open(args.asm, "w") as f:
            for at in sorted(code):
                n = counts.get(("run", at - offset), 0)
                f.write(f"{at - offset:6x} {n:6d}  {_short(code[at])}\n")
    windows = collections.Counter()
    for (name, off), n in counts.items():
        if name == "run":
            windows[off // args.window] += n
    print(f"\nhottest {args.window}-byte windows of run: start, samples, %")
    for w, n in windows.most_common(12):
        print(f"  {w * args.window:6x} {n:6d} {100 * n / total:5.1f}")
    print(f"\nhottest instructions of run (size {size} bytes): offset, samples, %, instruction")
    for (name, off), n in counts.most_common():
        if name != "run":
            continue
        at = offset + off
        if at in code:
            i = offsets.index(at)
            for before in offsets[max(0, i - args.context):i]:
                print(f"            {before - offset:6x}  {_short(code[before])}")
            print(f"  {off:6x} {n:6d} {100 * n / total:5.2f}  {_short(code[at])}")
        args.top -= 1
        if args.top <= 0:
            break


if __name__ == "__main__":
    main()
