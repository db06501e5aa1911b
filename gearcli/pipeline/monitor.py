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
from gearcli.errors import ResultsError
from gearcli.io.results import StoredRun, read_run, window_mask
from gearcli.model.monitoring import (
    SynchronousAverage,
    gear_metrics,
    resample_to_angle,
    samples_per_revolution,
    time_synchronous_average,
)
from gearcli.pipeline.geometry import run_geometry
from gearcli.results import MonitorDocument, ShaftMonitor

SIGNAL = "transmission error r_b1 θ1 − r_b2 θ2 from the shaft angles"
SIGNAL_UNIT = "mm"
SHAFTS = (("pinion", "theta1_rad"), ("gear", "theta2_rad"))


def steady_signal(run: StoredRun) -> tuple[dict[str, np.ndarray], tuple[float, float]]:
    """The steady window's shaft angles and TE: {"theta1_rad", "theta2_rad" [rad], "te" [mm],
    "pinion", "gear" (teeth)}, and the window (T0, T1) [s]."""
    import json

    for col in ("theta1_rad", "theta2_rad"):
        if col not in run.columns:
            raise ResultsError(f"{run.folder}: no {col} column in the time series; expected a "
                               "table written by gearcli simulate")
    loaded = load_case_text(json.dumps(run.manifest["resolved_case"]),
                            str(run.folder / "manifest.json"))
    geo = run_geometry(loaded).geometry
    t0, t1 = map(float, run.summary.scalars.window_s)
    sel = window_mask(run.column("t_s"), t0, t1)
    th1, th2 = run.column("theta1_rad")[sel], run.column("theta2_rad")[sel]
    te = geo.pinion.r_b_mm * th1 - geo.gear.r_b_mm * th2
    return {"theta1_rad": th1, "theta2_rad": th2, "te": te,
            "pinion": geo.pinion.teeth, "gear": geo.gear.teeth}, (t0, t1)


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


def monitor(folder: str | Path, baseline: str | Path | None = None) -> MonitorDocument:
    """Monitoring metrics of a results folder (optionally against a healthy baseline run)."""
    run = read_run(folder)
    signal, window = steady_signal(run)
    base = None
    if baseline is not None:
        base, _ = steady_signal(read_run(baseline))
        for shaft, _col in SHAFTS:
            if base[shaft] != signal[shaft]:
                raise ResultsError(f"--baseline {baseline}: the {shaft} has {base[shaft]} "
                                   f"teeth, the run {signal[shaft]}; expected the same pair")
    shafts = []
    for shaft, _col in SHAFTS:
        angle, n = angle_record(signal, shaft, what=str(folder))
        if base is None:
            records, how = _revolutions(angle), "the run's own revolutions"
        else:
            records = _revolutions(angle_record(base, shaft, n, f"--baseline {baseline}")[0])
            how = f"the baseline run's revolutions ({baseline})"
        metrics = gear_metrics(time_synchronous_average(angle), int(signal[shaft]),
                               signal_unit=SIGNAL_UNIT, baseline=records)
        z = int(signal[shaft])
        first = round(angle.start_angle_rad * z / (2.0 * np.pi)) % z
        shafts.append(ShaftMonitor(shaft=shaft, teeth=z, first_tooth=first,
                                   n_revolutions=angle.n_revolutions, samples_per_revolution=n,
                                   normalisation=f"NA4, NB4 against {how}", metrics=metrics))
    return MonitorDocument(case=run.summary.case or run.folder.name, run=str(folder),
                           baseline=None if baseline is None else str(baseline),
                           signal=SIGNAL, signal_unit=SIGNAL_UNIT, window_s=window,
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
