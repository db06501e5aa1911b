"""Linear modal analysis of the spur-pair model that `gearcli simulate` integrates.

The bodies, shafts and supports come from ONE description, :class:`gearcli.model.structure.
Structure` (read its docstring: frame, signs, line of action), the mesh from its linearisation
at the operating load (gearcli.model.mesh.mesh_mode: k_mesh, c_mesh; friction off).

Coordinates q, only the active ones, in this order (:meth:`LinearSystem.dofs`)::

    theta_m_rad   motor inertia            (drive 'torque' with a motor inertia)
    theta1_rad    pinion                   (not with drive 'speed': prescribed)
    theta2_rad    gear, in ITS sense of rotation (clockwise), as in core/rhs.py
    theta_L_rad   load inertia, in the gear's sense (load shaft + load inertia)
    x1_mm, y1_mm, x2_mm, y2_mm   gear centres (model 'lateral-torsional')

Linearised about the operating point (docs/theory.md §4, §6)::

    M q̈ + C q̇ + K q = 0
    M = diag(J_m, J1, J2, J_L, m1, m1, m2, m2)
    K = k_mesh g gᵀ + Σ_shafts k_s s sᵀ + diag(bearing k_x, k_y)
    C = c_mesh g gᵀ + Σ_shafts c_s s sᵀ + diag(dampers)

- Mesh: the dynamic transmission error along the drive-flank line of action (structure.py)
  δ = r_b1 θ1 − r_b2 θ2 + (u1 − u2)·n_d, so g = ∂δ/∂q has r_b1 on θ1, −r_b2 on θ2, n_d on
  (x1, y1) and −n_d on (x2, y2), n_d = line_of_action(α_w, 'drive'): the classic 6-DOF
  spur-pair model (Kahraman & Singh, J. Sound Vib. 144(3), 469-506, 1991, with the mesh
  stiffness and damping at their mean values and the backlash closed on the drive flanks).
  A rigid rotation of the pair (δ = 0) has θ2/θ1 = r_b1/r_b2.
- Shafts (s the shaft twist's gradient): drive shaft θm − θ1 (torque drive with a motor
  inertia) or θ_motor(t) − θ1 with the prescribed motor angle as ground (drive 'shaft'); load
  shaft θ2 − θL.
- Dampers on single coordinates: torsional bearing damping c1 on θ1, c2 on θ2; the motor
  curve T = T(t)(1 − ω/ω0) linearised, c_m = −∂T/∂ω = T/ω0, on the motor inertia (or the
  pinion without one); the load's viscous term c_v and its quadratic term c_q ω|ω|
  linearised, ∂(c_q ω|ω|)/∂ω = 2 c_q |ω|, at the operating speed, on the body that carries
  the load (load inertia, else gear); lateral bearing damping on x_i, y_i.

Undamped modes: the generalised symmetric eigenproblem K φ = ω² M φ (Rao, Mechanical
Vibrations, 6th ed., §6.9-6.14). Damped modes: the state-space eigenproblem A x = λ x,
A = [[0, I], [−M⁻¹K, −M⁻¹C]] (Rao §6.15); a complex pair gives ω_n = |λ|, ζ = −Re λ / |λ|; an
overdamped mode gives two real roots with λa λb = ω_n², λa + λb = −2 ζ ω_n. Damped roots are
assigned to undamped modes by the modal assurance criterion (MAC) of their displacement parts.

Mode descriptions: from the shares of the modal strain energy φᵀK_eφ/2 of each element
(mesh, drive shaft, load shaft, pinion bearings, gear bearings) and of the kinetic energy
ω²φᵀM_bφ/2 of each body (for an undamped mode both maxima are equal; Rao, ch. 6).

Units: mm, N, s, t, rad (J in t·mm², m in t, torsional k in N·mm/rad, lateral k in N/mm,
torsional c in N·mm·s/rad, lateral c in N·s/mm). Mixing rotations and translations in one
eigenproblem is consistent in this system (N·mm/rad · rad² and N/mm · mm² are both N·mm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

# the model, its descriptions and the resonance map live in topic modules; their public names
# are importable from here (gearcli.model.modal is the one entry point)
from gearcli.model.modal_describe import (  # noqa: F401  (re-exported)
    COUPLED_SHARE,
    describe,
    energy_shares,
    normalise_shape,
)
from gearcli.model.modal_resonance import (  # noqa: F401  (re-exported)
    Crossing,
    Margin,
    Order,
    crossings,
    excitation_orders,
    margins,
)
from gearcli.model.modal_system import (  # noqa: F401  (re-exported)
    ALL_DOFS,
    BODIES,
    ELEMENTS,
    LinearSystem,
    linearised_dampers,
)

#: A mode with ζ >= 1/√2 has no resonant peak: |H(f)| <= |H(0)| at every frequency (single-DOF
#: oscillator; Rao, Mechanical Vibrations, §3.4). The one place this rule is written.
NO_PEAK_DAMPING_RATIO = 1.0 / math.sqrt(2.0)

#: ω² below this fraction of the largest ω² counts as a rigid-body mode.
RIGID_TOLERANCE = 1e-9

#: A state-space root with |λ| (or decay rate -Re λ) below this fraction of the largest |λ|
#: is round-off of a free rigid-body root.
LIVE_ROOT_FRACTION = 1e-9

#: The double zero root of a free rigid-body mode is defective (a Jordan block: angle and
#: speed), and round-off ε splits it into a pair ±r, real or imaginary, of size ~√ε |A|
#: (Golub & Van Loan, Matrix Computations, 4th ed., §7.2.2: a perturbation ε of a defective
#: eigenvalue of multiplicity 2 moves it by O(ε^(1/2))), ~1e-8 of the largest root, above
#: LIVE_ROOT_FRACTION. Two roots below this fraction of the largest |λ| that sum to ~0 are
#: that pair (:func:`roundoff_pairs`); a genuine decay root -c/J has no opposite partner.
DEFECTIVE_ROOT_FRACTION = 1e-6


def roundoff_pairs(lam, scale: float) -> set[int]:
    """Indices of the roots that are round-off of a defective double zero root (see
    DEFECTIVE_ROOT_FRACTION): pairs below DEFECTIVE_ROOT_FRACTION * ``scale`` with
    |λ_i + λ_j| < 0.1 |λ_i|."""
    small = [j for j in range(len(lam)) if abs(lam[j]) <= DEFECTIVE_ROOT_FRACTION * scale]
    out: set[int] = set()
    for a in small:
        for b in small:
            if a < b and abs(lam[a] + lam[b]) < 0.1 * max(abs(lam[a]), abs(lam[b])):
                out.update((a, b))
    return out


#: Natural frequencies this close (relative) are one repeated frequency.
REPEATED_TOLERANCE = 1e-6


def has_resonant_peak(damping_ratio: float) -> bool:
    """True when a mode of damping ratio ζ [-] has a resonant peak (ζ < 1/√2)."""
    return damping_ratio < NO_PEAK_DAMPING_RATIO


@dataclass(frozen=True)
class Mode:
    """One mode. Rigid-body modes have ``rigid`` True and no frequency or damping ratio."""

    number: int
    rigid: bool
    natural_frequency_Hz: float | None  #: ω_n/2π of the damped mode (linear_modes)
    damping_ratio: float | None
    damped_frequency_Hz: float | None  #: None when overdamped
    eigenvalues: tuple[complex, ...]  #: state-space roots assigned to this mode [1/s]
    #: mode shape as lengths (rotations as roll distance r_b θ, :func:`_shape`), realised
    #: damped shape, largest component +1
    shape: tuple[float, ...]
    description: str
    undamped_frequency_Hz: float | None = None  #: of the undamped mode it was matched to
    #: share of the modal strain energy per element of ELEMENTS (empty for a rigid mode)
    strain_energy: dict[str, float] = field(default_factory=dict, compare=False)
    #: share of the modal kinetic energy per body of BODIES
    kinetic_energy: dict[str, float] = field(default_factory=dict, compare=False)

    @property
    def has_peak(self) -> bool:
        return not self.rigid and has_resonant_peak(self.damping_ratio)


@dataclass(frozen=True)
class ModalResult:
    dofs: tuple[str, ...]
    modes: tuple[Mode, ...]
    eigenvalues: tuple[complex, ...] = field(default=())  #: all state-space roots [1/s]
    model: str = "torsional"

    @property
    def elastic(self) -> tuple[Mode, ...]:
        return tuple(m for m in self.modes if not m.rigid)

    def slowest_decay_rate_1_s(self) -> float | None:
        """Smallest decay rate -Re λ [1/s] over the damped roots (a damped rigid-body mode
        too: a motor curve or a viscous load on a torque drive); None if nothing decays.
        Free rigid-body roots (round-off around 0) are skipped."""
        lam = self.eigenvalues
        scale = max((abs(x) for x in lam), default=0.0)
        noise = roundoff_pairs(lam, scale)
        rates = [-x.real for j, x in enumerate(lam)
                 if j not in noise and -x.real > LIVE_ROOT_FRACTION * scale]
        return min(rates) if rates else None


def _shape(system: LinearSystem, v: np.ndarray) -> tuple[float, ...]:
    """The reported shape: every coordinate as a length [mm] (a rotation as the roll distance
    r_b θ at its base circle: r_b1 for the motor and pinion, r_b2 for the gear and load; the
    centre displacements as they are), then realised and normalised (:func:`normalise_shape`).
    Rotations in rad next to displacements in mm would compare numbers, not motions."""
    return tuple(float(x) for x in normalise_shape(np.asarray(v) * system.length_scales()))


def _mac(a: np.ndarray, b: np.ndarray) -> float:
    """Modal assurance criterion |aᴴb|² / (aᴴa bᴴb) in [0, 1]."""
    return float(abs(np.vdot(a, b)) ** 2 / (np.vdot(a, a).real * np.vdot(b, b).real))


#: |ζ| below this counts as 0 (an undamped mode's roots carry round-off of this order).
_ZETA_ROUNDOFF = 1e-10


def linear_modes(system: LinearSystem) -> ModalResult:
    """Undamped and damped modes of the linearised model (module docstring).

    1. Undamped: K φ = ω² M φ (scipy.linalg.eigh); ω² <= RIGID_TOLERANCE max ω² is a rigid-body
       mode (reported without frequency or damping ratio).
    2. Damped: the roots λ of the state-space matrix A. Complex pairs (one root each, Im λ > 0)
       are assigned one to one to the elastic undamped modes (Hungarian algorithm on the MAC
       of the displacement parts). Such a mode reports ω_n = |λ|, ζ = −Re λ/|λ|, the damped
       frequency Im λ, and the damped shape (realised; for proportional damping it is φ).
    3. Elastic modes without a complex pair are overdamped: the real roots are assigned to them
       (and to the rigid-body modes, whose decay roots are dropped) by MAC, and the two roots
       closest to ω (in log) give ω_n = √(λa λb), ζ = −(λa + λb)/(2 ω_n) (single-DOF
       oscillator, Rao §2.6); the shape is the eigenvector of the slower root (the motion that
       persists). Without two roots: modal damping φᵀCφ / (2 ω φᵀMφ).

    For proportional damping ω_n equals the undamped ω; for strongly non-proportional damping
    (e.g. a heavily damped mesh in the lateral model) the damped modes differ from the
    undamped ones and the damped values are the ones that place the resonances, so they are
    reported (the undamped frequency too, as ``undamped_frequency_Hz``).
    Modes are sorted by ω_n, rigid-body modes first. Raises ValueError naming the field for a
    non-physical system (:meth:`LinearSystem.validate`).
    """
    import scipy.linalg  # here, not at the top: readers of has_resonant_peak (the report's
    # Campbell diagram) need no scipy (~0.3-0.8 s to import)

    system.validate()
    M, K, C = system.matrices()
    n = M.shape[0]
    w2, phi = scipy.linalg.eigh(K, M)
    w2_scale = max(float(np.max(np.abs(w2))), 1e-300)
    rigid = w2 <= RIGID_TOLERANCE * w2_scale

    Minv = np.diag(1.0 / np.diag(M))  # M is diagonal
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    lam, vec = scipy.linalg.eig(A)
    lam_scale = max(float(np.max(np.abs(lam))), 1e-300)
    live = [j for j in range(2 * n) if abs(lam[j]) > LIVE_ROOT_FRACTION * lam_scale]
    elastic = [i for i in range(n) if not rigid[i]]

    def mac(j: int, i: int) -> float:
        return _mac(vec[:n, j], phi[:, i].astype(complex))

    pair: dict[int, int] = {}  # undamped mode -> index of its complex root
    noise = roundoff_pairs(lam, lam_scale)
    live = [j for j in live if j not in noise]
    cplx = [j for j in live if lam[j].imag > 1e-12 * lam_scale]
    if cplx and elastic:
        from scipy.optimize import linear_sum_assignment  # ~0.3 s to import: only here

        # ties (degenerate modes) broken by the closeness of |λ| to ω
        cost = np.array([[-mac(j, i) + 1e-3 * abs(math.log(abs(lam[j]) / math.sqrt(w2[i])))
                          for i in elastic] for j in cplx])
        for r, c in zip(*linear_sum_assignment(cost), strict=True):
            pair[elastic[c]] = cplx[r]
    reals: dict[int, list[int]] = {i: [] for i in elastic if i not in pair}  # root indices
    open_modes = list(reals) + [i for i in range(n) if rigid[i]]
    for j in (j for j in live if abs(lam[j].imag) <= 1e-12 * lam_scale):
        i = max(open_modes, key=lambda i: mac(j, i)) if open_modes else None
        if i in reals:
            reals[i].append(j)

    modes = []
    for i in range(n):
        if rigid[i]:
            _, kinetic = energy_shares(system, phi[:, i])
            modes.append(Mode(0, True, None, None, None, (), _shape(system, phi[:, i]),
                              describe(system, phi[:, i], True), None, {}, kinetic))
            continue
        omega_u = math.sqrt(w2[i])
        shape_vec: np.ndarray = phi[:, i]
        if i in pair:
            r = complex(lam[pair[i]])
            omega_n, zeta, fd = abs(r), -r.real / abs(r), r.imag / (2.0 * math.pi)
            roots = (r, r.conjugate())
            shape_vec = vec[:n, pair[i]]
        elif len(reals[i]) >= 2:
            ja, jb = sorted(reals[i], key=lambda j: abs(math.log(abs(lam[j]) / omega_u)))[:2]
            a, b = float(lam[ja].real), float(lam[jb].real)
            omega_n = math.sqrt(a * b)
            zeta, fd, roots = -(a + b) / (2.0 * omega_n), None, (complex(a), complex(b))
            # the shape that persists: the eigenvector of the slower root
            shape_vec = np.real(vec[:n, ja if abs(a) < abs(b) else jb])
        else:  # roots not separable: modal damping φᵀCφ / (2 ω φᵀMφ) (Rao ch. 6)
            omega_n = omega_u
            zeta = float(phi[:, i] @ C @ phi[:, i]) / (2.0 * omega_u * (phi[:, i] @ M
                                                                          @ phi[:, i]))
            fd = omega_u * math.sqrt(1.0 - zeta**2) / (2.0 * math.pi) if zeta < 1.0 else None
            roots = ()
        if abs(zeta) < _ZETA_ROUNDOFF:
            zeta = 0.0
        strain, kinetic = energy_shares(system, shape_vec)
        modes.append(Mode(0, False, omega_n / (2.0 * math.pi), float(zeta), fd, roots,
                          _shape(system, shape_vec), describe(system, shape_vec, False),
                          omega_u / (2.0 * math.pi), strain, kinetic))
    modes.sort(key=lambda m: (not m.rigid, m.natural_frequency_Hz or 0.0))
    # Modes sharing a frequency: any combination of their shapes is a mode too, so the shapes
    # (and the words) are one choice among many; say so.
    f = [m.natural_frequency_Hz for m in modes]
    repeated = [m.natural_frequency_Hz is not None and any(
        g is not None and k != j and abs(g - f[k]) <= REPEATED_TOLERANCE * f[k]
        for j, g in enumerate(f)) for k, m in enumerate(modes)]
    modes = [replace(m, description=m.description + " [repeated frequency]") if rep else m
             for m, rep in zip(modes, repeated, strict=True)]
    numbered = tuple(replace(m, number=k + 1) for k, m in enumerate(modes))
    return ModalResult(system.dofs(), numbered, tuple(complex(x) for x in lam), system.model)

