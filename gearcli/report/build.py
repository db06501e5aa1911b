"""`build_report`: figures, then one self-contained HTML or a Markdown file, of a results folder."""

from __future__ import annotations

from pathlib import Path

from gearcli.case.overrides import text_name
from gearcli.errors import OutputError
from gearcli.io.files import write_atomic
from gearcli.report.data import load_report_data
from gearcli.report.document import build_document
from gearcli.report.figures import build_figures
from gearcli.report.html import render_html
from gearcli.report.markdown import render_markdown
from gearcli.report.monitoring import add_monitoring

FORMATS = ("html", "md")


def build_report(folder: str | Path, fmt: str = "html", out_file: str | Path | None = None,
                 units: str = "engineering", svg: bool = False) -> Path:
    """Write the report of a results folder that ``gearcli analyze`` has processed.

    Parameters
    ----------
    folder : results folder (manifest.json, summary.json, timeseries.csv, analysis.json,
        spectrum.csv)
    fmt : "html" (one self-contained file: inline CSS, figures embedded as PNG data URIs) or
        "md" (Markdown linking the PNG files in ``folder/figures``)
    out_file : report path; default ``folder/report.html`` or ``folder/report.md``
    units : display units of tables and figures, "engineering" (rpm, µm, N·m) or "si"
        (gearcli/display_units.py)
    svg : also write every figure as SVG (vector, for print or editing); off by default, as
        saving an SVG costs about as much as drawing the figure

    Returns
    -------
    Path of the report. The figures are always written to ``folder/figures/`` as PNG (and SVG
    with ``svg``; an SVG of an earlier report without ``svg`` is removed);
    every file is written atomically and replaces an older report.

    Raises
    ------
    ResultsError
        Not a finished results folder, or no analysis.json ("run gearcli analyze first").
    OutputError
        The report's folder does not exist or cannot be written.
    ValueError
        ``fmt`` is not "html" or "md".
    """
    if fmt not in FORMATS:
        raise ValueError(f"report format must be one of {', '.join(FORMATS)}; got {fmt!r}")
    data = load_report_data(folder, units)
    out = Path(out_file) if out_file is not None else data.folder / f"report.{fmt}"
    if out.is_dir():
        raise OutputError(f"{out}: is a folder; expected a report file name")
    if not out.parent.is_dir():
        raise OutputError(f"{out}: folder {out.parent} does not exist; expected an existing "
                          "folder")
    figures = build_figures(data, data.folder / "figures", svg)
    doc = build_document(data, figures)
    add_monitoring(doc, data, data.folder / "figures", svg)  # with monitor.json (faults)
    text = render_html(doc) if fmt == "html" else render_markdown(doc, out.parent)
    write_atomic(out, text_name(text))  # a file name's non-UTF-8 bytes (manifest) as U+FFFD
    return out
