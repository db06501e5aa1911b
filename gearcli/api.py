"""gearcli as a Python library: the functions the command line is made of, for notebooks and
scripts.

Every function takes a case as a path, a mapping (the YAML as Python data) or a loaded case,
raises the exceptions of :mod:`gearcli.errors` with the same one-line messages as the command
line (never ``SystemExit``), and changes no global state of the calling process (no environment
variables, warnings filters or matplotlib backend; figures are ``matplotlib.figure.Figure``
objects, shown or saved by the caller). Units: the case file's engineering units in, internal
units out (mm, N, s, t, rad; every name and column carries its unit, docs/theory.md §1).

>>> import gearcli
>>> sim = gearcli.simulate("cases/seed.yaml", set={"run.end_time": "0.5 s"})  # doctest: +SKIP
>>> sim.summary.dynamic_factor, sim.series["force_total_N"].max()              # doctest: +SKIP
"""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gearcli.case.overrides import (
    callable_argument,
    flag_argument,
    folder_argument,
    mesh_options,
    overrides_from_set,
    quantity_arguments,
    timeout_argument,
)
from gearcli.errors import CaseError

if TYPE_CHECKING:
    from gearcli.pipeline.analyze import Analysis
    from gearcli.pipeline.mesh import MeshAnalysis as Mesh
    from gearcli.pipeline.modal import ModalAnalysis as Modal
    from gearcli.pipeline.simulation import SimulationResult as Simulation
    from gearcli.pipeline.stress import StressResult as Stress
    from gearcli.results import (
        SCHEMA_VERSION,
        AnalysisMetrics,
        GearStress,
        MeshSummary,
        Mode,
        Summary,
    )

__all__ = ["load_case", "geometry", "simulate", "analyze", "spectra_frame", "modal", "mesh",
           "stress", "rate", "monitor", "sweep", "Simulation", "Analysis", "Stress", "Modal",
           "Mesh", "Summary", "AnalysisMetrics", "GearStress", "Mode", "MeshSummary",
           "SCHEMA_VERSION"]

#: The typed documents live in gearcli/results/, the result classes (one per command, with
#: the methods to_pandas, save, plot, document) in the pipeline; both imported on first use
#: (building their dataclasses costs ~15 ms that `gearcli geometry` does not need).
_RESULTS = ("SCHEMA_VERSION", "AnalysisMetrics", "GearStress", "Mode", "MeshSummary",
            "Summary")
_CLASSES = {"Simulation": ("simulation", "SimulationResult"), "Analysis": ("analyze", "Analysis"),
            "Stress": ("stress", "StressResult"), "Modal": ("modal", "ModalAnalysis"),
            "Mesh": ("mesh", "MeshAnalysis")}


def __getattr__(name: str):
    if name in _RESULTS:
        from gearcli import results

        return getattr(results, name)
    if name in _CLASSES:
        import importlib

        module, cls = _CLASSES[name]
        return getattr(importlib.import_module(f"gearcli.pipeline.{module}"), cls)
    raise AttributeError(f"module 'gearcli.api' has no attribute {name!r}")


