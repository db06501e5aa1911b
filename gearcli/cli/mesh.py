"""`gearcli mesh CASE`: quasi-static loaded tooth contact (static transmission error)."""

from __future__ import annotations

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
    table_options,
)
from gearcli.io.files import write_stdout


@app.command()
@handle_errors
@table_options
def mesh(
    case: Path = typer.Argument(..., help="Case file (YAML)."),
    load: str | None = typer.Option(
        None, "--load", help="Static normal force: a force with units ('5 kN') or a number in N "
        "(default: the case's load torque / r_b2)."),
    harris: bool = typer.Option(False, "--harris", help="Also compute the Harris map (STE "
                                "peak-to-peak against 0.1 .. 2 x the load)."),
    as_json: bool = typer.Option(False, "--json", help="Print the results as JSON."),
    plot: Path | None = typer.Option(None, "--plot", help="Write the figure (.png, .svg, .pdf)."),
    faults_plot: Path | None = typer.Option(
        None, "--faults-plot", help="With faults: write the faulted stiffness and STE over one "
        "pinion revolution (.png, .svg, .pdf)."),
    out: Path | None = typer.Option(None, "-o", "--out", help="Write mesh.json, mesh.csv, "
                                    "mesh.png and manifest.json into this folder."),
    force: bool = typer.Option(False, "--force", help="Replace an earlier results folder "
                               "(files gearcli did not write stay) or --plot file."),
    set_: list[str] = typer.Option(
        [], "--set", help="Override a case value: key.path=value (repeatable)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No tables; errors only."),
    method: str = typer.Option("pe", "--method", help="pe: the tooth law (default); fe: also "
                               "the finite-element model of the pair beside it (needs the "
                               "extra 'fe': pip install 'gearcli[fe]')."),
) -> None:
    """Loaded tooth contact of the pair without dynamics: at each roll position over two mesh
    cycles the static equilibrium with the case's load (all gaps: profile modifications,
    extended contact), so the number of pairs in contact emerges. Reports the loaded static
    transmission error (µm and arcsec, peak-to-peak, first three mesh harmonics), load sharing
    and mesh stiffness beside ISO 6336-1 c′b and c_γα b.

    With --method fe, the pair's finite-element model (docs/theory.md, "Finite-element check
    of the tooth compliance") beside the tooth law: pair stiffness at the pitch point, mean
    mesh stiffness, loaded STE and FE/PE - 1; its influence coefficients are cached per
    geometry in the user cache folder.

    With faults (case ``faults:``), also the faulted mesh stiffness and STE over one pinion
    revolution (mesh.json ``faulted_revolution``, mesh_faults.csv and mesh_faults.png with -o,
    --faults-plot); the tables of the healthy pair stay.

    Example: gearcli mesh cases/seed.yaml --harris --plot mesh.png

    Exit codes: 0 ok, 1 bad input.
    """
    import json

    from gearcli import api
    from gearcli.errors import CaseError
    from gearcli.pipeline.mesh import (
        mesh_document,
        save_mesh_plot,
        save_revolution_plot,
        write_mesh,
    )

    if method not in ("pe", "fe"):
        raise CaseError(f"--method {method!r:.40}: expected pe or fe")
    if load is not None:  # a number in N or a force with units, as the case file writes it
        (load,) = option_quantities([load], "FORCE", "--load")
        if not load > 0.0:
            raise CaseError(f"--load must be a force > 0 N, got {load:g} N")
    from gearcli.io.outdir import check_target

    check_figure_path("--plot", plot, force)
    check_figure_path("--faults-plot", faults_plot, force)
    if out is not None:
        check_target(out, force)  # before the work, not after
    analysis = api.mesh(case, set_, load_N=load, harris=harris, method=method)
    res, units = analysis, display_units()
    typed = mesh_document(res, units)  # its texts (the single-pair limit's note) in ``units``
    doc = typed.to_dict()
    if out is not None:
        write_mesh(res, out, force, set_, units, doc)
    if plot is not None:
        save_mesh_plot(res, plot, units)
    if faults_plot is not None:
        if res.revolution is None:
            raise CaseError(f"--faults-plot {faults_plot}: the case has no tooth faults of "
                            "nonzero size; expected a case with 'faults:'")
        save_revolution_plot(res, faults_plot, units)
    if as_json:
        write_stdout(json.dumps(doc, indent=2) + "\n")
        return
    if quiet:
        return
    _print(typed, units)
    for path in (out, plot, faults_plot):
        if path is not None:
            typer.echo(f"wrote {path}")


