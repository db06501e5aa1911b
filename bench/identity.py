"""Bit-identity of results across a change: dump them from one checkout, compare with another.

    .venv/bin/python bench/identity.py dump  /tmp/before.npz   # in the old checkout
    .venv/bin/python bench/identity.py dump  /tmp/after.npz    # in the new one
    .venv/bin/python bench/identity.py check /tmp/before.npz /tmp/after.npz

What is dumped, per case (seed; seed rigid without friction; drivetrain; iso_pair): the
kernel's sampled series, slot forces, extrema, counters, the parameter vector, the gap
tables and output times (compared with ``np.array_equal``, NaNs equal), and as text the
geometry JSON of ``gearcli geometry --json`` and the time-series CSV of ``gearcli simulate``
(compared byte for byte). Timings (``wall_time_s``) are left out.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "seed": ("cases/seed.yaml", []),
    "seed_rigid": ("cases/seed.yaml", ["contact.engagement=rigid", "friction.enabled=false"]),
    "drivetrain": ("cases/drivetrain.yaml", []),
    "iso_pair": ("cases/iso_pair.yaml", []),
}


def _text(s: str) -> np.ndarray:
    return np.frombuffer(s.encode(), dtype=np.uint8)


def dump(path: str) -> None:
    from gearcli.io.tables import columns_to_csv
    from gearcli.pipeline.geometry import geometry_dict, run_geometry
    from gearcli.pipeline.simulate import run_simulation

    arrays: dict[str, np.ndarray] = {}
    for name, (case, overrides) in CASES.items():
        res = run_simulation(ROOT / case, overrides)
        k, ki = res.kernel, res.kernel_input
        arrays.update({
            f"{name}/series": k.series, f"{name}/slot_force": k.slot_force,
            f"{name}/slot_force_coast": k.slot_force_coast, f"{name}/extrema": k.extrema,
            f"{name}/slot_extrema": k.slot_extrema,
            f"{name}/counters": np.array(sorted(k.counters.items()), dtype=object).astype(str),
            f"{name}/params": ki.params, f"{name}/tables": ki.tables.tables,
            f"{name}/t_out": ki.t_out, f"{name}/csv": _text(columns_to_csv(res.columns())),
            f"{name}/summary": _text(json.dumps(res.summary.to_dict(), sort_keys=True)),
        })
        if not overrides:
            geo = geometry_dict(run_geometry(ROOT / case))
            arrays[f"{name}/geometry_json"] = _text(json.dumps(geo, indent=2))
        print(f"{name}: {k.series.shape[0]} rows, {k.counters['accepted_steps']} steps",
              flush=True)
    np.savez_compressed(path, **arrays)


def check(before: str, after: str) -> int:
    a, b = np.load(before, allow_pickle=False), np.load(after, allow_pickle=False)
    bad = 0
    for key in sorted(set(a.files) | set(b.files)):
        if key not in a.files or key not in b.files:
            print(f"{key}: only in {'after' if key in b.files else 'before'}")
            bad += 1
            continue
        x, y = a[key], b[key]
        same = x.shape == y.shape and x.dtype == y.dtype and (
            np.array_equal(x, y, equal_nan=x.dtype.kind == "f"))
        print(f"{key:<28} {str(x.shape):<14} {'identical' if same else 'DIFFERENT'}")
        bad += not same
    print("all identical" if not bad else f"{bad} differ")
    return 1 if bad else 0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("dump").add_argument("path")
    c = sub.add_parser("check")
    c.add_argument("before")
    c.add_argument("after")
    args = ap.parse_args()
    if args.cmd == "dump":
        dump(args.path)
    else:
        sys.exit(check(args.before, args.after))


if __name__ == "__main__":
    main()
