"""`gearcli schema` and `gearcli new`: the case file's JSON Schema and a starter case."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import handle_errors
from gearcli.io.files import write_stdout


@app.command()
@handle_errors
def schema(
    results: bool = typer.Option(False, "--results",
                                 help="The JSON Schema of a result document instead of the "
                                      "case's (--kind)."),
    kind: str | None = typer.Option(
        None, "--kind", metavar="summary|analysis|stress|modal|mesh|rating|monitor",
        help="With --results: summary.json, analysis.json, stress.json, gearcli modal --json, "
             "gearcli mesh --json, rating.json or monitor.json."),
    study: bool = typer.Option(False, "--study",
                               help="The JSON Schema of a study file (gearcli sweep)."),
) -> None:
    """Print the case file's JSON Schema (for editor completion and validation), or with
    --results that of a result document (summary.json unless --kind), or with --study that of
    a study file.

    Example: gearcli schema --results --kind analysis > analysis.schema.json"""
    from gearcli.errors import OutputError

    if kind is not None and not results:  # it printed the case's schema without a word
        raise OutputError(f"--kind {kind}: applies to --results only (the JSON Schema of a "
                          "result document)")
    if study and results:
        raise OutputError("--study and --results: expected one of them")
    if study:
        import json

        from gearcli.pipeline.sweep.study import StudyFile

        write_stdout(json.dumps(StudyFile.model_json_schema(), indent=2) + "\n")
        return
    if results:
        import json

        from gearcli.results import KINDS, json_schema

        kind = kind or "summary"
        if kind not in KINDS:
            raise OutputError(f"--kind {kind}: expected one of {', '.join(KINDS)}")
        write_stdout(json.dumps(json_schema(kind), indent=2) + "\n")
        return
    from gearcli.case.schema_text import schema_text

    write_stdout(schema_text() + "\n")


@app.command()
@handle_errors
def new(path: Path = typer.Argument(..., help="Where to write the starter case (.yaml); "
                                     "'-' prints it."),
        template: str = typer.Option("pair", "--template", "-t",
                                     metavar="pair|seed|drivetrain|speed-curve|study",
                                     help="pair (default): a commented spur pair in "
                                          "engineering units (rpm, N*m, mm) that runs clean; "
                                          "seed: the seed article's Adams case; drivetrain: "
                                          "the seed pair on bearings between shafts and "
                                          "inertias; speed-curve and study: study files for "
                                          "gearcli sweep (a run-up/run-down, a grid) with "
                                          "the pair inline.")) -> None:
    """Write a commented starter case; never overwrites a file.

    Example: gearcli new mypair.yaml, gearcli new --template study study.yaml, or
    gearcli new - > mycase.yaml"""
    from gearcli.case.starter import TEMPLATES, starter_text
    from gearcli.errors import OutputError
    from gearcli.io.files import write_new_text

    if template not in TEMPLATES:
        raise OutputError(f"--template {template}: expected one of: {', '.join(TEMPLATES)}")
    text = starter_text(template)
    if str(path) == "-":  # the shell convention: standard output
        typer.echo(text, nl=False)
        return
    write_new_text(path, text)
    from gearcli.case.starter import STUDY_TEMPLATES

    if template in STUDY_TEMPLATES:
        typer.echo(f"wrote {path} (the '{template}' template; edit it, then: gearcli sweep "
                   f"{path} -o out/{path.stem})")
        return
    typer.echo(f"wrote {path} (the '{template}' template; edit it, then: gearcli geometry "
               f"{path}, gearcli simulate {path})")