def _table(title: str, rows: list[tuple[str, float, str]], units: str):
    """A (quantity, value, unit) table; values in their stored unit, shown in ``units``."""
    from rich.table import Table

    from gearcli.display_units import convert

    t = Table(title=title, title_justify="left")
    for col in ("quantity", "value", "unit"):
        t.add_column(col)
    for label, value, unit in rows:
        shown, shown_unit = convert(value, unit, units)
        t.add_row(label, format_value(shown), shown_unit)
    return t


def _sharing_rows(sh) -> list[tuple[str, float | str, str]]:
    """Pairs in contact and the single-pair limit (MeshSharing), or why there is none."""
    rows = [("pairs in contact, fewest / most",
             f"{sh.pairs_in_contact_min} / {sh.pairs_in_contact_max}", "–"),
            ("share of the cycle with one pair alone", sh.single_pair_share, "fraction")]
    label = "one pair alone somewhere in the cycle up to"
    if sh.single_pair_limit_N is None or sh.single_pair_limit_N <= 0.0:
        return [*rows, (label, sh.single_pair_limit_note, "–")]
    return [*rows, (label, sh.single_pair_limit_N, "N"),
            ("  the same per face width", sh.single_pair_limit_N_per_mm, "N/mm (line load)")]


def _print(doc, units: str) -> None:
    from rich.markup import escape

    emit(f"[bold]{escape(doc.case)}[/bold]: loaded contact at "
         f"{format_value(doc.force_N)} N, {doc.contact_law}")
    ste, st = doc.ste, doc.stiffness
    emit(_table("Static transmission error", [
        ("mean", ste.mean_um, "µm"),
        ("peak-to-peak", ste.peak_to_peak_um, "µm"),
        ("peak-to-peak at the pinion", ste.peak_to_peak_arcsec, "arcsec"),
        *((f"{k} amplitude", v, "µm") for k, v in ste.harmonics_um.items()),
        ("unloaded TE peak-to-peak", ste.unloaded_te_peak_to_peak_um, "µm"),
    ], units))
    emit(_table("Mesh stiffness", [
        ("mean over the cycle", st.mesh_mean_N_mm, "N/mm"),
        ("single-pair zone (mean)", st.single_pair_zone_N_mm, "N/mm"),
        ("double-pair zone (mean)", st.double_pair_zone_N_mm, "N/mm"),
        ("ISO 6336-1 c′b (single pair; no low-load factor)",
         st.iso6336_single_pair_c_prime_b_N_mm, "N/mm"),
        ("ISO 6336-1 c_γα b (mean; no low-load factor)",
         st.iso6336_mean_c_gamma_alpha_b_N_mm, "N/mm"),
    ], units))
    emit(_table("Load sharing", _sharing_rows(doc.sharing), units))
    kv = doc.iso6336_method_b
    if kv is not None:
        rows = [("low-load factor L_f (rating only)", kv.low_load_factor, "–"),
                ("c′ with L_f", kv.c_prime_N_mm_um, "N/(mm·µm)"),
                ("c_γα with L_f", kv.c_gamma_alpha_N_mm_um, "N/(mm·µm)"),
                ("reduced mass m_red", kv.reduced_mass_kg_mm, "kg/mm"),
                ("resonance speed n_E1 (both gears free)", kv.resonance_speed_rpm, "rpm"),
                ("B_p / B_f / B_k", f"{kv.B_p:.4g} / {kv.B_f:.4g} / {kv.B_k:.4g}", "–")]
        if kv.k_v is not None:
            rows += [("resonance ratio N = n1/n_E1", kv.resonance_ratio, "–"),
                     (f"K_v ({kv.speed_range})", kv.k_v, "–")]
        emit(_table("ISO 6336-1 Method B dynamic factor (K_A = 1)", rows, units))
    if doc.harris is not None:
        from rich.table import Table

        from gearcli.display_units import convert

        ptp, unit = convert(list(doc.harris.ste_peak_to_peak_um), "µm", units)
        h = Table(title="Harris map", title_justify="left")
        h.add_column(escape("force [N]"))
        h.add_column(escape(f"STE peak-to-peak [{unit}]"))  # rich reads "[m]" as markup
        for f, p in zip(doc.harris.force_N, ptp, strict=True):
            h.add_row(format_value(f), format_value(p))
        emit(h)
        if None in doc.harris.ste_peak_to_peak_um:
            emit("note: — in the Harris map: no static equilibrium inside the contact tables "
                 "at that force (outside the contact model's range)")
    if doc.fe_check is not None:
        emit(_fe_table(doc.fe_check, units))
    if doc.faulted_revolution is not None:
        r = doc.faulted_revolution
        emit(_table(f"Faulted mesh over one pinion revolution ({', '.join(r.faults)}; "
                    "the tables above: the healthy pair)", [
            ("mesh stiffness, minimum", r.stiffness_min_N_mm, "N/mm"),
            ("  healthy", r.stiffness_healthy_min_N_mm, "N/mm"),
            ("largest stiffness drop 1 − k_f/k", r.stiffness_largest_drop, "–"),
            ("  at pinion roll from t = 0", r.stiffness_largest_drop_at_roll_mm, "mm"),
            ("loaded STE peak-to-peak", r.ste_peak_to_peak_um, "µm"),
            ("  healthy", r.ste_healthy_peak_to_peak_um, "µm"),
            ("share of the revolution without a carrying pair", r.no_contact_share, "–"),
        ], units))
    for note in doc.notes:
        emit(f"note: {escape(note)}")


