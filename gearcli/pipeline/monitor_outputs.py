"""The figures and the audio of `gearcli monitor` (docs/theory.md, "Condition-monitoring
signals" §3–§4 and "What a sensor sees"): the order spectrum with the shaft-order sidebands
around each mesh harmonic, the TSA tooth by tooth, and the signal as a WAV file."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gearcli.results import MonitorDocument


def shaft_averages(doc: MonitorDocument) -> list:
    """The document's shafts as :class:`gearcli.plotting.monitoring.ShaftAverage`."""
    from gearcli.plotting.monitoring import ShaftAverage

    return [ShaftAverage(shaft=s.shaft, teeth=s.teeth, first_tooth=s.first_tooth,
                         tsa=np.asarray(s.tsa, float), faulted_teeth=tuple(s.faulted_teeth),
                         n_revolutions=s.n_revolutions) for s in doc.shafts]


def orders_figure(doc: MonitorDocument):
    """The order spectra (plotting.monitoring.plot_order_sidebands)."""
    from gearcli.pipeline.monitor import SIDEBAND_HARMONICS, SIDEBANDS
    from gearcli.plotting.monitoring import plot_order_sidebands

    return plot_order_sidebands(shaft_averages(doc), doc.signal_unit, SIDEBAND_HARMONICS,
                                SIDEBANDS)


def teeth_figure(doc: MonitorDocument):
    """The TSA tooth by tooth (plotting.monitoring.plot_tsa_teeth)."""
    from gearcli.plotting.monitoring import plot_tsa_teeth

    return plot_tsa_teeth(shaft_averages(doc), doc.signal_unit)


def save_monitor_figure(fig, path: str | Path) -> Path:
    from gearcli.io.files import save_figure

    save_figure(fig, path, dpi=120)
    return Path(path)


def signal_record(folder: str | Path, signal: str = "te") -> tuple[np.ndarray, np.ndarray]:
    """(t [s], x) of the whole run: the TE from the time series' angles [mm], or a column of
    the sensors table (:data:`gearcli.pipeline.monitor.SIGNALS`)."""
    import json

    from gearcli.case.load import load_case_text
    from gearcli.io.results import read_run
    from gearcli.io.sensor_files import read_sensors
    from gearcli.pipeline.geometry import run_geometry

    run = read_run(folder)
    if signal != "te":
        cols = read_sensors(folder)
        return cols["t_s"], cols[signal]
    loaded = load_case_text(json.dumps(run.manifest["resolved_case"]),
                            str(run.folder / "manifest.json"))
    g = run_geometry(loaded).geometry
    c = run.columns
    return c["t_s"], g.pinion.r_b_mm * c["theta1_rad"] - g.gear.r_b_mm * c["theta2_rad"]


def write_audio(folder: str | Path, path: str | Path, signal: str = "te") -> tuple[Path, int, int]:
    """The run's ``signal`` as a mono 16-bit WAV in real time at 44.1 kHz
    (model.sensors.audio_samples); returns (path, rate [Hz], samples)."""
    from gearcli.io.sensor_files import write_wav
    from gearcli.model.sensors import AUDIO_RATE_HZ, audio_samples

    t, x = signal_record(folder, signal)
    samples = audio_samples(t, x, AUDIO_RATE_HZ)
    return write_wav(path, AUDIO_RATE_HZ, samples), AUDIO_RATE_HZ, int(samples.size)
