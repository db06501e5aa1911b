"""`gearcli modal CASE`: natural frequencies, mode shapes and the resonance map."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import format_value, handle_errors, print_checks_table


@app.command()
@handle_errors
def modal(
    case: Path = typer.Argument(..., help="Case file (YAML)."),
    as_json: bool = typer.Option(False, "--json", help="Print the report as JSON."),
    speed_range: tuple[float, float] | None = typer.Option(
        None, "--speed-range", help="Pinion speed range A B [deg/s] of the Campbell diagram "
        "(default 0 .. 1.5 x case speed)."),
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

    from gearcli.errors import CheckFailed
    from gearcli.io.files import check_new_file
    from gearcli.pipeline.modal import modal_document, run_modal, save_campbell_plot

    check_new_file(plot, force, "--plot")
    res = run_modal(case, set_, speed_range)
    doc = modal_document(res)
    if plot is not None:
        save_campbell_plot(res, plot)
    if as_json:
        typer.echo(json.dumps(doc, indent=2))
    elif not quiet:
        _print(doc)
        if plot is not None:
            typer.echo(f"wrote {plot}")
    if not res.passed:
        failed = [c.name for c in res.checks if not c.passed]
        raise CheckFailed(f"{case}: check(s) failed: {', '.join(failed)}")


def _print(doc: dict) -> None:
    from rich.console import Console
    from rich.table import Table

    console = Console()
    lin = doc["linearisation"]
    console.print(
        f"[bold]{doc['case']}[/bold]: {doc['model']} model, drive '{doc['drive']}', "
        f"linearised at F = {lin['static_force_N']:.1f} N: k_mesh = "
        f"{lin['mesh_stiffness_N_mm']:.4g} N/mm (single pair "
        f"{lin['single_pair_stiffness_N_mm']:.4g}, double pair "
        f"{lin['double_pair_stiffness_N_mm']:.4g}), c_mesh = "
        f"{lin['mesh_damping_Ns_mm']:.4g} N*s/mm, friction off")
    t = Table(title="Modes", title_justify="left")
    for col in ("mode", "f [Hz]", "zeta", "description",
                "shape as lengths, rotations as r_b θ (largest = 1): "
                + ", ".join(d.rsplit("_", 1)[0] for d in doc["dofs"])):
        t.add_column(col)
    for m in doc["modes"]:
        f = "rigid body" if m["rigid_body"] else format_value(m["natural_frequency_Hz"])
        zeta = m["damping_ratio"]
        z = format_value(zeta) if zeta is None or zeta <= 1.0 else \
            f"{format_value(zeta)} (overdamped)"
        shape = ", ".join(f"{v:+.3f}" for v in m["shape"].values())
        t.add_row(str(m["mode"]), f, z, m["description"], shape)
    console.print(t)
    lo, hi = doc["speed_range_deg_s"]
    c = Table(title=f"Crossings (pinion speed, {lo:g}-{hi:g} deg/s)", title_justify="left")
    for col in ("order", "mode", "f [Hz]", "pinion speed [deg/s]"):
        c.add_column(col)
    for x in doc["crossings"]:
        if x["in_range"]:
            c.add_row(x["order"], str(x["mode"]), format_value(x["frequency_Hz"]),
                      format_value(x["pinion_speed_deg_s"]))
    console.print(c)
    print_checks_table(doc["checks"])
