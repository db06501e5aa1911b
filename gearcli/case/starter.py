"""The commented starter cases written by `gearcli new`, bundled in gearcli/data.

``pair`` (the default) is a neutral spur pair in engineering units (rpm, N*m, mm; the tooth
law with measured-range mesh damping) that runs clean; ``seed`` the seed article's Adams case
(cases/seed.yaml) and ``drivetrain`` the seed pair in a lateral-torsional drivetrain
(cases/drivetrain.yaml); the tests check that the bundled copies equal those files.
"""

from importlib import resources

#: Template name -> bundled file; the first is the default.
TEMPLATES = {"pair": "pair.yaml", "seed": "seed.yaml", "drivetrain": "drivetrain.yaml"}
DEFAULT_TEMPLATE = next(iter(TEMPLATES))


def starter_text(template: str = DEFAULT_TEMPLATE) -> str:
    """Text of the bundled starter case ``template`` (a key of :data:`TEMPLATES`)."""
    if template not in TEMPLATES:
        raise ValueError(f"unknown template {template!r}; expected one of: "
                         + ", ".join(TEMPLATES))
    return resources.files("gearcli.data").joinpath(TEMPLATES[template]).read_text(
        encoding="utf-8")
