"""Issue 29, "every ... repr in display units with labels, never a raw key": the reprs of
what the Python API returns are one labelled line in engineering units (gearcli/
display_units.py), not a dataclass dump of internal fields."""

from __future__ import annotations

import re

import gearcli
from gearcli.results import MonitorDocument, ShaftMonitor
from tests.conftest import ROOT, SEED

#: a field name with its internal unit (force_max_N, mesh_mean_N_mm, pinion_speed_deg_s, ...)
RAW_KEY = re.compile(r"\b[a-z][a-z0-9]*(_[a-zA-Z0-9]+)*_(mm|N|Hz|deg_s|rad_s|Nmm|um|MPa|N_mm|s)\b")
LIMITS = {"material.contact_fatigue_limit": 1500, "material.bending_fatigue_limit": 500}


def _labelled(text: str, *words: str) -> None:
    assert text.startswith("<") and text.endswith(">"), text
    assert len(text) < 400, text  # one line, not a dump
    assert not RAW_KEY.search(text), text
    for w in words:
        assert w in text, (w, text)


def test_reprs_of_the_case_geometry_mesh_and_rating():
    _labelled(repr(gearcli.load_case(SEED)), "17/25 teeth", "module 10 mm")
    _labelled(repr(gearcli.geometry(SEED)), "centre distance 210 mm", "ε_α 1.563")
    # mesh stiffness in the engineering unit N/µm (71.37 N/µm = 7.137e4 N/mm)
    _labelled(repr(gearcli.mesh(SEED)), "µm peak to peak", "N/µm")
    rating = repr(gearcli.rate(ROOT / "cases" / "iso_pair.yaml", set=LIMITS))
    _labelled(rating, "ISO 6336:2019", "S_H ", "S_F ", "K_v ")


def test_repr_of_a_monitor_document_leaves_out_the_tsa():
    shaft = ShaftMonitor(shaft="pinion", teeth=17, n_revolutions=3,
                         metrics={"rms": 0.5, "kurtosis": 3.1, "fm4": 3.0, "na4": None},
                         tsa=tuple(float(i) for i in range(4096)))
    text = repr(MonitorDocument(case="seed", signal="encoder transmission error",
                                signal_unit="µm", shafts=(shaft,)))
    _labelled(text, "pinion: RMS 0.5 µm", "kurtosis 3.1", "FM4 3", "NA4 –")


def test_documents_repr_labelled_numbers_in_engineering_units():
    """A typed document (gearcli.simulate(...).summary, analyze(...).metrics, stress, modes,
    mesh summaries) reads as labelled numbers in engineering units, not as its field names."""
    from gearcli.results import AnalysisMetrics, Summary

    s = Summary(dynamic_factor=1.5, dte_peak_to_peak_mm=0.0071, mesh_stiffness_N_mm=8.4e5,
                contact_loss_fraction=0.02, pinion_speed_mean_deg_s=7200.0)
    text = repr(s)
    assert not RAW_KEY.search(text) and "dynamic_factor" not in text, text
    for line in ("dynamic factor F_max / F_static: 1.5", "DTE, peak to peak: 7.1 µm",
                 "mesh stiffness (linearised): 840 N/µm", "time without drive-flank contact: 2 %",
                 "pinion speed, mean: 1200 rpm"):
        assert f"\n  {line}" in text, (line, text)
    assert "speed ratio error: 0.5 %" in repr(AnalysisMetrics(speed_ratio_error_percent=0.5))
