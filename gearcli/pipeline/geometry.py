"""`gearcli geometry`: checked pair geometry, mass properties and mesh frequencies of a case."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from gearcli.case.build import mass_inputs, nominal_pinion_speed, pair_spec
from gearcli.case.inspection import PairInspection, pair_inspection
from gearcli.case.load import LoadedCase, load_case
from gearcli.model.frequencies import mesh_frequencies
from gearcli.model.geometry import Finding, PairGeometry, compute_pair_geometry
from gearcli.model.params import MassProperties, gear_mass_properties


@dataclass(frozen=True)
class GeometryResult:
    """Everything `gearcli geometry` reports, in internal units."""

    name: str
    geometry: PairGeometry
    mass: tuple[MassProperties, MassProperties]  #: (pinion, gear)
    pinion_speed_rad_s: float | None
    warnings: tuple[Finding, ...]
    #: span, balls, M_dK, chordal thickness/height (None where the closed forms do not apply)
    inspection: PairInspection | None = None

    def to_dict(self) -> dict:
        """What ``gearcli geometry --json`` prints (:func:`geometry_dict`; key names carry
        their units)."""
        return geometry_dict(self)

    def __repr__(self) -> str:  # engineering units (gearcli/display_units.py), labelled
        g = self.geometry
        return (f"<Geometry {self.name}: {g.pinion.teeth}/{g.gear.teeth} teeth, module "
                f"{g.module_mm:g} mm, centre distance {g.a_w_mm:.4g} mm, transverse contact "
                f"ratio ε_α {g.eps_alpha:.4g}, {len(self.warnings)} warning(s)>")


# Which case key an error finding is about, by code (and gear, where it names one).
_FINDING_KEYS = {
    "pressure_angle": ("gears", "pressure_angle"),
    "contact_ratio": ("gears", "centre_distance"),
    "centre_distance": ("gears", "centre_distance"),
    "interference": ("gears", "{gear}", "teeth"),  # or its profile shift: _interference_key
    "undercut": ("gears", "{gear}", "profile_shift"),
    "pointed_tip": ("gears", "{gear}", "profile_shift"),
    "clearance": ("gears", "{gear}", "tip_shortening"),
    "root_diameter": ("gears", "{gear}", "profile_shift"),
    "tip_diameter": ("gears", "{gear}", "profile_shift"),
    "tip_rounding": ("gears", "{gear}", "tip_rounding"),
}


# Other keys that change what a finding checks: when a --set changed one of them (and not the
# key above), the error names that override, the user's edit ("{gear}": the finding's gear).
_FINDING_LEVERS = {
    "pointed_tip": (("gears", "{gear}", "thickness_allowance"), ("gears", "{gear}", "teeth"),
                    ("gears", "module"), ("gears", "rack", "addendum")),
    "undercut": (("gears", "{gear}", "teeth"), ("gears", "rack", "dedendum")),
    "interference": (("gears", "rack", "addendum"), ("gears", "rack", "dedendum"),
                     ("gears", "pinion", "profile_shift"), ("gears", "gear", "profile_shift"),
                     ("gears", "pinion", "tip_shortening"), ("gears", "gear", "tip_shortening"),
                     ("gears", "module")),
    "centre_distance": (("gears", "pinion", "profile_shift"), ("gears", "gear", "profile_shift"),
                        ("gears", "pinion", "teeth"), ("gears", "gear", "teeth"),
                        ("gears", "module")),
    "contact_ratio": (("gears", "pinion", "profile_shift"), ("gears", "gear", "profile_shift"),
                      ("gears", "pinion", "tip_shortening"), ("gears", "gear", "tip_shortening"),
                      ("gears", "pinion", "teeth"), ("gears", "gear", "teeth")),
}


# When several errors hold, report the root cause first (a wrong centre distance also breaks
# clearance and contact ratio).
_ROOT_CAUSE_ORDER = [
    "pressure_angle",
    "centre_distance",
    "root_diameter",
    "tip_diameter",
    "interference",
    "contact_ratio",
    "pointed_tip",
    "tip_rounding",
    "clearance",
]


def refuse_reverse_drive(loaded: LoadedCase) -> None:
    """A reverse drive (negative pinion speed or drive torque) is refused with its key.

    gearcli's conventions (docs/theory.md §1) have the pinion turning forward: frequencies,
    drive/coast flanks and the window all assume it. A reverse run is the mirror image of a
    forward one: give the speed (torque) as a positive value.
    """
    d = loaded.case.drive
    for key, fn in (("speed", d.speed), ("torque", d.torque)):
        if fn is None:
            continue
        pp = fn.pp
        times = [0.0, *pp.breakpoints]
        low = min(float(pp(t)) for t in times)
        final = pp.final_value()
        if low < 0.0 or (final is not None and final < 0.0):
            raise loaded.error_at(("drive", key), f"a reverse drive (negative {key}) is not "
                                  f"supported; expected a {key} >= 0 (the pinion turns "
                                  "forward: a reverse run is the mirror image of a forward one)")
    if d.initial_speed < 0.0:
        raise loaded.error_at(("drive", "initial_speed"), "a reverse drive (negative speed) is "
                              "not supported; expected initial_speed >= 0")


def run_geometry(source: str | Path | LoadedCase) -> GeometryResult:
    """Load (if needed) and check the case's geometry; geometry errors raise a located CaseError."""
    loaded = source if isinstance(source, LoadedCase) else load_case(source)
    case = loaded.case
    refuse_reverse_drive(loaded)
    try:
        geo = compute_pair_geometry(pair_spec(case))
    except ValueError as exc:  # impossible input the schema cannot see (e.g. a rack that
        raise loaded.error(("gears",), f"impossible geometry: {exc}") from None  # cannot exist)
    errors = sorted(
        (f for f in geo.findings if f.severity == "error"),
        key=lambda f: _ROOT_CAUSE_ORDER.index(f.code) if f.code in _ROOT_CAUSE_ORDER else 99,
    )
    if errors:
        raise _located(loaded, errors[0], len(errors) - 1)
    check_relief_extents(loaded, geo)
    check_bores(loaded, geo)
    check_runout(loaded, geo)
    check_faults(loaded, geo)
    pinion_in, gear_in = mass_inputs(case)
    mass = tuple(
        gear_mass_properties(
            m.model,
            m.density_t_mm3,
            m.diameter_mm,
            gg.d_mm,
            gg.face_width_mm,
            m.inertia_t_mm2,
            m.mass_t,
            m.extra_inertia_t_mm2,
            m.bore_diameter_mm,
        )
        for m, gg in ((pinion_in, geo.pinion), (gear_in, geo.gear))
    )
    warnings = tuple(f for f in geo.findings if f.severity == "warning")
    try:
        inspection = pair_inspection(case, geo)
    except ValueError:  # e.g. no ball that touches within the tooth: no inspection section
        inspection = None
    return GeometryResult(loaded.name, geo, mass, nominal_pinion_speed(case), warnings,
                          inspection)


