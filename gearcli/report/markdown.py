"""The report as Markdown (CommonMark + pipe tables); figures are linked as files in figures/."""

from __future__ import annotations

import os
import re
from pathlib import Path

from gearcli.report.document import (
    Bullets,
    Document,
    NumberedFigure,
    NumberedTable,
    Paragraph,
    Preformatted,
)
from gearcli.report.figures import saved_formats

_SPECIAL = re.compile(r"([\\`*_\[\]<>|#])")


def md_escape(text: str) -> str:
    """Backslash-escape Markdown punctuation so that case strings render literally."""
    return _SPECIAL.sub(r"\\\1", " ".join(str(text).split()))


def render_markdown(doc: Document, base: Path) -> str:
    """The whole report as Markdown; image links are relative to ``base`` (the file's folder)."""
    out = [f"# {md_escape(doc.title)}", ""]
    if doc.description:
        out += [md_escape(doc.description), ""]
    out += [" · ".join(f"[{md_escape(s.title)}](#{s.anchor})" for s in doc.sections), ""]
    for section in doc.sections:
        out += [f"## {md_escape(section.title)}", ""]
        for block in section.blocks:
            out += _block(block, base) + [""]
    figures = [b.figure for s in doc.sections for b in s.blocks if isinstance(b, NumberedFigure)]
    out += ["---", "Written by gearcli report from the files of this results folder; the "
            f"figures are in figures/ as {saved_formats(figures)}.", ""]
    return "\n".join(out)


def _block(block, base: Path) -> list[str]:
    if isinstance(block, Paragraph):
        text = md_escape(block.text)
        return [f"**{text}**" if block.kind else text]
    if isinstance(block, Bullets):
        mark = "⚠ " if block.kind == "warn" else ""
        return [f"- {mark}{md_escape(item)}" for item in block.items]
    if isinstance(block, NumberedTable):
        return _table(block)
    if isinstance(block, Preformatted):
        fence = "`" * max(3, 1 + max((len(m) for m in re.findall(r"`+", block.text)), default=0))
        return [f"*{md_escape(block.caption)}*", "", f"{fence}yaml", block.text.rstrip("\n"),
                fence]
    if isinstance(block, NumberedFigure):
        f = block.figure
        rel = Path(os.path.relpath(f.png, base)).as_posix()
        caption = md_escape(f"Figure {block.number}. {f.caption}")
        return [f"![Figure {block.number}: {md_escape(f.name)}]({rel})", "", f"*{caption}*"]
    return []


def _table(nt: NumberedTable) -> list[str]:
    t = nt.table
    lines = [f"**Table {nt.number}. {md_escape(t.title)}**", "",
             "| " + " | ".join(md_escape(h) for h in t.headers) + " |",
             "|" + "|".join("---" for _ in t.headers) + "|"]
    for i, row in enumerate(t.rows):
        cells = [md_escape(c) for c in row]
        if i < len(t.status) and t.status[i] == "fail":
            cells = [f"**{c}**" if c else c for c in cells]
        lines.append("| " + " | ".join(cells) + " |")
    if t.note:
        lines += ["", f"_{md_escape(t.note)}_"]
    return lines
