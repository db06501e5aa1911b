"""Custom post-processing of the spectra: the gear-speed and force spectra of the seed case as
DataFrames, the mesh harmonics read off at k f_z, and the energy between the harmonics.

Run: python examples/spectra_postprocessing.py
"""

from pathlib import Path

import numpy as np

import gearcli

ROOT = Path(__file__).resolve().parents[1]
sim = gearcli.simulate(ROOT / "cases" / "seed.yaml")
analysis = gearcli.analyze(sim)
spectra = gearcli.spectra_frame(analysis)  # index frequency_Hz, one column per signal
print("spectra columns:", ", ".join(spectra.columns))

f_z = sim.summary.gear_mesh_frequency_Hz
df = spectra.index[1] - spectra.index[0]
column = next(c for c in spectra.columns if c.startswith("force"))
rows = []
for k in range(1, 6):
    near = spectra.loc[k * f_z - 2 * df:k * f_z + 2 * df, column]
    rows.append((k, k * f_z, near.max()))
for k, f, a in rows:
    print(f"harmonic {k}: {f:8.1f} Hz  amplitude {a:10.2f}")
between = spectra[column][~np.any([np.abs(spectra.index - k * f_z) < 3 * df
                                   for k in range(1, 6)], axis=0)]
print(f"largest line between the harmonics: {between.max():.2f} at {between.idxmax():.1f} Hz")
