"""The report's tables as plain data (rows of strings), shared by the HTML and Markdown writers."""

from __future__ import annotations

import math
import shlex
from dataclasses import dataclass, field

from gearcli.display_units import DEFAULT, convert, unit_and_factor
from gearcli.report.data import ReportData
from gearcli.results import shown_values
from gearcli.results.metrics import display
from gearcli.results.stress import Safety
from gearcli.units import split_internal


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


def _cells(value, system: str, unit: str | None = None) -> tuple[str, str]:
    """(value, unit) cells in the display units ``system`` (gearcli/display_units.py) of a
    stored "number unit" string (internal units), or of the number ``value`` in ``unit``."""
    x, u = (value, unit) if unit is not None else split_internal(value)
    shown, shown_unit = convert(x, u, system)
    return fmt(shown), shown_unit


def qty(value, system: str = DEFAULT, unit: str | None = None) -> str:
    """:func:`_cells` as one 'number unit' text ("104.7 rad/s" -> "1000 rpm"); None as "–"."""
    return "–" if value is None else " ".join(_cells(value, system, unit)).strip()


def _unit(text: str) -> str:
    """The unit of a stored "number unit" text; "" for a word ("derived", "linear")."""
    try:
        return split_internal(text)[1]
    except ValueError:
        return ""


def _is_number(value) -> bool:
    """Whether a stored case value is a number (or "number unit"), not a word like "derived"."""
    try:
        return math.isfinite(split_internal(value)[0])
    except (TypeError, ValueError):
        return False


def _deg(value) -> str:
    return "–" if value is None else f"{math.degrees(split_internal(value)[0]):.4g} deg"


# --- the case ---------------------------------------------------------------------------------
def gears_table(data: ReportData) -> Table:
    """Table 1-style: teeth, module, pressure angle, face width, diameters, material."""
    case, geo, u = data.case_data, data.geometry, data.units
    g = case["gears"]
    p, w = g["pinion"], g["gear"]
    mat = case.get("material") or {}
    rows = [
        ("number of teeth z", str(p["teeth"]), str(w["teeth"])),
        ("module m", qty(g["module"], u), qty(g["module"], u)),
        ("pressure angle α", _deg(g["pressure_angle"]), _deg(g["pressure_angle"])),
        ("face width b", qty(p.get("face_width") or g["face_width"], u),
         qty(w.get("face_width") or g["face_width"], u)),
        ("profile shift x", fmt(p.get("profile_shift", 0.0)), fmt(w.get("profile_shift", 0.0))),
    ]
    # the tooth-form and body settings a case may give (shown when either gear sets one)
    for label, key in (("thickness allowance", "thickness_allowance"),
                       ("tip shortening", "tip_shortening"), ("tip rounding", "tip_rounding"),
                       ("bore diameter", "bore_diameter")):
        values = [gear.get(key) for gear in (p, w)]
        if any(v is not None and _setting(v, u) not in ("0", "0 mm", "0 m") for v in values):
            rows.append((label, *(_setting(v, u) if v is not None else "–" for v in values)))
    if geo is not None:
        for label, attr in (("reference diameter d", "d_mm"), ("tip diameter d_a", "d_a_mm"),
                            ("base diameter d_b", "d_b_mm"), ("root diameter d_f", "d_f_mm")):
            rows.append((label, qty(getattr(geo.pinion, attr), u, "mm"),
                         qty(getattr(geo.gear, attr), u, "mm")))
    for label, key in (("density ρ", "density"), ("Young's modulus E", "youngs_modulus"),
                       ("Poisson ratio ν", "poisson_ratio")):
        cells = []
        for gear in (p, w):
            m = gear.get("material") or mat
            cells.append(qty(m.get(key), u) if m.get(key) is not None else "–")
        rows.append((label, *cells))
    rows.append(("inertia model", *(_inertia(gear, u) for gear in (p, w))))
    return Table("Gears and material", ("quantity", "pinion", "gear"), rows)


def _inertia(gear: dict, u: str) -> str:
    i = gear.get("inertia") or {}
    model = i.get("model", "disc")
    if model == "disc":
        d = i.get("diameter")
        text = "solid disc, " + ("pitch diameter" if d is None else qty(d, u))
    else:
        text = f"given J = {qty(i.get('value'), u)}"
    extra = split_internal(i.get("extra"))[0] if i.get("extra") is not None else 0.0
    return text + (f" + {qty(i.get('extra'), u)}" if extra else "")


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
    note = "; ".join(f.message for f in geo.findings)
    return Table("Pair geometry (derived)", ("quantity", "value", "unit"), rows, note)


