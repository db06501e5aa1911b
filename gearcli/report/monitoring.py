"""The report's "Condition monitoring" section (docs/theory.md, "Condition-monitoring
signals"), when the results folder holds monitor.json (written by `gearcli run` and `gearcli
report` for a case with ``faults:``, pipeline/monitor.write_run_monitor; of the housing
accelerometer when the case has ``sensors.accelerometer``, else of the encoder TE): each
shaft's metrics, its order spectrum around the mesh harmonics with the shaft-order sidebands,
and the figures of `gearcli monitor --orders/--teeth`."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gearcli.io.files import save_figure
from gearcli.io.results import read_json
from gearcli.report import tables as tb
from gearcli.report.data import ReportData
from gearcli.report.document import Document, NumberedFigure, NumberedTable, Paragraph, Section
from gearcli.report.figures import FigureFile
from gearcli.results import MonitorDocument
from gearcli.results.monitor import METRIC_DEFINITIONS

MONITOR_FILE = "monitor.json"
FIGURE_DPI = 110


def _metrics_table(doc: MonitorDocument) -> tb.Table:
    rows = []
    for name, definition, ref in METRIC_DEFINITIONS:
        rows.append((name, *(tb.fmt(s.value(name)) for s in doc.shafts), definition, ref))
    w0, w1 = doc.window_s
    return tb.Table(
        f"Condition-monitoring metrics of the TSA, {doc.signal} [{doc.signal_unit}], "
        f"steady window {w0:.3f}–{w1:.3f} s",
        ("metric", *(f"{s.shaft} ({s.n_revolutions} rev.)" for s in doc.shafts),
         "definition", "reference"), rows,
        note="; ".join(f"{s.shaft}: {s.normalisation}" for s in doc.shafts))


def _sideband_table(doc: MonitorDocument) -> tb.Table:
    rows = []
    for s in doc.shafts:
        for r in s.sidebands:
            rows.append((s.shaft, f"{r.harmonic} × {s.teeth} = {r.order}",
                         *(tb.fmt(a) for a in r.amplitudes)))
    n = len(doc.shafts[0].sidebands[0].amplitudes) // 2 if doc.shafts and \
        doc.shafts[0].sidebands else 3
    return tb.Table(f"Order spectrum around the mesh harmonics [{doc.signal_unit}]: "
                    "sidebands at the shaft's own order",
                    ("shaft", "mesh order h z",
                     *(f"{k:+d}" if k else "h z" for k in range(-n, n + 1))), rows,
                    note="A fault on a gear's tooth repeats once per revolution of that gear: "
                    "its sidebands sit at that shaft's orders h z ± 1, 2, …")


def _figures(doc: MonitorDocument, out_dir: Path, svg: bool) -> list[FigureFile]:
    from gearcli.plotting.monitoring import ShaftAverage, plot_order_sidebands, plot_tsa_teeth

    shafts = [ShaftAverage(s.shaft, s.teeth, s.first_tooth, np.asarray(s.tsa, float),
                           tuple(s.faulted_teeth), s.n_revolutions) for s in doc.shafts]
    out = []
    for name, caption, fig in (
            ("monitor_orders", "Order spectrum of each shaft's TSA: mesh harmonics (black), "
             "their shaft-order sidebands (orange).",
             plot_order_sidebands(shafts, doc.signal_unit)),
            ("monitor_teeth", "Each shaft's TSA and difference signal over one revolution, "
             "tooth by tooth (x = k: tooth k at the pitch point); faulted teeth in red.",
             plot_tsa_teeth(shafts, doc.signal_unit))):
        paths = {}
        for fmt in ("png", "svg") if svg else ("png",):
            paths[fmt] = out_dir / f"{name}.{fmt}"
            save_figure(fig, paths[fmt], FIGURE_DPI)
        out.append(FigureFile(name, caption, paths["png"], paths.get("svg")))
    return out


def _last_number(document: Document, kind: type) -> int:
    return max((b.number for s in document.sections for b in s.blocks if isinstance(b, kind)),
               default=0)


def _why(doc: MonitorDocument) -> str:
    """Why the section shows this signal (pipeline/monitor.report_signal's choice)."""
    if "accelerometer" in doc.signal:
        return "the case's sensors.accelerometer, what a rig would record"
    return "the signal of a case without sensors.accelerometer"


def add_monitoring(document: Document, data: ReportData, out_dir: Path, svg: bool) -> None:
    """Insert the "Condition monitoring" section after "Figures" when the folder has
    monitor.json; otherwise leave ``document`` as it is."""
    path = data.folder / MONITOR_FILE
    if not path.is_file():
        return
    doc = MonitorDocument.from_document(read_json(path))
    if not doc.shafts or any(not s.tsa for s in doc.shafts):
        return
    t0, f0 = _last_number(document, NumberedTable), _last_number(document, NumberedFigure)
    faults = [f"{s.shaft} tooth {k}" for s in doc.shafts for k in s.faulted_teeth]
    blocks = [Paragraph(
        f"Faulted: {', '.join(faults) or 'none'}. Signal: {doc.signal} [{doc.signal_unit}] "
        f"({_why(doc)}), time-synchronously averaged per shaft over the whole revolutions of "
        "the steady window (docs/theory.md, Condition-monitoring signals; `gearcli monitor`)."),
        NumberedTable(t0 + 1, _metrics_table(doc)), NumberedTable(t0 + 2, _sideband_table(doc))]
    blocks += [NumberedFigure(f0 + k, f) for k, f in
               enumerate(_figures(doc, out_dir, svg), start=1)]
    where = next((k for k, s in enumerate(document.sections) if s.anchor == "provenance"),
                 len(document.sections))
    document.sections.insert(where, Section("Condition monitoring", "monitoring", blocks))
