"""`gearcli modal` (table, not only --json) on a mesh without a single-pair zone: exit 0 with
the single-pair stiffness reported as not applicable (issue 31 item 4: it ended with exit 3).
Pairs: tests/unit/test_modal_no_single_zone.py."""

import json

from typer.testing import CliRunner

from gearcli.cli import app
from tests.unit.test_modal_no_single_zone import ALPHA_15, ISO_PAIR, PAIR_62

runner = CliRunner()


def modal(overrides, *args):
    sets = [a for o in overrides for a in ("--set", o)]
    return runner.invoke(app, ["modal", str(ISO_PAIR), *sets, *args])


def test_table_without_single_pair_zone_exit_0():
    r = modal(ALPHA_15)
    assert r.exit_code == 0, r.output
    text = " ".join(r.output.split())  # rich wraps the header line
    assert "single pair not applicable: no single-pair zone" in text
    assert "mesh mode" in text and "resonance_margin" in text  # rich truncates the name
    doc = json.loads(modal(ALPHA_15, "--json").stdout)
    assert doc["linearisation"]["single_pair_stiffness_N_mm"] is None
    f = doc["modes"][0]["natural_frequency_Hz"]
    assert f"{f:g}" in text  # the same mode in the table as in the JSON


def test_issue_pair_table_exit_0(tmp_path):
    # the pair of the issue (ε_α 1.79 at ~200 N/mm); table and plot, exit 0 either way
    out = tmp_path / "campbell.png"
    r = modal(PAIR_62, "--plot", str(out))
    assert r.exit_code == 0, r.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