def load_case(source, set: Mapping[str, Any] | None = None):  # noqa: A002  (the CLI's --set)
    """Read and validate a case.

    Parameters
    ----------
    source : str, Path, mapping or LoadedCase
        A case file [YAML], the case as Python data (the YAML's mapping), or an already
        loaded case (returned as is when ``set`` is empty).
    set : mapping or sequence of str, optional
        Overrides ``{"key.path": value}`` as ``--set`` gives them, e.g.
        ``{"gears.module": "8 mm", "run.end_time": 0.5}`` (numbers in the key's default unit),
        or the command line's ``["key.path=value", ...]``.

    Returns
    -------
    LoadedCase
        ``.case`` the typed, unit-converted case (internal units), ``.name``, ``.source``.

    Raises
    ------
    gearcli.errors.CaseError
        The located one-line message of the command line.

    Examples
    --------
    >>> case = gearcli.load_case("cases/seed.yaml", set={"gears.face_width": "80 mm"})
    ... # doctest: +SKIP
    """
    from gearcli.case.load import LoadedCase, validate_source
    from gearcli.case.load import load_case as load_file
    from gearcli.case.overrides import apply_overrides
    from gearcli.case.schema import Case
    from gearcli.case.yamlsrc import parse_source

    overrides = overrides_from_set(set)
    if isinstance(source, LoadedCase):
        if not overrides:
            return source
        source = json.loads(source.case.model_dump_json())
    if isinstance(source, Mapping):
        import yaml

        src = parse_source(yaml.safe_dump(dict(source), sort_keys=False), "<mapping>")
        if overrides:
            src.data = apply_overrides(src.data, overrides, Case)
        return validate_source(src, str(source.get("name") or "case"))
    if not isinstance(source, str | os.PathLike):
        raise CaseError(f"load_case({source!r:.60}): expected the path of a case file (str or "
                        "Path), the case as a mapping, or a LoadedCase")
    return load_file(source, overrides)


def geometry(case, set: Mapping[str, Any] | None = None):  # noqa: A002
    """Involute geometry and feasibility of the pair (`gearcli geometry`).

    Parameters
    ----------
    case : str, Path, mapping or LoadedCase
    set : mapping, optional
        Overrides as in :func:`load_case`.

    Returns
    -------
    gearcli.pipeline.geometry.GeometryResult
        ``.geometry`` the pair [mm, rad], ``.to_dict()`` what ``gearcli geometry --json``
        prints.
    """
    from gearcli.pipeline.geometry import run_geometry

    return run_geometry(load_case(case, set))


def simulate(case, set=None, progress=None, zoom: bool = False,  # noqa: A002
             status=None):
    """Integrate the tooth-contact model of a case (`gearcli simulate`).

    Parameters
    ----------
    case : str, Path, mapping or LoadedCase
    set : mapping or sequence of str, optional
        Overrides as in :func:`load_case`.
    progress : callable(t, t_start, t_end), optional
        Called as the integration advances [s].
    zoom : bool
        Also evaluate the dense output for the figures' zooms (one more solve).
    status : callable(str), optional
        Told the stage the call is in ("building the model", ...).

    Returns
    -------
    gearcli.pipeline.simulation.SimulationResult
        ``.series`` (a DataFrame), ``.summary`` (:class:`~gearcli.results.Summary`),
        ``.warnings``, ``.status``, ``.save(folder)``, ``.plot(what)``.

    Raises
    ------
    gearcli.errors.CaseError, gearcli.errors.GeometryError, gearcli.errors.SolverError

    Examples
    --------
    >>> sim = gearcli.simulate("cases/seed.yaml")                      # doctest: +SKIP
    >>> sim.series[["force_total_N", "delta_mm"]].describe()          # doctest: +SKIP
    """
    from gearcli.pipeline.simulate import run_simulation

    callable_argument(progress, "progress")
    flag_argument(zoom, "zoom")
    if callable_argument(status, "status"):
        status("loading the case")
    sim = run_simulation(load_case(case, set), progress=progress, zoom=zoom, status=status)
    sim.overrides = overrides_from_set(set)
    return sim


def _folder_of(run, stack) -> Path:
    """A results folder for a Simulation (written to a temporary folder) or a path."""
    from gearcli.pipeline.simulation import SimulationResult

    if isinstance(run, SimulationResult):
        tmp = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="gearcli-")))
        return run.save(tmp / "run")
    if not isinstance(run, str | os.PathLike):
        raise CaseError(f"run={run!r:.60}: expected a Simulation or the path of a results "
                        "folder of gearcli simulate")
    return Path(run)


