"""Python entry point of the simulation kernel: checks shapes, calls the compiled loop.

:func:`simulate` takes the parameter vector of :mod:`gearcli.core.layout` and plain arrays
(gap tables, time functions, tooth offsets, output times), runs the compiled loop
:func:`gearcli.core.timeloop.run` and returns a :class:`KernelResult` with named access to
its arrays. Only structural checks happen here (shapes, sizes, ordering); physical validity
is the caller's business (pipeline layer), and a physically absurd input comes back as a
status code, never as an exception.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from gearcli.core.bundles import EMPTY_3D, Model, Out
from gearcli.core.derive import derive
from gearcli.core.laws import KNOWN_LAWS
from gearcli.core.layout import (
    COAST_FLANKS,
    COLUMN_NAMES,
    COUNTER_NAMES,
    DRIVE_FLANKS,
    DRIVE_SHAFT,
    DRIVE_SPEED,
    DRIVE_TORQUE,
    EXTREMA_NAMES,
    LAW_TOOTH,
    LAYOUT_KEY,
    N_COLUMNS,
    N_COUNTERS,
    N_DERIVED,
    N_EXTREMA,
    N_FAMILIES,
    N_FAMILY,
    N_GEARS,
    N_PARAMS,
    N_RESUME,
    N_SLOT_EXTREMA,
    N_TABLES,
    SLOT_EXTREMA_NAMES,
    STATUS_MESSAGES,
    STATUS_OK,
    STATUS_STALE_CACHE,
    TABLE_ROWS,
    P,
)
from gearcli.core.records import finish_extrema, init_extrema
from gearcli.core.timeloop import new_work, run


class KernelResult(NamedTuple):
    """Everything :func:`run` returns, with names (internal units, see layout.py)."""

    status: int
    message: str
    counters: dict
    series: np.ndarray  # (n_out, N_COLUMNS), columns layout.COLUMN_NAMES
    slot_force: np.ndarray  # (n_out, N) drive pair-slot forces [N]
    slot_force_coast: np.ndarray  # (n_out, N) coast pair-slot forces [N]
    extrema: np.ndarray  # (N_EXTREMA,), layout.EXTREMA_NAMES
    slot_extrema: np.ndarray  # (N_SLOT_EXTREMA, N), layout.SLOT_EXTREMA_NAMES
    n_valid: int  # rows of series filled (all of them when status == OK)

    @property
    def ok(self) -> bool:
        return self.status == STATUS_OK

    def column(self, name: str) -> np.ndarray:
        """One sampled column by name (e.g. ``"delta_mm"``)."""
        return self.series[:, COLUMN_NAMES.index(name)]

    def extremum(self, name: str) -> float:
        """One entry of ``extrema`` by name (e.g. ``"force_total_max_N"``)."""
        return float(self.extrema[EXTREMA_NAMES.index(name)])

    def slot_extremum(self, name: str) -> np.ndarray:
        """One row of ``slot_extrema`` by name (e.g. ``"force_max_N"``)."""
        return self.slot_extrema[SLOT_EXTREMA_NAMES.index(name)]


def kernel_cached() -> bool | None:
    """Whether numba's cache holds the compiled time loop (:func:`run`) for these sources and
    this machine; False means the next run compiles it. None when that cannot be told (no
    cache, or numba's cache internals differ from 0.59-0.68's).

    Reads the cache index only (no code is loaded): an entry for this machine's code
    generator and this bytecode. The loop has one signature (every array float64, every
    bundle the same fields), so any such entry is the one a run loads.
    """
    try:
        cache = run._cache
        codegen = run.targetctx.codegen()
        _, magic, code = cache._index_key((), codegen)
        return any(key[1] == magic and key[2] == code
                   for key in cache._cache_file._load_index())
    except Exception:  # numba internals: no answer rather than a wrong one
        return None


def _f64(a, ndim: int, what: str) -> np.ndarray:
    """C-contiguous, writable float64 copy-if-needed (one compiled signature for all calls)."""
    out = np.require(np.asarray(a, dtype=np.float64), np.float64, ["C", "W"])
    if out.ndim != ndim:
        raise ValueError(f"{what} must have {ndim} dimension(s), got shape {out.shape}")
    return out


def _pp(pp, what: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    breaks, coefs, origins = pp
    b, c, o = _f64(breaks, 1, what + " breaks"), _f64(coefs, 2, what + " coefs"), \
        _f64(origins, 1, what + " origins")
    if c.shape[0] != b.size + 1 or o.size != b.size + 1:
        raise ValueError(f"{what}: {b.size} breaks need {b.size + 1} pieces and origins")
    return b, c, o


#: A run is integrated in chunks of at most this much simulated time [s] (and at most
#: MAX_CHUNKS of them): between chunks the caller's progress display updates and Ctrl-C is
#: honoured. The chunking depends on the run's time span only, never on whether anybody
#: watches, so results are the same with and without a progress display.
CHUNK_SPAN_S = 2.0
MAX_CHUNKS = 200


def chunk_ends(t_start: float, t_end: float) -> np.ndarray:
    """End times of the chunks of a run [s] (the last one is exactly ``t_end``)."""
    n = max(1, min(MAX_CHUNKS, math.ceil((t_end - t_start) / CHUNK_SPAN_S - 1e-9)))
    ends = t_start + (t_end - t_start) * np.arange(1, n + 1) / n
    ends[-1] = t_end
    return ends


def _factor_table(factors) -> np.ndarray:
    """Per-tooth stiffness factors as the kernel's table (N_GEARS, z, n_positions >= 2): a 2-D
    array (N_GEARS, z) of factors constant along the path becomes two equal columns (linear
    interpolation between equal values returns the value exactly, its slope is 0)."""
    a = np.asarray(factors, dtype=np.float64)
    return np.repeat(a[:, :, None], 2, axis=2) if a.ndim == 2 else a


def kernel_model(params, gap_tables, *, drive_pp, load_pp, drive_angle_pp=None,
                 tooth_offsets=None, **arrays) -> Model:
    """The kernel's read-only data (:class:`gearcli.core.bundles.Model`) from plain arrays,
    with structural checks (shapes, sizes, ordering; no physics checks) and the run's derived
    constants (:func:`gearcli.core.derive.derive`). Parameters as in :func:`simulate`;
    ``arrays`` are further optional fields of Model by name (float64, with the dimensions of
    the field's default)."""
    unknown = sorted(set(arrays) - set(Model._field_defaults))
    if unknown:
        raise ValueError(f"not an optional array of the kernel model: {', '.join(unknown)}")
    if "tooth_stiffness_factor" in arrays:  # (N_GEARS, z): constant along the path
        arrays["tooth_stiffness_factor"] = _factor_table(arrays["tooth_stiffness_factor"])
    optional = {name: _f64(a, Model._field_defaults[name].ndim, name)
                for name, a in arrays.items()}
    prm = _f64(params, 1, "params")
    if prm.size != N_PARAMS:
        raise ValueError(f"params has {prm.size} entries, the layout has {N_PARAMS}")
    mode = int(prm[P.drive_mode])
    if mode not in (DRIVE_SPEED, DRIVE_SHAFT, DRIVE_TORQUE):
        raise ValueError(f"drive_mode must be 0, 1 or 2, got {prm[P.drive_mode]}")
    tables = _f64(gap_tables, 3, "gap_tables")
    if tables.shape[0] == N_GEARS:  # one family given: the others use its tables
        tables = np.ascontiguousarray(np.concatenate([tables] * N_FAMILIES))
    if tables.shape[:2] != (N_TABLES, len(TABLE_ROWS)) or tables.shape[2] < 2:
        raise ValueError(f"gap_tables must have shape ({N_TABLES}, {len(TABLE_ROWS)}, n >= 2), "
                         f"got {tables.shape}")
    if not prm[P.x_hi] > prm[P.x_lo]:
        raise ValueError("x_hi must exceed x_lo")
    needed = math.ceil((prm[P.x_hi] - prm[P.x_lo]) / prm[P.p_b]) + 1
    if int(prm[P.n_slots]) < needed:
        raise ValueError(f"n_slots = {int(prm[P.n_slots])} < ceil((x_hi - x_lo)/p_b) + 1 = "
                         f"{needed}: pairs would be missed")
    z_max = max(int(prm[P.z1]), int(prm[P.z2]))
    if tooth_offsets is None:
        tooth_offsets = np.zeros((N_TABLES, z_max))
    offsets = _f64(tooth_offsets, 2, "tooth_offsets")
    if offsets.shape[0] == N_GEARS:
        offsets = np.ascontiguousarray(np.concatenate([offsets] * N_FAMILIES))
    if offsets.shape[0] != N_TABLES or offsets.shape[1] < z_max:
        raise ValueError(f"tooth_offsets must have shape ({N_TABLES}, >= {z_max}), "
                         f"got {offsets.shape}")
    if (prm[P.mu_s] != 0.0 or prm[P.mu_d] != 0.0) and not 0.0 < prm[P.v_s] < prm[P.v_d]:
        raise ValueError("friction needs 0 < v_s < v_d")
    if mode != DRIVE_TORQUE and drive_angle_pp is None:
        raise ValueError("speed and shaft drives need drive_angle_pp (antiderivative)")
    if drive_angle_pp is None:  # torque mode: unused, any valid piecewise polynomial
        drive_angle_pp = (np.zeros(0), np.zeros((1, 1)), np.zeros(1))
    law = int(prm[P.contact_law])
    if law not in KNOWN_LAWS:
        raise ValueError(f"contact_law must be one of {KNOWN_LAWS}, got {law}")
    stiffness_shape = (N_FAMILIES, len(TABLE_ROWS), tables.shape[2])
    stiffness = optional.get("pair_stiffness", EMPTY_3D)
    if (law == LAW_TOOTH or stiffness.size) and stiffness.shape != stiffness_shape:
        raise ValueError(f"the tooth law needs pair_stiffness of shape {stiffness_shape} (the gap "
                         "tables' grid)")
    derived = np.zeros(N_DERIVED)
    family = np.zeros((N_FAMILIES, N_FAMILY))
    factors = optional.get("tooth_stiffness_factor", EMPTY_3D)
    if factors.shape[0] == N_GEARS:  # one flank family given: the other has the same
        factors = optional["tooth_stiffness_factor"] = np.ascontiguousarray(
            np.concatenate([factors] * N_FAMILIES))
    if factors.size and (factors.shape[0] != N_TABLES or factors.shape[1] < z_max
                         or factors.shape[2] < 2):
        raise ValueError(f"tooth_stiffness_factor needs shape ({N_TABLES} or {N_GEARS}, "
                         f">= {z_max}[, >= 2]), got {factors.shape}")
    profile_gaps = optional.get("tooth_profile_gap", EMPTY_3D)
    if profile_gaps.shape[0] == N_GEARS:  # one flank family given: the other has the same
        profile_gaps = optional["tooth_profile_gap"] = np.ascontiguousarray(
            np.concatenate([profile_gaps] * N_FAMILIES))
    if profile_gaps.size and (profile_gaps.shape[0] != N_TABLES
                              or profile_gaps.shape[1] < z_max or profile_gaps.shape[2] < 2):
        raise ValueError(f"tooth_profile_gap needs shape ({N_TABLES} or {N_GEARS}, >= {z_max}, "
                         f">= 2), got {profile_gaps.shape}")
    derive(prm, tables, offsets, derived, family, factors, profile_gaps)
    return Model(prm=prm.copy(), derived=derived, family=family, tables=tables,
                 tooth_offsets=offsets, drive_pp=_pp(drive_pp, "drive_pp"),
                 angle_pp=_pp(drive_angle_pp, "drive_angle_pp"),
                 load_pp=_pp(load_pp, "load_pp"), **optional)


def kernel_out(model: Model, t_out) -> Out:
    """Empty outputs of a run of ``model`` sampled at ``t_out`` [s] (non-decreasing, within
    [t_start, t_end]): rows NaN, extrema at their start values, counters 0, a fresh start."""
    prm = model.prm
    times = _f64(t_out, 1, "t_out")
    if times.size and (np.any(np.diff(times) < 0.0) or times[0] < prm[P.t_start]
                       or times[-1] > prm[P.t_end]):
        raise ValueError("t_out must be non-decreasing within [t_start, t_end]")
    n_out, n_slots = times.size, int(prm[P.n_slots])
    out = Out(t_out=times, series=np.full((n_out, N_COLUMNS), np.nan),
              slot_series=np.full((N_FAMILIES, n_out, n_slots), np.nan),
              extrema=np.empty(N_EXTREMA), slot_extrema=np.empty((N_SLOT_EXTREMA, n_slots)),
              counters=np.zeros(N_COUNTERS, dtype=np.int64), resume=np.zeros(N_RESUME))
    init_extrema(out.extrema, out.slot_extrema)
    return out


def simulate(params, gap_tables, *, t_out, drive_pp, load_pp, drive_angle_pp=None,
             tooth_offsets=None, progress=None, **arrays) -> KernelResult:
    """Run the compiled kernel on plain arrays; structural checks only (no physics checks).

    Parameters
    ----------
    params : ndarray, shape (N_PARAMS,)
        From :func:`gearcli.core.layout.make_params` (internal units).
    gap_tables : ndarray, shape (4, 2, n) or (2, 2, n)
        Gap tables G1, G2[, G1c, G2c]: ``[k, 0, i]`` gap [mm], ``[k, 1, i]`` slope [-] at
        ``x_lo + i (x_hi - x_lo)/(n - 1)``. With two tables the coast flanks use the drive
        tables (symmetric teeth).
    t_out : ndarray
        Output times [s], non-decreasing, within [t_start, t_end].
    drive_pp : (breaks, coefs, origins)
        Speed and shaft modes: omega(t) [rad/s]; torque mode: T(t) [N*mm]
        (:meth:`gearcli.model.timefunction.PiecewisePolynomial.to_arrays`).
    load_pp : (breaks, coefs, origins)
        Load torque T_load(t) [N*mm] on the gear (positive opposes forward rotation).
    drive_angle_pp : (breaks, coefs, origins), optional
        Antiderivative of ``drive_pp`` [rad] (any constant); required in speed and shaft mode.
    tooth_offsets : ndarray, shape (4 or 2, >= max(z1, z2)), optional
        Per-tooth flank offsets Ft1, Ft2[, Ft1c, Ft2c] [mm]; default zeros.
    tooth_stiffness_factor : ndarray, shape (4 or 2, >= max(z1, z2), n >= 2), optional
        (in ``arrays``) Stiffness factor [-] of every tooth, rows as ``tooth_offsets`` (with
        two rows both flank families have the same), at n pinion roll positions evenly spaced
        over [x_lo, x_hi], linearly interpolated; shape (4 or 2, >= max(z1, z2)): one factor
        per tooth along the whole path (docs/theory.md §4b.2). Absent: no factors.
    tooth_profile_gap : ndarray, shape (4 or 2, >= max(z1, z2), n >= 2), optional
        (in ``arrays``) Profile deviation gap [mm] of every tooth (positive = material
        missing), rows as ``tooth_offsets``, at n roll positions evenly spaced over
        [x_lo, x_hi], linearly interpolated; the pinion's at x1, the gear's at x2
        (docs/theory.md §3.5). Absent: none.
    progress : callable(t_reached, t_start, t_end), optional
        Called after every chunk (:func:`chunk_ends`) with times [s].
    **arrays : ndarray
        Optional model arrays by their field name in :class:`gearcli.core.bundles.Model`.

    Returns
    -------
    KernelResult

    Raises
    ------
    ValueError
        Shapes or layout inconsistent (a programming error of the caller).
    RuntimeError
        The compiled kernel comes from a stale cache (layout changed).
    """
    model = kernel_model(params, gap_tables, drive_pp=drive_pp, load_pp=load_pp,
                         drive_angle_pp=drive_angle_pp, tooth_offsets=tooth_offsets, **arrays)
    out = kernel_out(model, t_out)
    prm = model.prm
    t0, t_end = float(prm[P.t_start]), float(prm[P.t_end])
    status, i_out = STATUS_OK, 0
    for end in chunk_ends(t0, t_end):
        prm[P.t_end] = end
        status, i_out = run(model, new_work(prm), out, LAYOUT_KEY, i_out)
        if status == STATUS_STALE_CACHE:
            raise RuntimeError(STATUS_MESSAGES[STATUS_STALE_CACHE])
        if status != STATUS_OK:
            break
        prm[P.t_start] = end
        if progress is not None:
            progress(float(end), t0, t_end)
    finish_extrema(out.extrema, out.slot_extrema)
    return KernelResult(int(status), STATUS_MESSAGES[int(status)],
                        dict(zip(COUNTER_NAMES, (int(c) for c in out.counters), strict=True)),
                        out.series, out.slot_series[DRIVE_FLANKS], out.slot_series[COAST_FLANKS],
                        out.extrema, out.slot_extrema, int(i_out))
