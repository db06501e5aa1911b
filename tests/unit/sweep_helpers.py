"""Small fast studies for the sweep tests: 0.4 s simulated, 0.1 s ramps."""

from pathlib import Path

SEED = Path(__file__).resolve().parents[2] / "cases" / "seed.yaml"

FAST_SET = f"""base: {SEED}
set:
  run.end_time: 0.4 s
  drive.speed: STEP(time, 0, 0, 0.1, 3000)
  load.torque: STEP(time, 0, 0, 0.1, 4.5e+05)
  contact.max_damping: 5 N*s/mm
"""


def write_study(folder: Path, body: str, name: str = "study.yaml") -> Path:
    path = Path(folder) / name
    path.write_text(FAST_SET + body)
    return path
