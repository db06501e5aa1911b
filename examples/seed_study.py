"""The seed case from Python: simulate, look at the summary and the time series, analyze,
save the results folder the command line would write, and a figure.

Run: python examples/seed_study.py [OUTPUT_FOLDER]
"""

import sys
from pathlib import Path

import gearcli

ROOT = Path(__file__).resolve().parents[1]
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out/examples/seed")

sim = gearcli.simulate(ROOT / "cases" / "seed.yaml")
s = sim.summary
print(f"{sim.name}: {sim.status}; dynamic factor {s.dynamic_factor:.3f}, "
      f"max force {s.force_max_N:.0f} N against {s.force_static_N:.0f} N static, "
      f"f_z {s.gear_mesh_frequency_Hz:.1f} Hz, f_n {s.mesh_natural_frequency_Hz:.0f} Hz")

# the time series: a pandas DataFrame indexed by time, columns named with their units
steady = sim.series.loc[s.window_s[0]:s.window_s[1]]
print(steady[["force_total_N", "delta_mm", "pairs_in_contact"]].describe().round(4))

analysis = gearcli.analyze(sim)
print("checks:", "; ".join(f"{c.label}: {c.verdict}" for c in analysis.checks))

sim.save(out, force=True)  # timeseries.csv, summary.json, manifest.json
sim.plot("force").savefig(out / "force.png", dpi=100)
print(f"results in {out}")
