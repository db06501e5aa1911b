"""Shared fixtures: the seed case and helpers to write variants of it."""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SEED = ROOT / "cases" / "seed.yaml"


@pytest.fixture
def seed_text() -> str:
    return SEED.read_text()


@pytest.fixture
def write_case(tmp_path):
    """write_case(text, name="case.yaml") -> Path of a case file in a temp folder."""

    def _write(text: str, name: str = "case.yaml") -> Path:
        p = tmp_path / name
        p.write_text(text)
        return p

    return _write
