"""The kernel's arguments, bundled: read-only model data, work arrays, outputs.

numba passes a namedtuple of arrays like its fields and caches functions that take one, so the
compiled functions take these few bundles instead of dozens of positional arrays. Every packed
vector inside is indexed by the names of :mod:`gearcli.core.layout`.

A new per-pair or per-tooth array of the model (a stiffness table, a fault) is:
1. one optional field of :class:`Model` below, after the required ones, with an empty default
   of the right dimensions (e.g. ``EMPTY_3D``: absent unless the case asks for it);
2. its consumer in the compiled code (e.g. :func:`gearcli.core.flank.flank` reads
   ``model.<field>``, with a fast path when ``model.<field>.size == 0``);
3. its physics in ``gearcli/model/`` and one entry in ``KernelInput.arrays``
   (pipeline/kernel_input.py); :func:`gearcli.core.integrate.kernel_model` checks and passes it
   by name (no signature to extend).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

#: Defaults of optional model arrays: absent (size 0).
EMPTY_3D = np.zeros((0, 0, 0))


class Model(NamedTuple):
    """What the physics reads during a run (never written by the kernel).

    Internal units (layout.py): mm, N, s, t, rad.
    """

    prm: np.ndarray  #: (N_PARAMS,) parameter vector, layout.P
    derived: np.ndarray  #: (N_DERIVED,) constants of the run, layout.D (derive.derive)
    family: np.ndarray  #: (N_FAMILIES, N_FAMILY) constants per flank family, layout.F
    tables: np.ndarray  #: (N_TABLES, 2, n) gap tables: gap [mm], slope [-] (gaptable.py)
    tooth_offsets: np.ndarray  #: (N_TABLES, >= max(z1, z2)) flank offset per tooth [mm]
    drive_pp: tuple  #: (breaks, coefs, origins): omega(t) [rad/s] or T(t) [N*mm]
    angle_pp: tuple  #: antiderivative of drive_pp [rad] (speed and shaft drives)
    load_pp: tuple  #: load torque T_load(t) [N*mm]
    #: Tooth law (layout.LAW_TOOTH): pair stiffness k [N/mm] and its slope dk/dx [N/mm^2] per
    #: flank family on the gap tables' grid of pinion roll positions, (N_FAMILIES, 2, n)
    pair_stiffness: np.ndarray = EMPTY_3D
    #: Stiffness factor of every tooth along the path, (N_TABLES, >= max(z1, z2), n >= 2) [-]
    #: (rows as tooth_offsets: flank family x gear) at n pinion roll positions evenly spaced
    #: over [x_lo, x_hi], linearly interpolated; a pair's stiffness is k(x1) f_P(i1, x1)
    #: f_G(i2, x1) for its teeth i1, i2 (either law; faults: cracks, spalls, missing teeth;
    #: docs/theory.md §4b.2)
    tooth_stiffness_factor: np.ndarray = EMPTY_3D
    #: Profile deviation gap of every tooth along the path, (N_TABLES, >= max(z1, z2), n >= 2)
    #: [mm] (rows as tooth_offsets; positive = material missing) at n roll positions evenly
    #: spaced over [x_lo, x_hi], linearly interpolated: pinion tooth i1 adds row g1's value at
    #: x1, gear tooth i2 row g2's at x2 to the pair's gap (profile slope deviations f_Hα:
    #: docs/theory.md §3.5)
    tooth_profile_gap: np.ndarray = EMPTY_3D


class Work(NamedTuple):
    """Scratch arrays of the time loop (allocated once per chunk by timeloop.new_work)."""

    y: np.ndarray  #: (n_state,) state at t, layout.S
    ys: np.ndarray  #: (n_state,) stage / sample state
    y_new: np.ndarray  #: (n_state,) state at t + h
    aux: np.ndarray  #: (N_AUX,) auxiliary results of the last full RHS evaluation, layout.A
    slot_force: np.ndarray  #: (N_FAMILIES, n_slots) force of every pair slot [N]
    scratch: np.ndarray  #: (N_SCRATCH, n_slots) pairs in contact of one flank family, layout.SC
    #: (N_STAGES + 2, n_state) Runge-Kutta stages, K[0] = f(t, y), and a scratch row
    K: np.ndarray
    dy: np.ndarray  #: (n_state,) the scratch row of K (samples, the starting step's trial)
    atol: np.ndarray  #: (N_STATE,) absolute tolerance per state


class Out(NamedTuple):
    """The run's results, owned by the caller across chunks (integrate.simulate)."""

    t_out: np.ndarray  #: (n_out,) output times [s]
    series: np.ndarray  #: (n_out, N_COLUMNS) sampled columns, layout.C
    slot_series: np.ndarray  #: (N_FAMILIES, n_out, n_slots) force of every slot [N]
    extrema: np.ndarray  #: (N_EXTREMA,) layout.X
    slot_extrema: np.ndarray  #: (N_SLOT_EXTREMA, n_slots) drive slots, layout.SX
    counters: np.ndarray  #: (N_COUNTERS,) int64, layout.N
    resume: np.ndarray  #: (N_RESUME,) carried between chunks, layout.R
