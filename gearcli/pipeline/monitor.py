"""`gearcli monitor RUN`: condition-monitoring metrics of a finished run, per shaft.

docs/theory.md, "Condition-monitoring signals" (§8 for this command). The signal is the
transmission error the two shaft encoders would measure, TE = r_b1 θ1 − r_b2 θ2 [mm] along the
line of action (docs/theory.md §1: the mesh deflection δ = s1 − s2), from the stored shaft angles
θ1, θ2 of the steady window (summary.json's ``window_s``). For each shaft it is resampled onto
that shaft's exact simulated angle, index 0 at the first θ = 2π k/z in the window (tooth k mod z
at the pitch point, docs/theory.md "Tooth faults": tooth indexing), so the TSA's sample j·n/z is
tooth k + j's pitch-point passage; it is averaged over the whole revolutions in the window (TSA)
and measured by :func:`gearcli.model.monitoring.gear_metrics`. NA4 and NB4 are normalised by
the records (single revolutions) of the baseline run's same shaft when a baseline is given, else
by the run's own revolutions (Zakrajsek et al. 1993 normalise by the run's records so far).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from gearcli.case.load import load_case_text
from gearcli.errors import GearcliError, ResultsError
from gearcli.io.results import StoredRun, read_run, window_mask
from gearcli.io.sensor_files import read_sensors
from gearcli.model.monitoring import (
    SynchronousAverage,
    gear_metrics,
    resample_to_angle,
    samples_per_revolution,
    time_synchronous_average,
)
from gearcli.model.monitoring.orders import sideband_table
from gearcli.pipeline.geometry import run_geometry
from gearcli.results import MonitorDocument, ShaftMonitor, SidebandRow

SIGNAL = "transmission error r_b1 θ1 − r_b2 θ2 from the shaft angles"
SIGNAL_UNIT = "mm"
SHAFTS = (("pinion", "theta1_rad"), ("gear", "theta2_rad"))


def steady_signal(run: StoredRun, signal: str = "te"
                  ) -> tuple[dict[str, np.ndarray], tuple[float, float]]:
    """The steady window's shaft angles and signal: {"theta1_rad", "theta2_rad" [rad], "te"
    [signal unit], "pinion", "gear" (teeth), "faulted" ({shaft: faulted teeth})}, and the
    window (T0, T1) [s]. ``signal``: "te" (the TE from the time series' angles, [mm]) or a
    column of the run's sensors table (:data:`gearcli.pipeline.sensors.CHANNELS`, on the
    sensors' own angles and times)."""
    import json

    for col in ("theta1_rad", "theta2_rad"):
        if col not in run.columns:
            raise ResultsError(f"{run.folder}: no {col} column in the time series; expected a "
                               "table written by gearcli simulate")
    loaded = load_case_text(json.dumps(run.manifest["resolved_case"]),
                            str(run.folder / "manifest.json"))
    geo = run_geometry(loaded).geometry
    t0, t1 = map(float, run.summary.scalars.window_s)
    cols = run.columns if signal == "te" else read_sensors(run.folder)
    if signal != "te" and signal not in cols:
        raise ResultsError(f"--signal {signal}: not in {run.folder}'s sensors table; expected "
                           f"te or one of {', '.join(c for c in cols if c != 't_s')}")
    sel = window_mask(cols["t_s"], t0, t1)
    th1, th2 = cols["theta1_rad"][sel], cols["theta2_rad"][sel]
    x = (geo.pinion.r_b_mm * th1 - geo.gear.r_b_mm * th2 if signal == "te"
         else cols[signal][sel])
    faulted = {shaft: tuple(sorted({f.tooth for f in loaded.case.faults if f.gear == shaft}))
               for shaft, _ in SHAFTS}
    return {"theta1_rad": th1, "theta2_rad": th2, "te": x, "t_s": cols["t_s"][sel],
            "pinion": geo.pinion.teeth, "gear": geo.gear.teeth, "faulted": faulted}, (t0, t1)


def angle_record(signal: dict, shaft: str, n: int | None = None, what: str = "the run"):
    """(TE on the ``shaft``'s angle grid, n): whole revolutions from the first tooth at the
    pitch point (:class:`gearcli.model.monitoring.AngleSignal`, start θ_s = 2π k/z: tooth k mod z
    at the pitch point) and the samples per revolution (``n``, or the rule of
    :func:`gearcli.model.monitoring.samples_per_revolution`); a window shorter than one such
    revolution is a one-line ResultsError."""
    theta = signal[dict(SHAFTS)[shaft]]
    try:
        if n is None:
            n = samples_per_revolution(theta, highest_order=int(signal[shaft]) + 2)
        pitch = 2.0 * np.pi / int(signal[shaft])
        first = math.ceil(float(theta[0]) / pitch - 1e-9)  # the first tooth at the pitch point
        return resample_to_angle(signal["te"], theta, n, first * pitch), n
    except ValueError:
        turns = abs(float(theta[-1] - theta[0])) / (2.0 * np.pi) if theta.size else 0.0
        raise ResultsError(f"{what}: the {shaft} turns {turns:.3g} revolutions in the steady "
                           "window; monitoring needs one whole revolution from the first tooth "
                           "at the pitch point; simulate longer (run.end_time)") from None


def _revolutions(angle) -> list[SynchronousAverage]:
    n = angle.samples_per_revolution
    return [SynchronousAverage(values=b, n_revolutions=1)
            for b in angle.values[: angle.n_revolutions * n].reshape(-1, n)]


#: Sidebands each side of a mesh harmonic, and mesh harmonics, in the document's table.
SIDEBANDS = 3
SIDEBAND_HARMONICS = 3
#: What each signal is, and its unit (the sensors table's columns: pipeline/sensors.CHANNELS).
SIGNALS = {"te": (SIGNAL, SIGNAL_UNIT), "te_mm": ("encoder transmission error (sensors)", "mm"),
           "alpha1_rad_s2": ("pinion torsional acceleration (sensors)", "rad/s^2"),
           "alpha2_rad_s2": ("gear torsional acceleration (sensors)", "rad/s^2"),
           "accel_m_s2": ("housing accelerometer (sensors)", "m/s^2"),
           **{f"bearing_force_{a}{k}_N": (f"{a} force on the {g} bearing (sensors)", "N")
              for a in "xy" for k, g in (("1", "pinion"), ("2", "gear"))}}


def sidebands_of(tsa, z: int) -> tuple[SidebandRow, ...]:
    """The order spectrum around the first mesh harmonics (docs/theory.md, "Condition-
    monitoring signals", §3): A_{hz+s}, s = −S … S, per harmonic h."""
    table = sideband_table(tsa, z, SIDEBANDS)[:SIDEBAND_HARMONICS]
    return tuple(SidebandRow(harmonic=h + 1, order=(h + 1) * z,
                             amplitudes=tuple(float(a) if math.isfinite(a) else None
                                              for a in row))
                 for h, row in enumerate(table))


def monitor(folder: str | Path, baseline: str | Path | None = None,
            signal: str = "te") -> MonitorDocument:
    """Monitoring metrics of a results folder (optionally against a healthy baseline run) of
    ``signal`` (:data:`SIGNALS`: "te" from the time series, or a sensors-table column)."""
    if signal not in SIGNALS:
        raise ResultsError(f"--signal {signal}: expected one of {', '.join(SIGNALS)}")
    run = read_run(folder)
    signal_data, window = steady_signal(run, signal)
    base = None
    if baseline is not None:
        base, _ = steady_signal(read_run(baseline), signal)
        for shaft, _col in SHAFTS:
            if base[shaft] != signal_data[shaft]:
                raise ResultsError(f"--baseline {baseline}: the {shaft} has {base[shaft]} "
                                   f"teeth, the run {signal_data[shaft]}; expected the same "
                                   "pair")
    shafts = []
    for shaft, _col in SHAFTS:
        angle, n = angle_record(signal_data, shaft, what=str(folder))
        if base is None:
            records, how = _revolutions(angle), "the run's own revolutions"
        else:
            records = _revolutions(angle_record(base, shaft, n, f"--baseline {baseline}")[0])
            how = f"the baseline run's revolutions ({baseline})"
        tsa = time_synchronous_average(angle)
        metrics = gear_metrics(tsa, int(signal_data[shaft]), signal_unit=SIGNALS[signal][1],
                               baseline=records)
        z = int(signal_data[shaft])
        first = round(angle.start_angle_rad * z / (2.0 * np.pi)) % z
        shafts.append(ShaftMonitor(shaft=shaft, teeth=z, first_tooth=first,
                                   n_revolutions=angle.n_revolutions, samples_per_revolution=n,
                                   normalisation=f"NA4, NB4 against {how}", metrics=metrics,
                                   faulted_teeth=signal_data["faulted"][shaft],
                                   sidebands=sidebands_of(tsa, z),
                                   tsa=tuple(float(v) for v in tsa.values)))
    return MonitorDocument(case=run.summary.case or run.folder.name, run=str(folder),
                           baseline=None if baseline is None else str(baseline),
                           signal=SIGNALS[signal][0], signal_unit=SIGNALS[signal][1],
                           window_s=window,
                           window_reason=run.summary.scalars.window_reason,
                           shafts=tuple(shafts))


def write_monitor(doc: MonitorDocument, folder: str | Path, force: bool) -> Path:
    """monitor.json and manifest.json (the run's case, io.manifest) in ``folder``, all or
    nothing (io.outdir.atomic_dir); an existing folder is replaced only with ``force``."""
    import json

    from gearcli.io.files import write_atomic
    from gearcli.io.manifest import manifest
    from gearcli.io.outdir import atomic_dir
    from gearcli.io.results import read_json

    source = Path(doc.run) / "manifest.json"
    case_json = read_json(source)["resolved_case"]
    loaded = load_case_text(json.dumps(case_json), str(source))
    with atomic_dir(folder, force) as tmp:
        write_atomic(tmp / "monitor.json", json.dumps(doc.to_dict(), indent=2) + "\n")
        provenance = manifest(loaded.source, case_json, [])
        write_atomic(tmp / "manifest.json", json.dumps(provenance, indent=2) + "\n")
    return Path(folder)


def report_signal(case: dict) -> str:
    """The signal of a run's monitoring section (its resolved case as a dict): the housing
    accelerometer ("accel_m_s2") when the case has one, else the TE from the shaft angles."""
    return "accel_m_s2" if (case.get("sensors") or {}).get("accelerometer") else "te"


def write_run_monitor(folder: str | Path) -> str:
    """monitor.json (:func:`monitor`) into a results folder whose case has ``faults:``, for the
    report's "Condition monitoring" section: of the housing accelerometer when the case has
    ``sensors.accelerometer`` (what a rig would record), else of the encoder TE; returns ""
    when written or not needed, else why it was not (a window shorter than a revolution of a
    shaft)."""
    import json

    from gearcli.io.files import write_atomic

    try:
        run = read_run(folder)
    except ResultsError:
        return ""  # not a results folder: the report says so in its own words
    case = run.manifest.get("resolved_case", {})
    if not case.get("faults"):
        return ""
    try:
        doc = monitor(folder, signal=report_signal(case))
        write_atomic(Path(folder) / "monitor.json", json.dumps(doc.to_dict(), indent=2) + "\n")
    except (GearcliError, OSError) as exc:  # a window too short; a folder we cannot write
        return str(exc).splitlines()[0]
    return ""
