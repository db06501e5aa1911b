"""The commented starter case written by `gearcli new` (the seed study, cases/seed.yaml)."""

from importlib import resources


def starter_text() -> str:
    """Text of the bundled seed case (identical to cases/seed.yaml; a test checks that)."""
    return resources.files("gearcli.data").joinpath("seed.yaml").read_text(encoding="utf-8")
