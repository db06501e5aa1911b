"""The tooth-compliance law from case files (issue 14): soft engagement without entry spikes
above resonance, stiffness that scales with Young's modulus, refused keys of the other law."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import find_peaks, peak_widths

from gearcli.case.load import load_case
from gearcli.errors import CaseError
from gearcli.pipeline.geometry import run_geometry
from gearcli.pipeline.mesh_input import case_mesh
from gearcli.pipeline.simulate import run_simulation
from tests.conftest import ROOT

ISO_PAIR = ROOT / "cases" / "iso_pair.yaml"


def entry_jumps(res, window):
    """Force jump [N] of every pair entering contact in ``window``: its first two loaded
    samples extrapolated back to the last unloaded one (about 0 for a force that rises from
    zero, the jump height for one that steps). Pairs are tracked by tooth, not by slot (a
    pair moves to the next slot every mesh cycle)."""
    n, x = res.slot_positions()
    n = n.astype(int)
    sf = res.kernel.slot_force
    idx = np.flatnonzero(window)
    out = []
    for a, b, c in zip(idx[:-2], idx[1:-1], idx[2:], strict=True):
        for j in range(sf.shape[1]):
            pair = n[b] - j
            ja, jc = n[a] - pair, n[c] - pair
            if not (0 <= ja < sf.shape[1] and 0 <= jc < sf.shape[1]):
                continue
            if sf[a, ja] == 0.0 and sf[b, j] > 0.0 and sf[c, jc] > 0.0:
                f1, f2 = sf[b, j], sf[c, jc]
                out.append(f1 - (f2 - f1) * (x[b, j] - x[a, ja]) / (x[c, jc] - x[b, j]))
    return np.array(out)


def test_soft_entry_and_no_spike_above_resonance():
    """At a mesh frequency 1.5x the mesh mode (ISO resonance ratio N = 1.5): the tooth law's
    dynamic factor with extended engagement exceeds the rigid-engagement one by at most 10 %
    (measured: 1.494 vs 1.498, ratio 0.998), each pair's force rises from zero at entry (jump
    estimate <= 2 % of the static force; measured -0.14 %, sampled at 1000 points per mesh
    period: with stiffness-proportional damping shares it was +2.3 % and did not shrink with
    finer sampling), and the total force has no peak narrower than 2 % of a mesh period
    (half-prominence width; measured 56 %). Issue 14's criteria; friction off to isolate the
    contact law."""
    loaded = load_case(ISO_PAIR)
    f_n = case_mesh(loaded.case, run_geometry(loaded)).natural_frequency_Hz
    f_z = 1.5 * f_n
    speed_deg_s = f_z / 21 * 360.0  # the field's default unit
    base = [f"drive.speed=STEP(time, 0, 0, 0.05, {speed_deg_s})", "run.end_time=0.08",
            "load.torque=STEP(time, 0, 0, 0.05, 3e5)", "friction.enabled=false",
            f"run.output_rate={1000 * f_z}"]
    ext = run_simulation(ISO_PAIR, base)
    rigid = run_simulation(ISO_PAIR, [*base, "contact.engagement=rigid"])
    assert ext.summary.dynamic_factor <= 1.10 * rigid.summary.dynamic_factor
    t = ext.kernel.column("t_s")
    window = t >= ext.window.t0_s
    static = ext.summary.force_static_N
    jumps = entry_jumps(ext, window)
    assert jumps.size > 50 and jumps.max() <= 0.02 * static
    force = ext.kernel.column("force_total_N")[window]
    peaks, _ = find_peaks(force, prominence=0.05 * static)
    widths = peak_widths(force, peaks, rel_height=0.5)[0] * (t[1] - t[0])
    assert peaks.size > 50 and widths.min() >= 0.02 / f_z


def test_mesh_stiffness_scales_with_youngs_modulus():
    """The tooth and body compliances are inversely proportional to E/(1 − ν²); Weber's
    contact term (docs/theory.md §4b) is δ/(w b) with δ E′/w a function of h/a and
    a ∝ √(w/E*): it scales the same way at a line load scaled with E. So aluminium's mesh at
    the load T is exactly E_al/E_st times steel's at T E_st/E_al (same ν). (With the linear
    Hertz term before issue 31 the mesh scaled with E at any load; now at equal loads the
    softer material is relatively stiffer, 0.351 against 70/206 = 0.340 on iso_pair.)"""
    k = {}
    for e, torque in (("206 GPa", 300.0 * 206.0 / 70.0), ("70 GPa", 300.0)):
        loaded = load_case(ISO_PAIR, [f"material.youngs_modulus={e}",
                                      "load.torque={function: 'STEP(time, 0, 0, 0.2, "
                                      f"{torque!r})', unit: N*m}}"])
        k[e] = case_mesh(loaded.case, run_geometry(loaded)).mesh_stiffness_N_mm
    assert k["70 GPa"] / k["206 GPa"] == pytest.approx(70.0 / 206.0, rel=1e-9)


@pytest.mark.parametrize("override, key", [
    ("contact.stiffness=1e5", "contact.stiffness"),
    ("contact.max_damping=10", "contact.max_damping"),
])
def test_impact_keys_with_the_tooth_law_are_refused(override, key):
    with pytest.raises(CaseError, match=rf"{key}.*applies to law 'impact' only"):
        load_case(ISO_PAIR, [override])


def test_damping_ratio_with_the_impact_law_is_refused():
    with pytest.raises(CaseError, match=r"contact.damping_ratio.*law 'tooth' only"):
        load_case(ROOT / "cases" / "seed.yaml", ["contact.damping_ratio=0.05"])


def test_run_and_mesh_of_the_iso_pair_and_the_seed_geometry(tmp_path, write_case, seed_text):
    """`gearcli run` and `gearcli mesh` with the tooth law on cases/iso_pair.yaml and on the seed
    geometry (the seed file without its IMPACT keys): valid results, the tooth mesh mode."""
    import json

    from typer.testing import CliRunner

    from gearcli.cli import app

    runner = CliRunner()
    res = runner.invoke(app, ["run", str(ISO_PAIR), "-o", str(tmp_path / "iso"), "-q",
                              "--set", "run.end_time=0.4"])
    assert res.exit_code == 0, res.output
    summary = json.loads((tmp_path / "iso" / "summary.json").read_text())
    assert summary["status"] == "ok" and 1.0 < summary["scalars"]["dynamic_factor"] < 3.0
    assert summary["scalars"]["mesh_damping_ratio"] == pytest.approx(0.07)
    lines = [ln for ln in seed_text.splitlines()
             if not ln.lstrip().startswith(("law:", "stiffness:", "exponent:", "max_damping:",
                                            "penetration_depth:"))]
    text = "\n".join(lines).replace("contact:", "contact:\n  law: tooth", 1)
    seed_tooth = write_case(text + "\n", "seed_tooth.yaml")
    res = runner.invoke(app, ["mesh", str(seed_tooth), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    assert doc["contact_law"].startswith("tooth")
    st = doc["stiffness"]
    ratio = st["double_pair_zone_N_mm"] / st["single_pair_zone_N_mm"]
    assert 1.5 < ratio < 2.0  # the tooth law: double-pair stiffness below twice single
