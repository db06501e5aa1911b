"""`gearcli new --template pair|seed|drivetrain` (issue 29): the default is a neutral pair in
engineering units that runs clean; every template runs; bundled copies equal cases/."""

import pytest
from typer.testing import CliRunner

from gearcli.case.load import load_case
from gearcli.case.starter import STUDY_TEMPLATES, TEMPLATES, starter_text
from gearcli.cli import app
from tests.conftest import ROOT

runner = CliRunner()


@pytest.mark.parametrize("name", ["seed", "drivetrain"])
def test_bundled_templates_are_the_repository_cases(name):
    assert starter_text(name) == (ROOT / "cases" / f"{name}.yaml").read_text()


def test_the_default_is_the_engineering_pair(tmp_path):
    target = tmp_path / "my_pair.yaml"
    res = runner.invoke(app, ["new", str(target)])
    assert res.exit_code == 0, res.output
    assert target.read_text() == starter_text("pair")
    loaded = load_case(target)
    assert loaded.case.units == "engineering"
    assert loaded.name == "my_pair"  # no name in the template: results are titled by the file
    assert loaded.case.contact.law == "tooth" and 0.03 <= loaded.case.contact.damping_ratio <= 0.1
    assert "units: engineering" in target.read_text().splitlines()[7]  # declared at the top


def test_the_pair_runs_clean(tmp_path):
    """Exit 0 and not one warning: no contact loss, no coast-flank impacts, no overdamping.
    The line load its description states is the one the run's input digest prints (the
    description rounds it to whole N/mm; it said 174, the gear's torque over the pinion's
    diameter, where the digest prints 2 T2/(d2 b) = 85.11 N/mm)."""
    import re

    target = tmp_path / "pair.yaml"
    assert runner.invoke(app, ["new", str(target)]).exit_code == 0
    res = runner.invoke(app, ["simulate", str(target), "-o", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    assert "warning" not in res.stderr, res.stderr
    stated = re.search(r"F_t/b about (\d+) N/mm", target.read_text())
    printed = re.search(r"F_t/b = ([\d.]+) N/mm", res.stdout)
    assert stated is not None and printed is not None, res.stdout
    assert abs(float(stated.group(1)) - float(printed.group(1))) <= 0.5


@pytest.mark.parametrize("name", [n for n in TEMPLATES
                                  if n != "pair" and n not in STUDY_TEMPLATES])
def test_every_other_template_runs(name, tmp_path):
    # new -> run (simulate, analyze, report): exit 0, the seed 4 with its findings (the
    # article's pair honestly fails its dynamic-factor and contact-loss checks)
    target = tmp_path / f"{name}.yaml"
    assert runner.invoke(app, ["new", "--template", name, str(target)]).exit_code == 0
    res = runner.invoke(app, ["run", str(target), "-o", str(tmp_path / "out"), "--format", "md",
                              "-q"])
    assert res.exit_code == {"seed": 4}.get(name, 0), res.output
    assert (tmp_path / "out" / "report.md").is_file()


def test_unknown_template_names_the_allowed_ones(tmp_path):
    res = runner.invoke(app, ["new", "--template", "helical", str(tmp_path / "c.yaml")])
    assert res.exit_code == 1
    assert res.stderr.strip() == "error: --template helical: expected one of: pair, seed, " \
        "drivetrain, speed-curve, study"
    assert not (tmp_path / "c.yaml").exists()


#: Shorter versions of the study templates for the test (the same keys, fewer and shorter
#: points): (text in the template, its replacement).
SHORTER = {"study": [('["40 mm", "50 mm", "60 mm"]', '["40 mm", "60 mm"]'),
                     ("[0.05, 0.1]", "[0.07]"), ("run.end_time: 0.6 s", "run.end_time: 0.3 s")],
           "speed-curve": [('["200 Hz", "4000 Hz"], num: 20', '["400 Hz", "800 Hz"], num: 2')]}


@pytest.mark.parametrize("name", STUDY_TEMPLATES)
def test_the_study_templates_sweep(name, tmp_path):
    """`new --template study|speed-curve` writes a study file (the pair case inline) that
    `gearcli sweep` runs to the end, exit 0, every point ok (shortened here), and writes the
    files its header names (the speed curve's named a speed_curve.csv it never wrote)."""
    import re

    target = tmp_path / f"{name}.yaml"
    res = runner.invoke(app, ["new", "--template", name, str(target)])
    assert res.exit_code == 0 and "gearcli sweep" in res.stdout, res.output
    text = target.read_text()
    assert text == starter_text(name) and "units: engineering" in text
    for old, new in SHORTER[name]:
        assert old in text
        text = text.replace(old, new)
    target.write_text(text)
    out = tmp_path / "out"
    res = runner.invoke(app, ["sweep", str(target), "-o", str(out), "-j", "1", "-q"])
    assert res.exit_code == 0, res.output
    rows = (out / "summary.csv").read_text().splitlines()
    status = rows[0].split(",").index("status")
    assert len(rows) > 2 and all(r.split(",")[status] == "ok" for r in rows[1:]), rows
    header = "".join(line for line in text.splitlines(True) if line.startswith("#"))
    named = set(re.findall(r"(?<![\w/.])\w+\.(?:csv|png|json|md|parquet)\b", header))
    assert "summary.csv" in named and named <= {p.name for p in out.iterdir()}, named


def test_a_fresh_pair_runs_to_a_report_titled_by_its_own_name(tmp_path):
    """`new` -> `run` (simulate, analyze, report): exit 0, every check passed or not checked,
    the report titled by the file's name, not the seed's (issue 29)."""
    target = tmp_path / "gearbox-stage1.yaml"
    assert runner.invoke(app, ["new", str(target)]).exit_code == 0
    out = tmp_path / "out"
    res = runner.invoke(app, ["run", str(target), "-o", str(out), "--format", "md"])
    assert res.exit_code == 0, res.output
    assert "findings" not in res.stderr and "FAIL" not in res.stdout
    text = (out / "report.md").read_text()
    assert text.startswith("# gearcli report: gearbox-stage1\n")
    assert "17 teeth" not in text and "seed" not in text.split("\n## ")[0].lower()


def test_the_seed_runs_to_its_findings_with_a_remedy(tmp_path):
    """The seed fails its dynamic factor and contact loss (its Adams contact): `run` exits 4
    and says so as findings with the remedy, not as an error line (issue 29). Shortened to
    2 s (the failures show from the first steady second)."""
    target = tmp_path / "seed.yaml"
    assert runner.invoke(app, ["new", "--template", "seed", str(target)]).exit_code == 0
    res = runner.invoke(app, ["run", str(target), "-o", str(tmp_path / "out"), "--set",
                              "run.end_time=2", "--format", "md"])
    assert res.exit_code == 4, res.output
    assert "error" not in res.stderr
    assert ("findings: 2 check(s) failed: dynamic factor F_max / F_static (dynamic_factor); "
            "time without drive-flank contact (contact_loss_fraction)") in res.stderr
    assert ("remedy (dynamic factor F_max / F_static; time without drive-flank contact): a "
            "linear tip relief") in res.stdout
    report = (tmp_path / "out" / "report.md").read_text()
    assert ("Remedy (dynamic factor F\\_max / F\\_static; time without drive-flank contact)"
            in report)
