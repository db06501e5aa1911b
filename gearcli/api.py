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

import dataclasses
import json
import math
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

__all__ = ["load_case", "geometry", "simulate", "analyze", "spectra_frame", "modal", "mesh",
           "stress", "sweep",
           "Simulation", "Summary", "SCHEMA_VERSION"]

#: Version of the result documents (summary.json, analysis.json, stress.json, modal and mesh
#: JSON) and of :class:`Summary`: raised when a key is renamed or removed.
from gearcli.io.manifest import RESULTS_SCHEMA_VERSION as SCHEMA_VERSION  # noqa: E402


def _overrides(set_: Mapping[str, Any] | None) -> list[str]:
    """``{"key.path": value}`` as the command line's ``--set key.path=value`` texts (values
    as JSON, which the override parser reads as YAML: numbers, strings with units, lists)."""
    out = []
    for key, value in (set_ or {}).items():
        text = value if isinstance(value, str) else json.dumps(value)
        out.append(f"{key}={text}")
    return out


def load_case(source, set: Mapping[str, Any] | None = None):  # noqa: A002  (the CLI's --set)
    """Read and validate a case.

    Parameters
    ----------
    source : str, Path, mapping or LoadedCase
        A case file [YAML], the case as Python data (the YAML's mapping), or an already
        loaded case (returned as is when ``set`` is empty).
    set : mapping, optional
        Overrides ``{"key.path": value}`` as ``--set`` gives them, e.g.
        ``{"gears.module": "8 mm", "run.end_time": 0.5}`` (numbers in the key's default unit).

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


def _field(key: str, default: Any = math.nan):
    """A Summary field with the label and display unit of metric ``key`` (gearcli/io/metrics.py,
    the one place the tables read them from)."""
    from gearcli.io.metrics import METRICS

    m = METRICS.get(key)
    meta = {"label": m.label, "unit": m.unit, "scale": m.scale} if m else {"label": key}
    return dataclasses.field(default=default, metadata=meta)


@dataclasses.dataclass(frozen=True)
class Summary:
    """The scalars of a run over its steady window (summary.json's ``scalars``), typed.

    Every field's unit is in its name (``_N``, ``_mm``, ``_Hz``, ``_s``, ``_deg_s``) or it is
    dimensionless; ``metadata`` holds the label and display unit the tables print
    (gearcli/io/metrics.py).
    """

    dynamic_factor: float | None = _field("dynamic_factor", None)
    force_max_N: float = _field("force_max_N")
    force_max_t_s: float = _field("force_max_t_s")
    force_min_N: float = _field("force_min_N")
    force_mean_N: float = _field("force_mean_N")
    force_rms_N: float = _field("force_rms_N")
    force_static_N: float = _field("force_static_N")
    dte_mean_mm: float = _field("dte_mean_mm")
    dte_peak_to_peak_mm: float = _field("dte_peak_to_peak_mm")
    dte_rms_mm: float = _field("dte_rms_mm")
    contact_loss_fraction: float = _field("contact_loss_fraction")
    coast_force_max_N: float = _field("coast_force_max_N")
    pairs_in_contact_mean: float = _field("pairs_in_contact_mean")
    speed_ratio_mean: float = _field("speed_ratio_mean")
    speed_ratio_theory: float = _field("speed_ratio_theory")
    pinion_speed_mean_deg_s: float = _field("pinion_speed_mean_deg_s")
    gear_speed_mean_deg_s: float = _field("gear_speed_mean_deg_s")
    gear_mesh_frequency_Hz: float | None = _field("gear_mesh_frequency_Hz", None)
    mesh_natural_frequency_Hz: float = _field("mesh_natural_frequency_Hz")
    mesh_damping_ratio: float = _field("mesh_damping_ratio")
    mesh_stiffness_N_mm: float = _field("mesh_stiffness_N_mm")
    static_deflection_mm: float = _field("static_deflection_mm")
    output_rate_Hz: float = _field("output_rate_Hz")
    window_s: tuple[float, float] = _field("window_s", (math.nan, math.nan))
    energy_relative_residual: float = _field("energy_relative_residual")
    status: str = _field("status", "ok")  # validity of the run: "ok" or "invalid"
    invalid_reason: str = _field("invalid_reason", "")

    @classmethod
    def from_scalars(cls, scalars: Mapping[str, Any], status: str = "ok",
                     invalid_reason: str = "") -> Summary:
        names = {f.name for f in dataclasses.fields(cls)}
        values = {k: v for k, v in scalars.items() if k in names}
        if "window_s" in values:
            values["window_s"] = tuple(values["window_s"])
        balance = scalars.get("energy_balance") or {}
        return cls(**values, energy_relative_residual=balance.get("relative_residual", math.nan),
                   status=status, invalid_reason=invalid_reason)

    def to_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)


def results_schema() -> dict:
    """JSON Schema (draft 2020-12) of summary.json: its top-level keys and ``scalars`` from
    :class:`Summary` (the modes, energy balance and solver counters as open objects)."""
    from pydantic import TypeAdapter

    from gearcli.io.manifest import RESULTS_SCHEMA_VERSION

    scalars = TypeAdapter(Summary).json_schema()
    for name in ("status", "invalid_reason", "energy_relative_residual"):
        scalars["properties"].pop(name, None)
    for f in dataclasses.fields(Summary):
        if f.name in scalars["properties"]:
            scalars["properties"][f.name]["description"] = f.metadata.get("label", "")
    scalars["properties"]["energy_balance"] = {"type": "object"}
    scalars["properties"]["modes"] = {"type": "array", "items": {"type": "object"}}
    scalars["additionalProperties"] = True
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "gearcli summary.json",
        "type": "object",
        "required": ["schema_version", "case", "status", "rows", "scalars"],
        "properties": {
            "schema_version": {"const": RESULTS_SCHEMA_VERSION},
            "case": {"type": "string"},
            "status": {"enum": ["ok", "invalid"]},
            "invalid_reason": {"type": "string"},
            "solver": {"type": "object"},
            "rows": {"type": "integer", "minimum": 1},
            "slots": {"type": "integer"},
            "warnings": {"type": "array", "items": {"type": "string"}},
            "scalars": scalars,
        },
    }


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
        self.summary = Summary.from_scalars(result.summary, result.status, result.invalid_reason)
        self.modes = list(result.summary.get("modes", []))
        self.warnings = list(result.warnings)
        self.status = result.status
        self.invalid_reason = result.invalid_reason
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
        folder only with ``force``). ``format``: "csv" or "parquet" for the time series."""
        from gearcli.pipeline.outputs import write_simulation

        return write_simulation(self.result, folder, force, None, format)

    def plot(self, what: str = "force"):
        """A figure of the run: ``"force"`` (mesh force with the static force and the true
        maximum), ``"dte"`` (dynamic transmission error) or ``"speeds"``; returns a
        ``matplotlib.figure.Figure``."""
        from gearcli.plotting import results as plots

        c = self.result.columns()
        t, window = c["t_s"], tuple(self.summary.window_s)
        f_z = self.summary.gear_mesh_frequency_Hz
        if what == "force":
            return plots.plot_force(t, c["force_total_N"], self.summary.force_static_N,
                                    self.summary.force_max_N, self.summary.force_max_t_s, window,
                                    None, f_z)
        if what == "dte":
            return plots.plot_dte(t, c["delta_mm"], window, None, f_z)
        if what == "speeds":
            g = self.result.geometry.geometry
            return plots.plot_speeds(t, c["omega1_rad_s"], c["omega2_rad_s"],
                                     (g.pinion.teeth, g.gear.teeth), window, None, f_z)
        raise ValueError(f"plot {what!r}: expected 'force', 'dte' or 'speeds'")

    def __repr__(self) -> str:
        df = self.summary.dynamic_factor
        return (f"<Simulation {self.name}: {self.status}, {len(self.result.kernel.series)} rows, "
                f"dynamic factor {df if df is None else round(df, 4)}>")


def simulate(case, set: Mapping[str, Any] | None = None, progress=None,  # noqa: A002
             zoom: bool = False) -> Simulation:
    """Integrate the tooth-contact model of a case (`gearcli simulate`).

    Parameters
    ----------
    case : str, Path, mapping or LoadedCase
    set : mapping, optional
        Overrides as in :func:`load_case`.
    progress : callable(t, t_start, t_end), optional
        Called as the integration advances [s].
    zoom : bool
        Also evaluate the dense output for the figures' zooms (one more solve).

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

    return Simulation(run_simulation(load_case(case, set), progress=progress, zoom=zoom))


def _folder_of(run, stack) -> Path:
    """A results folder for a Simulation (written to a temporary folder) or a path."""
    if isinstance(run, Simulation):
        tmp = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="gearcli-")))
        return run.save(tmp / "run")
    return Path(run)


def analyze(run, window: tuple[float, float] | None = None):
    """Metrics, spectra and checks of a run (`gearcli analyze`).

    Parameters
    ----------
    run : Simulation or str or Path
        A simulation, or a results folder of `gearcli simulate`.
    window : (float, float), optional
        Analysis window [s]; default the steady window.

    Returns
    -------
    gearcli.pipeline.analyze.Analysis
        ``.metrics`` (dict, internal units), ``.checks``, ``.passed``, ``.spectra`` (dict of
        arrays; :func:`spectra_frame` makes a DataFrame).
    """
    import contextlib

    from gearcli.pipeline.analyze import analyze as run_analysis

    with contextlib.ExitStack() as stack:
        return run_analysis(_folder_of(run, stack), window)


def spectra_frame(analysis):
    """The analysis' spectra as a DataFrame indexed by frequency [Hz] (spectrum.csv)."""
    import pandas as pd

    from gearcli.pipeline.analysis_io import spectrum_columns

    columns = spectrum_columns(analysis)
    f = columns.pop("frequency_Hz")
    return pd.DataFrame(columns, index=pd.Index(f, name="frequency_Hz"))


def modal(case, set: Mapping[str, Any] | None = None):  # noqa: A002
    """Natural frequencies, damping ratios and mode shapes of the linearised model
    (`gearcli modal`); returns :class:`gearcli.pipeline.modal.ModalAnalysis`."""
    from gearcli.pipeline.modal import run_modal

    return run_modal(load_case(case, set))


def mesh(case, set: Mapping[str, Any] | None = None, **options):  # noqa: A002
    """Quasi-static loaded tooth contact: static transmission error, load sharing, mesh
    stiffness against ISO 6336-1 (`gearcli mesh`); ``options`` as
    :func:`gearcli.pipeline.mesh.run_mesh` takes them (``load_N``, ``harris``, ...)."""
    from gearcli.pipeline.mesh import run_mesh

    return run_mesh(load_case(case, set), **options)


def stress(run, window: tuple[float, float] | None = None):
    """ISO 6336 contact and root stresses along the run (`gearcli stress`); ``run`` a
    Simulation or a results folder. Returns :class:`gearcli.pipeline.stress.StressResult`."""
    import contextlib

    from gearcli.pipeline.stress import compute_stress

    with contextlib.ExitStack() as stack:
        return compute_stress(_folder_of(run, stack), window)


def sweep(study, out: str | Path | None = None, jobs: int | None = None,
          scheduler: str | None = None, force: bool = False):
    """Run a study file (`gearcli sweep`) and return its summary as a DataFrame (one row per
    point; a ``design: speed_curve`` study: one row per speed and direction).

    Parameters
    ----------
    study : str or Path
        Study file [YAML].
    out : str or Path, optional
        Output folder (summary.csv, trends, plots); default a temporary folder, removed after.
    jobs : int, optional
        Worker processes (default: all cores); ``scheduler``: Dask ("local" or an address).
    force : bool
        Start over in ``out`` (discard its summary.csv).
    """
    import contextlib

    import pandas as pd

    from gearcli.pipeline.sweep_run import rows_as_table, run_study, summary_columns
    from gearcli.pipeline.sweep_study import load_study

    spec = load_study(study)
    with contextlib.ExitStack() as stack:
        if out is None:
            out = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="gearcli-"))) / "s"
        if spec.design == "speed_curve":
            from gearcli.pipeline.speed_curve import COLUMNS, run_speed_curve, write_speed_curve

            curve = run_speed_curve(spec, jobs, scheduler)
            write_speed_curve(curve, out, force)
            return pd.DataFrame(curve.rows, columns=list(COLUMNS))
        outcome = run_study(spec, Path(out), jobs, scheduler, False, force, None)
        return rows_as_table(outcome.rows, summary_columns(spec))

