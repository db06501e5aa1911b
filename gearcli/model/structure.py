"""The bodies, shafts and supports of a spur pair: ONE description for `simulate` and `modal`.

`gearcli simulate` (the kernel, core/rhs.py) and `gearcli modal` (model/modal.py) both build
their equations from a :class:`Structure`, so the time-domain and the modal results describe
one model. Internal units (gearcli.units): mm, N, s, t, rad.

Torsional chain (docs/theory.md §6), drive side to load side::

    [motor J_m] --shaft k_s, c_s-- [pinion J1] ==mesh== [gear J2] --shaft k_L, c_L-- [load J_L]

- drive 'speed': the pinion's speed is prescribed (Adams MOTION), no drive shaft;
- drive 'shaft': a prescribed motor speed drives the free pinion through the drive shaft;
- drive 'torque': the torque acts on the pinion, or, with ``motor_inertia_t_mm2 > 0``, on
  the motor inertia, which drives the pinion through the drive shaft;
- with ``load_inertia_t_mm2 > 0`` the load torque and its viscous/quadratic terms act on the
  load inertia, connected to the gear by the load shaft; otherwise they act on the gear.

Lateral-torsional model (``model == 'lateral-torsional'``; the classic 6-DOF spur-pair model,
Kahraman & Singh, J. Sound Vib. 144(3), 469-506, 1991; Cai & Hayashi, J. Mech. Des. 116,
1994): each gear centre also moves in x and y on its bearings (stiffness and damping per direction).

Frame: origin at the pinion centre O1, x along the line of centres towards the gear centre
O2, y perpendicular in the direction the pinion's pitch point moves (pinion turning
counter-clockwise, gear clockwise; θ2 is counted in the gear's sense of rotation).
Line-of-action unit vectors, the direction of the normal force ON THE GEAR (ISO 21771
geometry, operating pressure angle α_w)::

    drive flanks  n_d = (sin α_w,  cos α_w)
    coast flanks  n_c = (sin α_w, -cos α_w)     (mirror image about the line of centres)

Derivation: T1 = O1 + r_b1 m with m ⊥ n and |T1 C| = r_w1 n_x > 0 (the path runs from T1 to
T2 in the direction of the push), so n_x = sin α_w > 0 for both flank families.
Centre displacements u_i = (x_i, y_i) add ``(u1 - u2) · n`` to the approach of every pair of
a flank family (first order: the change of α_w and of the backlash with the centre distance
is neglected, as in the 6-DOF model). The friction force on a contact acts perpendicular to
the line of action; per unit signed friction force f (the torsional model's sign: moment
+f ρ1 on the pinion, -f ρ2 on the gear) the force on the PINION centre is f t with::

    drive  t_d = (-cos α_w, sin α_w)        coast  t_c = (cos α_w, sin α_w)

(moment of f t at the contact point O1 + r_b1 m + ρ1 n about O1 = +f ρ1, about O2 = -f ρ2
with ρ2 = a_w sin α_w - ρ1); the gear receives -f t, and the sliding speed gains
(u̇1 - u̇2) · t so that the friction power stays μ F v <= 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Support:
    """Lateral bearing of one gear: stiffness [N/mm] and damping [N·s/mm] per direction."""

    stiffness_x_N_mm: float
    stiffness_y_N_mm: float
    damping_x_Ns_mm: float = 0.0
    damping_y_Ns_mm: float = 0.0


@dataclass(frozen=True)
class Structure:
    """Everything of a case that the equations of motion need besides the mesh (module doc)."""

    model: str  #: 'torsional' or 'lateral-torsional'
    drive: str  #: 'speed', 'shaft' or 'torque'
    J1_t_mm2: float
    J2_t_mm2: float
    m1_t: float  #: gear body masses [t] (lateral model)
    m2_t: float
    r_b1_mm: float
    r_b2_mm: float
    alpha_w_rad: float  #: operating pressure angle (line-of-action directions)
    # drive side
    drive_shaft_stiffness_Nmm_rad: float = 0.0  #: drive 'shaft', or 'torque' with a motor
    drive_shaft_damping_Nmms_rad: float = 0.0
    motor_inertia_t_mm2: float = 0.0  #: 0 = no motor body (torque on the pinion)
    motor_no_load_speed_rad_s: float = 0.0  #: linear motor curve ω0 (0 = none)
    # load side
    load_shaft_stiffness_Nmm_rad: float = 0.0
    load_shaft_damping_Nmms_rad: float = 0.0
    load_inertia_t_mm2: float = 0.0  #: 0 = the load acts on the gear
    load_viscous_Nmms_rad: float = 0.0
    load_quadratic_Nmms2_rad2: float = 0.0
    # bearings
    pinion_bearing_damping_Nmms_rad: float = 0.0  #: torsional, to ground
    gear_bearing_damping_Nmms_rad: float = 0.0
    pinion_support: Support | None = None  #: lateral model only
    gear_support: Support | None = None

    @property
    def lateral(self) -> bool:
        return self.model == "lateral-torsional"

    @property
    def has_motor(self) -> bool:
        """A motor inertia behind a drive shaft (torque drive)."""
        return self.motor_inertia_t_mm2 > 0.0

    @property
    def has_load_inertia(self) -> bool:
        return self.load_inertia_t_mm2 > 0.0

    @property
    def pinion_prescribed(self) -> bool:
        return self.drive == "speed"


def line_of_action(alpha_w_rad: float, flank: str = "drive") -> tuple[float, float]:
    """Unit vector n of the normal force on the gear, (x, y) [-] (module docstring)."""
    s, c = math.sin(alpha_w_rad), math.cos(alpha_w_rad)
    return (s, c) if flank == "drive" else (s, -c)


def friction_direction(alpha_w_rad: float, flank: str = "drive") -> tuple[float, float]:
    """Unit vector t of the friction force on the pinion per unit signed friction force."""
    s, c = math.sin(alpha_w_rad), math.cos(alpha_w_rad)
    return (-c, s) if flank == "drive" else (c, s)
