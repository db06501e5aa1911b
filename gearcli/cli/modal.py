"""`gearcli modal CASE`: natural frequencies, mode shapes and the resonance map."""

from __future__ import annotations

import math
from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import (
    check_figure_path,
    display_units,
    emit,
    format_value,
    handle_errors,
    option_quantities,
    print_checks_table,
    report_findings,
    table_options,
)
from gearcli.io.files import write_stdout


@app.command()
@handle_errors
@table_options
def modal(
    case: Path = typer.Argument(..., help="Case file (YAML)."),
    as_json: bool = typer.Option(False, "--json", help="Print the report as JSON."),
    speed_range: tuple[str, str] | None = typer.Option(
        None, "--speed-range", metavar="A B", help="Pinion speed range of the Campbell "
        "diagram: two speeds with units ('0 rpm' '6000 rpm') or numbers in deg/s (default "
        "0 .. 1.5 x case speed)."),
    plot: Path | None = typer.Option(None, "--plot", help="Write the Campbell diagram and "
                                     "mode shapes (.png, .svg, .pdf)."),
    set_: list[str] = typer.Option(
        [], "--set", help="Override a case value: key.path=value (repeatable)."),
    force: bool = typer.Option(False, "--force", help="Replace an existing --plot file."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No tables; errors only."),
) -> None:
    """Modes of the linearised model that `simulate` integrates (case key `model`: torsional
    or lateral-torsional), crossings of the mesh harmonics and shaft orders, and the
    resonance-margin check at the case speed.

    Exit codes: 0 ok, 4 the margin check failed, 1 bad input.

    Example: gearcli modal cases/drivetrain.yaml --plot campbell.png
    """
    import json

    from gearcli import api
    from gearcli.pipeline.modal import save_campbell_plot

    check_figure_path("--plot", plot, force)
    units = display_units()
    speeds = option_quantities(speed_range, "ANGULAR_VELOCITY", "--speed-range")
    modal_result = api.modal(case, set_, None if speeds is None else
                             (math.degrees(speeds[0]), math.degrees(speeds[1])))
    from gearcli.pipeline.modal import modal_document

    res, typed = modal_result, modal_document(modal_result)
    if plot is not None:
        save_campbell_plot(res, plot, units)
    if as_json:
        write_stdout(json.dumps(typed.to_dict(), indent=2) + "\n")
    elif not quiet:
        _print(typed, res.checks, units)
        for note in res.notes:
            typer.echo(f"note: {note}")
        if plot is not None:
            typer.echo(f"wrote {plot}")
    report_findings(res.checks)


def _print(doc, checks, units: str) -> None:
    from rich.markup import escape
    from rich.table import Table

    from gearcli.display_units import convert

    lin = doc.linearisation

    def q(value, unit, zone=""):
        if value is None:  # the loaded mesh has no such zone (e.g. eps_alpha > ~1.7 loaded)
            return f"not applicable: no {zone} zone"
        x, u = convert(value, unit, units)
        return f"{x:.4g} {u}"

    emit(
        f"[bold]{escape(doc.case)}[/bold]: {doc.model} model, drive '{escape(doc.drive)}', "
        f"linearised at F = {lin.static_force_N:.1f} N: k_mesh = "
        f"{q(lin.mesh_stiffness_N_mm, 'N/mm')} (single pair "
        f"{q(lin.single_pair_stiffness_N_mm, 'N/mm', 'single-pair')}, double pair "
        f"{q(lin.double_pair_stiffness_N_mm, 'N/mm', 'double-pair')}), c_mesh = "
        f"{q(lin.mesh_damping_Ns_mm, 'N*s/mm')}, friction {lin.friction}")
    t = Table(title="Modes", title_justify="left")
    for col in ("mode", "f [Hz]", "zeta", "description",
                "shape as lengths, rotations as r_b θ (largest = 1): "
                + ", ".join(d.rsplit("_", 1)[0] for d in doc.dofs)):
        t.add_column(escape(col))
    for m in doc.modes:
        f = "rigid body" if m.rigid_body else format_value(m.natural_frequency_Hz)
        zeta = m.damping_ratio
        z = format_value(zeta) if zeta is None or zeta <= 1.0 else \
            f"{format_value(zeta)} (overdamped)"
        shape = ", ".join(f"{v:+.3f}" for v in m.shape.values())
        t.add_row(str(m.mode), f, z, escape(m.description), shape)
    emit(t)
    (lo, hi), unit = convert(list(doc.speed_range_deg_s), "deg/s", units)
    c = Table(title=f"Crossings (pinion speed, {lo:.4g}-{hi:.4g} {unit})", title_justify="left")
    for col in ("order", "mode", "f [Hz]", f"pinion speed [{unit}]"):
        c.add_column(escape(col))  # rich would read "[rpm]" as markup and drop it
    for x in doc.crossings:
        if x.in_range:
            c.add_row(escape(x.order), str(x.mode), format_value(x.frequency_Hz),
                      format_value(convert(x.pinion_speed_deg_s, "deg/s", units)[0]))
    emit(c)
    print_checks_table(checks, units)
