"""Layout of the kernel's flat inputs and outputs: one tuple of names per vector, indices from it.

The simulation kernel (:mod:`gearcli.core.integrate`) takes one float64 parameter vector and
returns float64 arrays whose columns are named here. Each layout is written ONCE as a tuple of
names; the index constants (``P.r_b1``, ``C.delta_mm``, ...) are generated from it, so adding a
name never shifts an index by hand. Compiled code reads the index namedtuples as compile-time
constants.

Internal units (docs/theory.md §1, the Adams "MMKS" family): mm, N, s, tonne (t), rad;
1 N = 1 t·mm/s², inertia in t·mm², torque in N·mm, energy in N·mm = mJ, power in N·mm/s = mW.

numba's on-disk cache does not notice when a module a kernel depends on changes (numba issue
#6845). The kernel therefore compares :data:`LAYOUT_KEY` frozen into its compiled code with the
value passed at run time and returns :data:`STATUS_STALE_CACHE` on a mismatch; after editing
any file of ``gearcli/core`` delete ``gearcli/core/__pycache__/*.nb[ic]``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

# --------------------------------------------------------------------------------------------
# Parameter vector. Name, unit, default (None = required). Integer-valued entries (modes, flags,
# counts, tooth indices) are stored as floats and rounded by the kernel.
# --------------------------------------------------------------------------------------------
_PARAM_SPEC = (
    # time span and initial state
    ("t_start", "s", 0.0),
    ("t_end", "s", None),
    ("theta1_init", "rad", 0.0),  # pinion angle at t_start (speed/shaft: offset of the motor angle)
    ("omega1_init", "rad/s", 0.0),  # pinion speed at t_start (torque and shaft modes)
    ("delta_init", "mm", 0.0),  # DTE along the drive LoA at t_start
    ("deltadot_init", "mm/s", 0.0),
    # initial values of the optional states (layout.STATE_NAMES after N_STATE_BASE; rates 0)
    ("x1_init", "mm", 0.0),
    ("y1_init", "mm", 0.0),
    ("x2_init", "mm", 0.0),
    ("y2_init", "mm", 0.0),
    ("tw_m_init", "rad", 0.0),
    ("tw_l_init", "rad", 0.0),
    # bodies
    ("r_b1", "mm", None),  # base radius, pinion
    ("r_b2", "mm", None),  # base radius, gear
    ("J1", "t*mm^2", None),  # polar inertia, pinion
    ("J2", "t*mm^2", None),  # polar inertia, gear
    ("z1", "-", None),  # number of teeth (indexes the per-tooth offsets)
    ("z2", "-", None),
    # mesh geometry along the LoA (docs/theory.md §2-3)
    ("p_b", "mm", None),  # base pitch
    ("T1A", "mm", None),  # |T1A|: distance of contact start A from T1 (friction arms)
    ("T1T2", "mm", None),  # |T1T2| = a_w sin(alpha_w)
    ("x_lo", "mm", None),  # first grid point of the gap tables (roll position from A)
    ("x_hi", "mm", None),  # last grid point of the gap tables
    ("n_slots", "-", None),  # N >= ceil((x_hi - x_lo)/p_b) + 1 pair slots per flank
    ("s1_0", "mm", 0.0),  # drive phase: slot 0 is at x_lo when s1 - s1_0 = 0 (mod p_b)
    ("s1c_0", "mm", 0.0),  # coast phase: coast slot 0 is at x_lo when -s1 - s1c_0 = 0 (mod p_b)
    ("backlash_n", "mm", 0.0),  # normal backlash j_n along the LoA
    ("coast_flanks", "-", 1.0),  # 1 = evaluate coast-flank contacts, 0 = drive flanks only
    # per-tooth flank offsets: index of the tooth in slot 0 at n_cyc = 0 (see rhs.py)
    ("tooth_k1", "-", 0.0),
    ("tooth_k2", "-", 0.0),
    ("tooth_k1_coast", "-", 0.0),
    ("tooth_k2_coast", "-", 0.0),
    # runout projected on the LoA: e_i = ecc_i sin(theta_i + phase_i)
    ("ecc1", "mm", 0.0),
    ("phase1", "rad", 0.0),
    ("ecc2", "mm", 0.0),
    ("phase2", "rad", 0.0),
    ("phase1_coast", "rad", 0.0),  # phase on the coast LoA (drive phase +- 2 alpha_w)
    ("phase2_coast", "rad", 0.0),
    # contact law: LAW_IMPACT (Adams IMPACT, docs/theory.md §4) or LAW_TOOTH (§4b, §4c)
    ("contact_law", "-", 0.0),
    ("mesh_damping", "N*s/mm", 0.0),  # tooth law: c_m on the mesh deflection rate (§4c)
    ("damping_force_ref", "N", 1.0),  # tooth law: below this elastic force damping ~ force
    ("k_contact", "N/mm^e", None),
    ("exponent", "-", None),
    ("c_max", "N*s/mm", 0.0),
    ("d_max", "mm", 0.1),
    # friction, Adams (docs/theory.md §5); mu_s = mu_d = 0 switches it off
    ("mu_s", "-", 0.0),
    ("mu_d", "-", 0.0),
    ("v_s", "mm/s", 0.01),
    ("v_d", "mm/s", 0.1),
    # drive (docs/theory.md §6)
    ("drive_mode", "-", None),  # DRIVE_SPEED, DRIVE_SHAFT or DRIVE_TORQUE
    ("shaft_k", "N*mm/rad", 0.0),
    ("shaft_c", "N*mm*s/rad", 0.0),
    ("motor_omega0", "rad/s", 0.0),  # torque mode: T (1 - omega1/omega0); 0 = no motor curve
    # drive side body (torque drive through the drive shaft; 0 = none): motor inertia
    ("motor_J", "t*mm^2", 0.0),
    # load side (0 = none): load inertia on a load shaft from the gear
    ("load_J", "t*mm^2", 0.0),
    ("load_k", "N*mm/rad", 0.0),
    ("load_c", "N*mm*s/rad", 0.0),
    # lateral-torsional model (model/structure.py: frame, line-of-action vectors)
    ("lateral", "-", 0.0),  # 1 = gear centres move in x, y on their bearings
    ("m1", "t", 0.0),  # gear body masses
    ("m2", "t", 0.0),
    ("sin_aw", "-", 0.0),  # sin, cos of the operating pressure angle
    ("cos_aw", "-", 1.0),
    ("kx1", "N/mm", 0.0),  # bearing stiffness and damping per direction
    ("ky1", "N/mm", 0.0),
    ("cx1", "N*s/mm", 0.0),
    ("cy1", "N*s/mm", 0.0),
    ("kx2", "N/mm", 0.0),
    ("ky2", "N/mm", 0.0),
    ("cx2", "N*s/mm", 0.0),
    ("cy2", "N*s/mm", 0.0),
    # losses
    ("c1", "N*mm*s/rad", 0.0),  # bearing viscous damping, pinion
    ("c2", "N*mm*s/rad", 0.0),  # bearing viscous damping, gear
    ("load_cv", "N*mm*s/rad", 0.0),  # viscous load term on the gear
    ("load_cq", "N*mm*s^2/rad^2", 0.0),  # quadratic load term on the gear
    # integrator (Dormand-Prince 5(4), see dopri5.py)
    ("rtol", "-", 1e-6),
    ("atol_delta", "mm", 1e-6),
    ("atol_deltadot", "mm/s", 1e-3),
    ("max_step", "s", math.inf),
    ("first_step", "s", 0.0),  # 0 = automatic (Hairer-Norsett-Wanner II.4)
    ("max_steps", "-", 5e6),  # accepted + rejected steps
    ("penetration_limit", "mm", math.inf),  # RUNAWAY_PENETRATION above it
    ("extrema_t_start", "s", -math.inf),  # extrema are tracked for t >= this
)

#: The parameter names, in vector order.
PARAM_NAMES = tuple(name for name, _, _ in _PARAM_SPEC)
#: Unit of every parameter, by name.
PARAM_UNITS = {name: unit for name, unit, _ in _PARAM_SPEC}
#: Default of every optional parameter, by name (required ones are absent).
PARAM_DEFAULTS = {name: d for name, _, d in _PARAM_SPEC if d is not None}

ParamIndex = NamedTuple("ParamIndex", [(n, int) for n in PARAM_NAMES])
#: Index constants of the parameter vector: ``params[P.r_b1]``.
P = ParamIndex(*range(len(PARAM_NAMES)))
N_PARAMS = len(PARAM_NAMES)

# Contact laws (docs/theory.md §4, §4b).
LAW_IMPACT = 0  # F = max(0, k p^e + STEP(p, 0, 0, d_max, c_max) pdot), one k per pair
LAW_TOOTH = 1  # F = max(0, k(x) p (1 + c_m v / max(sum k p, F_ref))), k(x) tabulated

# Drive modes (docs/theory.md §6).
DRIVE_SPEED = 0  # prescribed omega1(t) (Adams MOTION); only the gear is integrated
DRIVE_SHAFT = 1  # prescribed motor angle/speed through a torsional shaft to a free pinion
DRIVE_TORQUE = 2  # prescribed T_drive(t), optional linear motor curve

# --------------------------------------------------------------------------------------------
# Status codes returned by the kernel.
# --------------------------------------------------------------------------------------------
STATUS_OK = 0
STATUS_MAX_STEPS = 1
STATUS_NAN = 2
STATUS_RUNAWAY_PENETRATION = 3
STATUS_STEP_TOO_SMALL = 4
STATUS_STALE_CACHE = 5
STATUS_MESSAGES = {
    STATUS_OK: "integration finished",
    STATUS_MAX_STEPS: "maximum number of steps reached",
    STATUS_NAN: "non-finite state (NaN or overflow)",
    STATUS_RUNAWAY_PENETRATION: "tooth penetration above penetration_limit",
    STATUS_STEP_TOO_SMALL: "step size below the floating-point resolution of time",
    STATUS_STALE_CACHE: "compiled kernel is stale (delete gearcli/core/__pycache__/*.nb[ic])",
}

# --------------------------------------------------------------------------------------------
# Integrated state: relative mesh coordinate + pinion roll distance + energy quadratures.
# --------------------------------------------------------------------------------------------
STATE_NAMES = (
    "s1",  # pinion roll distance r_b1 theta1 [mm]
    "v1",  # its rate [mm/s]
    "delta",  # DTE s1 - s2 [mm]
    "deltadot",  # [mm/s]
    "work_in",  # integral of T_drive omega1 dt [N*mm]
    "work_load",  # integral of T_load omega2 dt [N*mm]
    "loss_bearing",  # viscous/quadratic load terms and bearing damping [N*mm]
    "loss_damping",  # contact damping dissipation [N*mm]
    "loss_friction",  # friction dissipation [N*mm]
    # Optional degrees of freedom: integrated only when the model has them (N_STATE_BASE ..)
    "x1",  # pinion centre displacement [mm] (lateral model)
    "y1",
    "x2",  # gear centre
    "y2",
    "vx1",  # their rates [mm/s]
    "vy1",
    "vx2",
    "vy2",
    "tw_m",  # drive-shaft twist theta_m - theta1 [rad] (motor inertia)
    "tw_m_dot",  # [rad/s]
    "tw_l",  # load-shaft twist theta2 - theta_L [rad] (load inertia)
    "tw_l_dot",  # [rad/s]
)
StateIndex = NamedTuple("StateIndex", [(n, int) for n in STATE_NAMES])
S = StateIndex(*range(len(STATE_NAMES)))
N_STATE = len(STATE_NAMES)
#: The states the right-hand side reads, s1 .. deltadot; the energy quadratures follow.
N_DYNAMIC = S.work_in
#: States of the 2-DOF torsional model (the optional ones follow); a run integrates either
#: these or all N_STATE.
N_STATE_BASE = S.x1

# --------------------------------------------------------------------------------------------
# Auxiliary results of one right-hand-side evaluation (rhs.py writes them).
# --------------------------------------------------------------------------------------------
AUX_NAMES = (
    "s1",  # pinion roll distance actually used [mm] (prescribed in speed mode)
    "v1",  # [mm/s]
    "force_drive",  # sum of drive-flank normal forces [N]
    "force_coast",  # sum of coast-flank normal forces [N]
    "n_drive",  # drive pairs with F > 0
    "n_coast",  # coast pairs with F > 0
    "friction_force",  # signed sum of friction forces f_j = mu(v_j) F_j [N]
    "friction_power",  # sum of f_j v_j [N*mm/s], never positive
    "drive_torque",  # on the pinion [N*mm]
    "load_torque",  # T_load(t) on the gear [N*mm]
    "contact_energy",  # sum of k p^(e+1)/(e+1) [N*mm]
    "max_penetration",  # largest penetration over all contacts [mm] (0 if none)
    "spring_energy",  # shafts and bearings: sum of k q^2 / 2 [N*mm]
    "bearing_fx1",  # force of the pinion on its bearings, k x + c xdot [N]
    "bearing_fy1",
    "bearing_fx2",  # of the gear
    "bearing_fy2",
    "motor_speed",  # [rad/s] (motor inertia or prescribed motor; else omega1)
    "drive_shaft_torque",  # torque the drive shaft applies to the pinion [N*mm]
    "load_speed",  # [rad/s] (load inertia; else omega2)
    "load_shaft_torque",  # torque the load shaft takes from the gear [N*mm]
)
AuxIndex = NamedTuple("AuxIndex", [(n, int) for n in AUX_NAMES])
A = AuxIndex(*range(len(AUX_NAMES)))
N_AUX = len(AUX_NAMES)

# --------------------------------------------------------------------------------------------
# Flank families and gap tables. A flank family is the set of pair slots on one line of action
# (drive flanks: sigma = +1, coast flanks: sigma = -1, rhs.py). Each family reads two gap
# tables, one per gear, in the gap-table array tables[table, row, i] (model/gap.py fills it,
# core/gaptable.py reads it); per-tooth flank offsets use the same rows.
# --------------------------------------------------------------------------------------------
FLANK_FAMILIES = ("drive", "coast")
N_FAMILIES = len(FLANK_FAMILIES)
DRIVE_FLANKS = FLANK_FAMILIES.index("drive")
COAST_FLANKS = FLANK_FAMILIES.index("coast")
GEARS = ("pinion", "gear")
N_GEARS = len(GEARS)
PINION = GEARS.index("pinion")
GEAR = GEARS.index("gear")
#: Gap tables (and tooth-offset rows): one per flank family and gear, index family * N_GEARS
#: + gear: G1, G2 (drive), G1c, G2c (coast).
N_TABLES = N_FAMILIES * N_GEARS
TABLE_G1 = DRIVE_FLANKS * N_GEARS + PINION
TABLE_G2 = DRIVE_FLANKS * N_GEARS + GEAR
TABLE_G1_COAST = COAST_FLANKS * N_GEARS + PINION
TABLE_G2_COAST = COAST_FLANKS * N_GEARS + GEAR
#: Rows of one gap table: the gap [mm] and its slope dG/dx [-] at the grid points.
TABLE_ROWS = ("gap_mm", "slope")
TABLE_GAP = TABLE_ROWS.index("gap_mm")
TABLE_SLOPE = TABLE_ROWS.index("slope")

# --------------------------------------------------------------------------------------------
# Constants derived once per run from the inputs (core/derive.py); saves divisions in the RHS.
# --------------------------------------------------------------------------------------------
DERIVED_NAMES = (
    "error_bound",  # largest overlap runout + tooth offsets add on either flank family [mm]
    "tooth_offsets_used",  # 1 when any per-tooth flank offset is non-zero, else 0
    "tooth_factors_used",  # 1 when per-tooth stiffness factors are given (tooth law), else 0
    "teeth_tracked",  # 1 when either needs the tooth index of every slot, else 0
    "inv_exponent_plus_1",  # 1/(e + 1) [-]
    "grid_step",  # gap-table spacing (x_hi - x_lo)/(n - 1) [mm]
    "inv_grid_step",  # [1/mm]
    "inv_p_b",  # [1/mm]
    "inv_r_b1",  # [1/mm]
    "inv_r_b2",  # [1/mm]
    "inv_J1",  # [1/(t*mm^2)]
    "inv_J2",  # [1/(t*mm^2)]
)
DerivedIndex = NamedTuple("DerivedIndex", [(n, int) for n in DERIVED_NAMES])
D = DerivedIndex(*range(len(DERIVED_NAMES)))
N_DERIVED = len(DERIVED_NAMES)

#: Constants of one flank family (``family[f, F.xxx]``, f in DRIVE_FLANKS, COAST_FLANKS), from
#: the parameters and the tables (core/derive.py). Per gear g (1 pinion, 2 gear): the table
#: rows are layout.N_GEARS * f + g - 1.
FAMILY_NAMES = (
    "phase0",  # slot phase s1_0 / s1c_0 [mm]
    "offset",  # 0 (drive) or the normal backlash j_n (coast) [mm]
    "tooth_k1",  # tooth index offsets of slot 0 (integer-valued)
    "tooth_k2",
    "phase1",  # runout phases on this family's line of action [rad]
    "phase2",
    "overlap",  # upper bound of -G1 - G2 - errors [mm] (derive.overlap_bound)
    "end_gap",  # lower bound of G1 + G2 with a position on a table end [mm]
    # [zero_lo, zero_hi]: roll positions [mm] where the gear's gap table is exactly zero
    "zero_lo1",
    "zero_hi1",
    "zero_lo2",
    "zero_hi2",
)
FamilyIndex = NamedTuple("FamilyIndex", [(n, int) for n in FAMILY_NAMES])
F = FamilyIndex(*range(len(FAMILY_NAMES)))
N_FAMILY = len(FAMILY_NAMES)
#: Where each family's phase0, offset, tooth indices and runout phases come from.
FAMILY_PARAMS = {
    "drive": (("phase0", "s1_0"), ("offset", None), ("tooth_k1", "tooth_k1"),
              ("tooth_k2", "tooth_k2"), ("phase1", "phase1"), ("phase2", "phase2")),
    "coast": (("phase0", "s1c_0"), ("offset", "backlash_n"), ("tooth_k1", "tooth_k1_coast"),
              ("tooth_k2", "tooth_k2_coast"), ("phase1", "phase1_coast"),
              ("phase2", "phase2_coast")),
}

# --------------------------------------------------------------------------------------------
# Sampled output columns (series[i, C.xxx]); names carry units.
# --------------------------------------------------------------------------------------------
COLUMN_NAMES = (
    "t_s",
    "theta1_rad",
    "omega1_rad_s",
    "theta2_rad",
    "omega2_rad_s",
    "delta_mm",  # DTE along the drive LoA, s1 - s2
    "deltadot_mm_s",
    "force_total_N",  # total normal force on the drive flanks (sum over pairs)
    "force_coast_N",  # total normal force on the coast flanks (sum over pairs)
    "pairs_in_contact",  # drive pairs with F > 0
    "pairs_in_contact_coast",
    "friction_force_N",  # SIGNED sum of friction forces mu(v_j) F_j, drive and coast
    "friction_power_mW",  # sum of f_j v_j [N*mm/s = mW], <= 0
    "drive_torque_Nmm",  # torque into the pinion (speed mode: the torque needed)
    "load_torque_Nmm",  # T_load(t)
    "kinetic_energy_mJ",  # 1/2 J w^2 + 1/2 m v^2 of every body [N*mm = mJ]
    "contact_energy_mJ",  # sum of k p^(e+1)/(e+1)
    "spring_energy_mJ",  # shafts and lateral bearings, sum of k q^2 / 2
    "work_in_mJ",  # integral of T_drive omega1
    "work_load_mJ",  # integral of T_load omega2
    "loss_bearing_mJ",  # load_cv, load_cq, c1, c2 losses
    "loss_damping_mJ",  # contact damping (IMPACT) dissipation
    "loss_friction_mJ",  # friction dissipation
    # lateral-torsional model: gear centre displacements and bearing forces
    "x1_mm",
    "y1_mm",
    "x2_mm",
    "y2_mm",
    "bearing_force_x1_N",  # force of the pinion on its bearings (k x + c xdot)
    "bearing_force_y1_N",
    "bearing_force_x2_N",  # of the gear
    "bearing_force_y2_N",
    # shafts
    "omega_motor_rad_s",
    "drive_shaft_torque_Nmm",  # torque the drive shaft applies to the pinion
    "omega_load_rad_s",
    "load_shaft_torque_Nmm",  # torque the load shaft takes from the gear
)
#: Columns that only mean something for some models: (column, needs) with needs one of
#: 'lateral', 'drive_shaft', 'load_shaft' (the pipeline leaves them out otherwise).
OPTIONAL_COLUMNS = {
    **{n: "lateral" for n in ("x1_mm", "y1_mm", "x2_mm", "y2_mm", "bearing_force_x1_N",
                               "bearing_force_y1_N", "bearing_force_x2_N",
                               "bearing_force_y2_N")},
    "omega_motor_rad_s": "drive_shaft",
    "drive_shaft_torque_Nmm": "drive_shaft",
    "omega_load_rad_s": "load_shaft",
    "load_shaft_torque_Nmm": "load_shaft",
}
ColumnIndex = NamedTuple("ColumnIndex", [(n, int) for n in COLUMN_NAMES])
C = ColumnIndex(*range(len(COLUMN_NAMES)))
N_COLUMNS = len(COLUMN_NAMES)

# --------------------------------------------------------------------------------------------
# Extrema over the accepted solver steps with t >= extrema_t_start (true extrema, NaN when
# no step fell in the window), plus two scalars of the run.
# --------------------------------------------------------------------------------------------
EXTREMA_NAMES = (
    "force_total_max_N",
    "force_total_max_t_s",
    "force_total_min_N",
    "force_total_min_t_s",
    "force_coast_max_N",
    "force_coast_max_t_s",
    "delta_max_mm",
    "delta_max_t_s",
    "delta_min_mm",
    "delta_min_t_s",
    "penetration_max_mm",
    "penetration_max_t_s",
    "bearing_force_max_1_N",  # largest |bearing force| of the pinion (lateral model)
    "bearing_force_max_2_N",  # of the gear
    "energy_initial_mJ",  # kinetic + contact + spring energy at t_start (E_0 of the energy balance)
    "t_reached_s",  # time the integration reached (t_end unless the status is an error)
)
ExtremaIndex = NamedTuple("ExtremaIndex", [(n, int) for n in EXTREMA_NAMES])
X = ExtremaIndex(*range(len(EXTREMA_NAMES)))
N_EXTREMA = len(EXTREMA_NAMES)

#: Rows of the per-slot scratch of one flank family (work.scratch[SC.xxx, m], m the m-th pair in
#: contact): what the tooth law's first pass over the slots keeps for the second (flank.py).
SCRATCH_NAMES = ("slot", "x1", "pen", "pdot", "dp1", "dp2", "k", "dk")
ScratchIndex = NamedTuple("ScratchIndex", [(n, int) for n in SCRATCH_NAMES])
SC = ScratchIndex(*range(len(SCRATCH_NAMES)))
N_SCRATCH = len(SCRATCH_NAMES)

#: Per-slot extrema rows of the drive slots (slot_extrema[SX.xxx, j]).
SLOT_EXTREMA_NAMES = ("force_max_N", "force_max_t_s", "force_min_N")
SlotExtremaIndex = NamedTuple("SlotExtremaIndex", [(n, int) for n in SLOT_EXTREMA_NAMES])
SX = SlotExtremaIndex(*range(len(SLOT_EXTREMA_NAMES)))
N_SLOT_EXTREMA = len(SLOT_EXTREMA_NAMES)

#: Solver counters (counters[N.xxx], int64).
COUNTER_NAMES = ("accepted_steps", "rejected_steps", "rhs_evaluations", "output_evaluations")
CounterIndex = NamedTuple("CounterIndex", [(n, int) for n in COUNTER_NAMES])
N = CounterIndex(*range(len(COUNTER_NAMES)))
N_COUNTERS = len(COUNTER_NAMES)

#: The ``resume`` vector that carries a run from one chunk to the next (timeloop.run):
#: started flag (0 = fresh start from the parameters), prescribed-angle offset [rad], next
#: step size [s], then the state (STATE_NAMES).
RESUME_NAMES = ("started", "theta_offset", "h")
ResumeIndex = NamedTuple("ResumeIndex", [(n, int) for n in RESUME_NAMES])
R = ResumeIndex(*range(len(RESUME_NAMES)))
RESUME_Y = len(RESUME_NAMES)
N_RESUME = RESUME_Y + N_STATE


def _layout_key() -> int:
    """Deterministic 62-bit checksum of every layout above (Python's hash() is salted)."""
    key = 1469598103934665603 % (1 << 62)
    layouts = (PARAM_NAMES, STATE_NAMES, AUX_NAMES, DERIVED_NAMES, FAMILY_NAMES, FLANK_FAMILIES,
               GEARS, TABLE_ROWS, COLUMN_NAMES, EXTREMA_NAMES, SLOT_EXTREMA_NAMES,
               COUNTER_NAMES, RESUME_NAMES, SCRATCH_NAMES, tuple(STATUS_MESSAGES))
    for text in repr(layouts):
        key = (key * 1099511628211 + ord(text)) % (1 << 62)
    return key



def _check_layouts() -> None:
    """Sizes come from one constant each; names are unique (run once at import, so a new table,
    family or name cannot silently share another's slot)."""
    for names in (PARAM_NAMES, STATE_NAMES, AUX_NAMES, DERIVED_NAMES, FAMILY_NAMES,
                  COLUMN_NAMES, EXTREMA_NAMES, COUNTER_NAMES, RESUME_NAMES, SCRATCH_NAMES):
        if len(set(names)) != len(names):
            raise RuntimeError(f"duplicate name in a kernel layout: {names}")
    if sorted(FAMILY_PARAMS) != sorted(FLANK_FAMILIES) or any(
            not {n for n, _ in v} <= set(FAMILY_NAMES) for v in FAMILY_PARAMS.values()):
        raise RuntimeError("FAMILY_PARAMS must name every flank family and only FAMILY_NAMES")
    if any(src is not None and src not in PARAM_NAMES
           for v in FAMILY_PARAMS.values() for _, src in v):
        raise RuntimeError("FAMILY_PARAMS refers to an unknown parameter")


_check_layouts()

#: Checksum of the layouts, compiled into the kernel and compared at run time.
LAYOUT_KEY = _layout_key()


def make_params(**values: float) -> np.ndarray:
    """Parameter vector from keyword values (internal units, see ``PARAM_UNITS``).

    Missing optional names take ``PARAM_DEFAULTS``; a missing required name or an unknown
    name raises ``KeyError`` naming it.
    """
    unknown = sorted(set(values) - set(PARAM_NAMES))
    if unknown:
        raise KeyError(f"unknown kernel parameter(s): {', '.join(unknown)}")
    missing = [n for n in PARAM_NAMES if n not in values and n not in PARAM_DEFAULTS]
    if missing:
        raise KeyError(f"missing kernel parameter(s): {', '.join(missing)}")
    merged = {**PARAM_DEFAULTS, **values}
    return np.array([float(merged[n]) for n in PARAM_NAMES], dtype=np.float64)


def params_dict(params: np.ndarray) -> dict[str, float]:
    """The parameter vector as ``{name: value}`` (for manifests and messages)."""
    return {n: float(params[i]) for i, n in enumerate(PARAM_NAMES)}
