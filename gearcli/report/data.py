"""Everything a report shows, read back from a results folder (simulate + analyze outputs)."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gearcli.case.build import gear_side_damping, pair_spec
from gearcli.case.load import load_case_text
from gearcli.case.schema import Case
from gearcli.errors import GearcliError, ResultsError
from gearcli.io.results import (
    StoredRun,
    read_analysis,
    read_columns,
    read_rating,
    read_run,
    read_stress,
)
from gearcli.model.geometry import PairGeometry, compute_pair_geometry
from gearcli.results import AnalysisDocument, AnalysisMetrics, StressDocument, Summary
from gearcli.results.rating_document import RatingDocument


@dataclass(frozen=True)
class ReportData:
    """A results folder as the report sees it (internal units: mm, N, s, rad)."""

    run: StoredRun
    analysis: AnalysisDocument
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
    #: rating.json of `gearcli run` (ISO 6336: the ISO and the simulated column), when written
    rating: RatingDocument | None = None

    @property
    def folder(self) -> Path:
        """The results folder."""
        return self.run.folder

    @property
    def metrics(self) -> AnalysisMetrics:
        """analysis.json's metrics."""
        return self.analysis.metrics

    @property
    def scalars(self) -> Summary:
        return self.run.summary.scalars

    @property
    def warnings(self) -> list[str]:
        """Warnings of simulate and analyze, each once, in order."""
        out: list[str] = []
        both = list(self.run.summary.warnings) + list(self.analysis.warnings)
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
        w = self.analysis.window_s if all(map(math.isfinite, self.analysis.window_s)) \
            else self.scalars.window_s
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
    analysis = read_analysis(path)
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
    rating = None
    if (run.folder / "rating.json").is_file():
        rating = read_rating(run.folder / "rating.json")
    return ReportData(run, analysis, spectrum, geometry, error, stress, stress_series, zoom,
                      units, gear_side_damping(loaded.case), loaded.case, rating)
