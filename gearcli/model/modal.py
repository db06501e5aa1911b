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
import scipy.linalg

from gearcli.model.structure import Structure, line_of_action

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

#: A second element holding at least this share of a mode's strain energy makes it "coupled".
COUPLED_SHARE = 0.25

#: Every coordinate the model knows, in the order of :meth:`LinearSystem.dofs`.
ALL_DOFS = ("theta_m_rad", "theta1_rad", "theta2_rad", "theta_L_rad",
            "x1_mm", "y1_mm", "x2_mm", "y2_mm")

#: Elastic elements (strain-energy shares) and bodies (kinetic-energy shares), in report order.
ELEMENTS = ("mesh", "drive shaft", "load shaft", "pinion bearings", "gear bearings")
BODIES = ("motor", "pinion rotation", "gear rotation", "load", "pinion translation",
          "gear translation")


def has_resonant_peak(damping_ratio: float) -> bool:
    """True when a mode of damping ratio ζ [-] has a resonant peak (ζ < 1/√2)."""
    return damping_ratio < NO_PEAK_DAMPING_RATIO


def linearised_dampers(structure: Structure, drive_torque_Nmm: float,
                       pinion_speed_rad_s: float | None) -> tuple[float, float]:
    """(c_m, c_q,lin) [N·mm·s/rad]: the motor curve and quadratic load term, linearised.

    c_m = |T|/ω0 (torque drive with a linear motor curve T(t)(1 − ω/ω0); core/rhs.py);
    c_q,lin = 2 c_q |ω_L| with the load speed ω_L = ω2 = ω1 r_b1/r_b2 (rigid kinematics,
    docs/theory.md §1; the load shaft turns with the gear). Derivatives of the torque laws with
    respect to speed: the linearisation of Rao, Mechanical Vibrations, ch. 13 (small motion
    about an operating point).
    """
    s = structure
    c_m = 0.0
    if s.drive == "torque" and s.motor_no_load_speed_rad_s > 0.0:
        c_m = abs(drive_torque_Nmm) / s.motor_no_load_speed_rad_s
    omega_load = abs(pinion_speed_rad_s or 0.0) * s.r_b1_mm / s.r_b2_mm
    return c_m, 2.0 * s.load_quadratic_Nmms2_rad2 * omega_load


