"""Spur gear pair geometry (ISO 21771 / DIN 3960 quantities) and its feasibility findings.

Input: :class:`PairSpec` (module, pressure angle, two :class:`GearSpec`, basic rack, optional
operating centre distance). Output: :class:`PairGeometry` with two :class:`GearGeometry`,
line-of-action points, contact ratio, backlash and a tuple of :class:`Finding`.
Invalid numbers raise ``ValueError``; a pair that cannot exist or cannot run is *reported*
through findings (severity "error" or "warning"), never raised, so callers can show all
problems at once. Units: mm, rad; coefficients in units of the module (the shaft and mesh
frequencies: gearcli/model/frequencies.py).

References
----------
ISO 21771:2007 Cylindrical involute gears and gear pairs — Concepts and geometry.
DIN 3960:1987 Begriffe und Bestimmungsgrößen für Stirnräder mit Evolventenverzahnung.
ISO 53:1998 Standard basic rack tooth profile.
ISO/TR 10064-2:1996 (backlash j_bn = j_wt cos α_wt for spur gears).
G. Niemann, H. Winter, *Maschinenelemente* Bd. II, 2. Aufl., Springer 1989 (spur gear geometry).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from numbers import Real
from typing import Literal

from gearcli.model import profile
from gearcli.model.involute import half_thickness_angle, inv, inv_inverse
from gearcli.model.toothform import RackSpec, ToothForm

__all__ = ["RackSpec", "GearSpec", "PairSpec", "Finding", "GearGeometry", "PairGeometry",
           "compute_pair_geometry"]


@dataclass(frozen=True)
class GearSpec:
    """One gear of the pair (input)."""

    teeth: int  #: z
    face_width_mm: float  #: b [mm]
    profile_shift: float = 0.0  #: x
    tip_shortening_coef: float = 0.0  #: k: d_a = d + 2m(h_aP* + x − k)
    thickness_allowance_mm: float = 0.0  #: reduction of s at the reference circle [mm], >= 0
    tip_rounding_mm: float = 0.0  #: tip rounding radius ρ_a [mm] (0 = sharp corner)


@dataclass(frozen=True)
class PairSpec:
    """A spur gear pair (input). ``centre_distance_mm=None``: zero-backlash a_w from x1 + x2."""

    module_mm: float
    pressure_angle_rad: float
    pinion: GearSpec
    gear: GearSpec
    rack: RackSpec = RackSpec()
    centre_distance_mm: float | None = None


@dataclass(frozen=True)
class Finding:
    """A feasibility problem: one line naming the quantity, its value and what is allowed."""

    severity: Literal["error", "warning"]
    code: str
    message: str
    subject: Literal["pinion", "gear"] | None = None  #: the gear concerned; None: the pair


@dataclass(frozen=True)
class GearGeometry(ToothForm):
    """Geometry of one gear in the pair. Diameters d_* [mm]; see the docstring of each field.

    Extends the gear's :class:`~gearcli.model.toothform.ToothForm` (teeth, module, pressure
    angle, profile shift, allowance, tip rounding, rack, d, d_b, d_a, d_f, s, undercut), so it
    can be passed to every :mod:`gearcli.model.profile` function. Pair-dependent fields (d_w,
    d_Nf, clearances) refer to the operating centre distance a_w; they are NaN when a_w admits
    no operating pressure angle.
    """

    tip_shortening_coef: float  #: k
    face_width_mm: float  #: b [mm]
    s_a_mm: float  #: arc tooth thickness at the tip circle (sharp corner) [mm]
    p_b_mm: float  #: base pitch p_b = π m cos α
    x_min: float  #: smallest shift without undercut (undercut: x < x_min)
    z_min: float  #: smallest tooth count without undercut at this x
    undercut_coef: float  #: x_min − x when undercut, else 0 (module units)
    undercut_mm: float  #: undercut_coef · m [mm]
    d_Ff_mm: float  #: root form diameter: start of the generated involute
    d_Fa_mm: float  #: tip form diameter: end of the involute (d_a unless rounded/pointed)
    d_w_mm: float  #: operating pitch diameter 2 a_w z / (z1 + z2)
    d_Nf_mm: float  #: active profile start (where the mate's tip contacts)
    tip_clearance_mm: float  #: a_w − r_a − r_f(mate): this tip to the mate's root
    root_clearance_mm: float  #: a_w − r_a(mate) − r_f: mate's tip to this root

    r_w_mm = property(lambda self: 0.5 * self.d_w_mm, doc="Operating pitch radius [mm].")


@dataclass(frozen=True)
class PairGeometry:
    """Geometry of the pair at its operating centre distance.

    Points on the line of action are distances from T1 (pinion base-circle tangency) [mm]:
    A start of active contact (mate's tip), B = E − p_b, C pitch point, D = A + p_b, E end of
    contact (pinion tip). ``pair_fractions`` lists (number of pairs in contact, fraction of a
    mesh period): ε_α = n + f gives n + 1 pairs during f and n pairs during 1 − f.
    """

    pinion: GearGeometry
    gear: GearGeometry
    module_mm: float  #: m [mm]
    pressure_angle_rad: float  #: α [rad]
    a_mm: float  #: reference centre distance m (z1 + z2)/2 [mm]
    a_w_mm: float  #: operating centre distance [mm]
    a_w_zero_backlash_mm: float  #: a_w giving zero backlash with the allowances [mm]
    alpha_w_rad: float  #: operating pressure angle [rad]
    j_wt_mm: float  #: circumferential backlash on the operating pitch circle [mm]
    j_n_mm: float  #: normal backlash along the line of action j_wt cos α_w [mm]
    ratio: float  #: i = z2 / z1
    T1T2_mm: float  #: length of the line of action a_w sin α_w [mm]
    g_alpha_mm: float  #: path of contact |AE| [mm]
    A_mm: float
    B_mm: float
    C_mm: float
    D_mm: float
    E_mm: float
    eps_alpha: float  #: transverse contact ratio g_α / p_b
    pair_fractions: tuple[tuple[int, float], ...]  #: ((pairs, fraction of time), ...)
    single_contact_fraction: float  #: fraction of time with exactly one pair in contact
    double_contact_fraction: float  #: fraction of time with exactly two pairs in contact
    findings: tuple[Finding, ...]

    errors = property(lambda self: tuple(f for f in self.findings if f.severity == "error"),
                      doc="Findings with severity 'error'.")
    warnings = property(lambda self: tuple(f for f in self.findings if f.severity == "warning"),
                        doc="Findings with severity 'warning'.")
    p_b_mm = property(lambda self: self.pinion.p_b_mm, doc="Base pitch [mm].")
    narrow_face_width_mm = property(
        lambda self: min(self.pinion.face_width_mm, self.gear.face_width_mm),
        doc="The narrower face width b = min(b1, b2) [mm]: the width in contact (ISO 6336-1).")

    def line_of_action_points(self) -> dict[str, float]:
        """Points T1, A, B, C, D, E, T2 as distances from T1 [mm]."""
        return {"T1": 0.0, "A": self.A_mm, "B": self.B_mm, "C": self.C_mm,
                "D": self.D_mm, "E": self.E_mm, "T2": self.T1T2_mm}


def _check_finite(name: str, value: float, *, positive: bool = False, nonneg: bool = False):
    """Raise ValueError unless value is a finite real (> 0 / >= 0 when asked)."""
    ok = isinstance(value, Real) and not isinstance(value, bool) and math.isfinite(value)
    if not ok or (positive and value <= 0.0) or (nonneg and value < 0.0):
        need = " > 0" if positive else " >= 0" if nonneg else ""
        raise ValueError(f"{name} must be a finite number{need}, got {value!r}")


def _validate(spec: PairSpec) -> None:
    """Raise ValueError for numbers no gear can have (the schema normally catches these)."""
    _check_finite("module_mm", spec.module_mm, positive=True)
    _check_finite("pressure_angle_rad", spec.pressure_angle_rad)
    if not 0.0 < spec.pressure_angle_rad < 0.25 * math.pi:
        raise ValueError(
            f"pressure_angle_rad must lie in (0, pi/4), got {spec.pressure_angle_rad!r}"
        )
    rack = spec.rack
    _check_finite("rack.addendum_coef", rack.addendum_coef, positive=True)
    _check_finite("rack.dedendum_coef", rack.dedendum_coef, positive=True)
    _check_finite("rack.root_radius_coef", rack.root_radius_coef, nonneg=True)
    # tool tip rounding must fit on the tool tooth (ξ_c >= 0, see profile._cutter):
    # ρ* (1 − sin α)/cos α <= π/4 − h_fP* tan α
    a = spec.pressure_angle_rad
    rho_max = (0.25 * math.pi - rack.dedendum_coef * math.tan(a)) * math.cos(a) / (1 - math.sin(a))
    if rack.root_radius_coef > rho_max:
        raise ValueError(
            f"rack.root_radius_coef = {rack.root_radius_coef:g} does not fit the rack tooth; "
            f"allowed: <= {rho_max:.4f} for h_fP* = {rack.dedendum_coef:g}, alpha = {a:.4f} rad"
        )
    for role, g in (("pinion", spec.pinion), ("gear", spec.gear)):
        z = g.teeth
        if isinstance(z, bool) or not isinstance(z, Real) or z != int(z) or z < 1:
            raise ValueError(f"{role}.teeth must be an integer >= 1, got {z!r}")
        _check_finite(f"{role}.face_width_mm", g.face_width_mm, positive=True)
        _check_finite(f"{role}.profile_shift", g.profile_shift)
        _check_finite(f"{role}.tip_shortening_coef", g.tip_shortening_coef)
        _check_finite(f"{role}.thickness_allowance_mm", g.thickness_allowance_mm, nonneg=True)
        _check_finite(f"{role}.tip_rounding_mm", g.tip_rounding_mm, nonneg=True)
    if spec.centre_distance_mm is not None:
        _check_finite("centre_distance_mm", spec.centre_distance_mm, positive=True)


def _gear_alone(
    g: GearSpec, m: float, alpha: float, rack: RackSpec
) -> tuple[ToothForm, dict[str, float]]:
    """Quantities of one gear that do not depend on the mate (ISO 21771, DIN 3960).

    Returns the gear's tooth form and, by name, the other :class:`GearGeometry` fields that do
    not depend on the mate (the form diameters d_Ff, d_Fa from the generated profile; NaN when
    there is no tooth to generate or the tip rounding does not fit: the findings report both).
    """
    z, x = int(g.teeth), g.profile_shift
    d = m * z
    d_b = d * math.cos(alpha)
    d_a = d + 2.0 * m * (rack.addendum_coef + x - g.tip_shortening_coef)
    d_f = d - 2.0 * m * (rack.dedendum_coef - x)
    s = m * (0.5 * math.pi + 2.0 * x * math.tan(alpha)) - g.thickness_allowance_mm
    # tip thickness s_a = d_a (s/d + inv α − inv α_a) (ISO 21771); none below d_b
    s_a = d_a * half_thickness_angle(s, d, alpha, 0.5 * d_a) if d_a > d_b else math.nan
    # undercut limit with the height of the straight tool flank above the reference line,
    # h* = h_fP* − ρ_fP* (1 − sin α) (≈ 1.0 for ISO 53 A); no undercut while the flank end stays
    # inside the interference point: h* − x <= z sin²α / 2 (Niemann/Winter II, undercut limit)
    h_lim = rack.dedendum_coef - rack.root_radius_coef * (1.0 - math.sin(alpha))
    sin2 = math.sin(alpha) ** 2
    x_min = h_lim - 0.5 * z * sin2
    z_min = 2.0 * (h_lim - x) / sin2
    undercut = x < x_min - 1e-12
    cut = max(x_min - x, 0.0) if undercut else 0.0
    form = ToothForm(
        teeth=z, module_mm=m, pressure_angle_rad=alpha, profile_shift=x,
        thickness_allowance_mm=g.thickness_allowance_mm, tip_rounding_mm=g.tip_rounding_mm,
        rack=rack, d_mm=d, d_b_mm=d_b, d_a_mm=d_a, d_f_mm=d_f, s_mm=s, undercut=undercut,
    )
    d_ff = d_fa = math.nan  # stay NaN without a tooth to generate: reported by the findings
    if not (d_f <= 0.0 or d_a <= d_b):
        d_ff = 2.0 * profile.root_form_radius(form)
        try:
            d_fa = 2.0 * profile.tip_form_radius(form)
        except ValueError:  # tip rounding does not fit: reported by the findings
            pass
    return form, {
        "tip_shortening_coef": g.tip_shortening_coef, "face_width_mm": g.face_width_mm,
        "s_a_mm": s_a, "p_b_mm": math.pi * m * math.cos(alpha), "x_min": x_min, "z_min": z_min,
        "undercut_coef": cut, "undercut_mm": cut * m, "d_Ff_mm": d_ff, "d_Fa_mm": d_fa,
    }


def _form_fields(form: ToothForm) -> dict[str, object]:
    """The fields of a tooth form by name (not deep-copied: the rack stays a RackSpec)."""
    return {f.name: getattr(form, f.name) for f in fields(ToothForm)}


def _sqrt(value: float) -> float:
    """√value, NaN for negative input (geometry that does not exist)."""
    return math.sqrt(value) if value >= 0.0 else math.nan


def _contact_fractions(eps: float) -> tuple[tuple[tuple[int, float], ...], float, float]:
    """Time fractions with n and n + 1 pairs for ε_α = n + f; single and double fractions."""
    if not math.isfinite(eps) or eps < 0.0:
        return (), math.nan, math.nan
    n = math.floor(eps)
    f = eps - n
    fractions = ((n, 1.0 - f), (n + 1, f)) if f > 0.0 else ((n, 1.0),)
    by_count = dict(fractions)
    return fractions, by_count.get(1, 0.0), by_count.get(2, 0.0)


def compute_pair_geometry(spec: PairSpec) -> PairGeometry:
    """Geometry, line of action, contact ratio, backlash and findings of a spur gear pair.

    Parameters
    ----------
    spec : PairSpec
        Module m [mm], pressure angle α [rad], the two gears, the basic rack and optionally
        the operating centre distance a_w [mm].

    Returns
    -------
    PairGeometry
        All quantities in mm/rad; ``findings`` lists errors and warnings.

    Raises
    ------
    ValueError
        For invalid numbers (z < 1, m <= 0, α outside (0, π/4), ...).

    Notes
    -----
    ISO 21771:2007 / DIN 3960:
    a = m (z1 + z2)/2; zero-backlash inv α_w = inv α + 2 (x1 + x2) tan α / (z1 + z2) (allowances
    excluded: they create backlash); a_w cos α_w = a cos α; d_w = 2 a_w z / (z1 + z2);
    s_w = d_w (s/d + inv α − inv α_w); j_wt = π d_w / z − s_w1 − s_w2; j_n = j_wt cos α_w
    (ISO/TR 10064-2). Line of action T1T2 = a_w sin α_w; T1E = √(r_a1² − r_b1²),
    T1A = T1T2 − √(r_a2² − r_b2²), T1C = r_b1 tan α_w, ε_α = (E − A)/p_b, with r_a replaced by
    the tip form radius when the tip is rounded or pointed (contact leaves the involute there).
    """
    _validate(spec)
    m, alpha = spec.module_mm, spec.pressure_angle_rad
    f1, more1 = _gear_alone(spec.pinion, m, alpha, spec.rack)
    f2, more2 = _gear_alone(spec.gear, m, alpha, spec.rack)
    z_sum = f1.teeth + f2.teeth
    a = 0.5 * m * z_sum
    tan_a, inv_a = math.tan(alpha), inv(alpha)
    x_sum = f1.profile_shift + f2.profile_shift
    inv_w0 = inv_a + 2.0 * x_sum * tan_a / z_sum
    a_w0 = a * math.cos(alpha) / math.cos(inv_inverse(inv_w0)) if inv_w0 >= 0 else math.nan
    # zero backlash with the thickness allowances: s1 + s2 = π m + m z_sum (inv α_w − inv α)
    inv_wj = inv_a + (f1.s_mm + f2.s_mm - math.pi * m) / (m * z_sum)
    a_wj = a * math.cos(alpha) / math.cos(inv_inverse(inv_wj)) if inv_wj >= 0 else math.nan
    a_w = a_w0 if spec.centre_distance_mm is None else float(spec.centre_distance_mm)
    cos_w = a * math.cos(alpha) / a_w if math.isfinite(a_w) else math.nan
    alpha_w = math.acos(cos_w) if 0.0 < cos_w <= 1.0 else math.nan
    inv_w = inv(alpha_w) if math.isfinite(alpha_w) else math.nan

    d_w1, d_w2 = 2.0 * a_w * f1.teeth / z_sum, 2.0 * a_w * f2.teeth / z_sum
    s_w1 = d_w1 * (f1.s_mm / f1.d_mm + inv_a - inv_w)
    s_w2 = d_w2 * (f2.s_mm / f2.d_mm + inv_a - inv_w)
    j_wt = math.pi * d_w1 / f1.teeth - s_w1 - s_w2
    if abs(j_wt) < 1e-12 * a_w:  # rounding of an exact zero-backlash mesh
        j_wt = 0.0
    j_n = j_wt * math.cos(alpha_w)

    p_b = more1["p_b_mm"]
    t1t2 = a_w * math.sin(alpha_w)
    e_pt = _sqrt((0.5 * more1["d_Fa_mm"]) ** 2 - f1.r_b_mm**2)
    a_pt = t1t2 - _sqrt((0.5 * more2["d_Fa_mm"]) ** 2 - f2.r_b_mm**2)
    c_pt = f1.r_b_mm * math.tan(alpha_w)
    g_alpha = e_pt - a_pt
    eps = g_alpha / p_b
    fractions, single, double = _contact_fractions(eps)

    def active_start(rb: float, roll_len: float) -> float:  # d_Nf from the mate's tip point
        if math.isnan(roll_len):
            return math.nan
        return 2.0 * math.hypot(rb, roll_len) if roll_len >= 0.0 else 2.0 * rb  # beyond T: d_b

    g1 = GearGeometry(
        **_form_fields(f1), **more1, d_w_mm=d_w1, d_Nf_mm=active_start(f1.r_b_mm, a_pt),
        tip_clearance_mm=a_w - f1.r_a_mm - f2.r_f_mm,
        root_clearance_mm=a_w - f2.r_a_mm - f1.r_f_mm,
    )
    g2 = GearGeometry(
        **_form_fields(f2), **more2, d_w_mm=d_w2, d_Nf_mm=active_start(f2.r_b_mm, t1t2 - e_pt),
        tip_clearance_mm=a_w - f2.r_a_mm - f1.r_f_mm,
        root_clearance_mm=a_w - f1.r_a_mm - f2.r_f_mm,
    )
    geo = PairGeometry(
        pinion=g1, gear=g2, module_mm=m, pressure_angle_rad=alpha, a_mm=a, a_w_mm=a_w,
        a_w_zero_backlash_mm=a_wj, alpha_w_rad=alpha_w, j_wt_mm=j_wt, j_n_mm=j_n,
        ratio=g2.teeth / g1.teeth, T1T2_mm=t1t2, g_alpha_mm=g_alpha,
        A_mm=a_pt, B_mm=e_pt - p_b, C_mm=c_pt, D_mm=a_pt + p_b, E_mm=e_pt, eps_alpha=eps,
        pair_fractions=fractions, single_contact_fraction=single,
        double_contact_fraction=double, findings=(),
    )
    return replace(geo, findings=_findings(geo, inv_w0 >= 0.0))


def _findings(geo: PairGeometry, shift_sum_ok: bool) -> tuple[Finding, ...]:
    """Feasibility checks (docs/theory.md §2; limits from ISO 21771 / Niemann/Winter II).

    Errors: ε_α < 1; involute interference; negative backlash / undefined α_w; tip not above
    the base circle; d_f <= 0; negative tip clearance; s_a <= 0; tip rounding that does not
    fit. Warnings: undercut; s_a < 0.2 m; tip clearance < 0.1 m.
    """
    out: list[Finding] = []
    m = geo.module_mm

    def add(severity: Literal["error", "warning"], code: str,
            subject: Literal["pinion", "gear"] | None, message: str) -> None:
        out.append(Finding(severity, code, message, subject))

    pair = (("pinion", geo.pinion, "gear"), ("gear", geo.gear, "pinion"))
    for role, g, mate in pair:
        if g.d_f_mm <= 0.0:
            add("error", "root_diameter", role, f"{role}: root diameter d_f = {g.d_f_mm:.3f} mm; "
                "allowed: d_f > 0 (raise the profile shift or the tooth count)")
        if g.d_a_mm <= g.d_b_mm:
            add("error", "tip_diameter", role, f"{role}: tip diameter d_a = {g.d_a_mm:.3f} mm is "
                f"not above the base diameter d_b = {g.d_b_mm:.3f} mm; allowed: d_a > d_b")
        if g.undercut:
            add("warning", "undercut", role, f"{role}: undercut: profile shift x = "
                f"{g.profile_shift:.4f} is {g.undercut_coef:.4f} module = {g.undercut_mm:.3f} mm "
                f"below x_min = {g.x_min:.4f} (z = {g.teeth} < z_min = {g.z_min:.2f}); "
                "allowed without undercut: x >= x_min")
        if g.s_a_mm <= 0.0:
            add("error", "pointed_tip", role, f"{role}: tip thickness s_a = {g.s_a_mm:.3f} mm "
                "(the flanks meet below the tip circle); allowed: s_a > 0, >= 0.2 module = "
                f"{0.2 * m:.3f} mm recommended")
        elif g.s_a_mm < 0.2 * m:
            add("warning", "pointed_tip", role, f"{role}: tip thickness s_a = {g.s_a_mm:.3f} mm = "
                f"{g.s_a_mm / m:.3f} module; recommended: s_a >= 0.2 module = {0.2 * m:.3f} mm")
        if g.tip_rounding_mm > 0.0 and g.d_a_mm > g.d_b_mm and math.isnan(g.d_Fa_mm):
            add("error", "tip_rounding", role, f"{role}: tip rounding radius "
                f"{g.tip_rounding_mm:.3f} mm does not fit on the tooth tip; allowed: the "
                "roundings of both flanks must not overlap and r_a - rho_a must exceed r_b")
        c = g.tip_clearance_mm
        if c < 0.0:
            add("error", "clearance", role, f"{role} tip to {mate} root: clearance c = {c:.3f} mm "
                f"(the tip hits the root); allowed: c >= 0, >= 0.1 module = {0.1 * m:.3f} mm "
                "recommended")
        elif c < 0.1 * m:
            add("warning", "clearance", role, f"{role} tip to {mate} root: clearance c = {c:.3f} mm"
                f"; recommended: c >= 0.1 module = {0.1 * m:.3f} mm")

    # The model is a plane one: the load is taken as uniform across the face (K_Hbeta = 1,
    # docs/theory.md §10.2). A face many pinion diameters wide bends and twists the pinion along
    # it, so the load concentrates at one end. The threshold is a generous one for a validity
    # warning: the upper end of VDI 2736-2:2014's initial-design range 0.2 ... 2.0 (written for
    # thermoplastic gears; steel-gear guidance is lower, about 1 ... 1.5).
    b = geo.narrow_face_width_mm
    b_d1 = b / geo.pinion.d_mm
    if b_d1 > FACE_WIDTH_RATIO_MAX:
        add("warning", "face_width", None, f"face width b = {b:.4g} mm is {b_d1:.2f} x the "
            f"pinion's reference diameter d1 = {geo.pinion.d_mm:.4g} mm; recommended: b/d1 <= "
            f"{FACE_WIDTH_RATIO_MAX:g} (VDI 2736-2, generous for steel): the pinion bends and "
            "twists along so wide a face, and the model takes the load as uniform across it")

    z_sum = geo.pinion.teeth + geo.gear.teeth
    alpha = geo.pressure_angle_rad
    if not shift_sum_ok:
        x_sum = geo.pinion.profile_shift + geo.gear.profile_shift
        limit = -z_sum * inv(alpha) / (2.0 * math.tan(alpha))
        add("error", "centre_distance", None, f"profile shift sum x1 + x2 = {x_sum:.4f} admits no "
            f"zero-backlash centre distance; allowed: x1 + x2 > {limit:.4f}")
    if math.isnan(geo.alpha_w_rad) and not math.isnan(geo.a_w_mm):
        add("error", "centre_distance", None, "operating centre distance a_w = "
            f"{geo.a_w_mm:.4f} mm gives no operating pressure angle; allowed: a_w > a cos(alpha) = "
            f"{geo.a_mm * math.cos(alpha):.4f} mm")
    elif geo.j_wt_mm < -1e-9 * geo.a_w_mm:
        add("error", "centre_distance", None, "operating centre distance a_w = "
            f"{geo.a_w_mm:.4f} mm gives negative backlash j_wt = {geo.j_wt_mm:.4f} mm (the "
            f"teeth overlap); allowed: a_w >= {geo.a_w_zero_backlash_mm:.4f} mm (zero backlash)")

    if geo.eps_alpha < 1.0:
        add("error", "contact_ratio", None, f"transverse contact ratio eps_alpha = "
            f"{geo.eps_alpha:.4f}; allowed: eps_alpha >= 1 (else contact is lost between pairs)")
    beyond = {"pinion": geo.A_mm < 0.0, "gear": geo.E_mm > geo.T1T2_mm}
    if beyond["pinion"]:
        add("error", "interference", "pinion", f"pinion: gear tip reaches beyond T1, |T1A| = "
            f"{geo.A_mm:.3f} mm (involute interference at the pinion root); allowed: >= 0 "
            f"({_BEYOND_T_CURE.format(gear='pinion', mate='gear')})")
    if beyond["gear"]:
        add("error", "interference", "gear", f"gear: pinion tip reaches beyond T2, |T2E| = "
            f"{geo.T1T2_mm - geo.E_mm:.3f} mm (involute interference at the gear root); "
            f"allowed: >= 0 ({_BEYOND_T_CURE.format(gear='gear', mate='pinion')})")
    for role, g, mate in pair:
        if not beyond[role] and g.d_Nf_mm < g.d_Ff_mm * (1.0 - 1e-9):
            zone = ("undercut: that part of the path has no involute, the real contact ratio "
                    "is lower" if g.undercut else "fillet: the tip hits the root fillet")
            # In an undercut the fillet lies inside the involute: no collision, only a shorter
            # active profile (ISO 21771 d_Nf >= d_Ff is then a rating issue): warn. Otherwise
            # the tip would cut the fillet: fillet interference, an error.
            severity = "warning" if g.undercut else "error"
            code = "undercut_contact" if g.undercut else "interference"
            add(severity, code, role, f"{role}: the {mate} tip reaches d_Nf = "
                f"{g.d_Nf_mm:.3f} mm, below the root form diameter d_Ff = {g.d_Ff_mm:.3f} mm "
                f"({zone}); allowed: d_Nf >= d_Ff" + (
                    "" if g.undercut else
                    f" ({_FILLET_CURE.format(gear=role, mate=mate)})"))
    return tuple(_pressure_angle_first(out, alpha))


def _pressure_angle_first(found: list[Finding], alpha: float) -> list[Finding]:
    """Led by a finding naming the pressure angle, the input that causes them, when the pair
    fails with one far outside the range of racks (0.349 deg for 0.349 rad: interference)."""
    errors, deg = [f for f in found if f.severity == "error"], math.degrees(alpha)
    low, high = PRESSURE_ANGLE_RANGE_DEG
    if not errors or low <= deg <= high:
        return found
    fails = ", ".join(dict.fromkeys(f.code.replace("_", " ") + (f" ({f.subject})" * bool(
        f.subject)) for f in errors))
    return [Finding("error", "pressure_angle", f"pressure angle alpha = {deg:.4g} deg is far "
                    f"outside the {low:g} ... {high:g} deg of gear racks (ISO 53: 20 deg) and the "
                    f"pair fails ({fails}); allowed: a pressure angle in deg, usually {low:g} ... "
                    f"{high:g}" + (f" ({deg:.4g} rad would be {math.degrees(deg):.4g} deg: write "
                                   f"'{deg:.4g} rad')" if deg < 1.0 else "")), *found]


#: Pressure angles of racks in use [deg], generously: ISO 53 20, old AGMA 14.5, Niemann/Winter II 28
PRESSURE_ANGLE_RANGE_DEG = (10.0, 35.0)

#: Largest face width to pinion reference diameter ratio b/d1 without a warning: the upper end
#: of VDI 2736-2:2014's initial-design range 0.2 <= b/d1 <= 2.0 (a thermoplastic-gear standard;
#: steel gears are usually designed below ~1.5), so only a face far outside usual designs warns.
FACE_WIDTH_RATIO_MAX = 2.0

#: What clears an involute interference at a gear's root, the mate's tip beyond the
#: interference point T (ISO 21771:2007 and Niemann/Winter II: more teeth or a positive profile
#: shift on that gear move T out along the line of action; a shorter mate tip ends the path
#: before T).
_BEYOND_T_CURE = ("more teeth or a larger profile shift on the {gear}, or a shorter {mate} tip")
#: The mate's tip inside the gear's root fillet (d_Nf < d_Ff): the gear's profile shift moves
#: d_Ff and, through the centre distance, d_Nf; which way clears it depends on the pair, so no
#: direction is given.
_FILLET_CURE = ("change the {gear}'s profile shift or teeth, or shorten the {mate} tip")