def check_relief_extents(loaded: LoadedCase, geo: PairGeometry) -> None:
    """A profile relief must start on the active flank: a length shorter than the path of
    contact g_alpha, a start diameter between the active profile start d_Nf and the tip d_a
    (model.gap measures it from the end of the path it grows towards); a tip relief must leave
    a tip (below s_a cos α_a / 2)."""
    for kind in ("tip_relief", "root_relief"):
        for role in ("pinion", "gear"):
            relief = getattr(getattr(loaded.case.modifications, kind), role)
            if relief is None:
                continue
            gg = getattr(geo, role)
            if relief.length is not None and relief.length >= geo.g_alpha_mm:
                loc = ("modifications", kind, role, "length")
                raise loaded.error_at(loc, f"a relief {relief.length:g} mm long does not start on "
                                      f"the path of contact, which is g_alpha = "
                                      f"{geo.g_alpha_mm:.4g} mm long; expected < "
                                      f"{geo.g_alpha_mm:.4g} mm")
            # a tip relief C_a (normal to the profile, both flanks: the coast flank mirrors the
            # drive flank) thins the tip's arc thickness by 2 C_a / cos α_a (ds_y = dC / cos α_y,
            # ISO 21771's thickness at a radius): at C_a >= s_a cos α_a / 2 no tip is left
            most = 0.5 * gg.s_a_mm * gg.d_b_mm / gg.d_a_mm
            if kind == "tip_relief" and relief.amount >= most:
                loc = ("modifications", kind, role, "amount")
                raise loaded.error_at(loc, f"a tip relief of {relief.amount:g} mm leaves no tip: "
                                      f"the reliefs of both flanks meet at C_a = s_a cos α_a / 2 = "
                                      f"{most:.4g} mm ({role} tip thickness s_a = "
                                      f"{gg.s_a_mm:.4g} mm); expected less (tip reliefs are "
                                      "typically tens of µm)")
            d = relief.start_diameter
            if d is not None and not gg.d_Nf_mm < d < gg.d_a_mm:
                loc = ("modifications", kind, role, "start_diameter")
                raise loaded.error_at(loc, f"{d:g} mm is off the {role}'s active flank; expected "
                                      f"between its active profile start d_Nf = {gg.d_Nf_mm:.4g} "
                                      f"mm and its tip d_a = {gg.d_a_mm:.4g} mm")


