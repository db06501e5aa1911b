"""Typed result documents: the summary of a run, the metrics of its analysis, the
stress peaks of a gear, the modes of the linearised model and the ISO 6336 rating
(rating.json), as frozen dataclasses.

Each field's name is its key in the JSON document (summary.json ``scalars``, analysis.json
``metrics``, stress.json per gear, the modal JSON's ``modes``) and carries its unit in the name
or is dimensionless; ``metadata`` holds the label and stored unit from the one metric registry
(gearcli/results/metrics.py), the registry the command line's and the report's tables print from
(gearcli/results/metrics.rows, in the chosen display units). :func:`json_schema` derives the
documents' JSON Schemas (``gearcli schema --results``). The documents' version is
:data:`SCHEMA_VERSION` (raised when a key is renamed or removed).
"""

from gearcli.results.analysis import (
    AnalysisDocument,
    AnalysisMetrics,
    Check,
    Remedy,
    ResonanceMargin,
    SpectrumLine,
)
from gearcli.results.fields import PLACES, Document, shown, shown_values
from gearcli.results.models import Linearisation, MeshSummary, ModalDocument, Mode
from gearcli.results.monitor import MonitorDocument, ShaftMonitor, SidebandRow
from gearcli.results.rating import GearSafeties, RatingColumn, RatingSummary
from gearcli.results.rating_document import RatingDocument
from gearcli.results.run import (
    EnergyBalance,
    PointLines,
    SpeedLevel,
    StoredMode,
    Summary,
    SummaryDocument,
    sweep_metrics,
)
from gearcli.results.schema import KINDS, json_schema
from gearcli.results.sensors import SensorChannel, SensorsDocument
from gearcli.results.stress import GearStress, StressDocument
from gearcli.results.version import RESULTS_SCHEMA_VERSION as SCHEMA_VERSION

__all__ = ["SCHEMA_VERSION", "Summary", "SummaryDocument", "EnergyBalance", "StoredMode",
           "AnalysisDocument", "AnalysisMetrics", "SpectrumLine", "ResonanceMargin",
           "Remedy", "Check",
           "GearStress", "StressDocument", "Mode", "ModalDocument", "MeshSummary", "PointLines",
           "SpeedLevel", "MonitorDocument", "ShaftMonitor", "Document", "PLACES", "shown",
           "shown_values", "sweep_metrics", "json_schema", "KINDS", "GearSafeties",
           "RatingColumn", "RatingSummary", "SensorChannel", "SensorsDocument", "SidebandRow",
           "Linearisation", "RatingDocument"]
