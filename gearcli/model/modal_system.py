"""The linearised spur-pair model of `gearcli modal`: coordinates, mass, stiffness and damping
matrices (M, K, C) assembled from a :class:`gearcli.model.structure.Structure`, the mesh
stiffness and damping, and the linearised dampers.

The model, its coordinates, signs and sources are described once, in the docstring of
gearcli.model.modal (docs/theory.md §4, §6); this module is its assembly. Units: mm, N, s, t,
rad (gearcli/units.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gearcli.model.structure import Structure, line_of_action

#: Every coordinate the model knows, in the order of :meth:`LinearSystem.dofs`.
ALL_DOFS = ("theta_m_rad", "theta1_rad", "theta2_rad", "theta_L_rad",
            "x1_mm", "y1_mm", "x2_mm", "y2_mm")

#: Elastic elements (strain-energy shares) and bodies (kinetic-energy shares), in report order.
ELEMENTS = ("mesh", "drive shaft", "load shaft", "pinion bearings", "gear bearings")
BODIES = ("motor", "pinion rotation", "gear rotation", "load", "pinion translation",
          "gear translation")


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

