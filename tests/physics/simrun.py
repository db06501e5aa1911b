"""Helpers for simulation tests: run the seed case with overrides, spectra, slot positions."""

import math

import numpy as np

from gearcli.pipeline.simulate import run_simulation
from tests.conftest import SEED

# Shorter ramps than the article's 1 s keep the physics tests fast; the steady state is the
# same (speed and load reach the seed's values).
FAST = ["drive.speed=STEP(time, 0, 0, 0.2, 3000)", "load.torque=STEP(time, 0, 0, 0.2, 4.5e5)",
        "run.end_time=0.6"]


def run(*overrides):
    return run_simulation(SEED, [*FAST, *overrides])


def window(res):
    t = res.kernel.column("t_s")
    return t >= res.window.t0_s


def amplitude_spectrum(signal, rate):
    """Hann-windowed, amplitude-correct one-sided spectrum of a zero-mean signal."""
    x = np.asarray(signal, float) - np.mean(signal)
    w = np.hanning(x.size)
    spec = np.abs(np.fft.rfft(x * w)) * 2.0 / w.sum()
    return np.fft.rfftfreq(x.size, 1.0 / rate), spec


def slot_positions(res):
    """Pinion roll position x (from A) of every drive slot at every sample [mm]."""
    return res.slot_positions()[1]


def deg(x):
    return math.degrees(x)


def write_run(folder, overrides, analysed=False):
    """A results folder of the seed case with ``overrides`` (and analysis files if asked)."""
    from gearcli.pipeline.analysis_io import write_analysis
    from gearcli.pipeline.analyze import analyze
    from gearcli.pipeline.outputs import write_simulation

    write_simulation(run_simulation(SEED, overrides), folder, force=False, overrides=overrides)
    if analysed:
        write_analysis(analyze(folder))
    return folder
