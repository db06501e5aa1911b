"""`gearcli monitor RUN`: condition-monitoring metrics (TSA, FM4, NA4, ...) of a finished run."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import emit, handle_errors, table_options
from gearcli.io.files import write_stdout


@app.command()
@handle_errors
@table_options
def monitor(
    run: Path = typer.Argument(..., help="Results folder written by gearcli simulate."),
    baseline: Path | None = typer.Option(
        None, "--baseline", help="A healthy run's results folder: NA4 and NB4 are normalised "
        "by its revolutions (default: the run's own)."),
    as_json: bool = typer.Option(False, "--json", help="Print monitor.json to stdout."),
    out: Path | None = typer.Option(None, "-o", "--out", help="Write monitor.json and "
                                    "manifest.json into this folder."),
    force: bool = typer.Option(False, "--force", help="Replace an earlier results folder "
                               "(files gearcli did not write stay)."),
    signal: str = typer.Option(
        "te", "--signal", help="te (the TE from the simulated shaft angles, default) or a "
        "column of the run's sensors table: accel_m_s2, te_mm, alpha1_rad_s2, alpha2_rad_s2, "
        "bearing_force_{x,y}{1,2}_N (docs/theory.md, What a sensor sees)."),
    orders: Path | None = typer.Option(
        None, "--orders", help="Write the order spectrum of each shaft's TSA with the "
        "sidebands around each mesh harmonic (.png, .svg, .pdf)."),
    teeth: Path | None = typer.Option(
        None, "--teeth", help="Write each shaft's TSA and difference signal tooth by tooth, "
        "the faulted teeth marked (.png, .svg, .pdf)."),
    wav: Path | None = typer.Option(
        None, "--wav", help="Write the signal of the whole run as audio: mono 16-bit WAV, "
        "44.1 kHz, real time, peak-normalised."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No tables; errors only."),
) -> None:
    """Condition-monitoring metrics of a run (docs/theory.md, "Condition-monitoring signals"):
    the transmission error from the simulated shaft angles, resampled onto each shaft's angle,
    time-synchronously averaged over the whole revolutions of the steady window, and RMS,
    kurtosis, crest factor, FM0, FM4, M6A, M8A, NA4, NB4, energy ratio and sideband level and
    index of each shaft's average.

    With --orders, --teeth and --wav: the order spectra (also in the JSON: ``sidebands``), the
    TSA tooth by tooth, and the sound of the signal.

    Example: gearcli monitor out/cracked --baseline out/healthy --orders orders.png
    --teeth teeth.png --wav cracked.wav

    Exit codes: 0 done, 1 bad input (e.g. less than one whole revolution in the window).
    """
    import json

    from gearcli import api
    from gearcli.cli.common import check_figure_path
    from gearcli.io.files import check_new_file, check_suffix
    from gearcli.io.outdir import check_target
    from gearcli.pipeline import monitor_outputs as views
    from gearcli.pipeline.monitor import write_monitor

    if out is not None:
        check_target(out, force)  # before the work, not after
    check_figure_path("--orders", orders, force)
    check_figure_path("--teeth", teeth, force)
    if wav is not None:
        check_suffix("--wav", wav, (".wav",))
        check_new_file(wav, force, "--wav")
    doc = api.monitor(run, baseline, signal=signal)
    if out is not None:
        write_monitor(doc, out, force)
    written = [out] if out is not None else []
    for path, draw in ((orders, views.orders_figure), (teeth, views.teeth_figure)):
        if path is not None:
            written.append(views.save_monitor_figure(draw(doc), path))
    if wav is not None:
        written.append(views.write_audio(run, wav, signal)[0])
    if as_json:
        write_stdout(json.dumps(doc.to_dict(), indent=2) + "\n")
    elif not quiet:
        print_monitor(doc)
        for path in written:
            typer.echo(f"wrote {path}")


def print_monitor(doc) -> None:
    """One table per shaft: metric, value, definition and its reference."""
    from rich.markup import escape
    from rich.table import Table

    from gearcli.cli.common import format_value
    from gearcli.results.monitor import METRIC_DEFINITIONS

    w0, w1 = doc.window_s
    for s in doc.shafts:
        t = Table(title=escape(f"{doc.case}, {s.shaft} ({s.teeth} teeth): TSA of {s.n_revolutions} "
                               f"revolution(s) in {w0:.3f}-{w1:.3f} s, {doc.signal} "
                               f"[{doc.signal_unit}]; {s.normalisation}"),
                  title_justify="left")
        for col in ("metric", "value", "definition", "reference"):
            t.add_column(col, justify="right" if col == "value" else "left")
        for name, definition, ref in METRIC_DEFINITIONS:
            value = s.value(name)
            t.add_row(name, escape("—" if value is None else format_value(value)),
                      escape(definition), escape(ref))
        emit(t)
