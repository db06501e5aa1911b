"""CLI: --help, --version, schema, new, python -m gearcli."""

import json
import subprocess
import sys

from typer.testing import CliRunner

from gearcli import __version__
from gearcli.cli import app
from tests.conftest import SEED

runner = CliRunner()


def test_help_lists_commands():
    result = runner.invoke(app, ["--help"])
    assert result.exit_code == 0
    for cmd in ("geometry", "schema", "new"):
        assert cmd in result.output


def test_version():
    result = runner.invoke(app, ["--version"])
    assert result.exit_code == 0
    assert result.output.strip() == f"gearcli {__version__}"


def test_python_m_gearcli_and_help_is_fast():
    # `gearcli --help` must not import numba/pandas/matplotlib/pydantic/pint, nor rich (typer's
    # rich help), nor the result documents (gearcli.results: ~50 ms, every document and the
    # metric registry; a command imports what it uses): check the imports it triggers (the
    # wall-time target is measured by `make bench`, never here).
    code = (
        "import sys, runpy; sys.argv=['gearcli','--help'];\n"
        "try:\n runpy.run_module('gearcli', run_name='__main__')\n"
        "except SystemExit: pass\n"
        "heavy=[m for m in ('numba','pandas','matplotlib','pydantic','pint','scipy','rich',"
        "'gearcli.results') "
        "if m in sys.modules]\nprint('HEAVY', heavy)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "HEAVY []" in out.stdout, out.stdout[-300:]
    assert "geometry" in out.stdout


def test_schema_is_json_schema():
    result = runner.invoke(app, ["schema"])
    assert result.exit_code == 0
    schema = json.loads(result.output)
    assert schema["type"] == "object"
    assert {"gears", "drive", "run"} <= set(schema["required"])
    assert schema["additionalProperties"] is False


def test_new_writes_seed_and_refuses_overwrite(tmp_path):
    target = tmp_path / "mine.yaml"
    result = runner.invoke(app, ["new", "--template", "seed", str(target)])
    assert result.exit_code == 0, result.output
    assert target.read_text() == SEED.read_text()
    result = runner.invoke(app, ["new", "--template", "seed", str(target)])
    assert result.exit_code == 1
    assert "already exists" in result.stderr
    assert target.read_text() == SEED.read_text()


def test_new_into_missing_folder(tmp_path):
    result = runner.invoke(app, ["new", str(tmp_path / "nope" / "c.yaml")])
    assert result.exit_code == 1
    assert "does not exist" in result.stderr


def test_unknown_command_is_usage_error():
    result = runner.invoke(app, ["frobnicate"])
    assert result.exit_code == 2


def test_every_command_has_an_example_in_its_help():
    """Issue 19: an example in every command's help, and shell completion is offered."""
    for command in ("geometry", "simulate", "analyze", "report", "run", "stress", "modal",
                    "mesh", "sweep", "schema", "new"):
        result = runner.invoke(app, [command, "--help"])
        assert result.exit_code == 0
        assert f"Example: gearcli {command}" in result.output, command
    assert "--install-completion" in runner.invoke(app, ["--help"]).output


def test_quiet_commands_print_nothing_on_success(tmp_path):
    """Issue 19: --quiet wherever a command prints tables."""
    for args in (["geometry", str(SEED), "-q"],
                 ["modal", str(SEED), "-q"],
                 ["mesh", str(SEED), "-q"]):
        result = runner.invoke(app, args)
        assert result.exit_code in (0, 4), (args, result.output)
        assert result.stdout.strip() == "", (args, result.stdout)


def test_simulate_of_an_impact_case_imports_no_unused_heavy_modules(tmp_path):
    # what the seed's run (IMPACT law, warm or cold cache) has no use for: the tooth-compliance
    # model's scipy.interpolate (~0.4 s), pandas, matplotlib, pint (issue 16: start-up)
    code = (
        "import sys, runpy\n"
        f"sys.argv=['gearcli','simulate',{str(SEED)!r},'-o',{str(tmp_path / 'o')!r},'--quiet',"
        "'--set','run.end_time=0.05']\n"
        "try:\n runpy.run_module('gearcli', run_name='__main__')\n"
        "except SystemExit as e: print('EXIT', e.code)\n"
        "heavy=[m for m in ('scipy.interpolate','pandas','matplotlib','pint') "
        "if m in sys.modules]\nprint('HEAVY', heavy)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert "HEAVY []" in out.stdout, (out.stdout[-300:], out.stderr[-300:])
    assert (tmp_path / "o" / "summary.json").exists()


def test_new_dash_prints_the_starter_case(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["new", "-t", "seed", "-"])
    assert result.exit_code == 0, result.output
    assert result.stdout == SEED.read_text()
    assert not (tmp_path / "-").exists()  # it wrote a file named '-'
