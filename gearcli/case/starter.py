"""The commented starter cases written by `gearcli new`, bundled in gearcli/data.

``pair`` (the default) is a neutral spur pair in engineering units (rpm, N*m, mm; the tooth
law with measured-range mesh damping) that runs clean; ``seed`` the seed article's Adams case
(cases/seed.yaml) and ``drivetrain`` the seed pair in a lateral-torsional drivetrain
(cases/drivetrain.yaml); the tests check that the bundled copies equal those files.
``study`` (a grid sweep) and ``speed-curve`` (a run-up and run-down) are study files for
`gearcli sweep` with the ``pair`` case inline as their base (one copy of it: its text is put
in at ``{base}``).
"""

from importlib import resources

#: Template name -> bundled file; the first is the default.
TEMPLATES = {"pair": "pair.yaml", "seed": "seed.yaml", "drivetrain": "drivetrain.yaml",
             "speed-curve": "speed-curve.yaml", "study": "study.yaml"}
#: The templates that are study files (`gearcli sweep`), not cases.
STUDY_TEMPLATES = ("speed-curve", "study")
DEFAULT_TEMPLATE = next(iter(TEMPLATES))


def starter_text(template: str = DEFAULT_TEMPLATE) -> str:
    """Text of the bundled starter case ``template`` (a key of :data:`TEMPLATES`)."""
    if template not in TEMPLATES:
        raise ValueError(f"unknown template {template!r}; expected one of: "
                         + ", ".join(TEMPLATES))
    text = _bundled(TEMPLATES[template])
    if template in STUDY_TEMPLATES:
        text = text.replace("{base}", "base:                         # the 'pair' starter case\n"
                            + _inline(_bundled(TEMPLATES[DEFAULT_TEMPLATE])))
    return text


def _bundled(name: str) -> str:
    return resources.files("gearcli.data").joinpath(name).read_text(encoding="utf-8")


def _inline(case_text: str) -> str:
    """A case file's text as an indented mapping under ``base:`` (its leading comment block,
    about the file itself, left out)."""
    lines = case_text.splitlines()
    start = next(i for i, line in enumerate(lines) if line and not line.startswith("#"))
    return "".join(f"  {line}\n" if line else "\n" for line in lines[start:])
