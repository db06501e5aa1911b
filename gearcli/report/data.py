"""Everything a report shows, read back from a results folder (simulate + analyze outputs)."""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from gearcli.case.build import gear_side_damping, pair_spec
from gearcli.case.load import load_case_text
from gearcli.case.schema import Case
from gearcli.errors import GearcliError, ResultsError
from gearcli.io.results import StoredRun, read_columns, read_json, read_run, read_stress
from gearcli.model.geometry import PairGeometry, compute_pair_geometry
from gearcli.results import AnalysisMetrics, StressDocument, Summary


@dataclass(frozen=True)
class ReportData:
    """A results folder as the report sees it (internal units: mm, N, s, rad)."""

    run: StoredRun
    analysis: dict
    spectrum: dict[str, np.ndarray]
    geometry: PairGeometry | None  #: None when the stored case's geometry cannot be rebuilt
    geometry_error: str = ""
    stress: StressDocument | None = None  #: stress.json of gearcli stress, when it was run
    stress_series: dict | None = None  #: stress.csv's columns, with stress.json
    #: zoom.csv: the solver's dense output around the force maximum and at the end of the run
    #: (pipeline/simulate.dense_zoom); empty for folders written without it
    zoom: dict = None  # type: ignore[assignment]
    #: display units of the tables and figures (gearcli/display_units.py)
    units: str = "engineering"
    #: the gear side's speed-dependent resisting torque coefficients (c_v + c_2, c_q) of the
    #: stored case (case/build.gear_side_damping), for the static force line
    gear_side_damping: tuple[float, float] = (0.0, 0.0)
    #: the stored case, typed and in internal units (gearcli.case.schema.Case)
    case: Case | None = None

    @property
    def folder(self) -> Path:
        return self.run.folder

    @property
    def case_data(self) -> dict:
        """The stored case as written (values as "number unit" texts): for the tables that
        print its settings as given."""
        return self.run.manifest["resolved_case"]

    @cached_property
    def metrics(self) -> AnalysisMetrics:
        """analysis.json's metrics (checked by :func:`check_analysis`), typed."""
        return AnalysisMetrics.from_document(self.analysis["metrics"])

    @property
    def scalars(self) -> Summary:
        return self.run.summary.scalars

    @property
    def warnings(self) -> list[str]:
        """Warnings of simulate and analyze, each once, in order."""
        out: list[str] = []
        both = list(self.run.summary.warnings) + list(self.analysis.get("warnings", []))
        for w in both:
            if w not in out:
                out.append(str(w))
        return out

    @property
    def f_z_Hz(self) -> float:
        return float(self.metrics.gear_mesh_frequency_Hz
                     or self.scalars.gear_mesh_frequency_Hz)

    @property
    def window_s(self) -> tuple[float, float]:
        w = self.analysis.get("window_s") or self.scalars.window_s
        return float(w[0]), float(w[1])

    def has_errors_or_relief(self) -> bool:
        m, e = self.case.modifications, self.case.errors
        return any(x is not None for x in (m.tip_relief.pinion, m.tip_relief.gear,
                                           m.root_relief.pinion, m.root_relief.gear,
                                           e.runout.pinion, e.runout.gear,
                                           e.pitch_deviation.pinion, e.pitch_deviation.gear))


