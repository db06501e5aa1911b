"""`gearcli rate CASE`: ISO 6336 Method B rating of the pair, safeties against their minimums."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import typer

from gearcli.cli.app import app
from gearcli.cli.common import emit, handle_errors, table_options
from gearcli.io.files import write_stdout

if TYPE_CHECKING:  # annotations only: the documents' package costs every command ~50 ms
    from gearcli.results.rating_document import (
        DutyCycleDocument,
        EditionRowDocument,
        RatingDocument,
        RatingResultDocument,
    )


@app.command()
@handle_errors
@table_options
def rate(
    case: Path = typer.Argument(..., help="Case file (YAML)."),
    as_json: bool = typer.Option(False, "--json", help="Print rating.json to stdout."),
    out: Path | None = typer.Option(None, "-o", "--out", help="Write rating.json and "
                                    "manifest.json into this folder."),
    force: bool = typer.Option(False, "--force", help="Replace an earlier results folder "
                               "(files gearcli did not write stay)."),
    set_: list[str] = typer.Option(
        [], "--set", help="Override a case value: key.path=value (repeatable)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No tables; errors only."),
    edition: str | None = typer.Option(
        None, "--edition", help="ISO 6336 edition followed where they differ: 2006 or 2019 "
        "(default: the case's rating.edition). Either way the table 'ISO 6336:2006 and :2019' "
        "shows the edition-dependent factors under both."),
) -> None:
    """ISO 6336 Method B load capacity of the pair (parts 1, 2, 3, 5, 6) from the case's
    `rating:` section, its load and its fatigue limits: every factor with its symbol, value and
    clause for pinion and gear, S_H and S_F against their minimums with verdicts, the lives at
    the minimum safeties and, with rating.duty_cycle, the Palmgren–Miner damage. Stresses in
    N/mm², lengths in mm, lives in h (the standard's units).

    Example: gearcli rate cases/nrel5mw_sun_planet.yaml --edition 2019

    Exit codes: 0 every safety at or above its minimum, 1 bad input, 4 a safety below its
    minimum (or a duty-cycle damage above 1).
    """
    import json

    from gearcli.errors import ExitCode
    from gearcli.io.outdir import check_target
    from gearcli.pipeline.rating import rate_case

    if edition is not None:
        if edition not in ("2006", "2019"):
            from gearcli.errors import CaseError

            raise CaseError(f"--edition {edition}: expected 2006 or 2019")
        set_ = [*set_, f"rating.edition={edition}"]
    if out is not None:
        check_target(out, force)  # before the work, not after
    result = rate_case(case, set_)
    doc = result.document()
    if out is not None:
        _write(result, doc.to_dict(), out, force, set_)
    if as_json:
        write_stdout(json.dumps(doc.to_dict(), indent=2) + "\n")
    elif not quiet:
        print_rating(doc)
        if out is not None:
            typer.echo(f"wrote {out}")
    if not result.ok:
        raise typer.Exit(int(ExitCode.CHECK_FAILED))


def _write(result, doc: dict, folder: Path, force: bool, overrides: list[str]) -> None:
    """rating.json and manifest.json, all or nothing (io.outdir.atomic_dir)."""
    import json

    from gearcli.io.files import write_atomic
    from gearcli.io.manifest import manifest
    from gearcli.io.outdir import atomic_dir

    loaded = result.source
    with atomic_dir(folder, force) as tmp:
        write_atomic(tmp / "rating.json", json.dumps(doc, indent=2) + "\n")
        provenance = manifest(loaded.source, json.loads(loaded.case.model_dump_json()),
                              overrides)
        write_atomic(tmp / "manifest.json", json.dumps(provenance, indent=2) + "\n")


def fmt(value) -> str:
    """A rating value as an engineer reads it: 4 decimals below 100, 2 above, big counts in
    exponent form, an infinite life as '∞', a missing value as '—'."""
    if value is None:
        return "∞"
    if isinstance(value, str):
        return value
    a = abs(value)
    if a >= 1e6:
        return f"{value:.4g}"
    if a >= 100:
        return f"{value:.2f}"
    return f"{value:.4f}" if a >= 0.01 or a == 0 else f"{value:.3g}"


def _table(title: str, columns: list[tuple[str, str]]):
    from rich.markup import escape
    from rich.table import Table

    t = Table(title=escape(title), title_justify="left")
    for name, justify in columns:
        t.add_column(name, justify=justify)
    return t


def gear_rows(column: RatingResultDocument) -> list[tuple[str, str, str, str, str, str]]:
    """(symbol, pinion, gear, unit, clause, name) rows: the two gears' factors side by side
    (same order; M1/M2 and Z_B/Z_D share a row)."""
    rows = []
    for p, g in zip(column.pinion.factors, column.gear.factors, strict=True):
        sym = p.symbol if p.symbol == g.symbol else f"{p.symbol} / {g.symbol}"
        rows.append((sym, fmt(p.value), fmt(g.value), p.unit, p.clause, p.name))
    return rows


def print_rating(doc: RatingDocument) -> None:
    """The rating as tables: pair factors, the gears' factors side by side, the verdicts."""
    from rich.markup import escape

    iso, load = doc.iso, doc.load
    emit(f"[bold]{escape(doc.case)}[/bold]: ISO 6336:{iso.edition} Method B, pinion "
         f"torque {fmt(load.pinion_torque_Nm)} N·m per mesh path at "
         f"{fmt(load.pinion_speed_rpm)} rpm, life {fmt(load.life_h)} h; K_v "
         f"{load.dynamic_factor_source}")
    pair = _table("Pair (ISO 6336-1, -2)", [("symbol", "left"), ("value", "right"),
                                            ("unit", "left"), ("clause", "left"),
                                            ("name", "left")])
    for f in iso.pair:
        pair.add_row(f.symbol, fmt(f.value), f.unit, f.clause, f.name)
    emit(pair)
    gears = _table("Pinion and gear (ISO 6336-2, -3, -5)", [
        ("symbol", "left"), ("pinion", "right"), ("gear", "right"), ("unit", "left"),
        ("clause", "left"), ("name", "left")])
    for row in gear_rows(iso):
        gears.add_row(*row)
    emit(gears)
    emit(verdict_table(iso, doc.duty_cycle))
    if doc.editions:
        emit(edition_table(doc.editions, iso.edition))
    for note in doc.notes:
        emit(f"note: {escape(note)}")
    emit(f"verdict: {doc.verdict.upper()}")


def verdict_table(column: RatingResultDocument, duty: DutyCycleDocument | None):
    """S_H, S_F of each gear against their minimums, with lives and damages."""
    from gearcli.results.rating import SAFETY_CHECKS  # loaded with the document by now

    t = _table("Safeties", [("", "left"), ("pinion", "right"), ("gear", "right"),
                            ("minimum", "right"), ("verdict", "left")])
    p, g = column.pinion, column.gear
    for safety, minimum, check in SAFETY_CHECKS:
        verdict = ", ".join(f"{x.name} {getattr(x, check)}" for x in (p, g))
        t.add_row(f"{safety} ({check})", fmt(getattr(p, safety)), fmt(getattr(g, safety)),
                  fmt(getattr(p, minimum)), verdict)
    t.add_row("life at S_H,min (h)", fmt(p.life_pitting_h), fmt(g.life_pitting_h), "", "")
    t.add_row("life at S_F,min (h)", fmt(p.life_bending_h), fmt(g.life_bending_h), "", "")
    if duty is not None:
        dp, dg = duty.pinion, duty.gear
        for kind in ("pitting", "bending"):
            damages = (getattr(dp, kind), getattr(dg, kind))
            ok = all(d is not None and d <= 1.0 for d in damages)
            t.add_row(f"duty-cycle damage, {kind}", *map(fmt, damages), "1",
                      "pass" if ok else "fail")
    return t


def edition_table(rows: tuple[EditionRowDocument, ...], followed: str):
    """The edition-dependent factors under ISO 6336:2006 and :2019 (model/iso6336/editions)."""
    t = _table(f"ISO 6336:2006 and :2019 (this rating follows {followed})", [
        ("symbol", "left"), ("gear", "left"), ("2006", "right"), ("2019", "right"),
        ("unit", "left"), ("", "left")])
    for r in rows:
        t.add_row(r.symbol, r.gear, f"{r.value_2006:.6g}", f"{r.value_2019:.6g}", r.unit,
                  "differs" if r.differs else "same")
    return t
