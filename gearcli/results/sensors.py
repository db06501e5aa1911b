"""sensors.json: what the sensors table (sensors.csv / sensors.parquet) of a run holds —
channels with units, where each comes from, the noise added and the sample rate
(docs/theory.md, "What a sensor sees")."""

from __future__ import annotations

import dataclasses
import math

from gearcli.results.fields import Document, metric_field


@dataclasses.dataclass(frozen=True)
class SensorChannel(Document):
    """One column of the sensors table."""

    name: str = metric_field("name", "")  #: column name (carries its unit)
    unit: str = metric_field("unit", "")
    source: str = metric_field("source", "")  #: what it is computed from
    noise_rms: float = metric_field("noise_rms", 0.0)  #: measurement noise added [unit]


@dataclasses.dataclass(frozen=True)
class SensorsDocument(Document):
    """The sensors of a run: rate, bearing-force model, housing model, channels."""

    case: str = metric_field("case", "")
    sample_rate_Hz: float = metric_field("sample_rate_Hz", math.nan)
    anti_alias: str = metric_field("anti_alias", "")  #: the recorder's low-pass, or "none"
    bearing_forces: str = metric_field("bearing_forces", "")  #: lateral model or quasi-static
    housing: str = metric_field("housing", "")  #: the accelerometer's transfer model
    noise_seed: int = metric_field("noise_seed", 0)
    channels: tuple[SensorChannel, ...] = metric_field("channels", (), nested=SensorChannel)

    def channel(self, name: str) -> SensorChannel:
        return next(c for c in self.channels if c.name == name)
