"""`gearcli geometry CASE`: the checked involute geometry of the pair (table, JSON, drawing)."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import (
    check_figure_path,
    display_units,
    format_value,
    handle_errors,
    table_options,
)
from gearcli.io.files import write_stdout

# (label, json key, stored unit) rows of the per-gear and per-pair tables (shown in the display
# units, gearcli/display_units.py).
GEAR_ROWS = [
    ("teeth z", "z", ""),
    ("module m", "module_mm", "mm"),
    ("pressure angle α", "pressure_angle_deg", "deg"),
    ("profile shift x", "profile_shift", ""),
    ("reference diameter d", "d_mm", "mm"),
    ("base diameter d_b", "d_b_mm", "mm"),
    ("tip diameter d_a", "d_a_mm", "mm"),
    ("root diameter d_f", "d_f_mm", "mm"),
    ("operating pitch diameter d_w", "d_w_mm", "mm"),
    ("root form diameter d_Ff", "d_Ff_mm", "mm"),
    ("active profile start d_Nf", "d_Nf_mm", "mm"),
    ("tooth thickness at d, s", "s_mm", "mm"),
    ("tooth thickness at d_a, s_a", "s_a_mm", "mm"),
    ("base pitch p_b", "p_b_mm", "mm"),
    ("tip clearance (to mate's root)", "tip_clearance_mm", "mm"),
    ("root clearance (mate's tip)", "root_clearance_mm", "mm"),
    ("undercut limit x_min", "x_min_undercut", ""),
    ("undercut", "undercut", ""),
    ("mass", "mass_kg", "kg"),
    ("polar inertia J", "inertia_kg_m2", "kg·m²"),
]
PAIR_ROWS = [
    ("reference centre distance a", "a_mm", "mm"),
    ("operating centre distance a_w", "a_w_mm", "mm"),
    ("operating pressure angle α_w", "alpha_w_deg", "deg"),
    ("backlash, normal (along LoA) j_n", "backlash_normal_mm", "mm"),
    ("backlash, circumferential j_wt", "backlash_circumferential_mm", "mm"),
    ("ratio i = z2/z1", "ratio", ""),
    ("T1T2 (line of action)", "T1T2_mm", "mm"),
    ("path of contact g_α = AE", "path_of_contact_mm", "mm"),
    ("T1A (start of contact)", "T1A_mm", "mm"),
    ("T1B (start of single contact)", "T1B_mm", "mm"),
    ("T1C (pitch point)", "T1C_mm", "mm"),
    ("T1D (end of single contact)", "T1D_mm", "mm"),
    ("T1E (end of contact)", "T1E_mm", "mm"),
    ("transverse contact ratio ε_α", "contact_ratio", ""),
    ("single-contact fraction", "single_contact_fraction", ""),
    ("double-contact fraction", "double_contact_fraction", ""),
    ("pinion speed", "pinion_speed_deg_s", "deg/s"),
    ("gear-mesh frequency f_z", "gear_mesh_frequency_Hz", "Hz"),
    ("pinion shaft frequency n1", "pinion_shaft_frequency_Hz", "Hz"),
    ("gear shaft frequency n2", "gear_shaft_frequency_Hz", "Hz"),
]

# (label, json key of data["inspection"][gear], index into its (nominal, upper, lower) list or
# None for a single value, unit) rows of the inspection table.
_AT = (("nominal", 0), ("at A_sne", 1), ("at A_sni", 2))  # upper, lower allowance
INSPECTION_ROWS = [
    ("thickness allowances A_sne / A_sni", "thickness_allowances_mm", "both", "mm"),
    ("span measurement teeth k", "span_teeth", None, ""),
    *[(f"span W_k, {at}", "span_mm", i, "mm") for at, i in _AT],
    ("ball diameter D_M, theoretical", "ball_theoretical_mm", None, "mm"),
    ("ball diameter D_M, used", "ball_mm", None, "mm"),
    *[(f"over balls M_dK, {at}", "over_balls_mm", i, "mm") for at, i in _AT],
    *[(f"chordal thickness s_c, {at}", "chordal_thickness_mm", i, "mm") for at, i in _AT],
    *[(f"chordal height h_c, {at}", "chordal_height_mm", i, "mm") for at, i in _AT],
]


@app.command()
@handle_errors
@table_options
def geometry(
    case: Path = typer.Argument(..., help="Case file (YAML)."),
    as_json: bool = typer.Option(False, "--json", help="Print JSON (keys carry units)."),
    plot: Path | None = typer.Option(
        None, "--plot", help="Draw the pair in mesh to FILE (.png, .svg or .pdf)."
    ),
    force: bool = typer.Option(False, "--force", help="Replace an existing --plot file."),
    set_: list[str] = typer.Option(
        [], "--set", help="Override a case value: key.path=value (repeatable)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No tables; errors and warnings."),
) -> None:
    """Involute geometry of the pair, checked (ISO 21771): per gear, per pair, warnings.

    Example: gearcli geometry cases/seed.yaml --set gears.module=8 --json"""
    from gearcli import api
    from gearcli.pipeline.geometry import geometry_dict

    check_figure_path("--plot", plot, force)
    result = api.geometry(case, set_)
    data = geometry_dict(result)
    if plot is not None:
        from gearcli.pipeline.geometry import save_geometry_plot

        save_geometry_plot(result, plot)
    if as_json:
        import json

        write_stdout(json.dumps(data, indent=2) + "\n")
    elif not quiet:
        _print_tables(data, display_units())
        if plot is not None:
            typer.echo(f"drawing written to {plot}")
    for w in data["warnings"]:
        typer.echo(f"warning: {w['message']}", err=True)


def _print_tables(data: dict, units: str) -> None:
    from rich.markup import escape
    from rich.table import Table

    from gearcli.cli.common import emit
    from gearcli.display_units import convert

    t = Table(title=escape(f"Gear geometry — {data['case']}"), title_justify="left")
    t.add_column("quantity")
    t.add_column("pinion", justify="right")
    t.add_column("gear", justify="right")
    t.add_column("unit")
    for label, key, unit in GEAR_ROWS:
        (pinion, gear), shown = convert([data["pinion"].get(key), data["gear"].get(key)], unit,
                                        units)
        t.add_row(label, format_value(pinion), format_value(gear), shown)
    emit(t)
    p = Table(title="Pair", title_justify="left")
    p.add_column("quantity")
    p.add_column("value", justify="right")
    p.add_column("unit")
    for label, key, unit in PAIR_ROWS:
        if data["pair"].get(key) is not None:
            value, shown = convert(data["pair"][key], unit, units)
            p.add_row(label, format_value(value), shown)
    emit(p)
    if data.get("inspection") is not None:
        emit(_inspection_table(data["inspection"], units))


def _inspection_table(inspection: dict, units: str):
    """Span, balls, M_dK and chordal dimensions of both gears (pipeline.geometry.
    pair_inspection), at the nominal thickness and at the allowances."""
    from rich.table import Table

    from gearcli.display_units import convert

    t = Table(title="Inspection dimensions", title_justify="left")
    t.add_column("quantity")
    t.add_column("pinion", justify="right")
    t.add_column("gear", justify="right")
    t.add_column("unit")
    for label, key, index, unit in INSPECTION_ROWS:
        values = [inspection[g][key] for g in ("pinion", "gear")]
        if index == "both":
            cells, shown = [], unit
            for pair in values:
                converted, shown = convert(list(pair), unit, units)
                cells.append(" / ".join(format_value(v) for v in converted))
            t.add_row(label, *cells, shown)
            continue
        if index is not None:
            values = [v[index] for v in values]
        (pinion, gear), shown = convert(values, unit, units)
        t.add_row(label, format_value(pinion), format_value(gear), shown)
    return t
