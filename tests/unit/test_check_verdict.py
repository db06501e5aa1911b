"""A check that was not made reads "not checked" everywhere (issue 29): the typed Check,
its JSON (passed null), the CLI table, and the overall pass/fail ignores it."""

import json

from gearcli.cli.common import print_checks_table
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


def test_overall_ignores_unchecked():
    from gearcli.pipeline.analyze import Analysis

    class _A:  # only the checks matter for Analysis.passed
        checks = _checks()[:2]
    assert Analysis.passed.fget(_A())
    _A.checks = _checks()
    assert not Analysis.passed.fget(_A())