def analyze(run, window: tuple[float, float] | None = None, strict: bool = False,
            remedies: bool = True):
    """Metrics, spectra and checks of a run (`gearcli analyze`).

    Parameters
    ----------
    run : Simulation or str or Path
        A simulation, or a results folder of `gearcli simulate`.
    window : (T0, T1), optional
        Analysis window: numbers [s] or texts with units ("250 ms"), as ``--window``; default
        the steady window.
    strict : bool
        Warnings count as failed checks.
    remedies : bool
        A failed check gets its remedy (``check.remedy``): for the dynamic factor and contact
        loss the tip relief that minimises the loaded STE at the case load and the dynamic
        factor of a short run with it; for the resonance margin the speeds to avoid. False
        skips them (the relief search and its run take a few seconds).

    Returns
    -------
    gearcli.pipeline.analyze.Analysis
        ``.metrics`` (:class:`~gearcli.results.AnalysisMetrics`), ``.checks``, ``.passed``,
        ``.spectra`` (a DataFrame indexed by frequency [Hz]), ``.warnings``, ``.document()``.
    """
    import contextlib

    from gearcli import units
    from gearcli.pipeline.analyze import analyze as run_analysis

    if window is not None:
        window = quantity_arguments(window, units.TIME, "window", 2)
    flag_argument(strict, "strict")
    with contextlib.ExitStack() as stack:
        return run_analysis(_folder_of(run, stack), window, strict, remedies)


def spectra_frame(analysis):
    """The analysis' spectra as a DataFrame indexed by frequency [Hz] (spectrum.csv)."""
    from gearcli.pipeline.analyze import Analysis

    if not isinstance(analysis, Analysis):
        raise CaseError(f"spectra_frame({analysis!r:.60}): expected the Analysis that "
                        "analyze() returns")
    return analysis.spectra


def monitor(run, baseline=None, signal: str = "te"):
    """Condition-monitoring metrics of a run per shaft (`gearcli monitor`): the transmission
    error from the shaft angles, its time-synchronous average over the steady window's whole
    revolutions and the metrics of docs/theory.md, "Condition-monitoring signals".

    Parameters
    ----------
    run : Simulation or str or Path
        A simulation, or a results folder of `gearcli simulate`.
    baseline : Simulation or str or Path, optional
        A healthy run of the same pair: NA4 and NB4 are normalised by its revolutions (default:
        the run's own).
    signal : str
        "te" (default: from the time series' shaft angles) or a column of the run's sensors
        table (a case with ``sensors:``), e.g. "accel_m_s2".

    Returns
    -------
    gearcli.results.MonitorDocument
        ``.shafts`` (pinion, gear: :class:`~gearcli.results.ShaftMonitor`, each with its
        ``.metrics``, a :class:`gearcli.model.monitoring.GearMetrics`), ``.to_dict()``.
    """
    import contextlib

    from gearcli.pipeline.monitor import monitor as run_monitor

    with contextlib.ExitStack() as stack:
        base = None if baseline is None else _folder_of(baseline, stack)
        return run_monitor(_folder_of(run, stack), base, signal)


def modal(case, set=None,  # noqa: A002
          speed_range_deg_s: tuple[float, float] | None = None):
    """Natural frequencies, damping ratios and mode shapes of the linearised model
    (`gearcli modal`).

    Parameters
    ----------
    case : str, Path, mapping or LoadedCase
    set : overrides as in :func:`load_case`
    speed_range_deg_s : (float, float), optional
        Pinion speed range of the Campbell diagram [deg/s], or texts with units ("6000 rpm");
        default 0 .. 1.5 x case speed.

    Returns
    -------
    gearcli.pipeline.modal.ModalAnalysis
        ``.modes`` (:class:`~gearcli.results.Mode`), ``.checks``, ``.passed``, ``.plot()``,
        ``.document()``.
    """
    import math

    from gearcli import units
    from gearcli.pipeline.modal import run_modal

    if speed_range_deg_s is not None:
        speed_range_deg_s = tuple(math.degrees(v) for v in quantity_arguments(
            speed_range_deg_s, units.ANGULAR_VELOCITY, "speed_range_deg_s", 2))
    return run_modal(load_case(case, set), speed_range_deg_s=speed_range_deg_s)


