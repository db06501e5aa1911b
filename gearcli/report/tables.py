"""The report's tables as plain data (rows of strings), shared by the HTML and Markdown writers."""

from __future__ import annotations

import math
import shlex
from dataclasses import dataclass, field

from pydantic import BaseModel

from gearcli.case.inspection import PairInspection, pair_inspection
from gearcli.case.schema import Case
from gearcli.case.schema_gears import Gear
from gearcli.case.types import TimeFunction, field_dim
from gearcli.display_units import DEFAULT, convert, unit_and_factor
from gearcli.report.data import ReportData
from gearcli.results import shown_values
from gearcli.results.metrics import display
from gearcli.results.stress import Safety


@dataclass(frozen=True)
class Table:
    """A titled table of strings; ``status`` marks rows "pass" or "fail" (else "")."""

    title: str
    headers: tuple[str, ...]
    rows: list[tuple[str, ...]]
    note: str = ""
    status: list[str] = field(default_factory=list)


def fmt(value, digits: int = 4) -> str:
    """A value for a table cell: numbers with ``digits`` significant digits, None as "–"."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            return str(value)
        if value == 0.0:
            return "0"
        if 1e-3 <= abs(value) < 1e6:
            text = f"{value:.{digits}g}"
            return text if "e" not in text else f"{value:.0f}"
        return f"{value:.{digits}g}"
    if isinstance(value, list | tuple):
        return ", ".join(fmt(v, digits) for v in value)
    return str(value)


def _cells(value, system: str, unit: str) -> tuple[str, str]:
    """(value, unit) cells in the display units ``system`` (gearcli/display_units.py) of the
    number (or numbers) ``value`` in the internal ``unit``."""
    shown, shown_unit = convert(value, unit, system)
    return fmt(shown), shown_unit


def qty(value, system: str = DEFAULT, unit: str = "") -> str:
    """:func:`_cells` as one 'number unit' text (104.7 rad/s -> "1000 rpm"); None as "–"."""
    return "–" if value is None else " ".join(_cells(value, system, unit)).strip()


def _deg(value) -> str:
    return "–" if value is None else f"{math.degrees(value):.4g} deg"


def _setting(section, name: str, u: str) -> str:
    """Field ``name`` of a typed case section (read as an attribute: a renamed schema field is
    an AttributeError, not an empty cell) for a table: a quantity in the display units ``u``
    with the unit its schema field records (angles in degrees, as the case takes them), a
    sub-section as "name value unit" pairs, numbers with 4 significant digits."""
    value = getattr(section, name)
    if isinstance(value, BaseModel):
        return _section(value, u)
    if isinstance(value, TimeFunction):
        return _function(value)
    dim = field_dim(section, name)
    if dim is None or value is None:
        return fmt(value)
    if isinstance(value, list | tuple):  # each with its unit ("0.001 mm, -0.002 mm")
        return ", ".join(_deg(v) if dim.internal == "rad" else qty(v, u, dim.internal)
                         for v in value)
    if dim.internal == "rad":
        return _deg(value)
    return qty(value, u, dim.internal)


def _section(section: BaseModel, u: str, skip: tuple[str, ...] = (), sep: str = "; ",
             eq: str = " ", drop_none: bool = False) -> str:
    """Every field of a typed case section as "name value" pairs (:func:`_setting`)."""
    return sep.join(f"{name.replace('_', ' ') if not drop_none else name}{eq}"
                    f"{_setting(section, name, u)}" for name in type(section).model_fields
                    if name not in skip and not (drop_none and getattr(section, name) is None))


def _setting_cells(section, name: str, u: str) -> tuple[str, str]:
    """(value, unit) cells of quantity field ``name`` of a typed case section."""
    dim = field_dim(section, name)
    return _cells(getattr(section, name), u, dim.internal if dim is not None else "")


# --- the case ---------------------------------------------------------------------------------
def _case(data: ReportData) -> Case:
    if data.case is None:
        raise ValueError(f"{data.folder}: the report's case tables need the typed case")
    return data.case


def gears_table(data: ReportData) -> Table:
    """Table 1-style: teeth, module, pressure angle, face width, diameters, material."""
    case, geo, u = _case(data), data.geometry, data.units
    g = case.gears
    p, w = g.pinion, g.gear
    rows = [
        ("number of teeth z", str(p.teeth), str(w.teeth)),
        ("module m", _setting(g, "module", u), _setting(g, "module", u)),
        ("pressure angle α", _setting(g, "pressure_angle", u),
         _setting(g, "pressure_angle", u)),
        *[("face width b", *(_setting(gear if gear.face_width is not None else g, "face_width",
                                      u) for gear in (p, w)))],
        ("profile shift x", fmt(p.profile_shift), fmt(w.profile_shift)),
    ]
    # the tooth-form and body settings a case may give (shown when either gear sets one)
    for label, key in (("thickness allowance", "thickness_allowance"),
                       ("tip shortening", "tip_shortening"), ("tip rounding", "tip_rounding"),
                       ("bore diameter", "bore_diameter")):
        values = [getattr(gear, key) for gear in (p, w)]
        if any(v is not None and _setting(gear, key, u) not in ("0", "0 mm", "0 m")
               for gear, v in zip((p, w), values, strict=True)):
            rows.append((label, *(_setting(gear, key, u) if v is not None else "–"
                                  for gear, v in zip((p, w), values, strict=True))))
    if geo is not None:
        for label, attr in (("reference diameter d", "d_mm"), ("tip diameter d_a", "d_a_mm"),
                            ("base diameter d_b", "d_b_mm"), ("root diameter d_f", "d_f_mm")):
            rows.append((label, qty(getattr(geo.pinion, attr), u, "mm"),
                         qty(getattr(geo.gear, attr), u, "mm")))
    for label, key in (("density ρ", "density"), ("Young's modulus E", "youngs_modulus"),
                       ("Poisson ratio ν", "poisson_ratio")):
        rows.append((label, *(_setting(gear.material or case.material, key, u)
                              for gear in (p, w))))
    rows.append(("inertia model", *(_inertia(gear, u) for gear in (p, w))))
    return Table("Gears and material", ("quantity", "pinion", "gear"), rows)


def _inertia(gear: Gear, u: str) -> str:
    i = gear.inertia
    if i.model == "disc":
        text = "solid disc, " + ("pitch diameter" if i.diameter is None
                                 else _setting(i, "diameter", u))
    else:
        text = f"given J = {_setting(i, 'value', u)}"
    return text + (f" + {_setting(i, 'extra', u)}" if i.extra else "")


def geometry_table(data: ReportData) -> Table | None:
    """Derived pair geometry (gearcli.model.geometry from the stored case)."""
    geo, u = data.geometry, data.units
    if geo is None:
        return None
    rows = [
        ("gear ratio i = z2/z1", fmt(geo.ratio), "–"),
        ("operating centre distance a_w", *_cells(geo.a_w_mm, u, "mm")),
        ("operating pressure angle α_w", fmt(math.degrees(geo.alpha_w_rad)), "deg"),
        ("base pitch p_b", *_cells(geo.p_b_mm, u, "mm")),
        ("path of contact g_α", *_cells(geo.g_alpha_mm, u, "mm")),
        ("transverse contact ratio ε_α", fmt(geo.eps_alpha), "–"),
        ("time with one pair in contact", fmt(100.0 * geo.single_contact_fraction), "%"),
        ("normal backlash j_n", *_cells(geo.j_n_mm, u, "mm")),
    ]
    if data.case is not None:
        rows += inspection_rows(pair_inspection(data.case, geo), u)
    note = "; ".join(f.message for f in geo.findings)
    return Table("Pair geometry (derived)", ("quantity", "value", "unit"), rows, note)


#: (label, key of InspectionDimensions, index: 0 nominal, 1 upper, 2 lower allowance, or None)
_INSPECTION = (
    ("span measurement teeth k", "span_teeth", None),
    *((f"span W_k, {at}", "span_mm", i) for i, at in enumerate(
        ("nominal", "upper allowance", "lower allowance"))),
    *((f"over balls M_dK, {at}", "over_balls_mm", i) for i, at in enumerate(
        ("nominal", "upper allowance", "lower allowance"))),
    *((f"chordal thickness s_c, {at}", "chordal_thickness_mm", i) for i, at in enumerate(
        ("nominal", "upper allowance", "lower allowance"))),
    *((f"chordal height h_c, {at}", "chordal_height_mm", i) for i, at in enumerate(
        ("nominal", "upper allowance", "lower allowance"))),
)


def inspection_rows(insp: PairInspection, u: str) -> list[tuple[str, str, str]]:
    """The inspection dimensions as rows "quantity, pinion / gear", "value / value", unit, to
    1 µm: the tooth thickness allowances, span W_k, balls, M_dK, chordal thickness and height
    at the nominal thickness and at the allowances (gearcli/case/inspection.py;
    docs/theory.md, "ISO 6336 rating" §6)."""
    unit = convert(1.0, "mm", u)[1]
    digits = 3 + round(-math.log10(convert(1.0, "mm", u)[0]))  # 1 µm in the display unit

    def cell(values) -> str:
        return " / ".join(f"{convert(float(v), 'mm', u)[0]:.{digits}f}" for v in values)

    gears = (insp.pinion, insp.gear)
    rows = [("tooth thickness allowances A_sne / A_sni, pinion; gear",
             "; ".join(cell(a) for a in insp.allowances_mm), unit),
            ("ball diameter D_M, theoretical / used, pinion; gear",
             "; ".join(cell((g.ball_theoretical_mm, g.ball_mm)) for g in gears), unit)]
    for label, key, i in _INSPECTION:
        if i is None:
            rows.append((label + ", pinion / gear",
                         " / ".join(str(getattr(g, key)) for g in gears), "–"))
        else:
            rows.append((label + ", pinion / gear", cell(getattr(g, key)[i] for g in gears),
                         unit))
    return rows


def contact_table(data: ReportData) -> Table:
    """Table 3-style: contact law and friction parameters."""
    case, u = _case(data), data.units
    c, f = case.contact, case.friction
    rows = [("contact law", str(c.law), ""), ("engagement model", str(c.engagement), "")]
    if c.law == "tooth":  # docs/theory.md §4b, §4c: no IMPACT parameters
        rows.append(("mesh damping ratio ζ", fmt(c.damping_ratio), "–"))
        for name in ("pinion", "gear"):
            gear = getattr(case.gears, name)
            rows.append((f"{name} bore (gear-body compliance)",
                         *(_setting_cells(gear, "bore_diameter", u)
                           if gear.bore_diameter is not None
                           else ("default (docs/theory.md §4b)", ""))))
        k = data.scalars.mesh_stiffness_N_mm
        if isinstance(k, int | float):
            rows.append(("mesh stiffness, linearised at the static load",
                         *_cells(k, u, "N/mm")))
    else:
        e = c.exponent
        rows += [
            ("stiffness K", fmt(c.stiffness), f"N/mm^{e:g}"),
            ("force exponent e", fmt(e), "–"),
            ("maximum damping c_max", *_setting_cells(c, "max_damping", u)),
            ("damping ramp depth d_max", *_setting_cells(c, "penetration_depth", u)),
        ]
    rows.append(("friction", "on" if f.enabled else "off", ""))
    if f.enabled:
        rows += [
            ("static coefficient μ_s", fmt(f.static_coefficient), "–"),
            ("dynamic coefficient μ_d", fmt(f.dynamic_coefficient), "–"),
            ("stiction velocity v_s", *_setting_cells(f, "stiction_velocity", u)),
            ("transition velocity v_d", *_setting_cells(f, "transition_velocity", u)),
        ]
    return Table("Contact and friction", ("parameter", "value", "unit"), rows)


def _function(spec: TimeFunction | None) -> str:
    return "–" if spec is None else f"{spec.expression} [{spec.unit}]"


def drive_table(data: ReportData) -> Table:
    """Drive and load functions, bearing losses and run settings."""
    case, u = _case(data), data.units
    d, ld, b, r = case.drive, case.load, case.bearings, case.run
    rows = [
        ("model", str(case.model)),
        # a speed or shaft drive prescribes drive.speed (the shaft is a row below)
        ("drive (pinion)", f"{d.type}: {_function(d.torque if d.type == 'torque' else d.speed)}"),
        ("initial pinion speed", _setting(d, "initial_speed", u)),
        (f"load torque (on the {ld.applied_to})", _function(ld.torque)),
        ("load: viscous / quadratic",
         f"{_setting(ld, 'viscous', u)} / {_setting(ld, 'quadratic', u)}"),
        ("bearing damping pinion / gear",
         f"{_setting(b.pinion, 'damping', u)} / {_setting(b.gear, 'damping', u)}"),
        ("end time", _setting(r, "end_time", u)),
        ("output", f"{fmt(data.scalars.output_rate_Hz)} Hz "
                   f"({data.run.summary.rows} rows)"),
        ("tolerances rtol / atol", f"{fmt(r.rtol)} / " + (
            _setting(r, "atol", u) if r.atol is not None
            else "default (1e-5 of the static deflection, at most 1 µm)")),
    ]
    for key in ("shaft", "motor_curve", "motor_inertia", "reference_speed"):
        if getattr(d, key) is not None:
            rows.append((f"drive {key.replace('_', ' ')}", _setting(d, key, u)))
    for key in ("shaft", "inertia"):
        if getattr(ld, key) is not None:
            rows.append((f"load {key}", _setting(ld, key, u)))
    for gear in ("pinion", "gear"):  # the lateral model's bearings (beyond the damping above)
        rows.append((f"bearings {gear}", _section(getattr(b, gear), u, skip=("damping",))))
    return Table("Model, drive, load and run", ("item", "setting"), rows)


def modifications_table(data: ReportData) -> Table | None:
    """Profile reliefs and manufacturing errors that are set (None when there are none)."""
    rows = []
    case = _case(data)
    for group in (case.modifications, case.errors):
        for kind in type(group).model_fields:
            pair = getattr(group, kind)
            for gear in type(pair).model_fields:
                spec = getattr(pair, gear)
                if spec is not None:
                    rows.append((f"{gear} {kind.replace('_', ' ')}",
                                 _section(spec, data.units, sep=", ", eq=" = ",
                                          drop_none=True)))
    return Table("Profile modifications and errors", ("item", "setting"), rows) if rows else None


# --- results ----------------------------------------------------------------------------------
def results_table(data: ReportData) -> Table:
    """The metrics of analysis.json shown at "report" (field metadata, gearcli/results/) with
    their labels and display units."""
    m = data.metrics
    w0, w1 = data.window_s
    rows = [("steady window analysed", f"{w0:.4g} – {w1:.4g}", "s")]
    for key, value in shown_values(m, "report").items():
        label, v, unit = display(key, list(value) if isinstance(value, tuple) else value,
                                 data.units)
        if key == "force_max_N" and m.force_max_source:
            label += f" (from the {m.force_max_source})"
        rows.append((label, fmt(v), unit))
    note = data.analysis.window_reason
    return Table("Results of the steady window", ("quantity", "value", "unit"), rows,
                 f"window: {note}" if note else "")


def lines_table(data: ReportData) -> Table | None:
    """Amplitude of the mesh harmonics k·f_z in each spectrum (sidebands: harmonics.csv)."""
    lines = data.analysis.lines
    # (signal, stored unit, a deflection?) -> the display unit and factor of its amplitudes
    signals = [(s, *unit_and_factor(u, data.units, fine)) for s, u, fine in
               (("gear_speed", "rad/s", False), ("dte", "mm", True), ("force", "N", False))
               if s in lines]
    if not signals:
        return None
    first = lines[signals[0][0]]
    rows = []
    for label, ln in first.items():
        if "+" in label or "-" in label:
            continue
        cells = [label.replace("fz", " f_z"), fmt(ln.expected_Hz)]
        for sig, _, factor in signals:
            other = lines[sig].get(label)
            amp = None if other is None else other.amplitude
            cells.append(fmt(None if amp is None else amp * factor)
                         if other is not None and other.resolvable else "not resolvable")
        rows.append(tuple(cells))
    names = {"gear_speed": "gear speed", "dte": "DTE", "force": "force"}
    headers = ("line", "frequency [Hz]") + tuple(
        f"{names[s]} amplitude [{u}]" for s, u, _ in signals)
    return Table("Mesh lines in the spectra", headers, rows,
                 "sidebands k·f_z ± n1, n2 are in harmonics.csv")


def modes_table(data: ReportData) -> Table | None:
    """Modes of the linearised model as simulate stored them (the ones `gearcli modal` gives)."""
    modes = data.scalars.modes
    if not modes:
        return None
    rows = [(str(m.mode), "rigid body" if m.rigid_body else fmt(m.natural_frequency_Hz),
             "–" if m.rigid_body else fmt(m.damping_ratio), str(m.description))
            for m in modes]
    return Table("Modes of the linearised model", ("mode", "f_n [Hz]", "damping ratio ζ",
                                                   "dominant motion"), rows,
                 "the margins of the results table are measured to these; details and mode "
                 "shapes: gearcli modal")


def check_cells(ck, units: str = "engineering") -> tuple[str, str, str]:
    """(value, unit, limit) of a check as the tables show it: one unit per column, a fraction
    in % (its limit too), a length in the display ``units`` (gearcli.results.Check.display)."""
    value, unit, limit = ck.display(units)
    return fmt(value) if not isinstance(value, str) else value, unit, limit


def checks_table(data: ReportData) -> Table:
    """Every check of analysis.json, marked pass or fail: one unit per column (a fraction in
    %), the note and the remedy of a failed check beside it."""
    rows, status = [], []
    for c in data.analysis.checks:
        ok = bool(c.passed)
        checked = c.checked is not False
        result = "not checked" if not checked else "pass" if ok else "FAIL"
        value, unit, limit = check_cells(c, data.units)
        note = str(c.note or "")
        if c.remedy is not None:
            note = (note + "; " if note else "") + "remedy: " + c.remedy.text
        rows.append((c.label, value, unit, limit, result, note, _check_key(c)))
        status.append("" if not checked else "pass" if ok else "fail")
    return Table("Checks", ("check", "value", "unit", "limit", "result", "note", "key"), rows,
                 note="key: the check's name in analysis.json, and where the case sets its "
                 "limit", status=status)


def _check_key(ck) -> str:
    """A check's name in analysis.json and, where the case sets it, its limit's key."""
    return f"{ck.name} ({ck.limit_key})" if ck.limit_key else ck.name


def _key_label(key: str) -> str:
    """'wall_time_s' -> 'wall time [s]'."""
    for suffix, unit in (("_rad_s", "rad/s"), ("_deg_s", "deg/s"), ("_N_mm", "N/mm"),
                         ("_Nmm", "N·mm"), ("_percent", "%"), ("_mJ", "mJ"), ("_W", "W"),
                         ("_s", "s"), ("_Hz", "Hz"), ("_N", "N"), ("_mm", "mm")):
        if key.endswith(suffix):
            return key[: -len(suffix)].replace("_", " ") + f" [{unit}]"
    return key.replace("_", " ")


def provenance_table(data: ReportData) -> Table:
    """Manifest: versions, case file and hash, command line, overrides."""
    man = data.run.manifest
    version = (man.get("versions") or {}).get("gearcli", "–")
    rows = [("results computed (UTC)", str(man.get("created_utc", "–"))),
            ("by gearcli", str(version)),
            ("case file", str(man.get("case_file", "–"))),
            ("case sha256", str(man.get("case_sha256", "–"))),
            ("command line", shlex.join(str(a) for a in man.get("command_line") or [])),
            ("overrides", "; ".join(str(o) for o in man.get("overrides") or []) or "none")]
    rows += [(name if name == "platform" else f"{name} version", str(v))
             for name, v in (man.get("versions") or {}).items()]
    s = data.run.summary.solver or {}
    if s:
        rows.append(("solver", ", ".join(f"{_key_label(k)} {fmt(v)}" for k, v in s.items())))
    return Table("Provenance (manifest.json, summary.json)", ("item", "value"), rows)


def stress_table(data: ReportData) -> Table | None:
    """Peak dynamic stresses against the static ISO 6336 values (from stress.json)."""
    st = data.stress
    if not st:
        return None
    rows, status = [], []
    for gear in ("pinion", "gear"):
        g, ref = getattr(st, gear), getattr(st.static, gear)
        safety = g.safety or Safety()
        for kind, peak, static, ratio, s_factor in (
            ("contact σ_H", g.peak_sigma_H, ref.sigma_H_iso_MPa, g.ratio_sigma_H_to_static,
             safety.S_H),
            ("root σ_F", g.peak_sigma_F, ref.sigma_F0_MPa, g.ratio_sigma_F_to_static,
             safety.S_F),
        ):
            rows.append((gear, kind, fmt(peak.MPa), f"{fmt(peak.t_s)} s, tooth "
                         f"{peak.tooth}, {peak.zone}", fmt(static), fmt(ratio), fmt(s_factor)))
            status.append("")
    note = st.ratio_definition
    window = st.window_s
    if all(math.isfinite(x) for x in window):  # gearcli stress has its own window: say which,
        # and when it is not analyze's
        note = (f"Peaks in the window {fmt(window[0])}-{fmt(window[1])} s of gearcli stress "
                f"({st.window_reason})" + (
                    f", not the analysis window {fmt(data.window_s[0])}-"
                    f"{fmt(data.window_s[1])} s of the tables above"
                    if data.window_s and any(abs(a - b) > 1e-9 for a, b in
                                             zip(window, data.window_s, strict=True)) else "")
                + (". " + note if note else "."))
    return Table("Stresses (ISO 6336 from the dynamic pair forces; MPa)",
                 ("gear", "stress", "peak", "where", "static ISO", "ratio", "safety"), rows,
                 note=note, status=status)
