"""One self-contained HTML file: inline CSS, PNG figures as base64 data URIs, no scripts, no
external links; every string from the case or the results is HTML-escaped."""

from __future__ import annotations

import base64
from html import escape

from gearcli.report.document import (
    Bullets,
    Document,
    NumberedFigure,
    NumberedTable,
    Paragraph,
    Preformatted,
    Section,
)
from gearcli.report.figures import saved_formats

CSS = """
body { font-family: -apple-system, "Segoe UI", Helvetica, Arial, sans-serif; color: #1d1d1d;
       margin: 0; background: #fafafa; line-height: 1.45; }
main { max-width: 1120px; margin: 0 auto; padding: 1.5rem 2rem 3rem; background: #fff; }
h1 { font-size: 1.7rem; margin: 0.4rem 0 0.3rem; }
h2 { font-size: 1.3rem; border-bottom: 2px solid #d9e2ec; padding-bottom: 0.2rem;
     margin-top: 2.2rem; }
.description { white-space: pre-line; color: #444; }
nav a { margin-right: 1rem; color: #1f5fa8; text-decoration: none; }
table { border-collapse: collapse; margin: 0.4rem 0 1.4rem; font-size: 0.92rem; }
caption { caption-side: top; text-align: left; font-weight: 600; padding: 0.3rem 0; }
th, td { border: 1px solid #d5dbe1; padding: 0.25rem 0.6rem; text-align: left;
         vertical-align: top; }
th { background: #eef2f6; }
td.note { color: #555; font-size: 0.86rem; max-width: 28rem; }
tr.pass td.result { background: #e3f4e1; color: #1e6b23; font-weight: 600; }
tr.fail td { background: #fdecea; }
tr.fail td.result { color: #b3261e; font-weight: 700; }
p.table-note { margin: -1.1rem 0 1.4rem; font-size: 0.85rem; color: #555; }
p.verdict { font-weight: 700; padding: 0.5rem 0.8rem; border-radius: 4px; }
p.pass { background: #e3f4e1; color: #1e6b23; }
p.fail { background: #fdecea; color: #b3261e; }
ul.warn li { background: #fff6e0; border-left: 4px solid #e0a100; padding: 0.2rem 0.6rem;
             margin: 0.3rem 0; list-style: none; }
ul.warn { padding-left: 0; }
figure { margin: 1.2rem 0 2rem; }
figure img { max-width: 100%; height: auto; border: 1px solid #e3e3e3; }
figcaption { font-size: 0.9rem; color: #333; margin-top: 0.3rem; }
footer { margin-top: 2.5rem; font-size: 0.8rem; color: #777; }
"""


def render_html(doc: Document) -> str:
    """The whole report as one HTML string (figures read from their PNG files)."""
    nav = " ".join(f'<a href="#{escape(s.anchor)}">{escape(s.title)}</a>' for s in doc.sections)
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en">',
        "<head>",
        '<meta charset="utf-8">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>{escape(doc.title)}</title>",
        f"<style>{CSS}</style>",
        "</head>",
        "<body>",
        "<main>",
        f"<h1>{escape(doc.title)}</h1>",
    ]
    if doc.description:
        parts.append(f'<p class="description">{escape(doc.description)}</p>')
    parts.append(f"<nav>{nav}</nav>")
    parts += [_section(s) for s in doc.sections]
    figures = [b.figure for s in doc.sections for b in s.blocks if isinstance(b, NumberedFigure)]
    parts += ["<footer>Written by gearcli report from the files of this results folder; the "
              f"figures are also in figures/ as {saved_formats(figures)}.</footer>",
              "</main>", "</body>", "</html>", ""]
    return "\n".join(parts)


def _section(section: Section) -> str:
    out = [f'<section id="{escape(section.anchor)}">', f"<h2>{escape(section.title)}</h2>"]
    for block in section.blocks:
        if isinstance(block, Paragraph):
            cls = f' class="verdict {block.kind}"' if block.kind else ""
            out.append(f"<p{cls}>{escape(block.text)}</p>")
        elif isinstance(block, Bullets):
            cls = f' class="{block.kind}"' if block.kind else ""
            out.append(f"<ul{cls}>" + "".join(f"<li>{escape(i)}</li>" for i in block.items)
                       + "</ul>")
        elif isinstance(block, NumberedTable):
            out.append(_table(block))
        elif isinstance(block, NumberedFigure):
            out.append(_figure(block))
        elif isinstance(block, Preformatted):
            out.append(f"<details><summary>{escape(block.caption)}</summary>"
                       f"<pre>{escape(block.text)}</pre></details>")
    out.append("</section>")
    return "\n".join(out)


def _table(nt: NumberedTable) -> str:
    t = nt.table
    head = "".join(f"<th>{escape(h)}</th>" for h in t.headers)
    rows = []
    for i, row in enumerate(t.rows):
        status = t.status[i] if i < len(t.status) else ""
        cls = f' class="{status}"' if status else ""
        cells = []
        for h, cell in zip(t.headers, row, strict=False):
            kind = {"result": ' class="result"', "note": ' class="note"'}.get(h, "")
            cells.append(f"<td{kind}>{escape(cell)}</td>")
        rows.append(f"<tr{cls}>{''.join(cells)}</tr>")
    html = (f"<table><caption>Table {nt.number}. {escape(t.title)}</caption>"
            f"<thead><tr>{head}</tr></thead><tbody>{''.join(rows)}</tbody></table>")
    if t.note:
        html += f'\n<p class="table-note">{escape(t.note)}</p>'
    return html


def _figure(nf: NumberedFigure) -> str:
    f = nf.figure
    data = base64.b64encode(f.png.read_bytes()).decode("ascii")
    caption = f"Figure {nf.number}. {f.caption}"
    return (f'<figure id="figure-{escape(f.name)}"><img src="data:image/png;base64,{data}" '
            f'alt="{escape(caption)}"><figcaption>{escape(caption)}</figcaption></figure>')