def check_bores(loaded: LoadedCase, geo: PairGeometry) -> None:
    """A bore lies inside the root circle: below the teeth there is a rim (or a hub)."""
    for role in ("pinion", "gear"):
        bore, d_f = getattr(loaded.case.gears, role).bore_diameter, getattr(geo, role).d_f_mm
        if bore is not None and bore >= d_f:
            loc = ("gears", role, "bore_diameter")
            raise loaded.error_at(loc, f"the bore must lie inside the root circle (a rim below "
                                  f"the teeth): expected < d_f = {d_f:.4g} mm")


#: Largest runout eccentricity, in modules: the centre distance varies by +-e, and a quarter
#: module takes the teeth out of the small-displacement contact the gap tables describe (ISO
#: 1328-2 runout tolerances F_r stay below ~0.02 m even in grade 11).
RUNOUT_MAX_MODULES = 0.25


def check_runout(loaded: LoadedCase, geo: PairGeometry) -> None:
    runout = loaded.case.errors.runout
    limit = RUNOUT_MAX_MODULES * geo.module_mm
    for role in ("pinion", "gear"):
        r = getattr(runout, role)
        if r is not None and r.eccentricity >= limit:
            loc = ("errors", "runout", role, "eccentricity")
            raise loaded.error_at(loc, f"a runout eccentricity of {RUNOUT_MAX_MODULES:g} module "
                                  "and more takes the teeth out of mesh contact (ISO 1328-2 "
                                  "runout tolerances are below ~0.02 m); expected < "
                                  f"{limit:.4g} mm")


def check_faults(loaded: LoadedCase, geo: PairGeometry) -> None:
    """A tooth fault must lie on its tooth (docs/theory.md, "Tooth faults"): a root crack that
    stops short of the other flank (the fault model's cracked section exists), a spall centred
    on the active flank, between the active profile start d_Nf and the tip d_a (inside the base
    circle there is no involute; beyond the flank the spall would change nothing, and the run
    would be the healthy pair's)."""
    if not loaded.case.faults:  # the fault model imports scipy.interpolate (~0.4 s)
        return
    from gearcli.case.schema_faults import RootCrackFault, SpallFault
    from gearcli.model.faults.factors import crack_section

    for i, fault in enumerate(loaded.case.faults):
        gg = getattr(geo, fault.gear)
        if isinstance(fault, RootCrackFault) and fault.depth > 0.0:
            try:
                crack_section(gg, fault.depth, math.degrees(fault.angle))
            except ValueError as exc:
                raise loaded.error_at(("faults", i, "depth"), f"{exc}; expected a crack that "
                                      "ends inside the tooth (a shorter depth or a smaller angle "
                                      "to the centreline), or a missing_tooth fault") from None
        if isinstance(fault, SpallFault):
            key = "diameter" if fault.diameter is not None else "roll_angle"
            d = fault.diameter if fault.diameter is not None else 2.0 * math.hypot(
                gg.r_b_mm, gg.r_b_mm * fault.roll_angle)  # involute: rho = r_b x roll angle
            if not gg.d_Nf_mm <= d <= gg.d_a_mm:
                raise loaded.error_at(("faults", i, key), f"the spall's centre at d = {d:.6g} mm "
                                      f"is off the {fault.gear}'s active flank; expected between "
                                      f"its active profile start d_Nf = {gg.d_Nf_mm:.6g} mm and "
                                      f"its tip d_a = {gg.d_a_mm:.6g} mm")


def _interference_key(loaded: LoadedCase, gear: str) -> tuple[str, ...]:
    """The key an interference error names: the gear's profile shift when a --set changed it
    (and not its teeth), else its teeth. Which value of a file the user edited is unknown, so
    a file's error names the teeth, the lever with the larger effect; the message names both."""
    shift, teeth = (("gears", gear, key) for key in ("profile_shift", "teeth"))
    overridden = loaded.source.overridden
    return shift if shift in overridden and teeth not in overridden else teeth


