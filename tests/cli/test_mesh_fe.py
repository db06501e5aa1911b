"""`gearcli mesh --method fe`: the tooth law (PE) beside the finite-element model, its JSON
section, the unchanged default and the on-disk cache of the influence coefficients."""

import dataclasses
import json
import sys

import numpy as np
import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.io.fe_store import FEStore
from gearcli.results.models import MeshSummary
from tests.conftest import SEED

runner = CliRunner()
COMPARED = ("pitch_pair_stiffness_N_mm", "mesh_mean_stiffness_N_mm", "ste_peak_to_peak_um")


@pytest.fixture
def cache_home(tmp_path, monkeypatch):
    """A private user cache folder: the FE store starts empty."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    return tmp_path / "cache"


def _counting_solver(monkeypatch):
    """Count the FE solves of single gears (model.fe.tooth.fe_tooth_compliance), on the path
    (model.fe.mesh_stiffness) and with the corner contact (model.fe.extended)."""
    import gearcli.model.fe.extended as ex
    import gearcli.model.fe.mesh_stiffness as ms

    calls = []
    real = ms.fe_tooth_compliance

    def counted(*args, **kwargs):
        calls.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(ms, "fe_tooth_compliance", counted)
    monkeypatch.setattr(ex, "fe_tooth_compliance", counted)
    return calls


def _fe_json(extra=()):
    res = runner.invoke(app, ["mesh", str(SEED), "--method", "fe", "--json", *extra])
    assert res.exit_code == 0, res.output
    return json.loads(res.output)["fe_check"]


def test_fe_table_json_and_cache_hit_on_rerun(cache_home, monkeypatch):
    pytest.importorskip("skfem", reason="optional extra 'fe'")
    pytest.importorskip("triangle", reason="optional extra 'fe'")
    calls = _counting_solver(monkeypatch)
    res = runner.invoke(app, ["mesh", str(SEED), "--method", "fe"])
    assert res.exit_code == 0, res.output
    for text in ("Tooth law (PE) against finite elements (FE)", "PE", "FE", "FE/PE − 1",
                 "single-pair stiffness at the pitch", "mean mesh stiffness",
                 "loaded STE peak-to-peak", "contact term", "with the tip corners"):
        assert text in res.output, text
    # pinion and gear solved once each on the path and once with the corner loads, stored
    assert len(calls) == 4
    assert len(list((cache_home / "gearcli" / "fe").glob("*.npz"))) == 4

    fe = _fe_json()  # the rerun: all four models from the disk store, no solve
    assert len(calls) == 4 and (fe["cache_hits"], fe["cache_misses"]) == (4, 0)
    for key in COMPARED:
        q = fe[key]
        assert q["pe"] > 0 and q["fe"] > 0
        assert q["fe_over_pe_minus_1"] == pytest.approx(q["fe"] / q["pe"] - 1, rel=1e-12)
    # the seed at its load is the first row of docs/theory.md's PE-against-FE table (+2.6 %
    # at C, +1.3 % mean since the law takes Weber's contact flattening, issue 31; −20.6 %,
    # −20.0 % with the linear Hertz term before; the same models, so to the table's 0.1 %
    # rounding + 0.1 %)
    assert fe["pitch_pair_stiffness_N_mm"]["fe_over_pe_minus_1"] == pytest.approx(0.026,
                                                                                  abs=2e-3)
    assert fe["mesh_mean_stiffness_N_mm"]["fe_over_pe_minus_1"] == pytest.approx(0.013,
                                                                                 abs=2e-3)
    # the same LTCA with the case's gaps on both sides: positive STEs, FE/PE − 1 consistent
    q = fe["loaded_ste_peak_to_peak_um"]
    assert q["pe"] > 0 and q["fe"] > 0
    assert q["fe_over_pe_minus_1"] == pytest.approx(q["fe"] / q["pe"] - 1, rel=1e-12)
    assert fe["plane_strain"] is True and "contact term" in fe["note"]

    for entry in (cache_home / "gearcli" / "fe").glob("*.npz"):
        entry.write_bytes(b"not an npz")  # corrupt entries are ignored and rewritten
    fe = _fe_json()
    assert len(calls) == 8 and (fe["cache_hits"], fe["cache_misses"]) == (0, 4)
    assert _fe_json()["cache_hits"] == 4


def test_method_pe_is_the_default_and_has_no_fe_section():
    base = runner.invoke(app, ["mesh", str(SEED), "--json"])
    pe = runner.invoke(app, ["mesh", str(SEED), "--json", "--method", "pe"])
    assert base.exit_code == 0 and pe.exit_code == 0, base.output + pe.output
    assert pe.output == base.output
    doc = json.loads(pe.output)
    keys = ({f.name for f in dataclasses.fields(MeshSummary)}
            - {"fe_check", "harris", "faulted_revolution"})  # optional sections, absent here
    assert set(doc) == keys
    bad = runner.invoke(app, ["mesh", str(SEED), "--method", "xfem"])
    assert bad.exit_code == 1 and "expected pe or fe" in bad.output


def test_without_the_extra_one_line_naming_it(cache_home, monkeypatch):
    monkeypatch.setitem(sys.modules, "skfem", None)  # import skfem now raises ImportError
    res = runner.invoke(app, ["mesh", str(SEED), "--method", "fe"])
    assert res.exit_code == 1
    lines = res.output.strip().splitlines()
    assert len(lines) == 1 and "gearcli[fe]" in lines[0] and "'fe'" in lines[0], res.output


def test_store_round_trip_atomic_and_corrupt(tmp_path):
    store = FEStore(tmp_path)
    key = "0123456789abcdef01234567"
    rec = {"radius_mm": np.linspace(1.0, 2.0, 5), "depth_mm": 0.25, "n_dofs": 7,
           "plane_strain": True}
    assert store.load(key) is None
    store.store(key, rec)
    back = store.load(key)
    assert np.array_equal(back["radius_mm"], rec["radius_mm"])
    assert float(back["depth_mm"]) == 0.25 and int(back["n_dofs"]) == 7
    assert bool(back["plane_strain"]) is True
    assert [p.name for p in tmp_path.iterdir()] == [f"{key}.npz"]  # no temporary left
    (tmp_path / f"{key}.npz").write_bytes(b"\x00" * 10)
    assert store.load(key) is None
    assert store.load("../escape") is None  # only hash keys name files
    store.store("../escape", rec)
    assert [p.name for p in tmp_path.iterdir()] == [f"{key}.npz"]