def _fe_table(fe, units: str):
    """The tooth law (PE) and the FE model side by side, with FE/PE − 1."""
    from rich.markup import escape
    from rich.table import Table

    from gearcli.display_units import convert

    state = "plane strain" if fe.plane_strain else "plane stress"
    t = Table(title=f"Tooth law (PE) against finite elements (FE), {state}, "
                    f"{format_value(fe.line_load_N_mm)} N/mm", title_justify="left",
              caption=f"note: {fe.note}", caption_justify="left")
    for col in ("quantity", "PE", "FE", "unit", "FE/PE − 1"):
        t.add_column(col)
    for label, q, unit in (("single-pair stiffness at the pitch point",
                            fe.pitch_pair_stiffness_N_mm, "N/mm"),
                           ("mean mesh stiffness", fe.mesh_mean_stiffness_N_mm, "N/mm"),
                           ("loaded STE peak-to-peak (pairs on the path)",
                            fe.ste_peak_to_peak_um, "µm"),
                           ("loaded STE peak-to-peak with the tip corners",
                            fe.loaded_ste_peak_to_peak_um, "µm"),
                           ("share of one pair in contact with the tip corners",
                            fe.single_pair_share, "–"),
                           ("  teeth + body at the pitch point", fe.teeth_at_pitch_N_mm, "N/mm"),
                           ("  contact term at the pitch point", fe.contact_at_pitch_N_mm,
                            "N/mm")):
        (pe, fe_value), shown_unit = convert([q.pe, q.fe], unit, units)
        rel = q.fe_over_pe_minus_1
        t.add_row(label, format_value(pe), format_value(fe_value), escape(shown_unit),
                  "—" if rel is None else f"{100.0 * rel:+.1f} %")
    return t
