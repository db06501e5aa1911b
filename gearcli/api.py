"""gearcli as a Python library: the functions the command line is made of, for notebooks and
scripts (issue 17).

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

from gearcli.errors import CaseError

if TYPE_CHECKING:
    from gearcli.results import (
        SCHEMA_VERSION,
        AnalysisMetrics,
        GearStress,
        MeshSummary,
        Mode,
        Summary,
    )

__all__ = ["load_case", "geometry", "simulate", "analyze", "spectra_frame", "modal", "mesh",
           "stress", "sweep", "Simulation", "Analysis", "Stress", "Modal", "Mesh", "Summary",
           "AnalysisMetrics", "GearStress", "Mode", "MeshSummary", "SCHEMA_VERSION"]

#: The typed documents live in gearcli/results.py, imported on first use (building their
#: dataclasses costs ~15 ms that `gearcli geometry` does not need).
_RESULTS = ("SCHEMA_VERSION", "AnalysisMetrics", "GearStress", "Mode", "MeshSummary",
            "Summary")


def __getattr__(name: str):
    if name in _RESULTS:
        from gearcli import results

        return getattr(results, name)
    raise AttributeError(f"module 'gearcli.api' has no attribute {name!r}")


def _overrides(set_) -> list[str]:
    """``{"key.path": value}`` as the command line's ``--set key.path=value`` texts (values
    as JSON, which the override parser reads as YAML: numbers, strings with units, lists);
    a sequence of such texts (the command line's) as it is."""
    if isinstance(set_, str):  # one "key.path=value" text, not a sequence of characters
        return [set_]
    if set_ is not None and not isinstance(set_, Mapping):
        if isinstance(set_, bytes) or not hasattr(set_, "__iter__"):
            raise CaseError(f"set={set_!r:.60}: expected a mapping {{'key.path': value}}, a "
                            "'key.path=value' text or a sequence of such texts")
        return [str(item) for item in set_]
    out = []
    for key, value in (set_ or {}).items():
        try:
            text = value if isinstance(value, str) else json.dumps(
                value, allow_nan=False, default=_plain)
        except (TypeError, ValueError):
            raise CaseError(f"set[{key!r}]: got {value!r:.60}; expected a number, a text "
                            "(with units) or a list of them") from None
        out.append(f"{key}={text}")
    return out


def _plain(value):
    """numpy scalars (np.int64(18), np.float32(2.0)) as the Python numbers they hold."""
    if hasattr(value, "item") and getattr(value, "shape", None) == ():
        return value.item()
    raise TypeError(type(value).__name__)


def _quantities(values, dim, what: str, count: int) -> tuple[float, ...]:
    """``count`` values given as numbers (in ``dim``'s case-file unit) or texts with units, in
    internal units, as the command line's options take them; anything else a CaseError."""
    from gearcli import units

    items = (values,) if count == 1 else values
    if count > 1 and (isinstance(values, str | bytes) or not hasattr(values, "__len__")):
        items = None
    if items is None or len(items) != count or any(isinstance(v, bool) for v in items):
        shape = "a value" if count == 1 else f"{count} values"
        raise CaseError(f"{what}={values!r:.60}: expected {shape}, each a number in "
                        f"{dim.default} or a text with units")
    try:
        return units.parse_quantities(items, dim)
    except (units.UnitError, TypeError, ValueError) as exc:
        raise CaseError(f"{what} {exc}") from None


def _callable_or_none(value, what: str):
    if value is not None and not callable(value):
        raise TypeError(f"{what}={value!r:.60}: expected a callable or None")
    return value


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

    overrides = _overrides(set)
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


class Simulation:
    """A finished run (`gearcli simulate`): the time series, the typed summary, the modes.

    Attributes
    ----------
    series : pandas.DataFrame
        timeseries.csv's columns (names carry units) indexed by time ``t_s`` [s].
    summary : Summary
    modes : list of dict
        The linearised model's modes (``gearcli modal``), as in summary.json.
    warnings : list of str
    status, invalid_reason : str
        ``"ok"``, or ``"invalid"`` with the reason when the run left the model's range
        (docs/theory.md §10.2): its numbers are then not results.
    result : gearcli.pipeline.simulate.SimulationResult
        Everything else (kernel arrays, counters, geometry, the resolved case).
    """

    def __init__(self, result) -> None:
        self.result = result
        from gearcli.results import Summary

        self.summary = Summary.from_scalars(result.summary, result.status, result.invalid_reason)
        self.modes = list(result.summary.get("modes", []))
        self.warnings = list(result.warnings)
        self.status = result.status
        self.invalid_reason = result.invalid_reason
        self.overrides: list[str] = []  #: the ``--set`` texts it was run with (manifest)
        self._series = None

    @property
    def name(self) -> str:
        return self.result.name

    @property
    def series(self):
        if self._series is None:
            import pandas as pd

            columns = self.result.columns()
            t = columns.pop("t_s")
            self._series = pd.DataFrame(columns, index=pd.Index(t, name="t_s"))
        return self._series

    def to_pandas(self):
        """The time series as a DataFrame (same as :attr:`series`)."""
        return self.series

    def save(self, folder: str | Path, force: bool = False, format: str = "csv") -> Path:  # noqa: A002
        """Write the results folder `gearcli simulate -o` writes (atomically; an existing
        folder only with ``force``). ``format``: "csv" or "parquet" for the time series. The
        dense zoom table (zoom.csv, the report's zooms) only when the simulation was made with
        ``zoom=True``."""
        from gearcli.pipeline.outputs import write_simulation

        return write_simulation(self.result, folder, force, self.overrides, format)

    def plot(self, what: str = "force", units: str = "engineering"):
        """A figure of the run: ``"force"`` (mesh force with the static force and the true
        maximum), ``"dte"`` (dynamic transmission error) or ``"speeds"`` (in the display
        ``units``: "engineering" rpm or "si" rad/s); returns a ``matplotlib.figure.Figure``."""
        from gearcli.plotting import results as plots

        c = self.result.columns()
        t, window = c["t_s"], tuple(self.summary.window_s)
        f_z = self.summary.gear_mesh_frequency_Hz
        if what == "force":
            return plots.plot_force(t, c["force_total_N"], self.summary.force_static_N,
                                    self.summary.force_max_N, self.summary.force_max_t_s, window,
                                    None, f_z)
        if what == "dte":
            return plots.plot_dte(t, c["delta_mm"], window, None, f_z, units=units)
        if what == "speeds":
            g = self.result.geometry.geometry
            return plots.plot_speeds(t, c["omega1_rad_s"], c["omega2_rad_s"],
                                     (g.pinion.teeth, g.gear.teeth), window, None, f_z,
                                     units)
        raise ValueError(f"plot {what!r}: expected 'force', 'dte' or 'speeds'")

    def __repr__(self) -> str:
        df = self.summary.dynamic_factor
        return (f"<Simulation {self.name}: {self.status}, {len(self.result.kernel.series)} rows, "
                f"dynamic factor {df if df is None else round(df, 4)}>")


def simulate(case, set=None, progress=None, zoom: bool = False,  # noqa: A002
             status=None) -> Simulation:
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
    Simulation

    Raises
    ------
    gearcli.errors.CaseError, gearcli.errors.GeometryError, gearcli.errors.SolverError

    Examples
    --------
    >>> sim = gearcli.simulate("cases/seed.yaml")                      # doctest: +SKIP
    >>> sim.series[["force_total_N", "delta_mm"]].describe()          # doctest: +SKIP
    """
    from gearcli.pipeline.simulate import run_simulation

    _callable_or_none(progress, "progress")
    if _callable_or_none(status, "status"):
        status("loading the case")
    sim = Simulation(run_simulation(load_case(case, set), progress=progress, zoom=zoom,
                                    status=status))
    sim.overrides = _overrides(set)
    return sim


def _folder_of(run, stack) -> Path:
    """A results folder for a Simulation (written to a temporary folder) or a path."""
    if isinstance(run, Simulation):
        tmp = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="gearcli-")))
        return run.save(tmp / "run")
    if not isinstance(run, str | os.PathLike):
        raise CaseError(f"run={run!r:.60}: expected a Simulation or the path of a results "
                        "folder of gearcli simulate")
    return Path(run)


class Analysis:
    """Metrics, spectra and checks of a run's window (`gearcli analyze`).

    Attributes
    ----------
    metrics : AnalysisMetrics
        Typed metrics (internal units, the unit in each name).
    checks : list of gearcli.pipeline.analyze.Check
        ``name``, ``value``, ``limit``, ``passed``, ``checked`` (False: not checked, with the
        reason in ``note``).
    passed : bool
    spectra : pandas.DataFrame
        One-sided amplitude spectra indexed by frequency [Hz] (spectrum.csv's columns).
    warnings : list of str
    result : gearcli.pipeline.analyze.Analysis
        The untyped analysis (dict metrics, spectra arrays, mesh lines).
    """

    def __init__(self, result) -> None:
        self.result = result
        from gearcli.results import AnalysisMetrics

        self.metrics = AnalysisMetrics.from_metrics(result.metrics)
        self.checks = list(result.checks)
        self.passed = result.passed
        self.warnings = list(result.warnings)
        self._spectra = None

    @property
    def spectra(self):
        if self._spectra is None:
            self._spectra = spectra_frame(self.result)
        return self._spectra

    def document(self) -> dict:
        """analysis.json as a dict (what `gearcli analyze` writes)."""
        from gearcli.pipeline.analysis_io import analysis_document

        return analysis_document(self.result)

    def __repr__(self) -> str:
        failed = [c.name for c in self.checks if not c.passed]
        return (f"<Analysis {self.result.run.summary.get('case', self.result.run.folder.name)}: "
                f"{'passed' if self.passed else 'failed: ' + ', '.join(failed)}>")


def analyze(run, window: tuple[float, float] | None = None, strict: bool = False) -> Analysis:
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

    Returns
    -------
    Analysis
    """
    import contextlib

    from gearcli import units
    from gearcli.pipeline.analyze import analyze as run_analysis

    if window is not None:
        window = _quantities(window, units.TIME, "window", 2)
    with contextlib.ExitStack() as stack:
        return Analysis(run_analysis(_folder_of(run, stack), window, strict))


def spectra_frame(analysis):
    """The analysis' spectra as a DataFrame indexed by frequency [Hz] (spectrum.csv)."""
    import pandas as pd

    from gearcli.pipeline.analysis_io import spectrum_columns

    columns = spectrum_columns(getattr(analysis, "result", analysis))
    f = columns.pop("frequency_Hz")
    return pd.DataFrame(columns, index=pd.Index(f, name="frequency_Hz"))


class Modal:
    """Modes of the linearised model, crossings and the resonance-margin check (`gearcli
    modal`).

    Attributes
    ----------
    modes : list of Mode
    checks : list, passed : bool
    result : gearcli.pipeline.modal.ModalAnalysis
    """

    def __init__(self, result) -> None:
        from gearcli.pipeline.modal import modal_document

        self.result = result
        self._doc = modal_document(result)
        from gearcli.results import Mode

        self.modes = [Mode.from_document(m) for m in self._doc["modes"]]
        self.checks = list(result.checks)
        self.passed = result.passed

    def document(self) -> dict:
        """What `gearcli modal --json` prints."""
        return self._doc

    def plot(self, units: str = "engineering"):
        """The Campbell diagram and mode shapes (a ``matplotlib.figure.Figure``); the speed
        axis in the display ``units`` ("engineering": rpm, "si": rad/s)."""
        from gearcli.pipeline.modal import campbell_figure

        return campbell_figure(self.result, units)

    def __repr__(self) -> str:
        f = [round(m.natural_frequency_Hz, 1) for m in self.modes if not m.rigid_body
             and m.natural_frequency_Hz]
        return f"<Modal {self.result.name}: modes at {f} Hz>"


def modal(case, set=None,  # noqa: A002
          speed_range_deg_s: tuple[float, float] | None = None) -> Modal:
    """Natural frequencies, damping ratios and mode shapes of the linearised model
    (`gearcli modal`).

    Parameters
    ----------
    case : str, Path, mapping or LoadedCase
    set : overrides as in :func:`load_case`
    speed_range_deg_s : (float, float), optional
        Pinion speed range of the Campbell diagram [deg/s], or texts with units ("6000 rpm");
        default 0 .. 1.5 x case speed.
    """
    import math

    from gearcli import units
    from gearcli.pipeline.modal import run_modal

    if speed_range_deg_s is not None:
        speed_range_deg_s = tuple(math.degrees(v) for v in _quantities(
            speed_range_deg_s, units.ANGULAR_VELOCITY, "speed_range_deg_s", 2))
    return Modal(run_modal(load_case(case, set), speed_range_deg_s=speed_range_deg_s))


class Mesh:
    """Quasi-static loaded tooth contact of a pair (`gearcli mesh`).

    Attributes
    ----------
    summary : MeshSummary
        STE [µm], mesh stiffness [N/mm] against ISO 6336-1 c′b and c_γα b, n_E1 and K_v.
    table : pandas.DataFrame
        Per pinion roll position ``roll_mm``: STE, unloaded TE [µm], mesh stiffness [N/mm],
        pairs in contact, each pair's position [mm] and force [N] (mesh.csv).
    notes : list of str
        What the analysis leaves out.
    result : gearcli.pipeline.mesh.MeshAnalysis
    """

    def __init__(self, result) -> None:
        from gearcli.pipeline.mesh import mesh_document
        from gearcli.results import MeshSummary

        self.result = result
        self._doc = mesh_document(result)
        self.summary = MeshSummary.from_document(self._doc)
        self.notes = list(self._doc["notes"])

    @property
    def table(self):
        import pandas as pd

        from gearcli.pipeline.mesh import mesh_table

        columns = mesh_table(self.result)
        x = columns.pop("roll_mm")
        return pd.DataFrame(columns, index=pd.Index(x, name="roll_mm"))

    def document(self) -> dict:
        """What `gearcli mesh --json` prints."""
        return self._doc

    def save_plot(self, path: str | Path, units: str = "engineering") -> None:
        """The figure of `gearcli mesh --plot` [.png, .svg, .pdf], in the display ``units``."""
        from gearcli.pipeline.mesh import save_mesh_plot

        save_mesh_plot(self.result, path, units)

    def __repr__(self) -> str:
        return (f"<Mesh {self.result.name}: STE {self.summary.ste_peak_to_peak_um:.3g} µm peak "
                f"to peak, mean stiffness {self.summary.mesh_mean_N_mm:.4g} N/mm>")


def mesh(case, set=None, load_N: float | None = None, harris: bool = False,  # noqa: A002
         **options) -> Mesh:
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
    options
        ``cycles``, ``points_per_cycle`` of :func:`gearcli.pipeline.mesh.run_mesh`.

    Returns
    -------
    Mesh
    """
    from gearcli import units
    from gearcli.pipeline.mesh import run_mesh

    if load_N is not None:
        (load_N,) = _quantities(load_N, units.FORCE, "load_N", 1)  # > 0: run_mesh checks it
    if not isinstance(harris, bool):
        raise CaseError(f"harris={harris!r:.60}: expected True or False")
    return Mesh(run_mesh(load_case(case, set), load_N=load_N, harris=harris, **options))


class Stress:
    """Contact and root stresses along a run (`gearcli stress`).

    Attributes
    ----------
    pinion, gear : GearStress
        Peak dynamic stresses against the ISO 6336 static values [MPa], safety factors.
    result : gearcli.pipeline.stress.StressResult
        The histories (``t_s``, ``sigma_H``, ...) per slot.
    """

    def __init__(self, result) -> None:
        from gearcli.pipeline.stress import stress_document

        self.result = result
        self._doc = stress_document(result)
        from gearcli.results import GearStress

        self.pinion = GearStress.from_document(self._doc, "pinion")
        self.gear = GearStress.from_document(self._doc, "gear")
        self.warnings = list(result.warnings)

    def document(self) -> dict:
        """stress.json as a dict."""
        return self._doc

    def __repr__(self) -> str:
        def mpa(value):
            return "–" if value is None else f"{value:.4g} MPa"

        return (f"<Stress {self.result.name}: σ_H peak {mpa(self.pinion.sigma_H_peak_MPa)}, "
                f"σ_F peak pinion {mpa(self.pinion.sigma_F_peak_MPa)}>")


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
    Stress
    """
    import contextlib

    from gearcli import units
    from gearcli.pipeline.stress import compute_stress

    if window is not None:
        window = _quantities(window, units.TIME, "window", 2)
    with contextlib.ExitStack() as stack:
        return Stress(compute_stress(_folder_of(run, stack), window,
                                     require_limits=require_limits))


def sweep(study, out: str | Path | None = None, jobs: int | None = None,
          scheduler: str | None = None, force: bool = False, keep_timeseries: bool = False,
          timeseries_format: str = "csv", progress=None, allow_large: bool = False):
    """Run a study (`gearcli sweep`) and return its summary as a DataFrame (one row per
    point; a ``design: speed_curve`` study: one row per speed and direction).

    Parameters
    ----------
    study : str, Path or gearcli.pipeline.sweep_study.Study
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

    Returns
    -------
    pandas.DataFrame
        ``attrs`` holds the outcome: ``kind`` ("sweep" or "speed_curve"), for a sweep
        ``total``, ``ran``, ``skipped``, ``failed``, ``wall_time_s``; for a speed curve
        ``errors`` (a direction whose solver failed).
    """
    import contextlib

    import pandas as pd

    from gearcli.pipeline.sweep_run import rows_as_table, run_study, summary_columns
    from gearcli.pipeline.sweep_study import Study, load_study

    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise CaseError(f"jobs {jobs!r}: expected a whole number of worker processes >= 1 "
                        "(or None: one per CPU)")
    if not isinstance(study, Study | str | os.PathLike):
        raise CaseError(f"sweep({study!r:.60}): expected the path of a study file (str or "
                        "Path) or a loaded Study")
    _callable_or_none(progress, "progress")
    spec = study if isinstance(study, Study) else load_study(study, allow_large=allow_large)
    with contextlib.ExitStack() as stack:
        if out is None:
            out = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="gearcli-"))) / "s"
        if spec.design == "speed_curve":
            from gearcli.io.outdir import check_target
            from gearcli.pipeline.speed_curve import COLUMNS, run_speed_curve, write_speed_curve

            check_target(out, force)  # before the runs, not after
            curve = run_speed_curve(spec, jobs, scheduler)
            write_speed_curve(curve, out, force)
            df = pd.DataFrame(curve.rows, columns=list(COLUMNS))
            df.attrs.update(kind="speed_curve", errors=list(curve.errors),
                            notes=list(curve.notes))
            return df
        from gearcli.pipeline.sweep_trends import write_trends

        outcome = run_study(spec, Path(out), jobs, scheduler, keep_timeseries, force, progress,
                            timeseries_format=timeseries_format)
        write_trends(Path(out), spec, outcome.rows)
        df = rows_as_table(outcome.rows, summary_columns(spec))
        df.attrs.update(kind="sweep", total=outcome.total, ran=outcome.ran,
                        skipped=outcome.skipped, failed=outcome.failed,
                        wall_time_s=outcome.wall_time_s)
        return df
