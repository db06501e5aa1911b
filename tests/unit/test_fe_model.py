"""Unit checks of gearcli.model.fe: the optional-extra error, the face-width rule, Weber's
term, the sector outline, the cache and the bookkeeping of fe_mesh_stiffness."""

from __future__ import annotations

import importlib
import math

import numpy as np
import pytest

from gearcli.model import profile
from gearcli.model.fe import ComplianceCache, FEUnavailableError, plane_strain_rule
from gearcli.model.fe.cache import from_record, to_record
from gearcli.model.fe.deps import require
from gearcli.model.fe.hertz import hertz_half_width, weber_approach
from gearcli.model.fe.sector import BORE, SIDE, SURFACE, flank_point_normal, sector_outline
from gearcli.model.fe.tooth import FEToothCompliance
from gearcli.model.geometry import GearSpec, PairSpec, compute_pair_geometry

A20 = math.radians(20.0)
SEED = compute_pair_geometry(PairSpec(10.0, A20, GearSpec(17, 100), GearSpec(25, 100)))
E, NU = 2.07e5, 0.29


def test_missing_extra_is_one_line_naming_it(monkeypatch):
    real = importlib.import_module

    def fake(name, *a, **k):
        if name == "skfem":
            raise ModuleNotFoundError("No module named 'skfem'", name="skfem")
        return real(name, *a, **k)

    monkeypatch.setattr(importlib, "import_module", fake)
    with pytest.raises(FEUnavailableError) as err:
        require()
    msg = str(err.value)
    assert "gearcli[fe]" in msg and "skfem" in msg and "\n" not in msg
    assert isinstance(err.value, ImportError)


def test_face_width_rule():
    assert plane_strain_rule(100.0, 10.0) and plane_strain_rule(20.0, 2.0)
    assert not plane_strain_rule(6.35, 3.175)


def test_weber_term_limits():
    """Exact half-plane approach → Weber's ln form for h ≫ a (Johnson 1985 §4.2); plane
    stress is (1 − ν²)… larger: ratio checked at h = 10³ a; a from eq. 4.43."""
    a, w = 0.1, 100.0
    h = 1e3 * a
    ln_form = 2 * w * (1 - NU**2) / (math.pi * E) * (math.log(2 * h / a) - NU / (2 * (1 - NU)))
    assert weber_approach(w, h, a, E, NU) == pytest.approx(ln_form, rel=1e-6)
    assert weber_approach(w, 0.0, a, E, NU) == 0.0
    stress = weber_approach(w, h, a, E, NU, plane_strain=False)
    assert stress > weber_approach(w, h, a, E, NU)
    assert hertz_half_width(w, 5.0, 1e5) ** 2 == pytest.approx(4 * w * 5.0 / (math.pi * 1e5))


def test_flank_point_and_normal_are_on_the_involute():
    g = SEED.pinion
    r = np.array([80.0, 85.0, 90.0])
    p, n = flank_point_normal(g, r)
    assert np.allclose(np.hypot(*p.T), r)
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0)
    # the flank normal is tangent to the base circle: its distance from the centre is r_b
    assert np.allclose(np.abs(p[:, 0] * n[:, 1] - p[:, 1] * n[:, 0]), g.r_b_mm, rtol=1e-9)
    # and perpendicular to the flank (central difference along the involute)
    t = flank_point_normal(g, r + 1e-4)[0] - flank_point_normal(g, r - 1e-4)[0]
    assert np.allclose(np.einsum("ij,ij->i", t, n) / np.linalg.norm(t, axis=1), 0.0, atol=1e-7)
    assert np.all(n[:, 0] < 0)  # outward on the x < 0 flank
    assert np.allclose(-p[:, 0] / r, np.sin(profile.flank_half_angle(g, r)))


