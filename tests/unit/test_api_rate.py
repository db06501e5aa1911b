"""gearcli.rate (gearcli/api.py): the library's rating equals `gearcli rate --json`, and with
a run the "simulated" column takes K_v = the run's F_max/F_static and the peak stresses of
`gearcli stress` (issue 28)."""

from __future__ import annotations

import json
import math

import pytest
from typer.testing import CliRunner

import gearcli
from gearcli.cli import app
from gearcli.errors import CaseError
from tests.conftest import ROOT

runner = CliRunner()
NREL = ROOT / "cases" / "nrel5mw_sun_planet.yaml"
ISO_PAIR = ROOT / "cases" / "iso_pair.yaml"
#: a short iso_pair run with fatigue limits for the rating (what test_rating_case uses)
SHORT = {"run.end_time": "0.4 s", "material.contact_fatigue_limit": 1500,
         "material.bending_fatigue_limit": 430}


def test_api_equals_cli_json():
    cli = runner.invoke(app, ["rate", str(NREL), "--json"])
    assert cli.exit_code in (0, 4), cli.output
    api = gearcli.rate(NREL).to_dict()
    assert api == json.loads(cli.output)
    assert api["simulated"] is None  # a case alone has no run


def _factor(result, symbol: str) -> float:
    (row,) = [f for f in result.pair_factors if f.symbol == symbol]
    return row.value


def _sigma_h_over_k(result) -> float:
    """σ_H / sqrt(K_A K_γ K_v K_Hβ K_Hα) of the pinion = Z_B σ_H0 (ISO 6336-2 eq. 2): the same
    in every column whatever its K factors."""
    (sigma_h,) = [f.value for f in result.pinion.factors if f.symbol == "σ_H"]
    k = 1.0
    for symbol in ("K_A", "K_γ", "K_v", "K_Hβ", "K_Hα"):
        k *= _factor(result, symbol)
    return sigma_h / k ** 0.5


def test_api_set_changes_the_rating():
    base = gearcli.rate(NREL)
    more = gearcli.rate(NREL, set={"rating.application_factor": 1.5})
    assert _factor(more.iso, "K_A") == 1.5
    assert more.iso.pinion.S_H < base.iso.pinion.S_H
    assert _sigma_h_over_k(more.iso) == pytest.approx(_sigma_h_over_k(base.iso), rel=1e-9)


@pytest.fixture(scope="module")
def run():
    return gearcli.simulate(ISO_PAIR, set=SHORT)


def _kv(result) -> float:
    return _factor(result, "K_v")


def test_simulated_kv_is_the_runs_dynamic_factor(run, tmp_path):
    s = run.summary
    expected = s.force_max_N / s.force_static_N
    assert expected == pytest.approx(s.dynamic_factor, rel=1e-9)
    rated = gearcli.rate(run)
    assert rated.simulated is not None
    assert _kv(rated.simulated) == pytest.approx(expected, rel=1e-12)
    assert _kv(rated.iso) != pytest.approx(expected, rel=1e-6)  # the ISO column's own K_v
    # the same from the run's results folder
    folder = run.save(tmp_path / "run")
    again = gearcli.rate(folder)
    assert _kv(again.simulated) == pytest.approx(expected, rel=1e-9)
    assert again.to_dict()["simulated"]["pair"] == rated.to_dict()["simulated"]["pair"]


def test_simulated_rating_responds_to_kv(run):
    """The simulated column differs from the ISO column only by its K factors (ISO 6336-2
    eq. 2): σ_H/sqrt(ΠK) is the same in both; the larger K_v has the smaller S_H."""
    rated = gearcli.rate(run)
    iso, sim = rated.iso, rated.simulated
    assert _sigma_h_over_k(sim) == pytest.approx(_sigma_h_over_k(iso), rel=1e-9)
    assert (sim.pinion.S_H < iso.pinion.S_H) == (_kv(sim) > _kv(iso))


def test_rate_refuses_a_bad_argument():
    with pytest.raises(CaseError, match="load_case"):
        gearcli.rate(42)


def test_simulated_peaks_are_the_stress_peaks(run):
    """The simulated column's peak safeties: S_H = σ_HG/(σ_H,peak √(K_A K_γ K_Hβ)), S_F =
    σ_FG/(σ_F,peak K_A K_γ K_Fβ Y_β Y_B Y_DT) with the peaks of gearcli.stress in the steady
    window (pipeline.rating.SimulatedLoad): the peaks carry the dynamics and the load sharing
    between the pairs, not the application and face load factors. Same arithmetic: rel 1e-12."""
    rated = gearcli.rate(run)
    stress = gearcli.stress(run)
    peaks = rated.simulated_peaks
    for which, g in (("pinion", rated.simulated.pinion), ("gear", rated.simulated.gear)):
        ref = getattr(stress, which)
        row = peaks[g.name]
        assert row.sigma_H_peak_MPa == pytest.approx(ref.sigma_H_peak_MPa, rel=1e-12)
        assert row.sigma_F_peak_MPa == pytest.approx(ref.sigma_F_peak_MPa, rel=1e-12)
        # the loads the torsional model does not see: K_A K_γ K_Hβ (K_Fβ), and Y_β Y_B Y_DT
        k_h = _factor(rated.simulated, "K_A") * _factor(rated.simulated, "K_γ") \
            * _factor(rated.simulated, "K_Hβ")
        k_f = _factor(rated.simulated, "K_A") * _factor(rated.simulated, "K_γ") \
            * _factor(rated.simulated, "K_Fβ")
        y = math.prod(g.factor(s).value for s in ("Y_β", "Y_B", "Y_DT"))
        assert row.S_H == pytest.approx(
            g.sigma_HG_MPa / (ref.sigma_H_peak_MPa * math.sqrt(k_h)), rel=1e-12)
        assert row.S_F == pytest.approx(
            g.sigma_FG_MPa / (ref.sigma_F_peak_MPa * k_f * y), rel=1e-12)
