"""Condition-monitoring signals and metrics of a gear pair (docs/theory.md,
"Condition-monitoring signals").

Pure functions and frozen dataclasses of numpy arrays (numpy and scipy only, no I/O), one
function per quantity:

===========  ==================================================================================
``angle``    samples per revolution, resampling onto the shaft angle, time-synchronous average
``orders``   order spectrum, sideband table, regular / residual / difference signals,
             narrow-band envelope around a mesh harmonic
``metrics``  RMS, kurtosis, crest factor, FM0, FM4, M6A, M8A, NA4, NB4, energy ratio,
             sideband level factor, sideband index
``summary``  :class:`GearMetrics`, every metric of one shaft's TSA, for a run's summary
===========  ==================================================================================

Units: angles in rad, orders in cycles per shaft revolution; signals keep the unit they come in
(written "[signal unit]").
"""

from gearcli.model.monitoring.angle import (
    AngleSignal,
    SynchronousAverage,
    resample_to_angle,
    samples_per_revolution,
    time_synchronous_average,
)
from gearcli.model.monitoring.summary import GearMetrics, gear_metrics

__all__ = ["AngleSignal", "SynchronousAverage", "resample_to_angle", "samples_per_revolution",
           "time_synchronous_average", "GearMetrics", "gear_metrics"]