def load_report_data(folder: str | Path, units: str = "engineering") -> ReportData:
    """Read manifest, summary, time series (validated by read_run), analysis.json, spectrum.csv.

    Raises
    ------
    ResultsError
        The folder is not a finished run, or ``gearcli analyze`` has not been run on it.
    """
    run = read_run(folder)
    path = run.folder / "analysis.json"
    if not path.is_file():
        raise ResultsError(f"{run.folder}: no analysis.json; run gearcli analyze {run.folder} "
                           "first")
    analysis = read_json(path, "run gearcli analyze again")
    if not isinstance(analysis, dict) or "checks" not in analysis or "metrics" not in analysis:
        raise ResultsError(f"{path}: not an analysis of gearcli analyze; run it again")
    check_analysis(path, analysis)
    if not (run.folder / "spectrum.csv").is_file():
        raise ResultsError(f"{run.folder}: no spectrum.csv; run gearcli analyze first")
    spectrum = read_columns(run.folder / "spectrum.csv", "frequency_Hz")
    try:
        loaded = load_case_text(json.dumps(run.manifest["resolved_case"]),
                                str(run.folder / "manifest.json"))
    except GearcliError as exc:  # the tables read the stored case: it must be one
        raise ResultsError(f"{run.folder / 'manifest.json'}: resolved_case is not a valid "
                           f"case ({str(exc).splitlines()[0]})") from None
    try:
        geometry, error = compute_pair_geometry(pair_spec(loaded.case)), ""
    except (GearcliError, KeyError, TypeError, ValueError) as exc:
        geometry, error = None, f"{type(exc).__name__}: {exc}"
    stress = stress_series = None
    if (run.folder / "stress.json").is_file():
        stress = read_stress(run.folder / "stress.json")
        if (run.folder / "stress.csv").is_file():
            stress_series = read_columns(run.folder / "stress.csv", "t_s")
    zoom = {}
    if (run.folder / "zoom.csv").is_file():
        zoom = read_columns(run.folder / "zoom.csv", "t_s")
    return ReportData(run, analysis, spectrum, geometry, error, stress, stress_series, zoom,
                      units, gear_side_damping(loaded.case), loaded.case)


#: Non-numeric entries of analysis.json's metrics, by kind (the annotations of
#: gearcli.results.AnalysisMetrics); every other entry is a number or null.
_TEXT_METRICS = tuple(f.name for f in dataclasses.fields(AnalysisMetrics) if f.type == "str")
_LIST_METRICS = tuple(f.name for f in dataclasses.fields(AnalysisMetrics)
                      if str(f.type).startswith("tuple"))


def check_analysis(path: Path, doc: dict) -> None:
    """Refuse an analysis.json whose entries the report cannot read (hand-edited, foreign):
    the first wrong entry, and the remedy (run gearcli analyze again)."""
    def bad(key: str, kind: str) -> ResultsError:
        return ResultsError(f"{path}: {key} is not {kind}; run gearcli analyze again (was the "
                            "file edited?)")

    def number(v) -> bool:
        return v is None or (isinstance(v, int | float) and not isinstance(v, bool))

    window = doc.get("window_s")
    if window is not None and not (isinstance(window, list) and len(window) == 2
                                   and all(number(v) and v is not None for v in window)):
        raise bad("window_s", "two numbers")
    metrics = doc["metrics"]
    if not isinstance(metrics, dict):
        raise bad("metrics", "a mapping")
    for key, value in metrics.items():
        if key in _TEXT_METRICS:
            ok = value is None or isinstance(value, str)
        elif key in _LIST_METRICS:
            ok = value is None or isinstance(value, list)
        else:
            ok = number(value)
        if not ok:
            raise bad(f"metrics.{key}", "text" if key in _TEXT_METRICS else
                      "a list" if key in _LIST_METRICS else "a number or null")
    if not isinstance(doc["checks"], list):
        raise bad("checks", "a list")
    for i, check in enumerate(doc["checks"]):
        if not (isinstance(check, dict) and isinstance(check.get("name"), str)
                and isinstance(check.get("passed"), bool)):
            raise bad(f"checks.{i}", "a check (name, value, limit, passed, note)")
    lines = doc.get("lines", {})
    if not isinstance(lines, dict) or not all(
            isinstance(v, dict) and all(isinstance(ln, dict) for ln in v.values())
            for v in lines.values()):
        raise bad("lines", "a mapping of signals to lines")
    if not isinstance(doc.get("warnings", []), list):
        raise bad("warnings", "a list")


# --- the stored case for display: values are "number unit" strings in internal units -------
def number(value) -> float:
    """The number of a stored value: 10.0, "10.0 mm" -> 10.0; None -> nan."""
    if value is None:
        return math.nan
    if isinstance(value, int | float):
        return float(value)
    return float(str(value).split()[0])


def unit_of(value) -> str:
    """The unit of a stored value: "10.0 mm" -> "mm", 10.0 -> ""."""
    parts = str(value).split(maxsplit=1)
    return parts[1] if isinstance(value, str) and len(parts) == 2 else ""
