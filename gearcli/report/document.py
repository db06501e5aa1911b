"""The report as a format-free document: sections of paragraphs, lists, tables and figures."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from gearcli.report import tables as tb
from gearcli.report.data import ReportData
from gearcli.report.figures import FigureFile
from gearcli.report.rating import missing_line, rating_table
from gearcli.results import shown_values
from gearcli.results.metrics import display


@dataclass(frozen=True)
class Paragraph:
    text: str
    kind: str = ""  #: "pass" / "fail" for the verdict


@dataclass(frozen=True)
class Preformatted:
    """Text shown as written (the case file), with a caption."""

    caption: str
    text: str


@dataclass(frozen=True)
class Bullets:
    items: tuple[str, ...]
    kind: str = ""  #: "warn" for warnings


@dataclass(frozen=True)
class NumberedTable:
    number: int
    table: tb.Table


@dataclass(frozen=True)
class NumberedFigure:
    number: int
    figure: FigureFile


@dataclass
class Section:
    title: str
    anchor: str
    blocks: list = field(default_factory=list)


@dataclass
class Document:
    title: str
    description: str
    sections: list[Section]


def _case_text(data: ReportData) -> list:
    """The case file as the user wrote it (manifest.json's case_text; folders written before
    it was recorded have none), with the command line's overrides."""
    text = data.run.manifest.get("case_text")
    if not isinstance(text, str) or not text.strip():
        return []
    overrides = data.run.manifest.get("overrides") or []
    caption = (f"The case file as written ({data.run.manifest.get('case_file', '')})"
               + (f", run with --set {'; '.join(map(str, overrides))}" if overrides else ""))
    return [Preformatted(caption, text)]


def build_document(data: ReportData, figures: list[FigureFile]) -> Document:
    """Assemble every section of the report from the folder's data and the saved figures."""
    counter = iter(range(1, 100))

    def tables(*items: tb.Table | None) -> list[NumberedTable]:
        return [NumberedTable(next(counter), t) for t in items if t is not None]

    checks = data.analysis.checks
    failed = [c.label for c in checks if c.checked is not False and not c.passed]
    skipped = [c.label for c in checks if c.checked is False]  # labels: never a raw key
    done = len(checks) - len(skipped)
    not_checked = (f" Not checked: {'; '.join(map(str, skipped))} (see the notes)."
                   if skipped else "")
    verdict = (Paragraph(f"Analysis passed: the {done} applicable checks pass.{not_checked}",
                         "pass") if not failed
               else Paragraph(f"Analysis FAILED: {len(failed)} of {done} checks fail "
                              f"({'; '.join(map(str, failed))}).{not_checked}", "fail"))
    headline = []
    for key, value in shown_values(data.metrics, "headline").items():
        if isinstance(value, int | float) and math.isfinite(value):
            label, value, unit = display(key, value, data.units)
            headline.append(f"{label}: {tb.fmt(value)} {unit if unit != '–' else ''}".rstrip())
    warnings = data.warnings
    overrides = [str(o) for o in data.run.manifest.get("overrides") or []]
    summary = [verdict]
    remedies: dict[str, list[str]] = {}
    for c in checks:
        if c.remedy is not None and c.failed:
            remedies.setdefault(c.remedy.text, []).append(c.label)
    if remedies:
        summary.append(Bullets(tuple(f"Remedy ({'; '.join(names)}): {text}"
                                     for text, names in remedies.items())))
    if overrides:
        summary.append(Paragraph("Case file values changed on the command line (the tables "
                                 "show the values used): " + "; ".join(overrides)))
    summary.append(Bullets(tuple(headline)))
    if warnings:
        summary.append(Paragraph(f"{len(warnings)} warning(s): see Warnings."))
    geometry_note = ([Paragraph(f"Geometry not recomputed: {data.geometry_error}")]
                     if data.geometry is None else [])
    sections = [
        Section("Summary", "summary", summary),
        Section("Case", "case", geometry_note + tables(
            tb.gears_table(data), tb.geometry_table(data), tb.contact_table(data),
            tb.drive_table(data), tb.modifications_table(data)) + _case_text(data)),
        Section("Results", "results", tables(tb.results_table(data), tb.lines_table(data),
                                             tb.modes_table(data))),
        Section("Checks", "checks", tables(tb.checks_table(data))),
        *([Section("Stress", "stress", tables(tb.stress_table(data)))] if data.stress else []),
        Section("Rating (ISO 6336)", "rating",
                tables(rating_table(data.rating)) if data.rating
                else [Paragraph(missing_line(data.case))]),
        Section("Warnings", "warnings",
                [Bullets(tuple(warnings), "warn")] if warnings else [Paragraph("None.")]),
        Section("Figures", "figures",
                [NumberedFigure(k, f) for k, f in enumerate(figures, start=1)]),
        Section("Provenance", "provenance", tables(tb.provenance_table(data))),
    ]
    name = str(data.case.name or data.run.summary.case or data.folder.name)
    return Document(f"gearcli report: {name}", data.case.description.strip(),
                    sections)
