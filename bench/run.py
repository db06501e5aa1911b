"""gearcli benchmarks (`make bench`): wall times of the commands users feel, solver speed.

Run from the repository root with the project's venv. Prints a table and writes nothing by
itself: copy the numbers you measured into bench/RESULTS.md with the date and machine.

Sections (issue 3, speed):
1. ``gearcli --help`` and ``gearcli geometry``: start-up.
2. Solver: the compiled kernel call alone (``SimulationResult.wall_time_s``) on the seed case,
   5 s simulated, default output rate, median of ``--runs`` after a warm-up (compile) run;
   rigid engagement without friction, and the full default model. Steps and RHS evaluations.
3. The same rigid model as a plain scipy ``solve_ivp(LSODA)`` with a Python right-hand side
   (bench/rigid_reference.py), its time over the compiled solver's, and the agreement of the
   mean force and mean gear speed over the steady window.
4. ``gearcli simulate`` end to end with a warm numba cache, and the first run with an empty
   one (``NUMBA_CACHE_DIR`` a fresh folder); the cache with the package folder read-only.
5. Peak RSS of a 60 s simulation (``/usr/bin/time -v``).
6. ``analyze`` + ``report`` of a written seed run (in process), target < 5 s (issue 12 moved
   this check out of the test suite: wall-clock times belong here, never in tests); and
   ``gearcli report`` of the seed run (warm) over ``python -c "import matplotlib.pyplot"``,
   alternating ``--rounds`` rounds, medians and their ratio, with and without ``--svg``
   (issue 29: target <= 3 s on a quiet 2-core machine; ``--report-only``, and
   ``--report-base DIR`` to time another checkout's gearcli in the same rounds).
7. Start-up as ratios (issue 16), so the targets hold on any machine: ``--rounds`` rounds, each
   running every command once in turn, so that a noisy neighbour slows all of them alike;
   medians and minima, ratio of the medians. ``simulate`` warm over ``python -c "import
   numba"``, ``geometry --json`` over ``python -c "import numpy"``, ``--help`` and ``schema``
   in seconds; the first run with an empty numba cache over ``import numba``, with its peak
   RSS; the import-time profile (``python -X importtime``) of simulate and geometry, summed
   per top-level package (``--importtime``).
8. ``gearcli mesh --method fe`` of the seed (in process, the finite-element check of the tooth
   compliance, issue 31): the first run with an empty FE store (both gears meshed and solved)
   and the cached reruns (influence coefficients from the on-disk store), whole analysis and
   FE part, and their ratio. Skipped without the optional extra ``fe``.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
_SCRIPT = Path(sys.executable).with_name("gearcli")
GEARCLI = [str(_SCRIPT)] if _SCRIPT.exists() else [sys.executable, "-m", "gearcli"]
SEED = ROOT / "cases" / "seed.yaml"
RIGID = ["contact.engagement=rigid", "friction.enabled=false"]

ROWS: list[tuple[str, str, str, str]] = []  # (what, measured, target, verdict)
STARTUP: dict[str, float] = {}  # median wall times of the start-up section [s]


def row(what: str, measured: str, target: str = "", ok: bool | None = None) -> None:
    verdict = "" if ok is None else ("ok" if ok else "MISSED")
    ROWS.append((what, measured, target, verdict))
    print(f"  {what:<52} {measured:<44} {target:<12} {verdict}", flush=True)


def wall(cmd: list[str], repeat: int, env: dict | None = None) -> list[float]:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True, env=env)
        times.append(time.perf_counter() - t0)
    return times


def startup(args) -> None:
    """Start-up of the commands users wait for, as ratios to bare imports (see section 7)."""
    print(f"start-up: {args.rounds} rounds, each command once per round in turn")
    with tempfile.TemporaryDirectory() as tmp:
        # numba's own floor: a process that loads one trivial function from numba's cache
        # (its first cache load initialises the CPU target: registries, scipy.linalg for BLAS)
        (Path(tmp) / "trivial_kernel.py").write_text(
            "import numba\n\n@numba.njit(cache=True)\ndef f(x):\n    return x + 1.0\n")
        floor_env = {**os.environ, "PYTHONPATH": tmp, "NUMBA_CACHE_DIR": str(Path(tmp) / "nb")}
        floor = [sys.executable, "-c", "import trivial_kernel; trivial_kernel.f(1.0)"]
        wall(floor, 1, floor_env)  # compiles it once
        cmds = {
            "import numba": [sys.executable, "-c", "import numba"],
            "import numpy": [sys.executable, "-c", "import numpy"],
            "cached numba call": floor,
            "simulate": GEARCLI + ["simulate", str(SEED), "-o", str(Path(tmp) / "out"),
                                   "--force", "--quiet"],
            "geometry": GEARCLI + ["geometry", str(SEED), "--json"],
            "help": GEARCLI + ["--help"],
            "schema": GEARCLI + ["schema"],
        }
        wall(cmds["simulate"], 1)  # the user cache is warm
        times: dict[str, list[float]] = {k: [] for k in cmds}
        for _ in range(args.rounds):
            for name, cmd in cmds.items():
                times[name] += wall(cmd, 1, floor_env if cmd is floor else None)
    med = {k: statistics.median(v) for k, v in times.items()}
    low = {k: min(v) for k, v in times.items()}
    STARTUP.update(med)

    def ms(name: str) -> str:
        return f"median {med[name] * 1e3:.0f} ms, min {low[name] * 1e3:.0f} ms"

    row('python -c "import numba"', ms("import numba"))
    row('python -c "import numpy"', ms("import numpy"))
    row("one trivial cached numba function, loaded and called (numba's floor)",
        f"{ms('cached numba call')}; {med['cached numba call'] / med['import numba']:.1f}x "
        "import numba")
    for name, base, target in (("simulate", "import numba", 2.5),
                               ("geometry", "import numpy", 3.0)):
        ratio = med[name] / med[base]
        row(f"gearcli {name} seed, warm ({base} = 1)",
            f"{ms(name)}; {ratio:.1f}x (min/min {low[name] / low[base]:.1f}x)",
            f"<= {target:g}x", ratio <= target)
    for name, label in (("help", "gearcli --help"), ("schema", "gearcli schema")):
        row(label, ms(name), "< 250 ms", med[name] < 0.25)
    if args.importtime:
        import_profile(cmds["simulate"][len(GEARCLI):], "simulate")
        import_profile(cmds["geometry"][len(GEARCLI):], "geometry")


def import_profile(argv: list[str], label: str, top: int = 8) -> None:
    """``python -X importtime`` of one command, self time summed per top-level package."""
    with tempfile.TemporaryDirectory() as tmp:
        argv = [str(Path(tmp) / "out") if a.endswith("/out") else a for a in argv]
        env = {**os.environ, "PYTHONPROFILEIMPORTTIME": "1"}
        proc = subprocess.run(GEARCLI + argv, capture_output=True, text=True, env=env)
    per: dict[str, int] = {}
    for line in proc.stderr.splitlines():
        m = re.match(r"import time:\s+(\d+) \|\s+\d+ \|\s*(\S+)", line)
        if m:
            pkg = m.group(2).split(".")[0]
            per[pkg] = per.get(pkg, 0) + int(m.group(1))
    total = sum(per.values())
    ranked = sorted(per.items(), key=lambda kv: -kv[1])[:top]
    row(f"import time, {label} (self time per package)",
        f"{total / 1e3:.0f} ms: " + ", ".join(f"{k} {v / 1e3:.0f}" for k, v in ranked))


def solver(args) -> dict:
    """Kernel-only times; returns the last results of both variants."""
    from gearcli.pipeline.simulate import run_simulation

    print(f"solver: seed case, 5 s, default output rate, kernel call only, median of "
          f"{args.runs} after a warm-up")
    out = {}
    for name, overrides, target in (("rigid, no friction", RIGID, 10e-3),
                                    ("full default model", [], 20e-3)):
        res = run_simulation(SEED, overrides)  # warm-up (compiles on an empty cache)
        times = []
        for _ in range(args.runs):
            res = run_simulation(SEED, overrides)
            times.append(res.wall_time_s)
        c = res.kernel.counters
        med = statistics.median(times)
        row(f"solver, {name}", f"median {med * 1e3:.2f} ms (min {min(times) * 1e3:.2f})",
            f"<= {target * 1e3:.0f} ms", med <= target)
        row("  steps acc/rej, RHS evals, output evals",
            f"{c['accepted_steps']}/{c['rejected_steps']}, {c['rhs_evaluations']}, "
            f"{c['output_evaluations']}")
        out[name] = (res, med)
    return out


def reference(args, solved: dict) -> None:
    from rigid_reference import run_reference, seed_rigid_model

    from gearcli.core.layout import PARAM_NAMES, P

    print("plain scipy reference (LSODA, Python RHS) of the rigid model")
    res, med = solved["rigid, no friction"]
    ki = res.kernel_input
    model = seed_rigid_model(ki.params, PARAM_NAMES)
    atol = [ki.params[P.atol_delta], ki.params[P.atol_deltadot]]
    runs = [run_reference(model, ki.t_out, ki.params[P.rtol], atol)
            for _ in range(args.ref_runs)]
    ref = runs[-1]
    t_ref = statistics.median(r.wall_s for r in runs)
    row("scipy solve_ivp LSODA, rigid, 5 s", f"median {t_ref:.3f} s (n={args.ref_runs}), "
        f"{ref.nfev} RHS evals")
    row("  ratio scipy / compiled", f"{t_ref / med:.0f}x", ">= 100x", t_ref / med >= 100)
    w = ref.t >= res.window.t0_s
    f_k, f_r = res.summary.force_mean_N, float(ref.force[w].mean())
    n_k, n_r = res.summary.gear_speed_mean_deg_s, math.degrees(float(ref.omega2[w].mean()))
    row("  mean force: compiled vs scipy", f"{f_k:.4f} vs {f_r:.4f} N ({(f_r - f_k) / f_k:+.1e})")
    row("  mean gear speed: compiled vs scipy",
        f"{n_k:.5f} vs {n_r:.5f} deg/s ({(n_r - n_k) / n_k:+.1e})")


def end_to_end(args) -> None:
    print("gearcli simulate cases/seed.yaml -o <tmp> --force --quiet")
    with tempfile.TemporaryDirectory() as tmp:
        cmd = GEARCLI + ["simulate", str(SEED), "-o", str(Path(tmp) / "out"), "--force",
                         "--quiet"]
        wall(cmd, 1)  # make sure the user cache is warm
        t = wall(cmd, 5)
        row("end to end, warm numba cache", f"median {statistics.median(t):.2f} s (n=5)",
            "<= 3 s", statistics.median(t) <= 3.0)
        if args.cold:
            env = {**os.environ, "NUMBA_CACHE_DIR": str(Path(tmp) / "numba-empty")}
            seconds, kb = timed_tree_rss(cmd, env)
            base = STARTUP.get("import numba") or statistics.median(
                wall([sys.executable, "-c", "import numba"], 5))
            row("end to end, first run, empty numba cache",
                f"{seconds:.1f} s = {seconds / base:.0f}x import numba, peak RSS "
                f"{kb / 1024:.0f} MB", "<= 60x", seconds / base <= 60)


def _tree_rss_kb(root: int) -> int:
    """Resident set size [kB] of a process and all its descendants now (Linux /proc)."""
    children: dict[int, list[int]] = {}
    rss: dict[int, int] = {}
    for status in Path("/proc").glob("[0-9]*/status"):
        try:
            fields = dict(line.split(":", 1) for line in status.read_text().splitlines()
                          if ":" in line)
        except OSError:
            continue
        pid = int(status.parent.name)
        children.setdefault(int(fields["PPid"]), []).append(pid)
        rss[pid] = int(fields.get("VmRSS", "0 kB").split()[0])
    total, todo = 0, [root]
    while todo:
        pid = todo.pop()
        total += rss.get(pid, 0)
        todo += children.get(pid, [])
    return total


def timed_tree_rss(cmd: list[str], env: dict | None = None) -> tuple[float, int]:
    """Wall time [s] and peak RSS [kB] summed over the process and its children (sampled
    every 0.1 s, so that a run that starts helper processes is counted whole)."""
    if not Path("/proc/self/status").exists():
        return timed_rss(cmd, env)
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    peak = 0
    while proc.poll() is None:
        peak = max(peak, _tree_rss_kb(proc.pid))
        time.sleep(0.1)
    if proc.returncode:
        raise subprocess.CalledProcessError(proc.returncode, cmd)
    return time.perf_counter() - t0, peak


def timed_rss(cmd: list[str], env: dict | None = None) -> tuple[float, int]:
    """Wall time [s] and peak RSS [kB] of a command (``/usr/bin/time -v``, else getrusage)."""
    tool = Path("/usr/bin/time")
    t0 = time.perf_counter()
    if tool.exists():
        proc = subprocess.run([str(tool), "-v", *cmd], capture_output=True, text=True,
                              check=True, env=env)
        kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)",
                           proc.stderr).group(1))
    else:
        import resource

        subprocess.run(cmd, check=True, capture_output=True, env=env)
        kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    return time.perf_counter() - t0, kb


def read_only(args) -> None:
    """Package folder read-only (a read-only bind mount of gearcli/ in a private mount
    namespace, so that root is refused too), numba cache in a fresh XDG_CACHE_HOME."""
    print("numba cache with a read-only package folder")
    pkg = ROOT / "gearcli"
    with tempfile.TemporaryDirectory() as tmp:
        env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
        env["XDG_CACHE_HOME"] = str(Path(tmp) / "xdg")
        out = str(Path(tmp) / "out")
        sim = " ".join(GEARCLI + ["simulate", str(SEED), "-o", out, "--force", "--quiet"])
        script = (f"mount --bind {pkg} {pkg} && mount -o remount,ro,bind {pkg} && "
                  f"! touch {pkg}/core/__pycache__/.ro-probe 2>/dev/null && "
                  f"s=$(date +%s.%N) && {sim} && m=$(date +%s.%N) && {sim} && "
                  f"e=$(date +%s.%N) && echo TIMES $s $m $e")
        unshare = shutil.which("unshare")
        proc = subprocess.run([unshare, "-m", "sh", "-c", script] if unshare else ["false"],
                              capture_output=True, text=True, env=env)
        m = re.search(r"TIMES (\S+) (\S+) (\S+)", proc.stdout)
        if proc.returncode != 0 or not m:
            row("read-only package", "not measured (needs unshare -m and mount: "
                f"{(proc.stderr or 'unavailable').strip()[:60]})")
            return
        s, mid, e = (float(v) for v in m.groups())
        files = sorted((Path(tmp) / "xdg" / "gearcli" / "numba").rglob("*.nbi"))
        folder = files[0].relative_to(Path(tmp) / "xdg").parts[:3] if files else ("?",)
        row("read-only gearcli/: first run (compiles)", f"{mid - s:.1f} s")
        row("read-only gearcli/: second run (cache)", f"{e - mid:.2f} s", "<= 3 s",
            e - mid <= 3.0)
        row("  index files in $XDG_CACHE_HOME/" + "/".join(folder), f"{len(files)} .nbi",
            "> 0", len(files) > 0)


def memory(args) -> None:
    print("memory: 60 s simulation at the default output rate")
    with tempfile.TemporaryDirectory() as tmp:
        cmd = GEARCLI + ["simulate", str(SEED), "-o", str(Path(tmp) / "out"), "--force",
                         "--quiet", "--set", "run.end_time=60"]
        wall_s, kb = timed_rss(cmd)
        row("peak RSS, 60 s seed run (end to end)", f"{kb / 1024:.0f} MB (wall {wall_s:.1f} s)",
            "< 1 GB", kb < 1024 * 1024)


def formats(args) -> None:
    """Writing the time series of a 60 s seed run: numpy.savetxt (before issue 16), the
    compiled %.10g writer, Parquet (``--format parquet``). In process, best of 3."""
    from gearcli.io.tables import columns_to_csv
    from gearcli.pipeline.outputs import write_timeseries
    from gearcli.pipeline.simulate import run_simulation

    print("time series of a 60 s seed run: CSV and Parquet")
    res = run_simulation(SEED, ["run.end_time=60"])
    rows = res.kernel.series.shape[0]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)

        def savetxt() -> Path:
            path = folder / "savetxt.csv"
            path.write_text(columns_to_csv(res.columns()))
            return path

        results = {}
        for name, write in (
                ("numpy.savetxt CSV", savetxt),
                ("compiled CSV (default)", lambda: write_timeseries(res, folder, "csv")),
                ("Parquet (zstd)", lambda: write_timeseries(res, folder, "parquet"))):
            times = []
            for _ in range(3):
                t0 = time.perf_counter()
                path = write()
                times.append(time.perf_counter() - t0)
            results[name] = (min(times), path.stat().st_size)
    base_t, base_size = results["numpy.savetxt CSV"]
    for name, (t, size) in results.items():
        row(f"write {rows} rows: {name}", f"{t:.2f} s ({t / base_t:.2f}x), "
            f"{size / 1e6:.1f} MB ({size / base_size:.2f}x)")


def post_processing(args) -> None:
    from gearcli.pipeline.analysis_io import write_analysis
    from gearcli.pipeline.analyze import analyze
    from gearcli.pipeline.outputs import write_simulation
    from gearcli.pipeline.simulate import run_simulation
    from gearcli.report import build_report

    print("analyze + report of the seed run (in process, results folder already written)")
    times = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "seed"
        write_simulation(run_simulation(SEED), folder, force=False)
        for _ in range(3):
            t0 = time.perf_counter()
            write_analysis(analyze(folder))
            build_report(folder)
            times.append(time.perf_counter() - t0)
    med = statistics.median(times)
    row("analyze + report, seed", f"median {med:.2f} s (n=3)", "< 5 s", med < 5.0)


def fe_mesh(args) -> None:
    """Section 8: the FE mesh analysis of the seed, empty store against cached reruns."""
    import importlib.util

    if not all(importlib.util.find_spec(m) for m in ("skfem", "triangle")):
        print("FE mesh analysis: skipped (optional extra 'fe' not installed)")
        return
    from gearcli.pipeline.mesh import run_mesh

    print("gearcli mesh --method fe, seed (in process; a fresh FE store)")
    run_mesh(SEED)  # the LTCA's compiled code loaded: the FE part is what differs
    old = os.environ.get("XDG_CACHE_HOME")
    with tempfile.TemporaryDirectory() as tmp:
        os.environ["XDG_CACHE_HOME"] = tmp
        try:
            runs = []
            for _ in range(1 + args.fe_reruns):
                t0 = time.perf_counter()
                res = run_mesh(SEED, method="fe")
                runs.append((time.perf_counter() - t0, res.fe))
        finally:
            if old is None:
                os.environ.pop("XDG_CACHE_HOME", None)
            else:
                os.environ["XDG_CACHE_HOME"] = old
    (cold, first), reruns = runs[0], runs[1:]
    assert first.cache_misses == 2 and all(f.cache_hits == 2 for _, f in reruns)
    warm = statistics.median(t for t, _ in reruns)
    warm_fe = statistics.median(f.seconds for _, f in reruns)
    row("mesh --method fe, seed, empty FE store", f"{cold:.2f} s (FE part {first.seconds:.2f} s, "
        f"{sum(first.fe_dofs)} dofs)")
    row("mesh --method fe, seed, cached rerun", f"median {warm:.3f} s (FE part {warm_fe:.3f} s,"
        f" n={len(reruns)})")
    row("mesh --method fe, empty store / cached", f"{cold / warm:.1f}x (FE part "
        f"{first.seconds / warm_fe:.0f}x)")


def report_timing(args) -> None:
    """`gearcli report` of the seed run (warm caches) against ``python -c "import
    matplotlib.pyplot"`` (the floor of any process that draws), alternating rounds, medians."""
    print(f"gearcli report of the seed run: {args.rounds} rounds, each command once per round")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "seed"
        subprocess.run(GEARCLI + ["simulate", str(SEED), "-o", str(folder), "--quiet"],
                       check=True, capture_output=True)
        # exit 4: the seed fails its checks, the analysis is written all the same
        subprocess.run(GEARCLI + ["analyze", str(folder), "--quiet"], capture_output=True)
        report = GEARCLI + ["report", str(folder), "--force", "--quiet"]
        cmds = {"import matplotlib.pyplot": [sys.executable, "-c", "import matplotlib.pyplot"],
                "report": report, "report --svg": report + ["--svg"],
                "report, one process": report}
        envs: dict[str, dict | None] = dict.fromkeys(cmds)
        # the figures in one process (gearcli/report/parallel.py forks two workers only with
        # a CPU to spare: on a busy machine "report" is this too)
        envs["report, one process"] = {**os.environ, "GEARCLI_REPORT_JOBS": "1"}
        if args.report_base:  # the same command from another checkout's gearcli package
            cmds["report (base)"] = report
            envs["report (base)"] = {**os.environ, "PYTHONPATH": str(Path(args.report_base))}
        for name, cmd in cmds.items():  # warm: bytecode, font cache, numba cache
            wall(cmd, 1, envs[name])
        times: dict[str, list[float]] = {k: [] for k in cmds}
        cpu: dict[str, list[float]] = {k: [] for k in cmds}  # user + sys of the process
        for _ in range(args.rounds):
            for name, cmd in cmds.items():
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                times[name] += wall(cmd, 1, envs[name])
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu[name].append(after.ru_utime - before.ru_utime
                                 + after.ru_stime - before.ru_stime)
    med = {k: statistics.median(v) for k, v in times.items()}
    floor = med["import matplotlib.pyplot"]
    row('python -c "import matplotlib.pyplot"', f"median {floor:.2f} s, min "
        f"{min(times['import matplotlib.pyplot']):.2f} s")
    for name in cmds:
        if name.startswith("report"):
            row(f"gearcli {name} seed, warm (import matplotlib.pyplot = 1)",
                f"median {med[name]:.2f} s, min {min(times[name]):.2f} s; "
                f"{med[name] / floor:.1f}x", "<= 3 s quiet")
    # CPU time (user + sys, workers included) is what a quiet machine's wall time of one
    # process approaches; on a loaded machine it is the steadier measure
    cpu_med = {k: statistics.median(v) for k, v in cpu.items()}
    cpu_floor = cpu_med["import matplotlib.pyplot"]
    for name in cmds:
        row(f"CPU time of {name}" + ("" if name.startswith("import") else
                                     " (import matplotlib.pyplot = 1)"),
            f"median {cpu_med[name]:.2f} s" + ("" if name.startswith("import") else
                                               f"; {cpu_med[name] / cpu_floor:.1f}x"))