@dataclass(frozen=True)
class LinearSystem:
    """The linearised model: a :class:`Structure` plus mesh and linearised dampers.

    ``motor_curve_damping_Nmms_rad`` = c_m and ``load_quadratic_damping_Nmms_rad`` =
    2 c_q |ω_L| (:func:`linearised_dampers`); the load's viscous term, shafts and bearings come
    from the structure.
    """

    structure: Structure
    mesh_stiffness_N_mm: float
    mesh_damping_Ns_mm: float = 0.0
    motor_curve_damping_Nmms_rad: float = 0.0
    load_quadratic_damping_Nmms_rad: float = 0.0

    @property
    def drive(self) -> str:
        return self.structure.drive

    @property
    def model(self) -> str:
        return self.structure.model

    def dofs(self) -> tuple[str, ...]:
        s = self.structure
        active = {"theta_m_rad": s.has_motor, "theta1_rad": not s.pinion_prescribed,
                  "theta2_rad": True, "theta_L_rad": s.has_load_inertia}
        return tuple(d for d in ALL_DOFS if active.get(d, s.lateral))

    def validate(self) -> None:
        """ValueError naming the field when a value cannot give a physical model."""
        s = self.structure

        def positive(obj, name: str) -> None:
            if not getattr(obj, name) > 0.0:  # also catches NaN
                raise ValueError(f"{name} must be > 0, got {getattr(obj, name)}")

        def non_negative(obj, name: str) -> None:
            if not getattr(obj, name) >= 0.0:
                raise ValueError(f"{name} must be >= 0, got {getattr(obj, name)}")

        for name in ("J1_t_mm2", "J2_t_mm2", "r_b1_mm", "r_b2_mm"):
            positive(s, name)
        for name in ("load_viscous_Nmms_rad", "pinion_bearing_damping_Nmms_rad",
                     "gear_bearing_damping_Nmms_rad", "drive_shaft_damping_Nmms_rad",
                     "load_shaft_damping_Nmms_rad", "motor_inertia_t_mm2", "load_inertia_t_mm2"):
            non_negative(s, name)
        for name in ("mesh_stiffness_N_mm", "mesh_damping_Ns_mm", "motor_curve_damping_Nmms_rad",
                     "load_quadratic_damping_Nmms_rad"):
            non_negative(self, name)
        if s.drive == "shaft" or s.has_motor:
            positive(s, "drive_shaft_stiffness_Nmm_rad")
        if s.has_load_inertia:
            positive(s, "load_shaft_stiffness_Nmm_rad")
        if s.lateral:
            positive(s, "m1_t")
            positive(s, "m2_t")
            for body in ("pinion", "gear"):
                sup = getattr(s, f"{body}_support")
                if sup is None:
                    raise ValueError(f"{body}_support: the lateral-torsional model needs the "
                                     "bearing stiffness of both gears")
                for name in ("stiffness_x_N_mm", "stiffness_y_N_mm"):
                    if not getattr(sup, name) > 0.0:
                        raise ValueError(f"{body}_support.{name} must be > 0, got "
                                         f"{getattr(sup, name)}")
                for name in ("damping_x_Ns_mm", "damping_y_Ns_mm"):
                    if not getattr(sup, name) >= 0.0:
                        raise ValueError(f"{body}_support.{name} must be >= 0, got "
                                         f"{getattr(sup, name)}")

    # --- assembly ------------------------------------------------------------------------------
    def length_scales(self) -> np.ndarray:
        """Length per unit of each coordinate of :meth:`dofs` [mm/rad or -]: the base radius
        of the body a rotation belongs to (motor and pinion r_b1, gear and load r_b2), 1 for
        a centre displacement (for reporting shapes as lengths)."""
        s = self.structure
        scale = {"theta_m_rad": s.r_b1_mm, "theta1_rad": s.r_b1_mm, "theta2_rad": s.r_b2_mm,
                 "theta_L_rad": s.r_b2_mm}
        return np.array([scale.get(d, 1.0) for d in self.dofs()])

    def mesh_vector(self) -> np.ndarray:
        """g = ∂δ/∂q over :meth:`dofs` [mm/rad, -] (module docstring; structure.py frame)."""
        s = self.structure
        nx, ny = line_of_action(s.alpha_w_rad, "drive")
        full = {"theta1_rad": s.r_b1_mm, "theta2_rad": -s.r_b2_mm,
                "x1_mm": nx, "y1_mm": ny, "x2_mm": -nx, "y2_mm": -ny}
        return np.array([full.get(d, 0.0) for d in self.dofs()])

    def _unit(self, **entries: float) -> np.ndarray:
        dofs = self.dofs()
        v = np.zeros(len(dofs))
        for name, value in entries.items():
            if name in dofs:
                v[dofs.index(name)] = value
        return v

    def element_matrices(self) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        """(K_e, C_e) of every elastic element of :data:`ELEMENTS` that is present."""
        s = self.structure
        out: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        g = self.mesh_vector()
        out["mesh"] = (self.mesh_stiffness_N_mm * np.outer(g, g),
                       self.mesh_damping_Ns_mm * np.outer(g, g))
        if s.has_motor or s.drive == "shaft":
            # twist θm − θ1; with drive 'shaft' the motor angle is prescribed (ground)
            v = self._unit(theta_m_rad=1.0, theta1_rad=-1.0)
            out["drive shaft"] = (s.drive_shaft_stiffness_Nmm_rad * np.outer(v, v),
                                  s.drive_shaft_damping_Nmms_rad * np.outer(v, v))
        if s.has_load_inertia:
            v = self._unit(theta2_rad=1.0, theta_L_rad=-1.0)
            out["load shaft"] = (s.load_shaft_stiffness_Nmm_rad * np.outer(v, v),
                                 s.load_shaft_damping_Nmms_rad * np.outer(v, v))
        if s.lateral:
            for body, i, sup in (("pinion", 1, s.pinion_support), ("gear", 2, s.gear_support)):
                kx, ky = self._unit(**{f"x{i}_mm": 1.0}), self._unit(**{f"y{i}_mm": 1.0})
                out[f"{body} bearings"] = (
                    np.diag(sup.stiffness_x_N_mm * kx + sup.stiffness_y_N_mm * ky),
                    np.diag(sup.damping_x_Ns_mm * kx + sup.damping_y_Ns_mm * ky))
        return out

    def body_masses(self) -> dict[str, np.ndarray]:
        """Diagonal of M per body of :data:`BODIES` that is present [t·mm² or t]."""
        s = self.structure
        out = {
            "motor": self._unit(theta_m_rad=s.motor_inertia_t_mm2),
            "pinion rotation": self._unit(theta1_rad=s.J1_t_mm2),
            "gear rotation": self._unit(theta2_rad=s.J2_t_mm2),
            "load": self._unit(theta_L_rad=s.load_inertia_t_mm2),
            "pinion translation": self._unit(x1_mm=s.m1_t, y1_mm=s.m1_t),
            "gear translation": self._unit(x2_mm=s.m2_t, y2_mm=s.m2_t),
        }
        return {k: v for k, v in out.items() if np.any(v)}

    def matrices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """M, K, C over :meth:`dofs` (module docstring; internal units)."""
        s = self.structure
        M = np.diag(sum(self.body_masses().values()))
        elements = self.element_matrices()
        K = sum(k for k, _ in elements.values())
        C = sum(c for _, c in elements.values())
        motor_body = "theta_m_rad" if s.has_motor else "theta1_rad"
        load_body = "theta_L_rad" if s.has_load_inertia else "theta2_rad"
        dampers = [("theta1_rad", s.pinion_bearing_damping_Nmms_rad),
                   ("theta2_rad", s.gear_bearing_damping_Nmms_rad),
                   (motor_body, self.motor_curve_damping_Nmms_rad),
                   (load_body, s.load_viscous_Nmms_rad + self.load_quadratic_damping_Nmms_rad)]
        for name, c in dampers:
            C = C + np.diag(self._unit(**{name: c}))
        return M, K, C


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


