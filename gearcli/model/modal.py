"""Linear modal analysis of the 2-DOF torsional spur-pair model that `gearcli simulate` integrates.

Coordinates θ = (θ1, θ2) [rad], θ1 the pinion's angle (counter-clockwise), θ2 the gear's angle
in ITS sense of rotation (clockwise), as in core/rhs.py: the DTE is δ = r_b1 θ1 − r_b2 θ2 and
a rigid rotation of the pair without mesh deflection has θ2/θ1 = r_b1/r_b2.

Linearised about the operating point (model.md §4, §6; friction off):

    M θ̈ + C θ̇ + K θ = 0
    M = diag(J1, J2)
    K = k_mesh g gᵀ + diag(k_s, 0),          g = (r_b1, −r_b2)
    C = c_mesh g gᵀ + diag(c1 + c_s + c_m, c2 + c_v + 2 c_q |ω2|)

k_mesh, c_mesh the linearised mesh (gearcli.model.mesh.mesh_mode), k_s, c_s the drive shaft
(drive `shaft`; to the prescribed motor angle), c_m = T_drive/ω0 the linear motor curve
(drive `torque`), c_v, c_q the load's viscous and quadratic terms (the latter linearised at the
gear speed ω2). A prescribed pinion speed (drive `speed`) removes θ1: only the gear moves.

Undamped modes: the generalised symmetric eigenproblem K φ = ω² M φ. Damped modes: the
state-space eigenproblem A x = λ x, A = [[0, I], [−M⁻¹K, −M⁻¹C]]; a complex pair gives
ω_n = |λ|, ζ = −Re λ / |λ|; an overdamped mode gives two real roots with λa λb = ω_n²,
λa + λb = −2 ζ ω_n. Damped roots are assigned to undamped modes by the modal assurance
criterion of their displacement parts.

References: Rao, Mechanical Vibrations, 6th ed., §6.9-6.14 (eigenproblem) and §6.15
(state space); Kahraman & Singh (1990), J. Sound Vib. 142(1), the torsional spur-pair model.
Units: N, mm, s, t, rad (J in t·mm², torsional k in N·mm/rad, c in N·mm·s/rad).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
import scipy.linalg

#: A mode with ζ >= 1/√2 has no resonant peak: |H(f)| <= |H(0)| at every frequency (single-DOF
#: oscillator; Rao, Mechanical Vibrations, §3.4). The one place this rule is written.
NO_PEAK_DAMPING_RATIO = 1.0 / math.sqrt(2.0)

#: ω² below this fraction of the largest ω² counts as a rigid-body mode.
RIGID_TOLERANCE = 1e-9

DOF_NAMES = ("theta1_rad", "theta2_rad")


def has_resonant_peak(damping_ratio: float) -> bool:
    """True when a mode of damping ratio ζ [-] has a resonant peak (ζ < 1/√2)."""
    return damping_ratio < NO_PEAK_DAMPING_RATIO


@dataclass(frozen=True)
class TorsionalSystem:
    """Linearised torsional model: inertias, radii, mesh, shaft and dampers (internal units)."""

    J1_t_mm2: float
    J2_t_mm2: float
    r_b1_mm: float
    r_b2_mm: float
    mesh_stiffness_N_mm: float
    mesh_damping_Ns_mm: float
    drive: str  #: 'speed' (pinion prescribed), 'shaft' or 'torque'
    shaft_stiffness_Nmm_rad: float = 0.0
    shaft_damping_Nmms_rad: float = 0.0
    pinion_damping_Nmms_rad: float = 0.0  #: bearing c1 (+ motor curve slope)
    gear_damping_Nmms_rad: float = 0.0  #: bearing c2 + linearised load terms

    def dofs(self) -> tuple[str, ...]:
        return DOF_NAMES[1:] if self.drive == "speed" else DOF_NAMES

    def matrices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """M [t·mm²], K [N·mm/rad], C [N·mm·s/rad] over :meth:`dofs`."""
        g = np.array([self.r_b1_mm, -self.r_b2_mm])
        gg = np.outer(g, g)
        M = np.diag([self.J1_t_mm2, self.J2_t_mm2])
        K = self.mesh_stiffness_N_mm * gg + np.diag([self.shaft_stiffness_Nmm_rad, 0.0])
        C = self.mesh_damping_Ns_mm * gg + np.diag(
            [self.pinion_damping_Nmms_rad + self.shaft_damping_Nmms_rad,
             self.gear_damping_Nmms_rad])
        if self.drive == "speed":
            return M[1:, 1:], K[1:, 1:], C[1:, 1:]
        return M, K, C


@dataclass(frozen=True)
class Mode:
    """One mode. Rigid-body modes have ``rigid`` True and no frequency or damping ratio."""

    number: int
    rigid: bool
    natural_frequency_Hz: float | None  #: undamped
    damping_ratio: float | None
    damped_frequency_Hz: float | None  #: None when overdamped
    eigenvalues: tuple[complex, ...]  #: state-space roots assigned to this mode [1/s]
    shape: tuple[float, ...]  #: undamped shape, largest component +1
    description: str

    @property
    def has_peak(self) -> bool:
        return not self.rigid and has_resonant_peak(self.damping_ratio)


@dataclass(frozen=True)
class ModalResult:
    dofs: tuple[str, ...]
    modes: tuple[Mode, ...]
    eigenvalues: tuple[complex, ...] = field(default=())  #: all state-space roots [1/s]

    @property
    def elastic(self) -> tuple[Mode, ...]:
        return tuple(m for m in self.modes if not m.rigid)


def _normalise(v: np.ndarray) -> np.ndarray:
    v = np.real_if_close(v, tol=1e6)
    v = np.real(v) if np.iscomplexobj(v) else v
    i = int(np.argmax(np.abs(v)))
    return np.asarray(v / v[i], dtype=float)


def _mac(a: np.ndarray, b: np.ndarray) -> float:
    return float(abs(np.vdot(a, b)) ** 2 / (np.vdot(a, a).real * np.vdot(b, b).real))


def describe(system: TorsionalSystem, shape: np.ndarray, rigid: bool) -> str:
    """The dominant motion of a mode, in words."""
    if rigid:
        return "rigid-body rotation (gears turn together, no mesh deflection)"
    if system.drive == "speed":
        return "mesh mode (gear against the fixed-speed pinion)"
    # Share of the mode's potential energy in the mesh vs the drive shaft.
    delta = system.r_b1_mm * shape[0] - system.r_b2_mm * shape[1]
    e_mesh = system.mesh_stiffness_N_mm * delta**2
    e_shaft = system.shaft_stiffness_Nmm_rad * shape[0] ** 2
    if e_shaft > e_mesh:
        return "torsional: drive shaft / pinion on the shaft"
    return "mesh mode (gears against each other)"


def torsional_modes(system: TorsionalSystem) -> ModalResult:
    """Undamped and damped modes of the linearised torsional model (module docstring).

    Returns modes sorted by frequency, rigid-body modes first.
    """
    for name in ("J1_t_mm2", "J2_t_mm2", "r_b1_mm", "r_b2_mm"):
        if not getattr(system, name) > 0.0:
            raise ValueError(f"{name} must be > 0, got {getattr(system, name)}")
    M, K, C = system.matrices()
    n = M.shape[0]
    w2, phi = scipy.linalg.eigh(K, M)
    w2_scale = max(float(np.max(np.abs(w2))), 1e-300)
    rigid = w2 <= RIGID_TOLERANCE * w2_scale

    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    lam, vec = scipy.linalg.eig(A)
    lam_scale = max(float(np.max(np.abs(lam))), 1e-300)
    # Assign each root to the mode it resembles most (MAC of the displacement parts): first the
    # complex pairs (one root of each), then the real roots of overdamped modes to the modes
    # still without a pair (a damped rigid-body mode keeps its own real root).
    assigned: dict[int, list[complex]] = {i: [] for i in range(n) if not rigid[i]}

    def best_mode(j: int, candidates) -> int | None:
        if not candidates:
            return None
        macs = {i: _mac(vec[:n, j], phi[:, i].astype(complex)) for i in candidates}
        return max(macs, key=macs.get)

    live = [j for j in range(2 * n) if abs(lam[j]) > 1e-9 * lam_scale]
    for j in (j for j in live if lam[j].imag > 0.0):
        i = best_mode(j, list(assigned))
        if i is not None:
            assigned[i].append(complex(lam[j]))
    open_modes = [i for i in assigned if not assigned[i]] + [i for i in range(n) if rigid[i]]
    for j in (j for j in live if lam[j].imag == 0.0):
        i = best_mode(j, open_modes)
        if i is not None and not rigid[i]:
            assigned[i].append(complex(lam[j]))

    modes = []
    for i in range(n):
        shape = _normalise(phi[:, i])
        if rigid[i]:
            modes.append(Mode(0, True, None, None, None, (), tuple(float(x) for x in shape),
                              describe(system, shape, True)))
            continue
        omega_u = math.sqrt(w2[i])
        roots = assigned[i]
        complex_roots = [r for r in roots if r.imag > 0.0]
        if complex_roots:
            r = min(complex_roots, key=lambda r: abs(abs(r) - omega_u))
            zeta, fd = -r.real / abs(r), r.imag / (2.0 * math.pi)
            roots = [r, r.conjugate()]
        elif len(roots) >= 2:
            # Overdamped: the two real roots closest (in log) to ω_n.
            roots = sorted(roots, key=lambda r: abs(math.log(abs(r) / omega_u)))[:2]
            a, b = roots[0].real, roots[1].real
            zeta, fd = -(a + b) / (2.0 * math.sqrt(a * b)), None
        else:  # roots shared with a damped rigid-body mode: modal (proportional) damping
            mm = phi[:, i] @ M @ phi[:, i]
            zeta = float(phi[:, i] @ C @ phi[:, i]) / (2.0 * omega_u * mm)
            fd = None
        modes.append(Mode(0, False, omega_u / (2.0 * math.pi), float(zeta), fd, tuple(roots),
                          tuple(float(x) for x in shape), describe(system, shape, False)))
    modes.sort(key=lambda m: (not m.rigid, m.natural_frequency_Hz or 0.0))
    numbered = tuple(replace(m, number=k + 1) for k, m in enumerate(modes))
    return ModalResult(system.dofs(), numbered, tuple(complex(x) for x in lam))


# --- resonance map ------------------------------------------------------------------------------
@dataclass(frozen=True)
class Order:
    """An excitation at ``per_rev`` events per pinion revolution (f = per_rev n1)."""

    name: str
    per_rev: float


def excitation_orders(z1: int, z2: int, harmonics: int) -> tuple[Order, ...]:
    """GMF harmonics k z1 (k = 1..N) and the shaft orders 1x pinion, 1x gear (= z1/z2)."""
    gmf = tuple(Order(f"{k}x GMF", float(k * z1)) for k in range(1, harmonics + 1))
    return (*gmf, Order("1x pinion", 1.0), Order("1x gear", z1 / z2))


@dataclass(frozen=True)
class Crossing:
    order: str
    mode: int
    frequency_Hz: float
    pinion_speed_rev_s: float  #: n1 at which order × n1 = f_mode


@dataclass(frozen=True)
class Margin:
    order: str
    mode: int
    excitation_Hz: float
    mode_Hz: float
    margin_percent: float  #: |f_exc − f_mode| / f_mode × 100
    has_peak: bool


def crossings(modes, orders) -> list[Crossing]:
    """Pinion speeds n1 [rev/s] where each order line meets each non-rigid mode."""
    return [Crossing(o.name, m.number, m.natural_frequency_Hz, m.natural_frequency_Hz / o.per_rev)
            for m in modes if not m.rigid for o in orders]


def margins(modes, orders, pinion_speed_rev_s: float) -> list[Margin]:
    """Margin [%] of every order at the pinion speed n1 [rev/s] to every non-rigid mode,
    nearest first."""
    out = [Margin(o.name, m.number, o.per_rev * pinion_speed_rev_s, m.natural_frequency_Hz,
                  abs(o.per_rev * pinion_speed_rev_s - m.natural_frequency_Hz)
                  / m.natural_frequency_Hz * 100.0, m.has_peak)
           for m in modes if not m.rigid for o in orders]
    return sorted(out, key=lambda x: x.margin_percent)
