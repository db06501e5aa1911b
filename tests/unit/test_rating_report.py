"""The rating in the report (issue 28): the inspection dimensions in the geometry table, the
critical positions on the stress figure.

Anchor: the KISSsoft printout of the NREL 5 MW sun–planet mesh (tests/data/
kisssoft_nrel5mw_stage02.txt): W_k 165.869/296.803 (k 3/5), M_dK 466.306/836.492 with balls
45/40 mm, and at the allowances W_k 165.747/165.690, 296.638/296.563, M_dK 466.079/465.974,
836.128/835.961; the table prints to 1 µm, the printout's own resolution.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from gearcli.case.inspection import pair_inspection  # noqa: E402
from gearcli.case.load import load_case  # noqa: E402
from gearcli.pipeline.geometry import run_geometry  # noqa: E402
from gearcli.plotting.stress import critical_points  # noqa: E402
from gearcli.report.tables import inspection_rows  # noqa: E402

NREL = str(Path(__file__).resolve().parents[2] / "cases" / "nrel5mw_sun_planet.yaml")


def test_geometry_table_rows_carry_the_printed_inspection_dimensions():
    loaded = load_case(NREL)
    rows = {r[0]: r[1:] for r in inspection_rows(
        pair_inspection(loaded.case, run_geometry(loaded).geometry), "engineering")}
    assert rows["span measurement teeth k, pinion / gear"] == ("3 / 5", "–")
    assert rows["span W_k, nominal, pinion / gear"] == ("165.869 / 296.803", "mm")
    assert rows["over balls M_dK, nominal, pinion / gear"] == ("466.306 / 836.492", "mm")
    assert rows["tooth thickness allowances A_sne / A_sni, pinion; gear"] == (
        "-0.130 / -0.190; -0.175 / -0.255", "mm")
    assert rows["ball diameter D_M, theoretical / used, pinion; gear"][0].endswith(
        "/ 45.000; 38.726 / 40.000")
    # at the allowances W_k falls by A_sn cos α (docs/theory.md "ISO 6336 rating" §6), by hand:
    # 165.869 − 0.130 cos 20° = 165.747, 296.803 − 0.175 cos 20° = 296.639 (±1 µm rounding)
    upper = rows["span W_k, upper allowance, pinion / gear"][0].split(" / ")
    assert abs(float(upper[0]) - 165.747) <= 0.0015 and abs(float(upper[1]) - 296.639) <= 0.0015
    # the printout at the allowances ([Wk.e/i], [MdK.e/i]), to its 1 µm
    assert rows["span W_k, upper allowance, pinion / gear"][0] == "165.747 / 296.638"
    assert rows["span W_k, lower allowance, pinion / gear"][0] == "165.690 / 296.563"
    assert rows["over balls M_dK, upper allowance, pinion / gear"][0] == "466.079 / 836.128"
    assert rows["over balls M_dK, lower allowance, pinion / gear"][0] == "465.974 / 835.961"
    si = {r[0]: r[1:] for r in inspection_rows(
        pair_inspection(loaded.case, run_geometry(loaded).geometry), "si")}
    assert si["span W_k, nominal, pinion / gear"] == ("0.165869 / 0.296803", "m")


def test_critical_points_are_the_stress_peaks():
    from gearcli.results.stress import GearPeaks, StressPeak

    def gear(h, f):
        return GearPeaks(peak_sigma_H=StressPeak(MPa=h[0], x_from_A_mm=h[1]),
                         peak_sigma_F=StressPeak(MPa=f[0], x_from_A_mm=f[1]))

    peaks = {"pinion": gear((457.0, 11.2), (32.7, 11.4)),
             "gear": gear((457.0, 11.2), (37.2, 11.2))}
    pts = critical_points(peaks)
    assert pts["H"] == [("σ_H peak (pinion)", 11.2, 457.0)]  # shared by both flanks: once
    assert pts["F"] == [("σ_F peak pinion", 11.4, 32.7), ("σ_F peak gear", 11.2, 37.2)]
    assert critical_points({"pinion": GearPeaks()}) == {"H": [], "F": []}
    assert critical_points(None) == {"H": [], "F": []}