def _normalise(v: np.ndarray) -> np.ndarray:
    """Real shape, largest component +1. A complex (damped) shape is first turned by the phase
    of its largest component and its real part taken (the "realised" mode shape)."""
    v = np.asarray(v)
    i = int(np.argmax(np.abs(v)))
    if np.iscomplexobj(v):
        v = np.real(v * np.exp(-1j * np.angle(v[i])))
    return np.asarray(v / v[i], dtype=float)


def _shape(system: LinearSystem, v: np.ndarray) -> tuple[float, ...]:
    """The reported shape: every coordinate as a length [mm] (a rotation as the roll distance
    r_b θ at its base circle: r_b1 for the motor and pinion, r_b2 for the gear and load; the
    centre displacements as they are), then realised and normalised (:func:`_normalise`).
    Rotations in rad next to displacements in mm would compare numbers, not motions."""
    return tuple(float(x) for x in _normalise(np.asarray(v) * system.length_scales()))


def _mac(a: np.ndarray, b: np.ndarray) -> float:
    """Modal assurance criterion |aᴴb|² / (aᴴa bᴴb) in [0, 1]."""
    return float(abs(np.vdot(a, b)) ** 2 / (np.vdot(a, a).real * np.vdot(b, b).real))


def energy_shares(system: LinearSystem, phi: np.ndarray) -> tuple[dict[str, float],
                                                                    dict[str, float]]:
    """(strain, kinetic) energy shares of a mode shape φ per element and per body.

    Strain φᴴK_eφ / φᴴKφ, kinetic φᴴM_bφ / φᴴMφ (Rao ch. 6; the Hermitian form is the
    time-averaged energy of a complex, damped shape and the usual one for a real shape).
    Strain shares are empty when the mode stores no strain energy (rigid body).
    """
    phi = np.asarray(phi)
    strain = {name: float(np.real(np.vdot(phi, k @ phi)))
              for name, (k, _) in system.element_matrices().items()}
    total = sum(strain.values())
    strain = {k: max(v, 0.0) / total for k, v in strain.items()} if total > 0.0 else {}
    kin = {name: float(np.sum(m * np.abs(phi) ** 2)) for name, m in system.body_masses().items()}
    ktot = sum(kin.values())
    return strain, {k: v / ktot for k, v in kin.items()}


#: A translation within this angle of a direction is described as along it.
_DIRECTION_TOLERANCE_RAD = math.radians(10.0)