def _located(loaded: LoadedCase, finding: Finding, more: int):
    keys = _FINDING_KEYS.get(finding.code, ("gears",))
    gear = finding.subject or "pinion"
    loc = tuple(k.format(gear=gear) for k in keys)
    if finding.code == "interference":
        loc = _interference_key(loaded, gear)
    if loc[-1] == "centre_distance" and loaded.case.gears.centre_distance is None:
        loc = ("gears",)
    overridden = loaded.source.overridden
    if loc not in overridden:
        levers = (tuple(k.format(gear=gear) for k in lever)
                  for lever in _FINDING_LEVERS.get(finding.code, ()))
        loc = next((lever for lever in levers if lever in overridden), loc)
    text = finding.message + (f" (+{more} more)" if more else "")
    return loaded.error_at(loc, text)


def geometry_dict(result: GeometryResult) -> dict:
    """JSON-ready dict; key names carry their units."""
    g = result.geometry
    deg = math.degrees

    def gear(gg, mp) -> dict:
        return {
            "z": gg.teeth,
            "module_mm": gg.module_mm,
            "pressure_angle_deg": deg(gg.pressure_angle_rad),
            "profile_shift": gg.profile_shift,
            "face_width_mm": gg.face_width_mm,
            "d_mm": gg.d_mm,
            "d_b_mm": gg.d_b_mm,
            "d_a_mm": gg.d_a_mm,
            "d_f_mm": gg.d_f_mm,
            "d_w_mm": gg.d_w_mm,
            "d_Ff_mm": gg.d_Ff_mm,
            "d_Nf_mm": gg.d_Nf_mm,
            "s_mm": gg.s_mm,
            "s_a_mm": gg.s_a_mm,
            "p_b_mm": gg.p_b_mm,
            "tip_clearance_mm": gg.tip_clearance_mm,
            "root_clearance_mm": gg.root_clearance_mm,
            "x_min_undercut": gg.x_min,
            "z_min_undercut": gg.z_min,
            "undercut": gg.undercut,
            "undercut_mm": gg.undercut_mm,
            "mass_kg": mp.mass_t * 1e3,  # t -> kg
            "inertia_kg_m2": mp.inertia_t_mm2 * 1e-3,  # t*mm^2 -> kg*m^2
        }

    pair = {
        "a_mm": g.a_mm,
        "a_w_mm": g.a_w_mm,
        "alpha_w_deg": deg(g.alpha_w_rad),
        "backlash_normal_mm": g.j_n_mm,
        "backlash_circumferential_mm": g.j_wt_mm,
        "ratio": g.ratio,
        "T1T2_mm": g.T1T2_mm,
        "path_of_contact_mm": g.g_alpha_mm,
        "T1A_mm": g.A_mm,
        "T1B_mm": g.B_mm,
        "T1C_mm": g.C_mm,
        "T1D_mm": g.D_mm,
        "T1E_mm": g.E_mm,
        "contact_ratio": g.eps_alpha,
        "single_contact_fraction": g.single_contact_fraction,
        "double_contact_fraction": g.double_contact_fraction,
    }
    w = result.pinion_speed_rad_s
    if w is not None:
        f_z, n1, n2 = mesh_frequencies(g.pinion.teeth, w, g.ratio)
        pair.update(
            pinion_speed_deg_s=deg(w),
            gear_mesh_frequency_Hz=f_z,
            pinion_shaft_frequency_Hz=n1,
            gear_shaft_frequency_Hz=n2,
        )
    return {
        "case": result.name,
        "pinion": gear(g.pinion, result.mass[0]),
        "gear": gear(g.gear, result.mass[1]),
        "pair": pair,
        "inspection": None if result.inspection is None else result.inspection.to_dict(),
        "warnings": [
            {"code": f.code, "subject": f.subject, "message": f.message} for f in result.warnings
        ],
    }


def save_geometry_plot(result: GeometryResult, path: str | Path) -> None:
    """Draw the pair in mesh and write it atomically (.png, .svg or .pdf)."""
    from gearcli.io.files import save_figure
    from gearcli.plotting.geometry import plot_pair

    save_figure(plot_pair(result.geometry, title=f"{result.name}: spur pair in mesh"), path, 150)