def mesh(case, set=None, load_N: float | None = None, harris: bool = False,  # noqa: A002
         method: str = "pe", **options):
    """Quasi-static loaded tooth contact: static transmission error, load sharing, mesh
    stiffness against ISO 6336-1 (`gearcli mesh`).

    Parameters
    ----------
    case : str, Path, mapping or LoadedCase
    set : overrides as in :func:`load_case`
    load_N : float or str, optional
        Static normal force [N], or a text with units ("2 kN"); default: the case's load
        torque / r_b2.
    harris : bool
        Also the Harris map (STE peak-to-peak against 0.1 .. 2 x the load).
    method : {"pe", "fe"}
        "fe": also the tooth law against the finite-element model (``.summary.fe_check``;
        needs the optional extra ``fe``).
    options
        ``cycles``, ``points_per_cycle`` of :func:`gearcli.pipeline.mesh.run_mesh`.

    Returns
    -------
    gearcli.pipeline.mesh.MeshAnalysis
        ``.summary`` (:class:`~gearcli.results.MeshSummary`), ``.table`` (a DataFrame),
        ``.notes``, ``.document()``.
    """
    from gearcli import units
    from gearcli.pipeline.mesh import run_mesh

    if load_N is not None:
        (load_N,) = quantity_arguments(load_N, units.FORCE, "load_N", 1)  # > 0: run_mesh checks it
    flag_argument(harris, "harris")
    if not isinstance(method, str) or method not in ("pe", "fe"):
        raise CaseError(f"method {method!r:.40}: expected 'pe' or 'fe'")
    return run_mesh(load_case(case, set), load_N=load_N, harris=harris, method=method,
                    **mesh_options(options))


def stress(run, window: tuple[float, float] | None = None, require_limits: bool = False):
    """ISO 6336 contact and root stresses along the run (`gearcli stress`).

    Parameters
    ----------
    run : Simulation or str or Path
        A simulation, or a results folder of `gearcli simulate`.
    window : (T0, T1), optional
        Window of the maxima: numbers [s] or texts with units ("250 ms"); default the steady
        window.
    require_limits : bool
        Raise CaseError when the case lacks the fatigue limits for safety factors.

    Returns
    -------
    gearcli.pipeline.stress.StressResult
        ``.pinion``, ``.gear`` (:class:`~gearcli.results.GearStress`), ``.warnings``,
        ``.document()``, the histories (``t_s``, ``sigma_H``, ...) per slot.
    """
    import contextlib

    from gearcli import units
    from gearcli.pipeline.stress import compute_stress

    if window is not None:
        window = quantity_arguments(window, units.TIME, "window", 2)
    flag_argument(require_limits, "require_limits")
    with contextlib.ExitStack() as stack:
        return compute_stress(_folder_of(run, stack), window, require_limits=require_limits)


def rate(case_or_run, set=None):  # noqa: A002
    """ISO 6336 Method B rating of the pair (`gearcli rate`), and with a run the "simulated"
    column beside it.

    Parameters
    ----------
    case_or_run : str, Path, mapping, LoadedCase, Simulation
        A case (as :func:`load_case` takes it), a simulation, or a results folder of `gearcli
        simulate` (its manifest's resolved case is rated).
    set : overrides as in :func:`load_case`, applied to the case rated.

    Returns
    -------
    gearcli.pipeline.rating.CaseRating
        ``.iso`` (the ISO column), ``.simulated`` (with a run: K_v = the run's
        F_max/F_static; its ``simulated_peaks`` the safeties of the peak contact and root
        stresses of :func:`stress` in the steady window, with K_A, K_γ, K_Hβ/K_Fβ, against
        σ_HG, σ_FG),
        ``.duty_cycle``, ``.ok``, ``.document()`` (the typed rating.json,
        :class:`gearcli.results.RatingDocument`, read back by ``gearcli report``) and
        ``.to_dict()`` (its JSON: what ``gearcli rate --json`` prints); docs/theory.md, "ISO
        6336 rating".
    """
    import contextlib

    from gearcli.pipeline.rating import rate_case, simulated_load
    from gearcli.pipeline.simulation import SimulationResult

    is_folder = isinstance(case_or_run, str | os.PathLike) and Path(case_or_run).is_dir()
    if not (is_folder or isinstance(case_or_run, SimulationResult)):
        return rate_case(load_case(case_or_run, set))
    with contextlib.ExitStack() as stack:
        simulated, loaded = simulated_load(_folder_of(case_or_run, stack))
    if isinstance(case_or_run, SimulationResult):
        loaded = case_or_run.loaded
    return rate_case(load_case(loaded, set), simulated=simulated)


