"""The first-run notice states a measured estimate (issue 29), not a constant."""

import json

import pytest

from gearcli.pipeline import compile_time


def test_without_a_record_the_estimate_scales_with_the_probe(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.setattr(compile_time, "probe_s", lambda: 2 * compile_time.REFERENCE_PROBE_CPU_S)
    seconds, how = compile_time.estimate()
    assert seconds == pytest.approx(2 * compile_time.REFERENCE_COMPILE_CPU_S)
    assert "probe" in how
    monkeypatch.setattr(compile_time, "probe_s", lambda: 4 * compile_time.REFERENCE_PROBE_CPU_S)
    assert compile_time.estimate()[0] == pytest.approx(4 * compile_time.REFERENCE_COMPILE_CPU_S)


def test_a_recorded_compile_is_scaled_by_the_probe_now(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.setattr(compile_time, "probe_s", lambda: 0.05)
    compile_time.record(64.0)
    rec = json.loads((tmp_path / "gearcli" / "timing" / "compile.json").read_text())
    assert rec == {"wall_s": 64.0, "probe_s": 0.05}
    monkeypatch.setattr(compile_time, "probe_s", lambda: 0.025)  # a quieter machine now
    seconds, how = compile_time.estimate()
    assert seconds == pytest.approx(32.0) and "took 64 s" in how
    assert compile_time.notice_text().startswith("compiling the solver once, ~32 s (the last")


def test_a_broken_record_falls_back_to_the_probe(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    (tmp_path / "gearcli" / "timing").mkdir(parents=True)
    (tmp_path / "gearcli" / "timing" / "compile.json").write_text("{not json")
    seconds, how = compile_time.estimate()
    assert seconds > 0 and "probe" in how
