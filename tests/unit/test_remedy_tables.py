"""Issue 29: the speed bands a failed resonance margin names, and the table formats."""

import json

import pytest

from gearcli.cli.common import format_rows
from gearcli.pipeline.speed_bands import resonance_remedy, speed_bands
from gearcli.report.tables import check_cells
from gearcli.results import Check, ResonanceMargin


def test_speed_bands_put_the_harmonic_within_the_margin_of_the_mode():
    """k z1 n1/60 = f_n (1 ± m): with z1 = 20, f_n = 1000 Hz, m = 10 %, k = 2 the band is
    1350-1650 rpm; a pair within its margin but without a resonant peak, or outside the
    margin, gives no band."""
    rows = (ResonanceMargin(2, 1, 1040.0, 1000.0, 4.0, True),
            ResonanceMargin(1, 2, 520.0, 3000.0, 82.7, True),
            ResonanceMargin(3, 3, 1560.0, 1500.0, 4.0, False))
    bands = speed_bands(rows, 10.0, 20)
    assert [(lo, hi) for lo, hi, _ in bands] == [pytest.approx((1350.0, 1650.0))]
    remedy = resonance_remedy(rows, 10.0, 20)
    assert remedy.kind == "speed_band" and "1350-1650 rpm" in remedy.text
    assert [tuple(b) for b in remedy.avoid_pinion_speed_rpm] == [pytest.approx((1350.0, 1650.0))]
    assert resonance_remedy(rows[1:], 10.0, 20) is None


def test_a_fraction_check_is_shown_in_percent_with_its_limit():
    ck = Check("contact_loss_fraction", 0.0555, "<= 0.01 (1 %)", False)
    assert check_cells(ck) == ("5.55", "%", "<= 1 %")
    ck = Check("dte_peak_to_peak_mm", 0.0457, "<= 0.05 mm", True)
    assert check_cells(ck) == ("45.7", "µm", "<= 50 µm")


def test_table_formats_keep_every_cell_uncut():
    headers = ["check", "value", "note"]
    rows = [["speed ratio error", "2.9e-05", "a long note, with a comma " * 5]]
    plain = format_rows("plain", "Checks", headers, rows)
    assert "speed ratio error  " in plain and plain.splitlines()[0] == "Checks"
    assert json.loads(format_rows("json", "Checks", headers, rows)) == {
        "table": "Checks", "columns": headers, "rows": [dict(zip(headers, rows[0], strict=True))]}
    import csv
    import io

    text = format_rows("csv", "Checks", headers, rows)
    assert text.startswith("# Checks\n")
    assert list(csv.reader(io.StringIO(text.split("\n", 1)[1]))) == [headers, rows[0]]


def test_modal_names_the_speed_band_around_the_resonance_it_fails():
    """The seed with a realistic mesh damping (5 N·s/mm: ζ ≈ 0.09, a resonant peak) puts
    2 x f_z = 283.3 Hz within 0.8 % of the mesh mode at 281.2 Hz: modal fails its margin and
    names 281.2 Hz (1 ± 10 %) × 60 / (2 × 17) = 446.6-545.8 rpm, which holds the case's
    500 rpm; findings, not an error line."""
    from typer.testing import CliRunner

    from gearcli.cli import app
    from tests.conftest import SEED

    res = CliRunner().invoke(app, ["modal", str(SEED), "--set", "contact.max_damping=5",
                                   "--json"])
    assert res.exit_code == 4, res.output
    (check,) = json.loads(res.stdout)["checks"]
    remedy = check["remedy"]
    assert remedy["kind"] == "speed_band"
    (lo, hi), *_ = remedy["avoid_pinion_speed_rpm"]
    assert (lo, hi) == pytest.approx((446.6, 545.8), abs=0.2)
    assert lo < 500.0 < hi
    assert res.stderr.startswith("findings: 1 check(s) failed: resonance margin of k·f_z to "
                                 "the nearest mode (resonance_margin_percent); remedy above")


def test_piped_tables_are_not_cut_and_every_format_parses():
    """In a pipe (CliRunner is one) the boxes use the width the table needs: no cell or title
    ends in "…" at 80 columns; json gives one object per table and line, csv a block each."""
    import csv
    import io

    from typer.testing import CliRunner

    from gearcli.cli import app
    from tests.conftest import SEED

    runner = CliRunner()
    boxed = runner.invoke(app, ["geometry", str(SEED)])
    assert boxed.exit_code == 0, boxed.output
    assert "…" not in boxed.stdout
    as_json = runner.invoke(app, ["geometry", str(SEED), "--table-format", "json"])
    tables = [json.loads(line) for line in as_json.stdout.splitlines() if line.strip()]
    titles = [t.get("table") for t in tables if "table" in t]
    assert titles[:2] == ["Gear geometry — seed", "Pair"]
    assert all(len(r) == len(t["columns"]) for t in tables if "rows" in t for r in t["rows"])
    root = runner.invoke(app, ["--table-format", "csv", "geometry", str(SEED)])
    blocks = [b for b in root.stdout.split("\n# ") if b.strip()]
    first = list(csv.reader(io.StringIO(blocks[0].split("\n", 1)[1])))
    assert first[0] == ["quantity", "pinion", "gear", "unit"] and len(first) > 5
    bad = runner.invoke(app, ["geometry", str(SEED), "--table-format", "xml"])
    assert bad.exit_code == 1 and "expected one of table, plain, csv, json" in bad.stderr
