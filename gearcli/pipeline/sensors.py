"""The sensors table of a run (case ``sensors:``): what a test rig would record, from the
simulated series (docs/theory.md, "What a sensor sees"; physics in
:mod:`gearcli.model.sensors`).

Channels, in this order (the order also numbers the noise streams):

- ``theta1_rad``, ``theta2_rad``: the shaft encoders' angles (exact, interpolated, no noise);
- ``te_mm``: the encoders' transmission error r_b1 θ1 − r_b2 θ2 along the line of action;
- ``alpha1_rad_s2``, ``alpha2_rad_s2``: each encoder's torsional acceleration dω/dt;
- ``bearing_force_x1_N`` … ``bearing_force_y2_N``: the force of each gear on its bearings, from
  the lateral-torsional model when the case uses it, else the quasi-static reaction of the mesh
  force (:func:`gearcli.model.sensors.quasi_static_bearing_forces`);
- ``accel_m_s2``: the housing accelerometer (with ``sensors.accelerometer``).
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.model import sensors as phys
from gearcli.results import SensorChannel, SensorsDocument

#: Channel name -> (unit, noise key of the case's ``sensors.noise``, stream number).
CHANNELS = {
    "theta1_rad": ("rad", None, 0), "theta2_rad": ("rad", None, 1),
    "te_mm": ("mm", "transmission_error", 2),
    "alpha1_rad_s2": ("rad/s^2", "torsional_acceleration", 3),
    "alpha2_rad_s2": ("rad/s^2", "torsional_acceleration", 4),
    "bearing_force_x1_N": ("N", "bearing_force", 5),
    "bearing_force_y1_N": ("N", "bearing_force", 6),
    "bearing_force_x2_N": ("N", "bearing_force", 7),
    "bearing_force_y2_N": ("N", "bearing_force", 8),
    "accel_m_s2": ("m/s^2", "accelerometer", 9),
}
#: The accelerometer column's unit from internal mm/s².
MM_S2_PER_M_S2 = 1000.0
BEARINGS = ("bearing_force_x1_N", "bearing_force_y1_N", "bearing_force_x2_N",
            "bearing_force_y2_N")


def output_rate_Hz(t_s) -> float:
    """The run's (uniform) output rate [Hz]."""
    return (len(t_s) - 1) / (t_s[-1] - t_s[0])


#: Fewest sensor samples over the run (as the output rate's floor, pipeline/simulate.py): a
#: lower rate has nothing to show, and its anti-alias filter (cut-off ANTI_ALIAS_CUTOFF x the
#: rate) becomes numerically singular far below the output rate.
MIN_SENSOR_SAMPLES = 10


def check_sensors(loaded, output_rate: float) -> None:
    """Refuse, before the run, a sensor rate above the run's output rate (nothing to sample) or
    giving fewer than MIN_SENSOR_SAMPLES samples over the run, and a housing resonance the
    output does not resolve (above the anti-alias band of the output, ANTI_ALIAS_CUTOFF ·
    output rate), with the key to change."""
    s = loaded.case.sensors
    if s is None:
        return
    if s.sample_rate is not None and s.sample_rate > output_rate * (1 + 1e-9):
        raise loaded.error_at(("sensors", "sample_rate"), f"{s.sample_rate:g} Hz is above the "
                              f"run's output rate {output_rate:.6g} Hz; expected at most that, "
                              "or a higher run.output_rate")
    end = loaded.case.run.end_time
    if s.sample_rate is not None and s.sample_rate * end < MIN_SENSOR_SAMPLES:
        raise loaded.error_at(("sensors", "sample_rate"), f"{s.sample_rate:g} Hz gives fewer "
                              f"than {MIN_SENSOR_SAMPLES} samples in the run of {end:g} s; "
                              f"expected at least {MIN_SENSOR_SAMPLES / end:.6g} Hz")
    if s.accelerometer is not None:
        top = phys.ANTI_ALIAS_CUTOFF * output_rate
        for i, m in enumerate(s.accelerometer.housing):
            if m.frequency >= top:
                raise loaded.error_at(
                    ("sensors", "accelerometer", "housing", str(i), "frequency"),
                    f"{m.frequency:g} Hz is not resolved by the run's output rate "
                    f"{output_rate:.6g} Hz; expected below {top:.6g} Hz, or run.output_rate "
                    f">= {m.frequency / phys.ANTI_ALIAS_CUTOFF:.6g} Hz")


