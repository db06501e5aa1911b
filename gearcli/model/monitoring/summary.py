"""All the metrics of one shaft's TSA in a small typed document.

docs/theory.md, "Condition-monitoring signals", §5–§6. :func:`gear_metrics` computes the
regular, residual, difference and envelope signals of a TSA with one set of order choices and
returns :class:`GearMetrics` (frozen; ``to_dict()`` gives plain JSON types, NaN and absent
baseline metrics as ``None``) for a run's summary document.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass

from gearcli.model.monitoring import metrics as m
from gearcli.model.monitoring.angle import SynchronousAverage
from gearcli.model.monitoring.orders import (
    DEFAULT_SHAFT_ORDERS,
    DEFAULT_SIDEBANDS,
    difference_signal,
    narrowband_envelope,
    regular_signal,
    residual_signal,
)

__all__ = ["GearMetrics", "gear_metrics"]


def _json(x):
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


@dataclass(frozen=True)
class GearMetrics:
    """Condition-monitoring metrics of one shaft's TSA (docs/theory.md, §5)."""

    signal_unit: str  #: unit of the signal, e.g. "m/s^2" ([signal unit] below)
    mesh_order: int  #: z, the shaft's mesh order (its gear's teeth) [-]
    n_revolutions: int  #: N, revolutions in the TSA [-]
    samples_per_revolution: int  #: n [-]
    n_shaft_orders: int  #: K, shaft orders in the regular signal [-]
    n_mesh_harmonics: int | None  #: H (None: all below n/2) [-]
    n_sidebands: int  #: S, sidebands each side in the regular signal [-]
    envelope_half_width_orders: int  #: w, NB4's band half width [shaft orders]
    rms: float  #: RMS of the TSA without its mean [signal unit]
    kurtosis: float  #: of the TSA [-]
    crest_factor: float  #: of the TSA without its mean [-]
    fm0: float  #: PP / Σ A_hz [-]
    fm4: float  #: kurtosis of the difference signal [-]
    m6a: float  #: sixth normalised moment of the difference signal [-]
    m8a: float  #: eighth normalised moment of the difference signal [-]
    energy_ratio: float  #: RMS(difference)/RMS(regular) [-]
    sideband_level_factor: float  #: (A_{z−1} + A_{z+1})/σ [-]
    sideband_index: float  #: (A_{z−1} + A_{z+1})/2 [signal unit]
    na4: float | None  #: against the baseline records (None: no baseline) [-]
    nb4: float | None  #: against the baseline records (None: no baseline) [-]
    n_baseline_records: int  #: M, baseline records that normalise NA4/NB4 [-]

    def to_dict(self) -> dict:
        return {k: _json(v) for k, v in asdict(self).items()}


def gear_metrics(tsa: SynchronousAverage, mesh_order: int, *, signal_unit: str,
                 baseline: Sequence[SynchronousAverage] = (),
                 n_shaft_orders: int = DEFAULT_SHAFT_ORDERS,
                 n_mesh_harmonics: int | None = None, n_sidebands: int = DEFAULT_SIDEBANDS,
                 envelope_half_width_orders: int | None = None) -> GearMetrics:
    """Every metric of a TSA, with the same order choices for all its derived signals.

    RMS and crest factor are of the TSA without its mean (order 0): a static offset such as a
    mean transmission error is not vibration. NA4 and NB4 are normalised by the baseline
    TSAs' residual and envelope variances (same order choices); without a baseline they are
    None.

    Parameters
    ----------
    tsa : SynchronousAverage [signal unit]
    mesh_order : int [-]
        z, the teeth of the shaft's gear.
    signal_unit : str
        The signal's unit, recorded in the document.
    baseline : sequence of SynchronousAverage [signal unit]
        Healthy records of the same shaft, same n.
    n_shaft_orders, n_mesh_harmonics, n_sidebands : int [-]
        K, H (None: all below n/2), S (see :mod:`gearcli.model.monitoring.orders`).
    envelope_half_width_orders : int or None [shaft orders]
        w of the NB4 band; None: ⌊(z − 1)/2⌋.
    """
    x = tsa.values
    choice = {"n_mesh_harmonics": n_mesh_harmonics, "n_shaft_orders": n_shaft_orders}
    width = (mesh_order - 1) // 2 if envelope_half_width_orders is None \
        else int(envelope_half_width_orders)
    regular = regular_signal(x, [mesh_order], n_sidebands=n_sidebands, **choice)
    difference = difference_signal(x, [mesh_order], n_sidebands=n_sidebands, **choice)
    ac = x - x.mean()
    na4 = nb4 = None
    if any(b.samples_per_revolution != tsa.samples_per_revolution for b in baseline):
        raise ValueError("baseline TSAs must have the record's samples per revolution")
    if baseline:
        residuals = [residual_signal(b.values, [mesh_order], **choice) for b in baseline]
        envelopes = [narrowband_envelope(b.values, mesh_order, half_width_orders=width)
                     for b in baseline]
        na4 = m.na4(residual_signal(x, [mesh_order], **choice), residuals)
        nb4 = m.nb4(narrowband_envelope(x, mesh_order, half_width_orders=width), envelopes)
    return GearMetrics(
        signal_unit=signal_unit, mesh_order=int(mesh_order), n_revolutions=tsa.n_revolutions,
        samples_per_revolution=tsa.samples_per_revolution, n_shaft_orders=int(n_shaft_orders),
        n_mesh_harmonics=n_mesh_harmonics, n_sidebands=int(n_sidebands),
        envelope_half_width_orders=width, rms=m.rms(ac), kurtosis=m.kurtosis(x),
        crest_factor=m.crest_factor(ac), fm0=m.fm0(x, [mesh_order], n_mesh_harmonics),
        fm4=m.fm4(difference), m6a=m.m6a(difference), m8a=m.m8a(difference),
        energy_ratio=m.energy_ratio(difference, regular),
        sideband_level_factor=m.sideband_level_factor(x, mesh_order),
        sideband_index=m.sideband_index(x, mesh_order), na4=na4, nb4=nb4,
        n_baseline_records=len(baseline))
