"""The document of `gearcli monitor`: condition-monitoring metrics of a run, per shaft.

docs/theory.md, "Condition-monitoring signals". The metrics of each shaft are the
:class:`gearcli.model.monitoring.GearMetrics` of its time-synchronous average (this leaf module
does not import the model: ``metrics`` is any object with ``to_dict()``, and a document read
back from JSON holds the plain mapping).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from gearcli.results.fields import Document, metric_field

#: The metrics of a shaft's TSA in table order, each with its definition's reference
#: (docs/theory.md, "Condition-monitoring signals", §5).
METRIC_DEFINITIONS = (
    ("rms", "RMS of the TSA without its mean", "theory.md monitoring §5; Lebold et al. 2000"),
    ("kurtosis", "kurtosis of the TSA", "theory.md monitoring §5; Lebold et al. 2000"),
    ("crest_factor", "peak / RMS of the TSA without its mean", "theory.md monitoring §5"),
    ("fm0", "peak-to-peak / sum of mesh-harmonic amplitudes", "Zakrajsek et al. 1993"),
    ("fm4", "kurtosis of the difference signal", "Zakrajsek et al. 1993"),
    ("m6a", "6th normalised moment of the difference signal", "Zakrajsek et al. 1993"),
    ("m8a", "8th normalised moment of the difference signal", "Zakrajsek et al. 1993"),
    ("na4", "residual kurtosis / baseline residual variance²", "Zakrajsek et al. 1993"),
    ("nb4", "envelope kurtosis / baseline envelope variance²", "Zakrajsek et al. 1993"),
    ("energy_ratio", "RMS(difference) / RMS(regular)", "Lebold et al. 2000"),
    ("sideband_level_factor", "(A_{z-1} + A_{z+1}) / σ of the TSA", "Lebold et al. 2000"),
    ("sideband_index", "(A_{z-1} + A_{z+1}) / 2", "Lebold et al. 2000"),
)


def _metric(obj: Any, name: str):
    return obj.get(name) if isinstance(obj, dict) else getattr(obj, name)


@dataclasses.dataclass(frozen=True)
class SidebandRow(Document):
    """The order spectrum of a shaft's TSA around one mesh harmonic h z: A_{hz+s} for
    s = −S … S (middle: the mesh harmonic; NaN outside the spectrum)."""

    harmonic: int = metric_field("harmonic", 0)  #: h [-]
    order: int = metric_field("order", 0)  #: h z, shaft orders [-]
    amplitudes: tuple[float, ...] = metric_field("amplitudes", ())  #: [signal unit]


@dataclasses.dataclass(frozen=True)
class ShaftMonitor(Document):
    """One shaft's time-synchronous average and its metrics."""

    shaft: str = metric_field("shaft", "")  #: "pinion" or "gear"
    teeth: int = metric_field("teeth", 0)  #: z, the shaft's mesh order [-]
    first_tooth: int = metric_field("first_tooth", 0)  #: tooth at the pitch point at TSA index 0
    n_revolutions: int = metric_field("n_revolutions", 0)  #: N, revolutions averaged [-]
    samples_per_revolution: int = metric_field("samples_per_revolution", 0)  #: n [-]
    normalisation: str = metric_field("normalisation", "")  #: NA4/NB4's records
    metrics: Any = metric_field("metrics", None)  #: GearMetrics (or its mapping)
    #: the case's faulted teeth of this shaft's gear (docs/theory.md, Tooth faults: indices)
    faulted_teeth: tuple[int, ...] = metric_field("faulted_teeth", ())
    #: the order spectrum around the first mesh harmonics, with the shaft-order sidebands
    sidebands: tuple[SidebandRow, ...] = metric_field("sidebands", (), nested=SidebandRow)
    #: the TSA itself, index 0 at ``first_tooth``'s pitch-point passage [signal unit]
    tsa: tuple[float, ...] = metric_field("tsa", ())

    def value(self, name: str) -> float | None:
        """A metric's value (None when absent or not finite)."""
        v = _metric(self.metrics, name)
        return None if v is None or (isinstance(v, float) and not math.isfinite(v)) else v

    def to_dict(self) -> dict[str, Any]:
        out = super().to_dict()
        m = self.metrics
        out["metrics"] = m if isinstance(m, dict) or m is None else m.to_dict()
        return out


@dataclasses.dataclass(frozen=True, repr=False)
class MonitorDocument(Document):
    """monitor.json: the signal, its window and each shaft's metrics."""

    case: str = metric_field("case", "")
    run: str = metric_field("run", "")  #: the results folder
    baseline: str | None = metric_field("baseline", None)  #: the baseline's folder, if any
    signal: str = metric_field("signal", "")  #: what was averaged
    signal_unit: str = metric_field("signal_unit", "")
    window_s: tuple[float, float] = metric_field("window_s", (math.nan, math.nan))
    window_reason: str = metric_field("window_reason", "")
    shafts: tuple[ShaftMonitor, ...] = metric_field("shafts", (), nested=ShaftMonitor)

    def __repr__(self) -> str:  # labelled, without the TSA's samples
        def shaft(m: ShaftMonitor) -> str:
            def v(name: str) -> str:
                x = m.value(name)
                return "–" if x is None else f"{x:.4g}"
            return (f"{m.shaft}: RMS {v('rms')} {self.signal_unit}, kurtosis "
                    f"{v('kurtosis')}, FM4 {v('fm4')}, NA4 {v('na4')} ({m.n_revolutions} "
                    "revolutions)")

        return (f"<Monitor {self.case}: {self.signal}; "
                + "; ".join(shaft(m) for m in self.shafts) + ">")

