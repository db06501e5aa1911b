"""gearcli benchmarks (`make bench`): wall times of the commands users feel.

Run from the repository root with the project's venv. Prints a table and appends nothing by
itself: copy the numbers you measured into bench/RESULTS.md with the date and machine.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
GEARCLI = [sys.executable, "-m", "gearcli"]
SEED = ROOT / "cases" / "seed.yaml"


def wall(cmd: list[str], repeat: int) -> list[float]:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    return times


def report(name: str, times: list[float], target: str) -> None:
    med = statistics.median(times)
    print(f"{name:<40} median {med * 1e3:8.1f} ms  min {min(times) * 1e3:8.1f} ms  "
          f"(n={len(times)}, target {target})")


def main() -> None:
    print(f"python {sys.version.split()[0]} on {sys.platform}")
    report("gearcli --help", wall(GEARCLI + ["--help"], 15), "< 300 ms")
    report("gearcli geometry seed --json", wall(GEARCLI + ["geometry", str(SEED), "--json"], 5),
           "interactive")


if __name__ == "__main__":
    main()
