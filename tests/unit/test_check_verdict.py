"""A check that was not made reads "not checked" everywhere (issue 29): the typed Check,
its JSON (passed null), the CLI table, and the overall pass/fail ignores it."""

import json

import pytest
import typer

from gearcli.cli.common import print_checks_table, report_findings
from gearcli.results.analysis import AnalysisDocument, Check


def _checks():
    return [Check("made", 1.0, "< 2", True),
            Check("skipped", None, "< 5", True, "not checked: no load", checked=False),
            Check("bad", 3.0, "< 2", False)]


def test_unchecked_check_verdict_and_json():
    made, skipped, bad = _checks()
    assert skipped.verdict == "not checked" and skipped.passed is None and not skipped.failed
    assert made.verdict == "passed" and bad.verdict == "failed" and bad.failed
    assert "not checked" in repr(skipped)
    doc = json.loads(json.dumps(skipped.to_dict()))
    assert doc["passed"] is None and doc["checked"] is False
    assert json.loads(json.dumps(made.to_dict()))["passed"] is True
    # read back: still not checked
    back = AnalysisDocument.from_document({"checks": [doc]}).checks[0]
    assert back.verdict == "not checked"


def test_unchecked_check_in_cli_table(capsys):
    print_checks_table(_checks())
    out = capsys.readouterr().out
    rows = {line.split("│")[1].strip(): line for line in out.splitlines() if "│" in line}
    assert "not checked" in rows["skipped"]
    assert "pass" in rows["made"] and "FAIL" in rows["bad"]
    assert "FAIL" not in rows["skipped"] and "pass" not in rows["skipped"]


def test_checks_read_by_label_with_their_key_quieter(capsys):
    """Issue 29, "never a raw key": the Checks table, the typed Check's repr and the findings
    line name a check by its label; the key where the case sets its limit is the table's
    last column, analysis.json's name a csv/json column and in the repr and findings after
    the label; values in the display units (a fraction in %, a DTE in µm)."""
    checks = [Check("dynamic_factor", 4.03, "<= 2", False, "max normal force / static force"),
              Check("contact_loss_fraction", 0.0555, "<= 0 (0 %)", False),
              Check("dte_peak_to_peak_mm", 0.0457, "<= 0.05 mm", True)]
    print_checks_table(checks)
    out = capsys.readouterr().out
    rows = {line.split("│")[1].strip(): line.split("│") for line in out.splitlines()
            if "│" in line}
    assert set(rows) == {"dynamic factor F_max / F_static",
                         "time without drive-flank contact", "DTE, peak to peak"}
    assert rows["dynamic factor F_max / F_static"][-2].strip() == "checks.dynamic_factor_max"
    assert [c.strip() for c in rows["DTE, peak to peak"][2:5]] == ["45.7", "µm", "<= 50 µm"]
    assert "  dynamic factor F_max / F_static: max normal force / static force" in out
    assert repr(checks[1]) == ("<Check time without drive-flank contact "
                               "(contact_loss_fraction): failed, 5.55 %, limit <= 0 %>")
    from gearcli.cli.app import settings

    old = settings["tables"]
    settings["tables"] = "json"
    try:
        print_checks_table(checks)
    finally:
        settings["tables"] = old
    table = json.loads(capsys.readouterr().out.splitlines()[0])
    assert table["columns"][:6] == ["check", "value", "unit", "limit", "result", "limit key"]
    row = table["rows"][0]
    assert row["check"] == "dynamic factor F_max / F_static" and row["name"] == "dynamic_factor"
    assert row["limit key"] == "checks.dynamic_factor_max"
    with pytest.raises(typer.Exit):
        report_findings(checks)
    assert ("findings: 2 check(s) failed: dynamic factor F_max / F_static (dynamic_factor); "
            "time without drive-flank contact (contact_loss_fraction) (exit 4)"
            in capsys.readouterr().err)


def test_overall_ignores_unchecked():
    from gearcli.pipeline.analyze import Analysis

    class _A:  # only the checks matter for Analysis.passed
        checks = _checks()[:2]
    assert Analysis.passed.fget(_A())
    _A.checks = _checks()
    assert not Analysis.passed.fget(_A())
