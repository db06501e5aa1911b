"""`gearcli analyze` does not pass a dynamic factor measured off a steady operating point
(docs/theory.md §7.8, §10.2 "Operating state").

Measured before: `cases/iso_pair.yaml` ended at 0.1 s, half-way up its 0.2 s ramps (the gear
speed changes by +88 % over the window, load and speed never reach the case's): analyze passed
``dynamic_factor`` with 1.095 (the steady run: 1.326); the seed ended inside its ramps passes
it while the steady seed fails it (4.03 > 2).
"""

from __future__ import annotations

from gearcli.pipeline.analyze import analyze
from tests.physics.simrun import FAST, write_run


def _check(analysis, name):
    return next(c for c in analysis.checks if c.name == name)


def test_a_run_that_ends_inside_its_ramps_has_no_dynamic_factor_verdict(tmp_path):
    folder = write_run(tmp_path / "short", [*FAST, "run.end_time=0.15"])
    check = _check(analyze(folder), "dynamic_factor")
    assert not check.checked and check.value is None
    assert check.note.startswith("not checked:") and "changes by" in check.note


def test_the_steady_seed_still_gets_its_verdict(tmp_path):
    folder = write_run(tmp_path / "steady", FAST)
    check = _check(analyze(folder), "dynamic_factor")
    assert check.checked and check.value > 2.0 and not check.passed  # the seed's 4.0


def test_stress_of_a_run_that_ends_inside_its_ramps_says_its_window_is_unsteady(tmp_path):
    # measured before: `gearcli stress` printed dynamic/static σ_H 1.003 against the static
    # load of the ramps' end (never reached) with no word of it
    from gearcli.pipeline.stress import compute_stress

    short = compute_stress(write_run(tmp_path / "short", [*FAST, "run.end_time=0.15"]), None)
    assert any("not one steady operating point" in w for w in short.warnings)
    steady = compute_stress(write_run(tmp_path / "steady", FAST), None)
    assert not any("steady operating point" in w for w in steady.warnings)


def test_a_remedy_run_off_its_operating_point_gives_no_dynamic_factor(tmp_path):
    # the NREL stage ended at 0.15 s, inside its 0.2 s ramps, fails its contact-loss check;
    # measured before: the remedy said "with it the dynamic factor is 0.931" (a transient's:
    # below 1) from its 0.15 s run
    from gearcli.pipeline.outputs import write_simulation
    from gearcli.pipeline.simulate import run_simulation
    from tests.conftest import ROOT

    folder = tmp_path / "nrel"
    write_simulation(run_simulation(ROOT / "cases" / "nrel5mw_sun_planet.yaml",
                                    ["run.end_time=0.15"], zoom=False), folder, force=False)
    remedy = next(c.remedy for c in analyze(folder, remedies=True).checks
                  if c.name == "contact_loss_fraction")
    assert remedy is not None and remedy.dynamic_factor is None
    assert "steady operating point" in remedy.text
