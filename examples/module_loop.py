"""A parameter loop into a DataFrame and a plot: the dynamic factor and the DTE against the
module, with the tooth-compliance law (the pair stiffness follows the teeth).

Run: python examples/module_loop.py [FIGURE.png]
"""

import sys
from pathlib import Path

import pandas as pd
from matplotlib.figure import Figure

import gearcli

ROOT = Path(__file__).resolve().parents[1]
figure = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out/examples/module_loop.png")

base = gearcli.load_case(ROOT / "cases" / "iso_pair.yaml", set={"run.end_time": "0.35 s"})
rows = []
for module_mm in (4.0, 4.5, 5.0, 5.5, 6.0):
    sim = gearcli.simulate(base, set={"gears.module": f"{module_mm} mm"})
    s = sim.summary
    rows.append({"module_mm": module_mm, "status": sim.status,
                 "dynamic_factor": s.dynamic_factor,
                 "dte_peak_to_peak_um": 1e3 * s.dte_peak_to_peak_mm,
                 "mesh_stiffness_N_um": 1e-3 * s.mesh_stiffness_N_mm,
                 "f_n_Hz": s.mesh_natural_frequency_Hz, "f_z_Hz": s.gear_mesh_frequency_Hz})
df = pd.DataFrame(rows).set_index("module_mm")
print(df.round(3).to_string())

fig = Figure(figsize=(7, 4), layout="constrained")
ax = fig.subplots()
ax.plot(df.index, df["dynamic_factor"], "o-", label="dynamic factor")
ax.set_xlabel("module [mm]")
ax.set_ylabel("dynamic factor [-]")
tw = ax.twinx()
tw.plot(df.index, df["dte_peak_to_peak_um"], "s--", color="C1", label="DTE peak-to-peak")
tw.set_ylabel("DTE peak-to-peak [µm]")
fig.legend(loc="upper right")
figure.parent.mkdir(parents=True, exist_ok=True)
fig.savefig(figure, dpi=100)
print(f"figure: {figure}")
