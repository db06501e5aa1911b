"""Inspection dimensions of an external spur gear: span, balls/pins, chordal tooth thickness.

docs/theory.md, "ISO 6336 rating", §6 (ISO 21771:2007 / DIN 3960:1987 quantities). A tooth
thickness allowance A_sn [mm] (< 0 thins the tooth) changes the arc tooth thickness at the
reference circle, s = m (π/2 + 2 x tan α) + A_sn; each dimension is returned for the given
allowance (0: the nominal, backlash-free value), so the caller evaluates it at the upper and the
lower allowance.

Span (base tangent length) over k teeth:
    W_k = m cos α [(k − 0.5) π + z inv α] + 2 x m sin α + A_sn cos α
    k = round(z/π (tan α_M − 2 x tan α/z − inv α) + 0.5), cos α_M = d_b/(d + 2 x m)
    (the span touching the flanks near the circle d + 2 x m).
Dimension over two balls (pins) of diameter D_M:
    inv α_K = s/d + inv α + D_M/d_b − π/z,
    M_dK = d_b/cos α_K + D_M (z even),  d_b cos(90°/z)/cos α_K + D_M (z odd).
Theoretical ball diameter touching the flanks on d + 2 x m (pressure angle α_y there):
    α_K = tan α_y − s/d − inv α + π/z,  D_M = d_b (tan α_K − tan α_y).
Chordal tooth thickness and height at the reference circle:
    s_c = d sin(s/d),  h_c = (d_a − d)/2 + d/2 (1 − cos(s/d)).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from gearcli.model.iso6336.common import inverse_involute, involute

__all__ = ["arc_tooth_thickness", "span_teeth", "span", "theoretical_ball_diameter",
           "BALL_SERIES_MM", "standard_ball_diameter", "ball_centre_involute",
           "dimension_over_balls", "chordal_thickness", "chordal_height", "InspectionDimensions",
           "inspection_dimensions", "inspection_input_error"]

#: Ball/pin diameters offered as "next standard size" [mm]: 0.05 mm steps from 0.1 to 1 (fine
#: pitch: from 1 mm on, modules below ~0.4 mm got a ball touching above the tip), 0.25 mm steps
#: to 10, 0.5 mm to 20, 1 mm to 25, 5 mm to 300. A project convention (the DIN 3977 series is
#: not at hand); it gives KISSsoft's choices of the NREL 5 MW printouts (stage 2: 34.70 → 35,
#: 38.73 → 40, 41.07 → 45 mm; stage 1, m_n 45: 75.93 → 80, 94.95 → 95, 106.19 → 110 mm). The 5
#: mm steps went to 100 mm only until stage 1's planet (106.19 mm) made the rating fail
#: (docs/theory.md, "ISO 6336 rating" §6); 300 mm covers modules to ~120 mm (D_M ≈ 1.7…2.4 m).
BALL_SERIES_MM: tuple[float, ...] = tuple(
    [round(0.1 + 0.05 * i, 2) for i in range(18)] + [1.0 + 0.25 * i for i in range(37)]
    + [10.5 + 0.5 * i for i in range(20)]
    + [21.0 + i for i in range(5)] + [30.0 + 5.0 * i for i in range(55)])


def arc_tooth_thickness(z: int, x: float, m_mm: float, alpha_rad: float,
                        allowance_mm: float = 0.0) -> float:
    """Arc tooth thickness at the reference circle s = m (π/2 + 2 x tan α) + A_sn [mm]
    (ISO 21771; spur: normal = transverse). z only checks the sign (external gears)."""
    if z <= 0:
        raise ValueError("external gears only (z > 0)")
    return m_mm * (0.5 * math.pi + 2.0 * x * math.tan(alpha_rad)) + allowance_mm


def span_teeth(z: int, x: float, alpha_rad: float) -> int:
    """Number of teeth spanned k [-] touching near d + 2 x m (DIN 3960; module notes)."""
    cos_m = math.cos(alpha_rad) / (1.0 + 2.0 * x / z)
    alpha_m = math.acos(min(cos_m, 1.0))
    k = z / math.pi * (math.tan(alpha_m) - 2.0 * x * math.tan(alpha_rad) / z
                       - involute(alpha_rad)) + 0.5
    return max(1, int(round(k)))


def span(z: int, x: float, m_mm: float, alpha_rad: float, k: int,
         allowance_mm: float = 0.0) -> float:
    """Span W_k [mm] over k teeth (ISO 21771 / DIN 3960; module notes), with the tooth
    thickness allowance A_sn [mm]."""
    return (m_mm * math.cos(alpha_rad) * ((k - 0.5) * math.pi + z * involute(alpha_rad))
            + 2.0 * x * m_mm * math.sin(alpha_rad) + allowance_mm * math.cos(alpha_rad))


def theoretical_ball_diameter(z: int, x: float, m_mm: float, alpha_rad: float,
                              allowance_mm: float = 0.0) -> float:
    """Ball diameter D_M [mm] touching the flanks on the circle d + 2 x m (DIN 3960; module
    notes), for the tooth thickness with allowance A_sn [mm]."""
    d = m_mm * z
    d_b = d * math.cos(alpha_rad)
    tan_y = math.sqrt(((d + 2.0 * x * m_mm) / d_b) ** 2 - 1.0)
    s = arc_tooth_thickness(z, x, m_mm, alpha_rad, allowance_mm)
    alpha_k = tan_y - s / d - involute(alpha_rad) + math.pi / z
    return d_b * (math.tan(alpha_k) - tan_y)


def standard_ball_diameter(theoretical_mm: float,
                           series: Sequence[float] = BALL_SERIES_MM) -> float:
    """The smallest size of ``series`` [mm] at or above the theoretical diameter [mm]; beyond
    the series' largest size, the series continued in its last step (a rating never fails
    for want of a ball size)."""
    sizes = sorted(series)
    for size in sizes:
        if size >= theoretical_mm - 1e-9:
            return float(size)
    last = sizes[-1]
    step = last - sizes[-2] if len(sizes) > 1 else last
    return float(last + step * math.ceil((theoretical_mm - last - 1e-9) / step))


def ball_centre_involute(z: int, x: float, m_mm: float, alpha_rad: float, ball_mm: float,
                         allowance_mm: float = 0.0) -> float:
    """inv α_K = s/d + inv α + D_M/d_b − π/z [rad] of the ball centre's pressure angle α_K
    (ISO 21771 / DIN 3960; module notes), thickness allowance A_sn [mm] in s; the ball touches
    both flanks only for 0 < inv α_K <= 1 (:func:`inspection_input_error`)."""
    d = m_mm * z
    s = arc_tooth_thickness(z, x, m_mm, alpha_rad, allowance_mm)
    return s / d + involute(alpha_rad) + ball_mm / (d * math.cos(alpha_rad)) - math.pi / z


def dimension_over_balls(z: int, x: float, m_mm: float, alpha_rad: float, ball_mm: float,
                         allowance_mm: float = 0.0) -> float:
    """Dimension over two balls (pins) M_dK [mm] for z even or odd (ISO 21771 / DIN 3960;
    module notes); ball diameter D_M [mm], thickness allowance A_sn [mm]."""
    d_b = m_mm * z * math.cos(alpha_rad)
    alpha_k = inverse_involute(ball_centre_involute(z, x, m_mm, alpha_rad, ball_mm,
                                                    allowance_mm))
    centre = d_b / math.cos(alpha_k)
    if z % 2:
        centre *= math.cos(0.5 * math.pi / z)
    return centre + ball_mm


def chordal_thickness(z: int, x: float, m_mm: float, alpha_rad: float,
                      allowance_mm: float = 0.0) -> float:
    """Chordal tooth thickness at the reference circle s_c = d sin(s/d) [mm] (DIN 3960)."""
    d = m_mm * z
    return d * math.sin(arc_tooth_thickness(z, x, m_mm, alpha_rad, allowance_mm) / d)


def chordal_height(z: int, x: float, m_mm: float, alpha_rad: float, tip_diameter_mm: float,
                   allowance_mm: float = 0.0) -> float:
    """Chordal height from the tip h_c = (d_a − d)/2 + d/2 (1 − cos(s/d)) [mm] (DIN 3960);
    d_a the (measured or mean) tip diameter [mm]."""
    d = m_mm * z
    s = arc_tooth_thickness(z, x, m_mm, alpha_rad, allowance_mm)
    return 0.5 * (tip_diameter_mm - d) + 0.5 * d * (1.0 - math.cos(s / d))


@dataclass(frozen=True)
class InspectionDimensions:
    """Inspection dimensions of one gear; tuples are (nominal, upper allowance, lower allowance)
    [mm]."""

    span_teeth: int  #: k
    span_mm: tuple[float, float, float]  #: W_k
    ball_theoretical_mm: float  #: D_M touching on d + 2 x m (nominal thickness)
    ball_mm: float  #: the ball used: given, else the next standard size
    over_balls_mm: tuple[float, float, float]  #: M_dK
    chordal_thickness_mm: tuple[float, float, float]  #: s_c
    chordal_height_mm: tuple[float, float, float]  #: h_c from the tip diameter

    def to_dict(self) -> dict:
        return {k: (list(v) if isinstance(v, tuple) else v) for k, v in self.__dict__.items()}


def inspection_dimensions(z: int, x: float, m_mm: float, alpha_rad: float,
                          tip_diameter_mm: float, allowances_mm: tuple[float, float] = (0.0, 0.0),
                          ball_mm: float | None = None) -> InspectionDimensions:
    """All inspection dimensions of an external spur gear (module notes): teeth z, profile shift
    x [-], module [mm], pressure angle [rad], tip diameter [mm], (upper, lower) tooth thickness
    allowances A_sn [mm], ball diameter [mm] (None: the next standard size)."""
    allow = (0.0, allowances_mm[0], allowances_mm[1])
    k = span_teeth(z, x, alpha_rad)
    d_th = theoretical_ball_diameter(z, x, m_mm, alpha_rad)
    ball = standard_ball_diameter(d_th) if ball_mm is None else float(ball_mm)
    return InspectionDimensions(
        k, tuple(span(z, x, m_mm, alpha_rad, k, a) for a in allow), d_th, ball,
        tuple(dimension_over_balls(z, x, m_mm, alpha_rad, ball, a) for a in allow),
        tuple(chordal_thickness(z, x, m_mm, alpha_rad, a) for a in allow),
        tuple(chordal_height(z, x, m_mm, alpha_rad, tip_diameter_mm, a) for a in allow))


def inspection_input_error(z: int, x: float, m_mm: float, alpha_rad: float,
                           tip_diameter_mm: float, allowances_mm: tuple[float, float],
                           ball_mm: float | None) -> tuple[str, str] | None:
    """What makes :func:`inspection_dimensions` of these inputs impossible, as (the input's
    name, "thickness_allowances" or "ball_diameter", and a one-line reason), or None.

    An allowance that thins the tooth to nothing at the reference circle (s + A_sn <= 0), or
    a ball that touches the flank (at every allowance) outside the involute between the base
    circle and the tip: the contact point's pressure angle from tan α_c = tan α_K − D_M/d_b
    (the ball centre on the base tangent at r_b tan α_K, the contact D_M/2 before it;
    DIN 3960 / ISO 21771, module notes)."""
    d = m_mm * z
    d_b = d * math.cos(alpha_rad)
    s0 = arc_tooth_thickness(z, x, m_mm, alpha_rad)
    if not s0 + min(0.0, *allowances_mm) > 0.0:
        return "thickness_allowances", (
            f"an allowance of {min(allowances_mm):g} mm leaves no tooth at the reference circle "
            f"(arc thickness {s0:.4g} mm); expected allowances above {-s0:.4g} mm (typically a "
            "few hundredths of the module)")
    d_th = theoretical_ball_diameter(z, x, m_mm, alpha_rad)
    ball = standard_ball_diameter(d_th) if ball_mm is None else float(ball_mm)
    for allowance in (0.0, *allowances_mm):
        inv_k = ball_centre_involute(z, x, m_mm, alpha_rad, ball, allowance)
        if not inv_k > 0.0:
            where = "falls between the flanks, too small to touch both"
        elif inv_k > 1.0:
            where = "does not enter the tooth space"
        else:
            tan_c = math.tan(inverse_involute(inv_k)) - ball / d_b
            d_c = d_b * math.sqrt(1.0 + tan_c * tan_c)
            where = ("touches below the base circle" if not tan_c > 0.0 else
                     f"touches at d = {d_c:.4g} mm, above the tip" if d_c > tip_diameter_mm
                     else "")
        if where:
            which = (f"a ball of {ball:g} mm" if ball_mm is not None else
                     f"the standard ball of {ball:g} mm (none given: the series' next size)")
            return "ball_diameter", (
                f"{which} {where} (d_b {d_b:.4g} mm, d_a {tip_diameter_mm:.4g} "
                f"mm); expected about {d_th:.4g} mm (the ball touching on d + 2 x m)")
    return None