@pytest.mark.parametrize("n_teeth", [3, 5, None])
def test_outline_holds_the_load_points_and_a_closed_boundary(n_teeth):
    g = SEED.gear
    r = np.hypot(g.r_b_mm, SEED.T1T2_mm - SEED.A_mm - np.linspace(0, SEED.g_alpha_mm, 7))
    o = sector_outline(g, r, bore_radius_mm=g.r_f_mm / 3, n_teeth=n_teeth, fine_mm=0.4,
                       coarse_mm=3.0)
    p, _ = flank_point_normal(g, r)
    assert np.allclose(o.points_mm[o.load_vertex_ids], p)
    seg = o.segments
    assert len(seg) == len(o.edge_markers) == len(o.points_mm)
    # every point starts exactly one segment and ends exactly one (closed loops)
    assert np.array_equal(np.sort(seg[:, 0]), np.arange(len(o.points_mm)))
    assert np.array_equal(np.sort(seg[:, 1]), np.arange(len(o.points_mm)))
    marks = set(o.edge_markers.tolist())
    assert marks == ({SURFACE, BORE} if n_teeth is None else {SURFACE, BORE, SIDE})
    bore_pts = o.points_mm[seg[o.edge_markers == BORE].ravel()]
    assert np.allclose(np.hypot(*bore_pts.T), g.r_f_mm / 3)
    assert np.all(np.hypot(*o.points_mm.T) <= g.r_a_mm + 1e-9)
    assert o.n_teeth == (g.teeth if n_teeth is None else n_teeth)


def test_outline_rejects_a_bad_bore_or_tooth_count():
    g = SEED.pinion
    with pytest.raises(ValueError, match="bore"):
        sector_outline(g, [85.0], bore_radius_mm=g.r_f_mm, n_teeth=5, fine_mm=1, coarse_mm=3)
    with pytest.raises(ValueError, match="odd"):
        sector_outline(g, [85.0], bore_radius_mm=20.0, n_teeth=4, fine_mm=1, coarse_mm=3)


def _fake(value: float) -> FEToothCompliance:
    return FEToothCompliance(np.array([1.0, 2.0]), np.array([value, 2 * value]), 0.5, 10, 17,
                             40.0, True, 0.01)


def test_cache_memory_and_persistent_callbacks(tmp_path):
    """The model does no I/O: the store is two callbacks (here np.savez files)."""
    def store(key, rec):
        np.savez(tmp_path / f"{key}.npz", **rec)

    def load(key):
        f = tmp_path / f"{key}.npz"
        return dict(np.load(f)) if f.exists() else None

    calls = []
    first = ComplianceCache(load=load, store=store)
    v = first.get_or_compute("k1", lambda: calls.append(1) or _fake(3.0))
    again = first.get_or_compute("k1", lambda: calls.append(1) or _fake(9.0))
    assert again is v and first.misses == 1 and first.hits == 1 and len(calls) == 1
    fresh = ComplianceCache(load=load, store=store)  # a new process: from the files
    w = fresh.get_or_compute("k1", lambda: calls.append(1) or _fake(9.0))
    assert len(calls) == 1 and fresh.hits == 1
    assert np.array_equal(w.compliance_mm2_N, v.compliance_mm2_N) and w.plane_strain
    back = from_record(to_record(v))
    assert np.array_equal(back.radius_mm, v.radius_mm) and back.n_teeth == v.n_teeth


def test_fe_mesh_stiffness_bookkeeping():
    """Mesh = Σ pairs with equal approach; single-pair zone = the single-pair curve; STE =
    F/k; a second call with the same cache solves nothing."""
    pytest.importorskip("skfem", reason="optional extra 'fe'")
    pytest.importorskip("triangle", reason="optional extra 'fe'")
    from gearcli.model.fe import fe_mesh_stiffness

    cache = ComplianceCache()
    kw = {"face_width_mm": 100.0, "load_N_mm": 38.3, "E1_MPa": E, "nu1": NU, "E2_MPa": E,
          "nu2": NU, "n_roll": 9, "cache": cache}
    r = fe_mesh_stiffness(SEED, **kw)
    assert cache.misses == 2 and r.plane_strain
    one = r.mesh_pairs == 1
    assert one.any() and (r.mesh_pairs == 2).any()
    x_single = r.mesh_x_mm[one]  # 1 < ε_α < 2: alone when x + p_b is past E
    assert np.all(x_single + SEED.p_b_mm > SEED.g_alpha_mm)
    from scipy.interpolate import CubicSpline

    expect = 1.0 / CubicSpline(r.x_mm, 1.0 / r.pair_N_mm)(x_single)
    assert np.allclose(r.mesh_N_mm[one], expect, rtol=2e-3)  # spline vs direct: same law
    assert np.all(r.mesh_N_mm[~one] > r.mesh_N_mm[one].max())
    assert np.allclose(r.ste_um, 1e3 * 38.3 * 100.0 / r.mesh_N_mm)
    assert r.mesh_N_mm.min() < r.mean_N_mm < r.mesh_N_mm.max()
    r2 = fe_mesh_stiffness(SEED, **kw)
    assert cache.misses == 2 and cache.hits == 2
    assert np.array_equal(r2.mesh_N_mm, r.mesh_N_mm)
