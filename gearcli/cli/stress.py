"""`gearcli stress DIR`: contact and root stress histories, per-tooth maxima, ISO references."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import (
    check_figure_path,
    emit,
    handle_errors,
    option_quantities,
    table_options,
)
from gearcli.io.files import write_stdout


@app.command()
@handle_errors
@table_options
def stress(
    folder: Path = typer.Argument(..., help="Results folder written by gearcli simulate."),
    as_json: bool = typer.Option(False, "--json", help="Print stress.json to stdout."),
    plot: Path | None = typer.Option(
        None, "--plot", help="Plot σ_H and σ_F over a few mesh cycles and along the path "
        "of contact to FILE (.png, .svg or .pdf)."
    ),
    window: tuple[str, str] | None = typer.Option(
        None, "--window", help="Window T0 T1 for the maxima: times with units or numbers in s "
        "(default: the run's steady window).", metavar="T0 T1"
    ),
    safety: bool = typer.Option(
        False, "--safety", help="Require safety factors: error when the case lacks "
        "contact_fatigue_limit / bending_fatigue_limit."
    ),
    force: bool = typer.Option(False, "--force",
                               help="Replace an earlier stress.json/stress.csv and --plot file."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No tables; errors only."),
) -> None:
    """Hertz contact stress and ISO 6336-3 root stress of every tooth pair from the simulated
    forces; writes DIR/stress.csv (histories) and DIR/stress.json (maxima, ISO static values,
    ratios, safety factors). Stresses in MPa.

    Example: gearcli stress out/seed --safety --plot out/seed/stress.png"""
    import json

    from gearcli import api
    from gearcli.io.files import check_no_earlier, record_outputs
    from gearcli.io.owner import folder_lock
    from gearcli.pipeline.stress import save_stress_plot, stress_document, write_stress

    check_figure_path("--plot", plot, force)
    with folder_lock(folder):  # nothing replaces the run between reading it and writing
        check_no_earlier(folder, ("stress.json", "stress.csv"), force, "stress rating")
        rating = api.stress(folder, option_quantities(window, "TIME", "--window"),
                            require_limits=safety)
        result, typed = rating, stress_document(rating)
        doc = write_stress(result, typed.to_dict())
        if plot is not None:
            save_stress_plot(result, plot)
        record_outputs(folder, ("stress.json", "stress.csv"))
    if as_json:
        write_stdout(json.dumps(doc, indent=2) + "\n")
    elif not quiet:
        print_tables(typed)


def _f(value, fmt: str = ".4g") -> str:
    return "—" if value is None else f"{value:{fmt}}"


def _tooth(tooth) -> str:
    return "—" if tooth is None else str(tooth)


def print_tables(doc) -> None:
    """One table per gear: ISO static values, dynamic peaks, ratios, safety factors."""
    from rich.markup import escape
    from rich.table import Table

    st = doc.static
    w = doc.window_s
    emit(f"{escape(doc.case)}: static load F_n = {st.force_normal_N:.6g} N "
                  f"(F_t = {st.force_tangential_N:.6g} N), σ_H0 (pitch point, Z_H Z_E) = "
                  f"{st.sigma_H0_MPa:.4g} MPa; window {w[0]:.4g}-{w[1]:.4g} s "
                  f"({doc.window_reason})")
    for which, point, z_name in (("pinion", "B", "Z_B"), ("gear", "D", "Z_D")):
        g, s = getattr(doc, which), getattr(st, which)
        t = Table(title=f"{which} (z = {g.teeth})", title_justify="left")
        for col, just in (("quantity", "left"), ("value", "right"), ("unit", "left")):
            t.add_column(col, justify=just)
        ph, pf = g.peak_sigma_H, g.peak_sigma_F
        per_h = [v for v in g.sigma_H_max_per_tooth_MPa if v is not None]
        per_f = [v for v in g.sigma_F_max_per_tooth_MPa if v is not None]
        rows = [
            (f"ISO static σ_H ({z_name} Z_ε σ_H0, single contact at {point})",
             _f(s.sigma_H_iso_MPa), "MPa"),
            ("ISO Y_F / Y_S (Method B, outer single contact)", f"{s.Y_F:.4f} / {s.Y_S:.4f}", ""),
            ("ISO static σ_F0 = F_t/(b m) Y_F Y_S", _f(s.sigma_F0_MPa), "MPa"),
            ("peak dynamic σ_H", _f(ph.MPa), "MPa"),
            ("  at", f"t = {_f(ph.t_s, '.5g')} s, tooth {_tooth(ph.tooth)}, {ph.zone or ''}",
             ""),
            ("peak dynamic σ_F", _f(pf.MPa), "MPa"),
            ("  at", f"t = {_f(pf.t_s, '.5g')} s, tooth {_tooth(pf.tooth)}, {pf.zone or ''}",
             ""),
            ("σ_H max per tooth (min … max over teeth)",
             f"{min(per_h):.4g} … {max(per_h):.4g}" if per_h else "—", "MPa"),
            ("σ_F max per tooth (min … max over teeth)",
             f"{min(per_f):.4g} … {max(per_f):.4g}" if per_f else "—", "MPa"),
            ("dynamic / static σ_H", _f(g.ratio_sigma_H_to_static), ""),
            ("dynamic / static σ_F", _f(g.ratio_sigma_F_to_static), ""),
        ]
        sf = g.safety
        if sf is not None:
            rows += [("safety S_H = σ_Hlim / σ_H,max", _f(sf.S_H, ".3f"), ""),
                     ("safety S_F = σ_Flim Y_ST / σ_F,max", _f(sf.S_F, ".3f"), "")]
        for row in rows:
            t.add_row(*row)
        emit(t)
    for text in doc.warnings:
        emit(f"[yellow]warning:[/yellow] {escape(text)}")
