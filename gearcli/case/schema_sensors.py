"""Case schema, sensors (docs/theory.md, "What a sensor sees"): the ``sensors:`` section, the
signals a test rig would record — shaft encoders (transmission error, torsional acceleration),
bearing forces and an accelerometer on the housing behind a transfer model of one or more
resonances — with a sample rate and seeded measurement noise. Values in internal units (see
:mod:`gearcli.case.types`); the physics is :mod:`gearcli.model.sensors`.

    sensors:
      sample_rate: 25.6 kHz
      accelerometer:
        bearing: gear
        direction: 90 deg
        housing: [{frequency: 3 kHz, damping_ratio: 0.05, modal_mass: 2 kg}]
      noise: {seed: 1, snr_db: 30, accelerometer: 0.5 m/s^2}
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, Strict

from gearcli import units
from gearcli.case.section import Coefficient, Section
from gearcli.case.types import Angle, Frequency, Length, qfield, quantity
from gearcli.units import Dim

__all__ = ["ACCELERATION", "ANGULAR_ACCELERATION", "Accelerometer", "Noise", "Resonance",
           "Sensors"]

#: Linear acceleration: bare numbers in m/s², internal mm/s² (1 m/s² = 1000 mm/s²).
ACCELERATION = Dim("acceleration", "m/s^2", "mm/s^2", "'0.5 m/s^2'", factor=1000.0)
#: Angular acceleration: bare numbers and internal in rad/s².
ANGULAR_ACCELERATION = Dim("angular acceleration", "rad/s^2", "rad/s^2", "'5 rad/s^2'", True)
Acceleration = quantity(ACCELERATION)
AngularAcceleration = quantity(ANGULAR_ACCELERATION)
Mass = quantity(units.MASS)
Force = quantity(units.FORCE)


class Resonance(Section):
    """One housing resonance: a single-degree-of-freedom oscillator driven by the bearing force
    (accelerance (−ω²/m)/(ω_r² − ω² + 2iζω_rω), docs/theory.md "What a sensor sees")."""

    frequency: Frequency = qfield(units.FREQUENCY, ..., "undamped natural frequency f_r", gt=0)
    damping_ratio: Coefficient = Field(0.05, gt=0, lt=1, description="damping ratio ζ (0.05)")
    modal_mass: Mass = qfield(units.MASS, ..., "modal mass m of the resonance at the "
                              "accelerometer (its high-frequency accelerance is 1/m)", gt=0)


class Accelerometer(Section):
    """An accelerometer on the housing near a bearing, along one direction of the pair frame."""

    bearing: Literal["pinion", "gear"] = Field(
        "gear", description="the bearing whose force drives the housing point ('gear')")
    direction: Angle = qfield(units.ANGLE, 90.0, "measuring axis in the pair frame, from x "
                              "towards y (docs/theory.md §11.1; 90 deg: along y)")
    housing: list[Resonance] = Field(
        min_length=1, description="the housing's transfer from bearing force to acceleration: "
        "a sum of single resonances (required)")


class Noise(Section):
    """Seeded measurement noise, white and Gaussian per sample at the sensor's rate: an rms per
    channel, or a signal-to-noise ratio for every channel without its own rms."""

    seed: Annotated[int, Strict()] = Field(0, ge=0, description="random seed (0)")
    snr_db: Coefficient | None = Field(
        None, description="signal-to-noise ratio 20 log10(RMS_signal/RMS_noise) [dB] of every "
        "channel without its own rms; the signal's RMS over the steady window, its mean "
        "removed (optional)")
    accelerometer: Acceleration | None = qfield(ACCELERATION, None, "noise rms of the "
                                                 "accelerometer", ge=0)
    transmission_error: Length | None = qfield(units.LENGTH, None, "noise rms of the encoder "
                                               "transmission error", ge=0)
    torsional_acceleration: AngularAcceleration | None = qfield(
        ANGULAR_ACCELERATION, None, "noise rms of each encoder's torsional acceleration", ge=0)
    bearing_force: Force | None = qfield(units.FORCE, None, "noise rms of each bearing force "
                                         "component", ge=0)


class Sensors(Section):
    """What a sensor sees (docs/theory.md, "What a sensor sees"): written as the sensors table
    (sensors.csv or sensors.parquet) beside the time series."""

    sample_rate: Frequency | None = qfield(
        units.FREQUENCY, None, "sensor sample rate (anti-alias low-pass and resampling of the "
        "simulated series); default: the run's output rate", gt=0)
    accelerometer: Accelerometer | None = Field(
        None, description="a housing accelerometer (optional)")
    noise: Noise = Field(default_factory=Noise, description="measurement noise (none)")