def _bearing_forces(res, cols: dict) -> tuple[dict[str, np.ndarray], str]:
    if "bearing_force_x1_N" in cols:
        return ({n: cols[n] for n in BEARINGS},
                "lateral-torsional model: k u + c u̇ of each bearing (docs/theory.md §11.1)")
    g = res.geometry.geometry
    forces = phys.quasi_static_bearing_forces(cols["force_total_N"], cols["force_coast_N"],
                                              g.alpha_w_rad)
    return (dict(zip(BEARINGS, forces, strict=True)),
            "quasi-static reaction of the mesh normal force on fixed centres (torsional model; "
            "friction left out; docs/theory.md, What a sensor sees)")


def _raw_channels(res, cols: dict) -> tuple[dict[str, np.ndarray], str, str]:
    """The channels at the run's output times (before sampling and noise), the bearing-force
    and housing descriptions."""
    s, g = res.loaded.case.sensors, res.geometry.geometry
    t = cols["t_s"]
    raw = {"theta1_rad": cols["theta1_rad"], "theta2_rad": cols["theta2_rad"],
           "te_mm": g.pinion.r_b_mm * cols["theta1_rad"] - g.gear.r_b_mm * cols["theta2_rad"],
           "alpha1_rad_s2": phys.torsional_acceleration(t, cols["omega1_rad_s"]),
           "alpha2_rad_s2": phys.torsional_acceleration(t, cols["omega2_rad_s"])}
    forces, how = _bearing_forces(res, cols)
    raw.update(forces)
    housing = "none"
    acc = s.accelerometer
    if acc is not None:
        k = "1" if acc.bearing == "pinion" else "2"
        f = (forces[f"bearing_force_x{k}_N"] * math.cos(acc.direction)
             + forces[f"bearing_force_y{k}_N"] * math.sin(acc.direction))
        modes = [phys.HousingMode(m.frequency, m.damping_ratio, m.modal_mass)
                 for m in acc.housing]
        raw["accel_m_s2"] = phys.housing_acceleration(t, f, modes)  # mm/s² until the end
        housing = (f"{acc.bearing} bearing force along {math.degrees(acc.direction):g} deg "
                   "through " + " + ".join(f"SDOF({m.frequency_Hz:g} Hz, ζ {m.damping_ratio:g}, "
                                           f"{m.modal_mass_t * 1e3:g} kg)" for m in modes))
    return raw, how, housing


def sensor_table(res) -> tuple[dict[str, np.ndarray], SensorsDocument]:
    """The sensors table of a finished run (``t_s`` and the channels of :data:`CHANNELS`) and
    its sensors.json; the case must have ``sensors:``."""
    s = res.loaded.case.sensors
    cols = res.columns()
    t = cols["t_s"]
    raw, how, housing = _raw_channels(res, cols)
    rate_in = output_rate_Hz(t)
    rate = s.sample_rate or rate_in
    resampled = rate < rate_in * (1 - 1e-9)
    t_new = None
    out: dict[str, np.ndarray] = {}
    for name, x in raw.items():
        t_new, out[name] = phys.resample(t, x, rate, t_new, anti_alias=not name.startswith(
            "theta")) if resampled else (t, x.copy())
    steady = (t_new >= res.window.t0_s) & (t_new <= res.window.t1_s)
    channels = []
    for name, x in out.items():
        unit, key, stream = CHANNELS[name]
        rms = 0.0
        if key is not None:
            given = getattr(s.noise, key)
            rms = given if given is not None else (
                phys.noise_rms_for_snr(x[steady], s.noise.snr_db)
                if s.noise.snr_db is not None and steady.any() else 0.0)
            out[name] = phys.add_noise(x, rms, s.noise.seed, stream)
        scale = MM_S2_PER_M_S2 if name == "accel_m_s2" else 1.0
        out[name] = out[name] / scale
        source = how if name in BEARINGS else housing if name == "accel_m_s2" else "encoders"
        channels.append(SensorChannel(name=name, unit=unit, source=source,
                                      noise_rms=rms / scale))
    doc = SensorsDocument(
        case=res.name, sample_rate_Hz=rate,
        anti_alias=(f"Butterworth order {phys.ANTI_ALIAS_ORDER} at "
                    f"{phys.ANTI_ALIAS_CUTOFF * rate:g} Hz, zero phase" if resampled else "none"),
        bearing_forces=how, housing=housing, noise_seed=s.noise.seed, channels=tuple(channels))
    return {"t_s": t_new, **out}, doc
