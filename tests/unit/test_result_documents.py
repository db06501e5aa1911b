"""One shape per result (issue 27): the typed documents of gearcli/results/ are what the
pipeline returns and what the JSON files hold, and what is shown where comes from their field
metadata, not from lists of metric names written out in the modules that show them."""

from __future__ import annotations

import ast
import dataclasses
import json
from pathlib import Path

import pytest

from gearcli import results
from gearcli.results.metrics import METRICS

PKG = Path(results.__file__).resolve().parents[1]
#: The one place of the metric names: the documents and the label/unit registry.
REGISTRY = {"io/metrics.py"}
#: Not result metrics: the kernel's extremum records (core/layout.py, its own registry).
NOT_RESULTS = {"core"}
#: Literal lists of metric names that remain: none (a list found anywhere fails).
REMAINING: set[tuple[str, str]] = set()


def _metric_names() -> set[str]:
    names = set(METRICS)
    for cls in (results.Summary, results.AnalysisMetrics, results.PointLines,
                results.EnergyBalance):
        names |= {f.name for f in dataclasses.fields(cls) if f.metadata.get("show")}
    return names


def _literal_lists(tree: ast.AST):
    """(enclosing function or "<module>", line, metric names) of every tuple/list/set literal
    holding two or more metric names."""
    names = _metric_names()

    def walk(node, scope):
        for child in ast.iter_child_nodes(node):
            inner = child.name if isinstance(child, ast.FunctionDef | ast.ClassDef) else scope
            if isinstance(child, ast.Tuple | ast.List | ast.Set):
                hits = [e.value for e in child.elts
                        if isinstance(e, ast.Constant) and e.value in names]
                if len(hits) >= 2:
                    yield scope, child.lineno, hits
            yield from walk(child, inner)

    yield from walk(tree, "<module>")


def test_no_literal_lists_of_metric_names_outside_the_registry():
    found = []
    for path in sorted(PKG.rglob("*.py")):
        rel = path.relative_to(PKG).as_posix()
        if rel in REGISTRY or rel.split("/")[0] in NOT_RESULTS | {"results"}:
            continue
        for scope, line, hits in _literal_lists(ast.parse(path.read_text())):
            if (rel, scope) not in REMAINING:
                found.append(f"{rel}:{line} ({scope}): {hits}")
    assert not found, ("metric names listed outside gearcli/results/ (give the fields "
                       "show=... metadata and query them):\n" + "\n".join(found))


def test_the_scan_finds_a_literal_list():
    """The test above can fail: a list like the ones it replaced is found."""
    tree = ast.parse('KEYS = ("force_max_N", "dynamic_factor")\n')
    assert [hits for _, _, hits in _literal_lists(tree)] == [["force_max_N", "dynamic_factor"]]


@pytest.mark.parametrize("place", results.PLACES)
def test_every_place_shows_registered_metrics(place):
    shown = (results.shown(results.Summary, place) + results.shown(results.AnalysisMetrics, place)
             + results.shown(results.SpeedLevel, place))
    assert set(shown) <= set(METRICS), place
    if place != "trend_plot":
        assert shown or results.sweep_metrics(place), place  # each place shows something


def test_the_tables_and_sweeps_are_queries_of_the_metadata():
    from gearcli.pipeline.sweep.metrics import METRICS as SWEEP
    from gearcli.pipeline.sweep.trends import PLOT_METRICS, TREND_METRICS

    assert SWEEP == results.sweep_metrics("sweep")
    assert TREND_METRICS == ("force_max_N", "dynamic_factor", "dte_peak_to_peak_mm",
                             "gear_speed_gmf_amplitude_rad_s")
    assert PLOT_METRICS == ("dte_rms_mm", "mesh_natural_frequency_Hz")
    s = results.Summary(force_max_N=2.0, energy_balance=results.EnergyBalance(
        relative_residual=1e-9))
    shown = results.shown_values(s, "simulate")
    assert shown["force_max_N"] == 2.0 and shown["energy_relative_residual"] == 1e-9
    assert list(shown) == list(results.shown(results.Summary, "simulate"))


def test_documents_round_trip_through_json():
    """to_dict() is the JSON, from_document() reads it back to the same document; an entry
    left out of an older file takes the field's default; None with omit_none is left out."""
    s = results.Summary(window_s=(1.0, 2.0), window_reason="w", output_rate_Hz=1e4,
                        dynamic_factor=None, modes=(results.StoredMode(1, None, None, "r", True),
                                                    results.StoredMode(2, 100.0, 0.05, "m")))
    doc = results.SummaryDocument(case="c", solver={"accepted_steps": 3}, rows=5, scalars=s)
    text = json.dumps(doc.to_dict())
    assert "invalid_reason" not in json.loads(text)
    back = results.SummaryDocument.from_document(json.loads(text))
    assert json.dumps(back.to_dict()) == text  # (NaN defaults: compared as JSON text)
    assert back.scalars.modes == s.modes and back.solver == doc.solver
    old = {k: v for k, v in json.loads(text)["scalars"].items() if k != "samples_in_window"}
    assert results.Summary.from_document(old).samples_in_window == 0
    m = results.AnalysisMetrics(resonance_margins=None)
    assert "resonance_margins" not in m.to_dict()
    m = results.AnalysisMetrics(resonance_margins=(results.ResonanceMargin(1, 2, 3.0, 4.0, 5.0,
                                                                           True),))
    text = json.dumps(m.to_dict())
    back = results.AnalysisMetrics.from_document(json.loads(text))
    assert back.resonance_margins == m.resonance_margins and json.dumps(back.to_dict()) == text


def test_one_check_type_for_analyze_and_modal():
    import gearcli.pipeline.analyze as analyze
    import gearcli.pipeline.modal as modal

    assert analyze.Check is modal.Check is results.Check
    assert not hasattr(modal, "ModalCheck")