def sweep(study, out: str | Path | None = None, jobs: int | None = None,
          scheduler: str | None = None, force: bool = False, keep_timeseries: bool = False,
          timeseries_format: str = "csv", progress=None, allow_large: bool = False,
          point_timeout: float | None = None, units: str = "engineering"):
    """Run a study (`gearcli sweep`) and return its summary as a DataFrame (one row per
    point; a ``design: speed_curve`` study: one row per speed and direction).

    Parameters
    ----------
    study : str, Path or gearcli.pipeline.sweep.study.Study
        Study file [YAML], or a study loaded by ``load_study``.
    out : str or Path, optional
        Output folder (summary.csv, trends, plots; resumable: points already in its
        summary.csv are not run again); default a temporary folder, removed after.
    jobs : int, optional
        Worker processes (default: all cores); ``scheduler``: Dask ("local" or an address).
    force : bool
        Start over in ``out`` (discard its summary.csv).
    keep_timeseries, timeseries_format : bool, str
        Also write each point's results folder, its time series as "csv" or "parquet".
    progress : callable(done, failed, total), optional
        Called as points finish.
    allow_large : bool
        Accept studies of more than 1000 points (the command line's ``--yes``).
    point_timeout : float, optional
        Seconds a point may run before it is recorded as failed ("timed out", retried by a
        resume); default from the solver's step limit (pipeline/sweep/workers.py).
    units : str
        Display units of the trend table and figures: "engineering" (default) or "si"
        (gearcli/display_units.py; the command line's ``--units``).

    Returns
    -------
    pandas.DataFrame
        ``attrs`` holds the outcome: ``kind`` ("sweep" or "speed_curve"), for a sweep
        ``total``, ``ran``, ``skipped``, ``failed``, ``wall_time_s`` and ``labels`` (a
        study with ``dataset:``: the labels table's rows, a list of dicts, also written to
        labels.csv/.parquet, every point's
        signals kept as Parquet — docs/theory.md "Fault datasets"; else None); for a speed
        curve ``errors`` (a direction whose solver failed).
    """
    from gearcli.display_units import SYSTEMS
    from gearcli.pipeline.sweep.frame import study_frame
    from gearcli.pipeline.sweep.run import check_timeseries_format
    from gearcli.pipeline.sweep.study import Study, load_study
    from gearcli.pipeline.sweep.workers import check_scheduler

    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise CaseError(f"jobs {jobs!r}: expected a whole number of worker processes >= 1 "
                        "(or None: one per CPU)")
    if not isinstance(study, Study | str | os.PathLike):
        raise CaseError(f"sweep({study!r:.60}): expected the path of a study file (str or "
                        "Path) or a loaded Study")
    callable_argument(progress, "progress")
    timeout_argument(point_timeout)
    for value, what in ((force, "force"), (keep_timeseries, "keep_timeseries"),
                        (allow_large, "allow_large")):
        flag_argument(value, what)
    folder_argument(out, "out")
    check_scheduler(scheduler)
    if units not in SYSTEMS:
        raise CaseError(f"units {units!r:.40}: expected one of {', '.join(SYSTEMS)}")
    spec = study if isinstance(study, Study) else load_study(study, allow_large=allow_large)
    check_timeseries_format(timeseries_format, keep_timeseries or spec.dataset is not None)
    return study_frame(spec, out, jobs, scheduler, force, keep_timeseries, timeseries_format,
                       progress, point_timeout, units)

