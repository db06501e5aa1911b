"""Write analyze's outputs into the results folder: analysis.json, spectrum.csv, harmonics.csv."""

from __future__ import annotations

import json
import math

import numpy as np

from gearcli.io.files import write_atomic_files
from gearcli.io.manifest import RESULTS_SCHEMA_VERSION
from gearcli.io.tables import columns_to_csv
from gearcli.pipeline.spectrum import SIGNALS
from gearcli.results import AnalysisDocument, SpectrumLine


def _clean(value):
    """JSON-safe: NaN/inf -> None, numpy scalars -> Python."""
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


#: The files `gearcli analyze` writes into a results folder.
ANALYSIS_FILES = ("analysis.json", "spectrum.csv", "harmonics.csv")


def analysis_document(res) -> dict:
    """analysis.json's data: the typed :class:`~gearcli.results.AnalysisDocument` of an
    :class:`~gearcli.pipeline.analyze.Analysis` as JSON (NaN and infinities as null)."""
    return _clean(AnalysisDocument(
        schema_version=RESULTS_SCHEMA_VERSION, case=res.run.summary.case, passed=res.passed,
        window_s=(res.window.t0_s, res.window.t1_s), window_reason=res.window.reason,
        metrics=res.metrics, checks=tuple(res.checks), warnings=tuple(res.warnings),
        lines={sig: {label: SpectrumLine(**ln.__dict__) for label, ln in lines}
               for sig, lines in res.lines.items()}).to_dict())


def spectrum_columns(res) -> dict[str, np.ndarray]:
    freq = res.amplitude_spectra["force"][0]
    cols = {"frequency_Hz": freq}
    for name, _, unit in SIGNALS:
        cols[f"{name}_amplitude_{unit.replace('/', '_')}"] = res.amplitude_spectra[name][1]
    return cols


def harmonics_csv(res) -> str:
    """harmonics.csv: every expected line of every signal; ``amplitude`` is in the signal's
    own unit, named in ``amplitude_unit`` (rad/s, mm or N: analyze.SIGNALS)."""
    units = {name: unit for name, _, unit in SIGNALS}
    rows = ["signal,line,expected_Hz,measured_Hz,amplitude,amplitude_unit,bin_error,resolvable"]
    for sig, lines in res.lines.items():
        for label, ln in lines:
            rows.append(f"{sig},{label},{ln.expected_Hz:.10g},{ln.measured_Hz:.10g},"
                        f"{ln.amplitude:.10g},{units.get(sig, '')},{ln.bin_error:.6g},"
                        f"{int(ln.resolvable)}")
    return "\n".join(rows) + "\n"


def write_analysis(res) -> dict:
    doc = analysis_document(res)
    folder = res.run.folder
    write_atomic_files({folder / "analysis.json": json.dumps(doc, indent=2) + "\n",
                        folder / "spectrum.csv": columns_to_csv(spectrum_columns(res)),
                        folder / "harmonics.csv": harmonics_csv(res)})  # all or none
    return doc
