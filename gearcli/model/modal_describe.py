"""Mode descriptions of `gearcli modal`: modal strain- and kinetic-energy shares per element
and body, and the dominant motion of a mode in words (docstring of gearcli.model.modal; Rao,
Mechanical Vibrations, 6th ed., ch. 6).
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.model.modal_system import LinearSystem
from gearcli.model.structure import line_of_action

#: A second element holding at least this share of a mode's strain energy makes it "coupled".
COUPLED_SHARE = 0.25


def normalise_shape(v: np.ndarray) -> np.ndarray:
    """Real shape, largest component +1. A complex (damped) shape is first turned by the phase
    of its largest component and its real part taken (the "realised" mode shape)."""
    v = np.asarray(v)
    i = int(np.argmax(np.abs(v)))
    if np.iscomplexobj(v):
        v = np.real(v * np.exp(-1j * np.angle(v[i])))
    return np.asarray(v / v[i], dtype=float)


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
    shape = normalise_shape(phi)

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

