"""Write a simulation's results folder: timeseries.csv, summary.json, manifest.json."""

from __future__ import annotations

import json
from pathlib import Path

from gearcli.io.manifest import manifest
from gearcli.io.outdir import atomic_dir
from gearcli.io.tables import columns_to_csv
from gearcli.pipeline.simulate import SimulationResult


def summary_document(res: SimulationResult) -> dict:
    k = res.kernel
    return {
        "case": res.name,
        "status": "ok",
        "solver": {
            "message": k.message,
            **k.counters,
            "wall_time_s": res.wall_time_s,
            "engagement": res.loaded.case.contact.engagement,
            "drive": res.loaded.case.drive.type,
        },
        "rows": int(k.series.shape[0]),
        "slots": int(k.slot_force.shape[1]),
        "warnings": res.warnings,
        "scalars": res.summary,
    }


def write_simulation(res: SimulationResult, target: str | Path, force: bool,
                     overrides: list[str] | None = None) -> Path:
    """Write the three files atomically into ``target`` (see io.outdir)."""
    with atomic_dir(target, force) as tmp:
        write_simulation_files(res, tmp, overrides)
    return Path(target)


def write_simulation_files(res: SimulationResult, folder: Path,
                           overrides: list[str] | None = None) -> None:
    """timeseries.csv, summary.json and manifest.json into an existing (temporary) folder."""
    case_json = json.loads(res.loaded.case.model_dump_json())
    (folder / "timeseries.csv").write_text(columns_to_csv(res.columns()))
    (folder / "summary.json").write_text(json.dumps(summary_document(res), indent=2) + "\n")
    doc = manifest(res.loaded.source, case_json, overrides)
    (folder / "manifest.json").write_text(json.dumps(doc, indent=2) + "\n")