def contact_table(data: ReportData) -> Table:
    """Table 3-style: contact law and friction parameters."""
    c = data.case_data.get("contact") or {}
    f = data.case_data.get("friction") or {}
    rows = [("contact law", str(c.get("law", "")), ""),
            ("engagement model", str(c.get("engagement", "")), "")]
    if c.get("law") == "tooth":  # docs/theory.md §4b, §4c: no IMPACT parameters
        rows.append(("mesh damping ratio ζ", fmt(c.get("damping_ratio")), "–"))
        for gear in ("pinion", "gear"):
            bore = ((data.case_data.get("gears") or {}).get(gear) or {}).get("bore_diameter")
            rows.append((f"{gear} bore (gear-body compliance)",
                         *(_cells(bore, data.units) if bore is not None
                           else ("default (docs/theory.md §4b)", ""))))
        k = data.scalars.mesh_stiffness_N_mm
        if isinstance(k, int | float):
            rows.append(("mesh stiffness, linearised at the static load",
                         *_cells(k, data.units, "N/mm")))
    else:
        e = split_internal(c.get("exponent", 1.0))[0]
        stiffness = c.get("stiffness")
        rows += [
            ("stiffness K", fmt(split_internal(stiffness)[0]) if _is_number(stiffness)
             else str(stiffness), f"N/mm^{e:g}"),
            ("force exponent e", fmt(e), "–"),
            ("maximum damping c_max", *_cells(c.get("max_damping"), data.units)),
            ("damping ramp depth d_max", *_cells(c.get("penetration_depth"), data.units)),
        ]
    rows.append(("friction", "on" if f.get("enabled") else "off", ""))
    if f.get("enabled"):
        rows += [
            ("static coefficient μ_s", fmt(f.get("static_coefficient")), "–"),
            ("dynamic coefficient μ_d", fmt(f.get("dynamic_coefficient")), "–"),
            ("stiction velocity v_s", *_cells(f.get("stiction_velocity"), data.units)),
            ("transition velocity v_d", *_cells(f.get("transition_velocity"), data.units)),
        ]
    return Table("Contact and friction", ("parameter", "value", "unit"), rows)


def _function(spec: dict | None) -> str:
    if not spec:
        return "–"
    return f"{spec.get('function', '')} [{spec.get('unit', '')}]"


def drive_table(data: ReportData) -> Table:
    """Drive and load functions, bearing losses and run settings."""
    case = data.case_data
    d, ld = case.get("drive") or {}, case.get("load") or {}
    b, r = case.get("bearings") or {}, case.get("run") or {}
    kind, u = d.get("type", ""), data.units
    rows = [
        ("drive (pinion)", f"{kind}: {_function(d.get(kind) if kind else None)}"),
        ("initial pinion speed", qty(d.get("initial_speed"), u)),
        (f"load torque (on the {ld.get('applied_to', 'gear')})", _function(ld.get("torque"))),
        ("load: viscous / quadratic",
         f"{qty(ld.get('viscous'), u)} / {qty(ld.get('quadratic'), u)}"),
        ("bearing damping pinion / gear", f"{qty((b.get('pinion') or {}).get('damping'), u)} / "
                                          f"{qty((b.get('gear') or {}).get('damping'), u)}"),
        ("end time", qty(r.get("end_time"), u)),
        ("output", f"{fmt(data.scalars.output_rate_Hz)} Hz "
                   f"({data.run.summary.rows} rows)"),
        ("tolerances rtol / atol", f"{fmt(r.get('rtol'))} / " + (
            qty(r.get("atol"), u) if r.get("atol") is not None
            else "default (1e-5 of the static deflection, at most 1 µm)")),
    ]
    for key in ("shaft", "motor_curve", "motor_inertia", "reference_speed"):
        if d.get(key) is not None:
            rows.append((f"drive {key.replace('_', ' ')}", _setting(d[key], u)))
    for key in ("shaft", "inertia"):
        if ld.get(key) is not None:
            rows.append((f"load {key}", _setting(ld[key], u)))
    rows.insert(0, ("model", str(case.get("model", "torsional"))))
    for gear in ("pinion", "gear"):  # the lateral model's bearings (beyond the damping above)
        lateral = {k: v for k, v in (b.get(gear) or {}).items() if k != "damping"}
        if lateral:
            rows.append((f"bearings {gear}", _setting(lateral, u)))
    return Table("Model, drive, load and run", ("item", "setting"), rows)


def _setting(value, u: str) -> str:
    """A resolved case value for a table: a mapping as "name value unit" pairs in the display
    units ``u``, numbers with 4 significant digits (never Python's repr)."""
    if isinstance(value, dict):
        return "; ".join(f"{k.replace('_', ' ')} {_setting(v, u)}" for k, v in value.items())
    if isinstance(value, str) and _unit(value) == "rad":  # angles as the case takes them
        return _deg(value)
    if isinstance(value, str) and _unit(value):
        return qty(value, u)
    return fmt(value)


def modifications_table(data: ReportData) -> Table | None:
    """Profile reliefs and manufacturing errors that are set (None when there are none)."""
    rows = []
    for group in ("modifications", "errors"):
        for kind, pair in (data.case_data.get(group) or {}).items():
            for gear, spec in (pair or {}).items():
                if spec is not None:
                    text = ", ".join(f"{k} = {_setting(v, data.units)}"
                                     for k, v in spec.items() if v is not None)
                    rows.append((f"{gear} {kind.replace('_', ' ')}", text))
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


def checks_table(data: ReportData) -> Table:
    """Every check of analysis.json, marked pass or fail."""
    rows, status = [], []
    for c in data.analysis.checks:
        ok = bool(c.passed)
        checked = c.checked is not False
        result = "not checked" if not checked else "pass" if ok else "FAIL"
        rows.append((str(c.name), fmt(c.value), str(c.limit), result, str(c.note or "")))
        status.append("fail" if not ok else "pass" if checked else "")
    return Table("Checks", ("check", "value", "limit", "result", "note"), rows, status=status)


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
