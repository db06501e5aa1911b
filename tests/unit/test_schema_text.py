"""`gearcli schema` from the user cache: the same text, regenerated when a source changes."""

import json

from gearcli.case import schema_text


def test_cached_text_is_the_generated_text(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    first = schema_text.schema_text()
    assert first == schema_text.generate()
    (cache,) = (tmp_path / "gearcli").glob("case-schema-*.json")
    doc = json.loads(cache.read_text())
    assert schema_text.__file__ in doc["sources"]
    assert any(src.endswith("case/schema.py") for src in doc["sources"])
    doc["schema"] = "stale"
    cache.write_text(json.dumps(doc))
    assert schema_text.schema_text() == "stale"  # served from the cache while sources match


def test_changed_source_regenerates(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    schema_text.schema_text()
    (cache,) = (tmp_path / "gearcli").glob("case-schema-*.json")
    doc = json.loads(cache.read_text())
    doc["schema"] = "stale"
    source = next(src for src in doc["sources"] if src.endswith("case/schema.py"))
    doc["sources"][source][1] -= 1  # an older modification time: the file has changed since
    cache.write_text(json.dumps(doc))
    assert schema_text.schema_text() == schema_text.generate()


def test_without_a_writable_cache(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker))  # not a folder: nothing can be cached
    assert schema_text.schema_text() == schema_text.generate()
