"""A finished simulation: what `gearcli simulate` computed, and the Python API's methods on it
(the time series as a DataFrame, save, plot)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from gearcli.case.load import LoadedCase
from gearcli.pipeline.geometry import GeometryResult
from gearcli.pipeline.kernel_input import KernelInput
from gearcli.pipeline.window import Window
from gearcli.results import Summary


@dataclass
class SimulationResult:
    """A finished run (`gearcli simulate`, :func:`gearcli.simulate`): inputs, the sampled
    series (:attr:`series`), true extrema, counters, the typed :class:`~gearcli.results.Summary`,
    warnings, and the validity ``status`` (``"ok"``, or ``"invalid"`` with ``invalid_reason``
    when the run left the model's range, docs/theory.md §10.2: its numbers are then not
    results)."""

    loaded: LoadedCase
    geometry: GeometryResult
    kernel_input: KernelInput
    kernel: object  # core.integrate.KernelResult
    wall_time_s: float
    window: Window
    modes: object = None  # model.modal.ModalResult of the same model, linearised
    summary: Summary = field(default_factory=Summary)
    warnings: list[str] = field(default_factory=list)
    #: "ok", or "invalid" when the run left the model's range (pipeline/validity.py)
    status: str = "ok"
    invalid_reason: str = ""
    #: the solver's dense output on a fine grid around the force maximum and over the last
    #: mesh cycles (:func:`dense_zoom`); empty when not made
    zoom: dict = field(default_factory=dict)
    #: whether ``wall_time_s`` includes compiling the solver (the first run after install)
    compiled: bool = False
    #: the same run at the default tolerances when the case loosened them (its kernel result;
    #: pipeline/validity.tolerance_reference), else None
    reference_kernel: object = None
    #: the ``--set`` texts it was run with (the manifest's)
    overrides: list[str] = field(default_factory=list)
    _series: object = field(default=None, repr=False, compare=False)

    @property
    def name(self) -> str:
        return self.loaded.name

    def __repr__(self) -> str:
        df = self.summary.dynamic_factor
        return (f"<Simulation {self.name}: {self.status}, {len(self.kernel.series)} rows, "
                f"dynamic factor {df if df is None else round(df, 4)}>")

    @property
    def series(self):
        """timeseries.csv's columns (names carry units) as a pandas DataFrame indexed by time
        ``t_s`` [s]."""
        if self._series is None:
            from gearcli.io.tables import columns_to_frame

            self._series = columns_to_frame(self.columns(), "t_s")
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

        return write_simulation(self, folder, force, self.overrides, format)

    def plot(self, what: str = "force", units: str = "engineering"):
        """A figure of the run: ``"force"`` (mesh force with the static force and the true
        maximum), ``"dte"`` (dynamic transmission error) or ``"speeds"`` (in the display
        ``units``: "engineering" rpm or "si" rad/s); returns a ``matplotlib.figure.Figure``."""
        from gearcli.plotting import results as plots

        c, s = self.columns(), self.summary
        t, window = c["t_s"], tuple(s.window_s)
        f_z = s.gear_mesh_frequency_Hz
        if what == "force":
            return plots.plot_force(t, c["force_total_N"], s.force_static_N, s.force_max_N,
                                    s.force_max_t_s, window, None, f_z)
        if what == "dte":
            return plots.plot_dte(t, c["delta_mm"], window, None, f_z, units=units)
        if what == "speeds":
            g = self.geometry.geometry
            return plots.plot_speeds(t, c["omega1_rad_s"], c["omega2_rad_s"],
                                     (g.pinion.teeth, g.gear.teeth), window, None, f_z,
                                     units)
        raise ValueError(f"plot {what!r}: expected 'force', 'dte' or 'speeds'")

    def sensors(self):
        """What a rig would record (case ``sensors:``; docs/theory.md, "What a sensor sees"):
        the sensors table as a pandas DataFrame indexed by ``t_s`` [s], its description
        (:class:`~gearcli.results.SensorsDocument`) in ``.attrs["sensors"]``. A case without
        ``sensors:`` is a ValueError."""
        from gearcli.io.tables import columns_to_frame
        from gearcli.pipeline.sensors import sensor_table

        if self.loaded.case.sensors is None:
            raise ValueError(f"{self.name}: the case has no 'sensors:' section")
        columns, doc = sensor_table(self)
        frame = columns_to_frame(columns, "t_s")
        frame.attrs["sensors"] = doc
        return frame

    def columns(self) -> dict[str, np.ndarray]:
        """Output columns in file order; names carry units."""
        from gearcli.core.layout import COLUMN_NAMES, DRIVE_SHAFT, OPTIONAL_COLUMNS, P

        k = self.kernel
        prm = self.kernel_input.params
        has = {"lateral": prm[P.lateral] != 0.0,
               "drive_shaft": prm[P.motor_J] > 0.0 or prm[P.drive_mode] == DRIVE_SHAFT,
               "load_shaft": prm[P.load_J] > 0.0}
        names = [n for n in COLUMN_NAMES if n not in OPTIONAL_COLUMNS or has[OPTIONAL_COLUMNS[n]]]
        cols = {name: k.series[:, i] for i, name in enumerate(COLUMN_NAMES)}
        out = {n: cols[n] for n in names if not n.endswith("_mJ")
               and n not in ("friction_power_mW",)}
        for j in range(k.slot_force.shape[1]):
            out[f"force_slot{j}_N"] = k.slot_force[:, j]
        cycle, x = self.slot_positions()
        out["mesh_cycle"] = cycle
        for j in range(x.shape[1]):
            out[f"x_slot{j}_mm"] = x[:, j]
        for n in names:
            if n.endswith("_mJ") or n == "friction_power_mW":
                out[n] = cols[n]
        return out


    def slot_positions(self) -> tuple[np.ndarray, np.ndarray]:
        """Mesh cycle n and each drive slot's pinion roll position x from A [mm] per sample.

        x_j = x_lo + ((s1 - s1_0) mod p_b) + j p_b with n = floor((s1 - s1_0)/p_b) (core/rhs.py);
        the pair in slot j has pinion tooth (n - j) mod z1 and gear tooth (n - j) mod z2.
        """
        from gearcli.core.layout import P

        prm, g = self.kernel_input.params, self.geometry.geometry
        r = self.kernel.column("theta1_rad") * g.pinion.r_b_mm - prm[P.s1_0]
        n = np.floor(r / g.p_b_mm)
        u = r - n * g.p_b_mm
        slots = np.arange(self.kernel.slot_force.shape[1])
        return n, prm[P.x_lo] + u[:, None] + g.p_b_mm * slots[None, :]