def _direction(system: LinearSystem, shape: np.ndarray, i: int) -> str:
    """Direction of gear i's centre motion in a real shape: 'along/across the line of action'
    (drive-flank LoA n_d, structure.py), 'x', 'y' or 'x-y'."""
    dofs = system.dofs()
    u = np.array([shape[dofs.index(f"x{i}_mm")], shape[dofs.index(f"y{i}_mm")]])
    norm = float(np.hypot(*u))
    if norm == 0.0:
        return "x-y"
    nx, ny = line_of_action(system.structure.alpha_w_rad, "drive")
    cos_tol = math.cos(_DIRECTION_TOLERANCE_RAD)
    for name, d in (("along the line of action", (nx, ny)),
                    ("across the line of action", (ny, -nx)), ("x", (1.0, 0.0)),
                    ("y", (0.0, 1.0))):
        if abs(u @ np.array(d)) / norm >= cos_tol:
            return name
    return "x-y"


def describe(system: LinearSystem, phi: np.ndarray, rigid: bool) -> str:
    """The dominant motion of a mode in words, from its strain-energy shares.

    The element with the largest share names the mode. When the bearings of the gears hold
    >= COUPLED_SHARE together beside a dominant mesh or shaft, or a second element holds
    >= COUPLED_SHARE, the mode is called coupled and both are named.
    """
    s = system.structure
    if rigid:
        _, kinetic = energy_shares(system, phi)
        still = [b for b, e in kinetic.items() if e < 1e-9 and "translation" not in b]
        if still:  # a body without a stiff link to the rest (e.g. no mesh stiffness)
            moving = [b.replace(" rotation", "") for b, e in kinetic.items() if e >= 1e-9]
            return f"rigid-body rotation of the {' and '.join(moving)} alone"
        if s.has_motor or s.has_load_inertia:
            return "rigid-body rotation (the whole drive train turns together)"
        return "rigid-body rotation (gears turn together, no mesh deflection)"
    strain, _ = energy_shares(system, phi)
    if not strain:
        return "rigid-body motion"
    shape = _normalise(phi)

    def translation(bodies: list[str]) -> str:
        if len(bodies) == 2:
            return "pinion and gear translation"
        i = 1 if bodies[0] == "pinion" else 2
        return f"{bodies[0]} translation ({_direction(system, shape, i)})"

    def full(name: str) -> str:
        if name == "mesh":
            if s.pinion_prescribed:
                return "mesh mode (gear against the fixed-speed pinion)"
            return "mesh mode (gears against each other)"
        if name == "drive shaft":
            if s.has_motor:
                return "torsional: drive shaft (motor against pinion)"
            return "torsional: drive shaft (pinion against the prescribed motor)"
        if name == "load shaft":
            return "torsional: load shaft (load inertia against gear)"
        body = name.split()[0]
        return f"lateral: {body} on its bearings " \
               f"({_direction(system, shape, 1 if body == 'pinion' else 2)})"

    ranked = sorted(strain, key=lambda k: -strain[k])
    first = ranked[0]
    bearings = {b: strain.get(f"{b} bearings", 0.0) for b in ("pinion", "gear")}
    if not first.endswith("bearings") and sum(bearings.values()) >= COUPLED_SHARE:
        # translation of the gear(s) whose bearings hold a tenth of the energy or more
        moving = [b for b, e in bearings.items() if e >= 0.1] or [max(bearings,
                                                                      key=bearings.get)]
        return f"coupled: {first} with {translation(moving)}"
    if len(ranked) > 1 and strain[ranked[1]] >= COUPLED_SHARE:
        if {ranked[0], ranked[1]} == {"pinion bearings", "gear bearings"}:
            d1, d2 = _direction(system, shape, 1), _direction(system, shape, 2)
            dofs = system.dofs()
            u1, u2 = (np.array([shape[dofs.index(f"x{i}_mm")], shape[dofs.index(f"y{i}_mm")]])
                      for i in (1, 2))
            phase = "in phase" if u1 @ u2 >= 0.0 else "in antiphase"
            return f"lateral: both gears on their bearings, {phase}" + \
                (f" ({d1})" if d1 == d2 else "")
        names = [translation([n.split()[0]]) if n.endswith("bearings") else n
                 for n in ranked[:2]]
        return f"coupled: {names[0]} with {names[1]}"
    return full(first)


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
