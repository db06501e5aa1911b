"""Quasi-static loaded tooth contact of a spur pair in one dimension (docs/theory.md §4b).

At each pinion roll position the pairs in mesh carry the static load torque T = F r_b2 of the
gear; the loaded static transmission error (STE) δ is the mesh deflection along the line of
action at which

    Σ_j F_j(p_j) (1 + G2'(x2_j)) = F,  p_j = δ − G1(x1_j) − G2(x2_j),  x2_j = x1_j − δ   (1)

with the same gap functions G1, G2 the dynamic model uses (gap tables: profile modifications and
extended contact outside the path, docs/theory.md §3) and the same force law per pair (IMPACT
elastic part k p^e, docs/theory.md §4, or the tooth law k(x) p, §4b). The factor
1 + G2' = −∂p/∂s2 is the pair's moment arm on the gear over r_b2: 1 on the line of action,
different where a tip touches outside it (the kernel's generalized forces, core/flank.py, so
the dynamic model at vanishing speed has exactly this equilibrium). Pair slots sit one base
pitch apart: x1_j = x_lo + u + j p_b, u the roll of slot 0 [mm]. The left side of (1)
increases with δ, so (1) has one root, bracketed and solved with Brent's method. The mesh
stiffness is its derivative by δ (central difference at the root, step 1e-7 mm). The Harris
map (Harris 1958) is the STE's peak-to-peak against load.

References
----------
S. L. Harris, "Dynamic loads on the teeth of spur gears", Proc. Instn Mech. Engrs 172 (1958)
87-112 (static transmission error, its dependence on load and tip relief).
R. P. Brent, "Algorithms for Minimization without Derivatives", Prentice-Hall 1973, ch. 4
(scipy.optimize.brentq).
All lengths in mm, forces in N.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from gearcli.core.gaptable import hermite_many
from gearcli.core.layout import TABLE_G1, TABLE_G2

#: Step of the central difference for the mesh stiffness [mm] (deflections are ~1e-2 mm).
DELTA_STEP_MM = 1e-7

#: Brent's absolute tolerance on the mesh deflection δ [mm] (:meth:`_Position.solve`).
DELTA_XTOL_MM = 1e-13


class LoadTooSmallError(ValueError):
    """The static force deflects the mesh by less than the solver resolves (no pair is found
    compressed at some roll position): a result would be round-off, not contact."""


#: A force law per pair: (penetration p [mm] > 0, pinion roll position x1 [mm]) ->
#: (force [N], dF/dp [N/mm]), vectorised.
ForceLaw = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


def impact_law(k: float, exponent: float) -> ForceLaw:
    """The elastic part of Adams IMPACT, F = k p^e, dF/dp = e k p^(e−1) (docs/theory.md §4;
    static: no damping) with k [N/mm^e]."""

    def law(p, x1):
        return k * p**exponent, exponent * k * p ** (exponent - 1.0)

    return law


def tooth_law(stiffness: np.ndarray, x_lo: float, x_hi: float) -> ForceLaw:
    """The tooth law's elastic force F = k(x1) p, dF/dp = k(x1) (docs/theory.md §4b), with k
    the cubic Hermite interpolant of ``stiffness`` (shape (2, n): k [N/mm], dk/dx [N/mm²] on
    the gap tables' grid x_lo … x_hi [mm]), the kernel's interpolant."""
    table = np.ascontiguousarray(np.asarray(stiffness, float)[None])

    def law(p, x1):
        k, _ = _gaps(table, 0, x_lo, x_hi, x1)
        return k * p, k

    return law


@dataclass(frozen=True)
class LoadedMesh:
    """Quasi-static loaded contact over whole mesh cycles (arrays over roll positions u)."""

    roll_mm: np.ndarray  #: pinion roll distance r_b1 θ1 from the start [mm], uniform
    force_N: float  #: the static normal force F shared by the pairs
    ste_mm: np.ndarray  #: loaded static transmission error δ [mm]
    unloaded_te_mm: np.ndarray  #: δ at first touch (zero load): the kinematic TE [mm]
    pair_x_mm: np.ndarray  #: (n, slots) pinion roll position of each slot from A [mm]
    pair_force_N: np.ndarray  #: (n, slots) force per slot [N] (0 out of contact)
    pair_stiffness_N_mm: np.ndarray  #: (n, slots) dF_j/dp at the solution [N/mm]
    mesh_stiffness_N_mm: np.ndarray  #: d(left side of (1))/dδ [N/mm]
    pairs_in_contact: np.ndarray  #: (n,) int
    cycles: int  #: whole mesh cycles covered

    @property
    def ste_peak_to_peak_mm(self) -> float:
        return float(np.ptp(self.ste_mm))

    @property
    def max_penetration_mm(self) -> float:
        """The largest compression of a pair over the cycle [mm], the STE above the unloaded
        TE: beyond the gap tables' reach the solution would leave out contacts."""
        return float(np.max(self.ste_mm - self.unloaded_te_mm))

    def ste_harmonics_mm(self, count: int = 3) -> np.ndarray:
        """Amplitudes [mm] of the first ``count`` mesh harmonics of the STE (DFT over the
        whole cycles sampled uniformly: exact bins, no window)."""
        spec = np.abs(np.fft.rfft(self.ste_mm - self.ste_mm.mean())) * 2.0 / self.ste_mm.size
        return spec[self.cycles * np.arange(1, count + 1)]

    def zone_stiffness_N_mm(self, pairs: int) -> float:
        """Mean mesh stiffness over the positions with exactly ``pairs`` pairs in contact
        (NaN if none)."""
        sel = self.pairs_in_contact == pairs
        return float(self.mesh_stiffness_N_mm[sel].mean()) if sel.any() else math.nan


def _gaps(tables, k, x_lo, x_hi, x):
    value = np.empty(x.size)
    slope = np.empty(x.size)
    hermite_many(tables, k, x_lo, x_hi, np.ascontiguousarray(x, float), value, slope)
    return value, slope


class _Position:
    """Equation (1) at one roll position: the pairs at pinion positions ``xs`` [mm]."""

    def __init__(self, tables, x_lo, x_hi, xs, law: ForceLaw):
        self.tables, self.x_lo, self.x_hi, self.xs, self.law = tables, x_lo, x_hi, xs, law
        self.g1 = _gaps(tables, TABLE_G1, x_lo, x_hi, xs)[0]

    def penetrations(self, delta: float) -> tuple[np.ndarray, np.ndarray]:
        """p_j [mm] (-inf where the gear position is off its table) and G2'(x2_j) [-]."""
        g2, s2 = _gaps(self.tables, TABLE_G2, self.x_lo, self.x_hi, self.xs - delta)
        p = delta - self.g1 - g2
        return np.where(np.isfinite(p), p, -np.inf), s2

    def total(self, delta: float) -> float:
        """Left side of (1) [N] at mesh deflection ``delta`` [mm]."""
        p, s2 = self.penetrations(delta)
        on = p > 0.0
        return float((self.law(p[on], self.xs[on])[0] * (1.0 + s2[on])).sum()) \
            if on.any() else 0.0

    def first_touch(self) -> float:
        """δ [mm] where the first pair touches (one fixed-point pass for G2's small dependence
        on δ)."""
        g2 = _gaps(self.tables, TABLE_G2, self.x_lo, self.x_hi, self.xs)[0]
        d0 = float(np.nanmin(self.g1 + g2))
        return d0 - float(self.penetrations(d0)[0].max())

    def touch_deflections(self) -> np.ndarray:
        """Each pair's first-touch deflection d_j [mm], the root of d = G1(x1_j) + G2(x1_j − d)
        (sorted; +inf where the gear position stays off its table): fixed-point passes, which
        contract because |G2'| < 1 wherever a pair can touch (G2' is 0 on the path and small
        outside it, docs/theory.md §3.3)."""
        d = self.g1.copy()
        for _ in range(60):
            g2 = _gaps(self.tables, TABLE_G2, self.x_lo, self.x_hi, self.xs - d)[0]
            new = np.where(np.isfinite(self.g1 + g2), self.g1 + g2, np.inf)
            with np.errstate(invalid="ignore"):  # inf - inf where a pair is off its table
                done = np.all((new == d) | (np.abs(new - d) <= 1e-15 * (1.0 + np.abs(d))))
            d = new
            if done:
                break
        return np.sort(d)

    def solve(self, force_N: float, d0: float) -> float:
        """δ [mm] with total(δ) = F: bracket by doubling steps from the first touch, then Brent."""
        from scipy.optimize import brentq  # only the `mesh` command needs it

        lo, step = d0, 1e-6 * (1.0 + abs(d0))
        hi = d0 + step
        while self.total(hi) < force_N:
            lo, step = hi, 2.0 * step
            hi = d0 + step
            if step > 1e3:
                raise ValueError("no static equilibrium: the pairs cannot carry the load")
        return brentq(lambda d: self.total(d) - force_N, lo, hi, xtol=DELTA_XTOL_MM,
                      rtol=1e-12)


def loaded_mesh(tables: np.ndarray, x_lo: float, x_hi: float, p_b: float, n_slots: int,
                law: ForceLaw, force_N: float, *, cycles: int = 2,
                points_per_cycle: int = 200, cap_mm: float = math.inf) -> LoadedMesh:
    """Solve (1) (module docstring) at ``cycles * points_per_cycle`` roll positions.

    Parameters
    ----------
    tables : ndarray, shape (N_TABLES, 2, n)
        Gap tables of the pair (model.gap.GapTables.tables); the drive flanks are used.
    x_lo, x_hi : float
        Their grid ends [mm] (pinion roll position from A).
    p_b : float
        Base pitch [mm].
    n_slots : int
        Pair slots (model.gap.slot_layout): every pair inside the grid has one.
    law : ForceLaw
        Force of one pair.
    force_N : float
        Static normal force F [N], > 0.
    cap_mm : float
        The gap tables' reach [mm] (their cap on the tip gap outside the path): a ValueError
        when the largest penetration (:attr:`LoadedMesh.max_penetration_mm`) passes it, since
        a pair whose tip gap lies beyond the cap would touch but has no table and the solution
        would leave out contacts (the range simulate's validity guard applies,
        pipeline/validity.table_exit).
    """
    if not force_N > 0.0:
        raise ValueError(f"the static force must be > 0 N, got {force_N}")
    n = cycles * points_per_cycle
    roll = np.arange(n) * (p_b / points_per_cycle)
    x1 = x_lo + np.mod(roll, p_b)[:, None] + p_b * np.arange(n_slots)[None, :]
    ste = np.empty(n)
    unloaded = np.empty(n)
    forces = np.zeros((n, n_slots))
    stiff = np.zeros((n, n_slots))
    k_mesh = np.empty(n)
    count = np.zeros(n, dtype=int)
    for i in range(n):
        inside = np.flatnonzero(x1[i] <= x_hi)
        pos = _Position(tables, x_lo, x_hi, x1[i, inside], law)
        unloaded[i] = pos.first_touch()
        ste[i] = pos.solve(force_N, unloaded[i])
        p, s2 = pos.penetrations(ste[i])
        on = p > 0.0
        f, dfdp = law(p[on], pos.xs[on])
        forces[i, inside[on]] = f
        stiff[i, inside[on]] = dfdp
        k_mesh[i] = (pos.total(ste[i] + DELTA_STEP_MM) - pos.total(ste[i] - DELTA_STEP_MM)) \
            / (2.0 * DELTA_STEP_MM)
        count[i] = int(on.sum())
        if count[i] == 0:  # F > 0 needs a compressed pair: δ is below the solver's tolerance
            raise LoadTooSmallError(
                f"the static force {force_N:.3g} N deflects the mesh by less than the "
                f"solver resolves ({DELTA_XTOL_MM:g} mm)")
    lm = LoadedMesh(roll, force_N, ste, unloaded, x1, forces, stiff, k_mesh, count, cycles)
    if lm.max_penetration_mm > cap_mm:
        raise ValueError(f"the mesh deflection {lm.max_penetration_mm:.4g} mm leaves the "
                         f"contact tables (they reach {cap_mm:.4g} mm): outside the contact "
                         "model's range")
    return lm


def single_pair_limit(tables: np.ndarray, x_lo: float, x_hi: float, p_b: float,
                      n_slots: int, law: ForceLaw, *, points_per_cycle: int = 64,
                      near_mm: float | None = None) -> tuple[float, float]:
    """The largest static normal force F* [N] at which one pair alone carries the load
    somewhere in the mesh cycle, and the roll position u* [mm] (0 <= u* < p_b, slot 0's
    position in its base pitch) where it does (docs/theory.md §4b, "Corner contact").

    At roll position u the second pair touches when the mesh deflection reaches the
    second-smallest first-touch deflection d_(2)(u), so one pair alone carries every force
    below F_1(u) = left side of (1) at δ = d_(2)(u) (only the first pair is compressed there),
    and F* = max_u F_1(u): 0 when two pairs touch at every position even unloaded (ε_α ≥ 2,
    no gaps), +inf when a second pair never reaches its table. Independent of the corner's
    own stiffness: a pair starts to touch at zero force. The maximum over ``points_per_cycle``
    positions of one cycle (or, with ``near_mm``, a known u*) is refined by a bounded scalar
    search (scipy.optimize.minimize_scalar, Brent's method: F_1 is unimodal around its
    maximum, where the entering and the leaving neighbour's gaps cross) on the grid cells
    beside it."""
    from scipy.optimize import minimize_scalar  # only the `mesh` command needs it

    slot = p_b * np.arange(n_slots)
    h = p_b / points_per_cycle

    def carried(u: float) -> float:
        x1 = x_lo + u % p_b + slot  # the pairs repeat every base pitch (as in loaded_mesh)
        pos = _Position(tables, x_lo, x_hi, x1[x1 <= x_hi], law)
        d = pos.touch_deflections()
        if d.size < 2 or not math.isfinite(d[1]):
            return math.inf
        return pos.total(float(d[1]))

    if near_mm is None:
        grid = np.array([carried(i * h) for i in range(points_per_cycle)])
        best = int(np.argmax(grid))
        u_best, f_best = best * h, float(grid[best])
    else:
        u_best, f_best = near_mm, carried(near_mm)
    if not math.isfinite(f_best) or f_best <= 0.0:
        return (f_best if f_best > 0.0 else 0.0), u_best
    found = minimize_scalar(lambda u: -carried(u), bounds=(u_best - h, u_best + h),
                            method="bounded", options={"xatol": 1e-9 * p_b})
    if -float(found.fun) > f_best:
        return -float(found.fun), float(found.x) % p_b
    return f_best, u_best


def harris_map(tables, x_lo, x_hi, p_b, n_slots, law: ForceLaw, force_N: float,
               fractions=None, law_of_load=None, cap_mm: float = math.inf,
               **kw) -> tuple[np.ndarray, np.ndarray]:
    """STE peak-to-peak [mm] against load [N] at ``fractions`` of ``force_N`` (default 0.1 to
    2 in steps of 0.1; Harris 1958); ``law_of_load(F)``, when given, the law at each load F [N]
    (the tooth law's contact term is a secant at the load, docs/theory.md §4b). NaN at a load
    without a static equilibrium or whose penetration (STE above the unloaded TE) passes
    ``cap_mm``, the gap tables' reach [mm]: outside the contact model's range."""
    frac = np.linspace(0.1, 2.0, 20) if fractions is None else np.asarray(fractions, float)
    loads = frac * force_N
    ptp = np.full(loads.size, math.nan)
    for i, f in enumerate(loads):
        try:
            ptp[i] = loaded_mesh(tables, x_lo, x_hi, p_b, n_slots,
                                 law if law_of_load is None else law_of_load(f), f,
                                 cap_mm=cap_mm, **kw).ste_peak_to_peak_mm
        except ValueError:  # no equilibrium within the deflection range, or past the cap
            continue
    return loads, ptp