def rating_timing(args) -> None:
    """`gearcli rate` of cases/nrel5mw_sun_planet.yaml in process: the whole rate_case (case
    loading, geometry, ISO 6336 factors, life, inspection) and the rating formulas alone."""
    from gearcli.case.load import load_case
    from gearcli.model.iso6336.rate import rate
    from gearcli.pipeline.rating import rate_case, rating_input

    case = ROOT / "cases" / "nrel5mw_sun_planet.yaml"
    print("ISO 6336 rating of the NREL 5 MW sun-planet mesh (in process, 20 calls each)")
    rate_case(case)  # warm: imports, tables
    loaded = load_case(case)
    inp = rating_input(loaded)[0]
    whole, formulas = [], []
    for _ in range(20):
        t0 = time.perf_counter()
        rate_case(loaded)
        whole.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        rate(inp)
        formulas.append(time.perf_counter() - t0)
    row("rate_case, NREL 5 MW sun-planet", f"median {1e3 * statistics.median(whole):.2f} ms")
    row("  of which the rating formulas", f"median {1e3 * statistics.median(formulas):.2f} ms")


def fault_dataset(args) -> None:
    """Fault-dataset throughput, `gearcli sweep` of a study with ``dataset:`` (issue 30): 8
    points of cases/studies/fault_dataset.yaml (4 fault cases x 2 noise seeds at 1500 rpm,
    300 N*m; 0.4 s each, signals as Parquet, labels with the TSA metrics) on 2 worker
    processes, points per minute of wall time (the solver cached; start-up included)."""
    import tempfile

    import yaml

    study = yaml.safe_load((ROOT / "cases" / "studies" / "fault_dataset.yaml").read_text())
    study["base"] = str(ROOT / "cases" / "iso_pair.yaml")
    p = study["parameters"]
    p["faults"], p["mesh_frequency"] = p["faults"][:4], ["525 Hz"]
    p["load.torque"], p["sensors.noise.seed"] = p["load.torque"][1:], [1, 2]
    print("fault dataset: 8 points of cases/studies/fault_dataset.yaml, -j 2")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "study.yaml"
        path.write_text(yaml.safe_dump(study))
        cmd = [*GEARCLI, "sweep", str(path), "-o", str(Path(tmp) / "out"), "-j", "2", "-q"]
        t = wall(cmd, 1)[0]
    row("fault dataset, 8 points on 2 workers", f"{t:.1f} s, {8 * 60.0 / t:.1f} points/min")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=9, help="timed solver runs (median), >= 7")
    ap.add_argument("--ref-runs", type=int, default=3, help="timed scipy reference runs")
    ap.add_argument("--no-cold", dest="cold", action="store_false",
                    help="skip the empty-cache end-to-end run (~15 s)")
    ap.add_argument("--rounds", type=int, default=7,
                    help="alternating rounds of the start-up commands (medians, minima)")
    ap.add_argument("--no-importtime", dest="importtime", action="store_false",
                    help="skip the python -X importtime profiles")
    ap.add_argument("--startup-only", action="store_true",
                    help="only the start-up section (ratios, import profile)")
    ap.add_argument("--report-only", action="store_true",
                    help="only the report timing (gearcli report vs import matplotlib.pyplot)")
    ap.add_argument("--report-base", metavar="DIR",
                    help="also time `gearcli report` with DIR's gearcli (PYTHONPATH=DIR)")
    ap.add_argument("--quick", action="store_true",
                    help="start-up and solver only (no scipy, end-to-end, memory)")
    ap.add_argument("--fe-only", action="store_true",
                    help="only the FE mesh analysis (section 8)")
    ap.add_argument("--fe-reruns", type=int, default=3,
                    help="cached reruns of the FE mesh analysis (median)")
    args = ap.parse_args()
    os.chdir(ROOT)
    print(f"python {sys.version.split()[0]} on {platform.platform()}, {os.cpu_count()} CPUs, "
          f"{platform.processor() or platform.machine()}")
    if args.fe_only:
        fe_mesh(args)
    elif args.report_only:
        report_timing(args)
    else:
        _sections(args)
    print("\n| what | measured | target | |\n|---|---|---|---|")
    for what, measured, target, verdict in ROWS:
        print(f"| {what.strip()} | {measured} | {target} | {verdict} |")


def _sections(args) -> None:
    startup(args)
    solved = {} if args.startup_only else solver(args)
    if not (args.quick or args.startup_only):
        reference(args, solved)
        end_to_end(args)
        read_only(args)
        memory(args)
        formats(args)
        post_processing(args)
        fe_mesh(args)
        report_timing(args)
        rating_timing(args)
        fault_dataset(args)


if __name__ == "__main__":
    main()
