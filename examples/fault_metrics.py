"""Condition-monitoring metrics against root-crack depth (docs/theory.md, "Tooth faults",
"Condition-monitoring signals"): cases/iso_pair.yaml with a crack on pinion tooth 2 of depth
0 ... 8 mm, the pinion's TSA of the encoder TE and of the housing accelerometer (30 dB seeded
noise), FM4, NA4 (against the healthy run) and the energy ratio; writes the figure of the
README, docs/fault_metrics.png, or FIGURE.

Run: python examples/fault_metrics.py [FIGURE.png]   (seven 0.4 s runs: ~10 s once compiled)
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import gearcli

ROOT = Path(__file__).resolve().parents[1]
DEPTHS_MM = (0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0)
SETS = ["run.end_time=0.4",
        "drive.speed={function: 'STEP(time, 0, 0, 0.05, 1500)', unit: rpm}",
        "load.torque={function: 'STEP(time, 0, 0, 0.05, 300)', unit: N*m}",
        "sensors={sample_rate: 10 kHz, accelerometer: {housing: [{frequency: 3 kHz, "
        "damping_ratio: 0.05, modal_mass: 2 kg}]}, noise: {seed: 3, snr_db: 30}}"]
METRICS = (("fm4", "FM4"), ("na4", "NA4 (healthy baseline)"), ("energy_ratio",
                                                                 "energy ratio"))


def main(figure: Path = ROOT / "docs" / "fault_metrics.png") -> None:
    from matplotlib.figure import Figure

    values = {s: {m: [] for m, _ in METRICS} for s in ("te", "accel_m_s2")}
    with tempfile.TemporaryDirectory() as tmp:
        runs = []
        for depth in DEPTHS_MM:
            crack = (f"faults=[{{kind: root_crack, gear: pinion, tooth: 2, depth: {depth} mm, "
                     "angle: 45 deg}]")
            folder = Path(tmp) / f"crack{depth:g}"
            gearcli.simulate(ROOT / "cases" / "iso_pair.yaml", [*SETS, crack]).save(folder)
            runs.append(folder)
        for signal in values:
            for folder in runs:
                doc = gearcli.monitor(folder, runs[0], signal=signal)
                pinion = next(s for s in doc.shafts if s.shaft == "pinion")
                for m, _ in METRICS:
                    values[signal][m].append(pinion.value(m))
    fig = Figure(figsize=(10, 3.2), layout="constrained")
    for k, (m, label) in enumerate(METRICS):
        ax = fig.add_subplot(1, 3, k + 1)
        for signal, name in (("te", "encoder TE"), ("accel_m_s2", "accelerometer, 30 dB")):
            ax.plot(DEPTHS_MM, values[signal][m], "o-", label=name)
        ax.set_yscale("log")
        ax.set_xlabel("crack depth [mm]")
        ax.set_title(f"pinion {label}", fontsize=10)
        ax.grid(alpha=0.3)
    fig.axes[0].legend(fontsize=8)
    figure.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(figure, dpi=100)
    for signal in values:
        print(signal, {m: [round(v, 4) for v in values[signal][m]] for m, _ in METRICS})


if __name__ == "__main__":
    main(*(Path(a) for a in sys.argv[1:2]))
