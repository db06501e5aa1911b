"""Bench of `gearcli sweep` (issue 6): the 200-point speed sweep on 1 and 2 worker processes
and on an embedded Dask LocalCluster; checks that the summaries agree (timings aside).

    .venv/bin/python bench/sweep_bench.py [--jobs 2]
"""

from __future__ import annotations

import argparse
import csv
import tempfile
import time
from pathlib import Path

from gearcli.pipeline.sweep.run import SUMMARY, TIMING_COLUMNS, run_study
from gearcli.pipeline.sweep.study import load_study

STUDY = Path(__file__).with_name("sweep_speed200.yaml")


def rows(path: Path) -> list[dict]:
    with open(path, newline="") as fh:
        out = list(csv.DictReader(fh))
    for r in out:
        for c in TIMING_COLUMNS:
            r.pop(c)
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--skip-dask", action="store_true")
    args = ap.parse_args()
    study = load_study(STUDY)
    n = len(study.points)
    tmp = Path(tempfile.mkdtemp(prefix="gearcli-sweep-bench-"))
    results = {}
    runs = [("serial", 1, None), ("processes", args.jobs, None)]
    if not args.skip_dask:
        runs.append(("dask-local", args.jobs, "local"))
    for label, jobs, scheduler in runs:
        t0 = time.perf_counter()
        out = run_study(study, tmp / label, jobs=jobs, scheduler=scheduler, force=True)
        wall = time.perf_counter() - t0
        solver = sum(float(r["solver_time_s"] or 0.0) for r in out.rows)
        worker = sum(float(r["wall_time_s"]) for r in out.rows)
        results[label] = (wall, jobs)
        print(f"{label:10s} jobs={jobs}: {wall:6.2f} s for {n} points "
              f"({out.failed} failed); solver {solver:.2f} s, in-worker total {worker:.2f} s; "
              f"overhead/point outside the solver: in worker "
              f"{1e3 * (worker - solver) / n:.1f} ms, whole study "
              f"{1e3 * (wall * jobs - solver) / n:.1f} ms")
    s1, s2 = results["serial"][0], results["processes"][0]
    print(f"speed-up 1 -> {args.jobs} jobs: {s1 / s2:.2f}x")
    same = rows(tmp / "processes" / SUMMARY) == rows(tmp / "serial" / SUMMARY)
    print(f"serial == processes (all columns but {', '.join(TIMING_COLUMNS)}): {same}")
    if "dask-local" in results:
        same = rows(tmp / "dask-local" / SUMMARY) == rows(tmp / "serial" / SUMMARY)
        print(f"serial == dask-local: {same}")
    print(f"outputs in {tmp}")


if __name__ == "__main__":
    main()
