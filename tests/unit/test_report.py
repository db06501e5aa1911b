"""`gearcli.report.build_report` and the result figures of `gearcli.plotting.results`.

One short run (0.6 s, ramps of 0.2 s) is simulated, analysed and reported once per module; the
tests read the HTML and Markdown it produced. The timing target of the issue ("analyze +
report of the seed case <= 5 s") is checked on the full 5 s seed run (marked slow).
"""

from __future__ import annotations

import base64
import json
import re
import shutil
from html.parser import HTMLParser

import numpy as np
import pytest

from gearcli.errors import OutputError, ResultsError
from gearcli.plotting import results as plots
from gearcli.plotting.spectra import plot_spectra
from gearcli.report import build_report
from gearcli.results import SpectrumLine
from tests.physics.simrun import write_run

SHORT = ["drive.speed=STEP(time, 0, 0, 0.2, 3000)", "load.torque=STEP(time, 0, 0, 0.2, 4.5e5)",
         "run.end_time=0.6"]
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def short_dir(tmp_path_factory):
    return write_run(tmp_path_factory.mktemp("report") / "run", SHORT, analysed=True)


@pytest.fixture(scope="module")
def html_report(short_dir):
    path = build_report(short_dir)
    return path, path.read_text(encoding="utf-8")


@pytest.fixture(scope="module")
def md_report(short_dir):
    path = build_report(short_dir, fmt="md")
    return path, path.read_text(encoding="utf-8")


class _Collector(HTMLParser):
    """Tags, attributes and the text of every table (by caption)."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags: list[tuple[str, dict]] = []
        self.tables: dict[str, list[list[str]]] = {}
        self._caption = self._in_caption = self._cell = None
        self._rows: list[list[str]] = []
        self.row_classes: dict[str, list[str]] = {}

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.append((tag, a))
        if tag == "table":
            self._caption, self._rows = "", []
            self._row_classes = []
        elif tag == "caption":
            self._in_caption = True
        elif tag == "tr":
            self._rows.append([])
            self._row_classes.append(a.get("class") or "")
        elif tag in ("td", "th"):
            self._cell = ""

    def handle_endtag(self, tag):
        if tag == "caption":
            self._in_caption = False
        elif tag in ("td", "th") and self._cell is not None:
            self._rows[-1].append(self._cell)
            self._cell = None
        elif tag == "table":
            self.tables[self._caption] = self._rows
            self.row_classes[self._caption] = self._row_classes

    def handle_data(self, data):
        if self._in_caption:
            self._caption += data
        elif self._cell is not None:
            self._cell += data


def _parse(text: str) -> _Collector:
    p = _Collector()
    p.feed(text)
    p.close()
    return p


def _table(parsed: _Collector, title: str) -> tuple[list[list[str]], list[str]]:
    for caption, rows in parsed.tables.items():
        if caption.endswith(title):
            return rows, parsed.row_classes[caption]
    raise AssertionError(f"no table {title!r} in {list(parsed.tables)}")


def test_html_is_written_next_to_the_results_and_figures_as_png(short_dir, html_report):
    path, text = html_report
    assert path == short_dir / "report.html"
    pngs = sorted((short_dir / "figures").glob("*.png"))
    # the short seed run has a run-up (order map) and an overdamped mesh mode (Campbell)
    assert {p.stem for p in pngs} == {"geometry", "speeds", "force", "mesh_cycles", "dte",
                                      "spectra", "campbell", "orders"}
    for p in pngs:
        assert p.read_bytes().startswith(PNG_SIGNATURE)
    # SVG only on request (issue 29: saving it doubled the report's time)
    assert not list((short_dir / "figures").glob("*.svg"))
    assert "figures/ as PNG." in text


def test_svg_on_request_and_removed_when_no_longer_asked_for(short_dir, tmp_path):
    folder = tmp_path / "svg"
    shutil.copytree(short_dir, folder, ignore=shutil.ignore_patterns("report.*", "figures"))
    md = build_report(folder, fmt="md", svg=True).read_text(encoding="utf-8")
    pngs = sorted((folder / "figures").glob("*.png"))
    svgs = sorted((folder / "figures").glob("*.svg"))
    assert pngs and [p.stem for p in pngs] == [p.stem for p in svgs]
    for p in svgs:
        assert b"<svg" in p.read_bytes()[:2000]
    assert "figures/ as PNG and SVG." in md
    assert ".svg)" not in md  # the page links the PNGs
    build_report(folder, fmt="md")
    assert not list((folder / "figures").glob("*.svg"))
    assert len(list((folder / "figures").glob("*.png"))) == len(pngs)


def test_html_parses_and_embeds_every_figure(short_dir, html_report):
    _, text = html_report
    parsed = _parse(text)
    n_figures = len(list((short_dir / "figures").glob("*.png")))
    assert text.count("data:image/png;base64") == n_figures
    imgs = [a["src"] for tag, a in parsed.tags if tag == "img"]
    assert len(imgs) == n_figures
    for src in imgs:
        assert base64.b64decode(src.split(",", 1)[1]).startswith(PNG_SIGNATURE)
    assert text.count("<figcaption>") == n_figures


def test_html_is_self_contained(html_report):
    _, text = html_report
    parsed = _parse(text)
    for tag, attrs in parsed.tags:
        assert tag not in ("script", "link", "iframe", "object"), tag
        for key in ("src", "href"):
            if key not in attrs:
                continue
            value = attrs[key] or ""
            assert not re.match(r"\s*(https?:)?//", value, re.I), (tag, value)
            if key == "href":
                assert value.startswith("#"), value  # only links inside the page
    assert "http://" not in text and "https://" not in text


def test_html_checks_table_names_every_check_with_its_result(short_dir, html_report):
    _, text = html_report
    rows, classes = _table(_parse(text), "Checks")
    doc = json.loads((short_dir / "analysis.json").read_text())
    # one unit a column; each check by its label, its key (analysis.json's name, where the
    # case sets its limit) last
    assert rows[0] == ["check", "value", "unit", "limit", "result", "note", "key"]
    body = {r[6].split(" (")[0]: (r[4], cls, r[0])
            for r, cls in zip(rows[1:], classes[1:], strict=True)}
    assert set(body) == {c["name"] for c in doc["checks"]}
    labels = {name: label for name, (_, _, label) in body.items()}
    assert labels["dynamic_factor"] == "dynamic factor F_max / F_static"
    assert labels["contact_loss_fraction"] == "time without drive-flank contact"
    assert all(" " in label and name not in label
               for name, label in labels.items())  # never a raw key
    key = next(r[6] for r in rows[1:] if r[0] == labels["dynamic_factor"])
    assert key == "dynamic_factor (checks.dynamic_factor_max)"
    for c in doc["checks"]:
        result, cls, _ = body[c["name"]]
        expected = (("not checked", "") if c.get("checked") is False and c["passed"] is None
                    else ("pass", "pass") if c["passed"] else ("FAIL", "fail"))
        assert (result, cls) == expected


def test_html_holds_the_case_tables_results_and_provenance(short_dir, html_report):
    _, text = html_report
    parsed = _parse(text)
    gears, _ = _table(parsed, "Gears and material")
    cells = {r[0]: r[1:] for r in gears}
    assert cells["number of teeth z"] == ["17", "25"]
    assert cells["module m"] == ["10 mm", "10 mm"]
    assert cells["pressure angle α"] == ["20 deg", "20 deg"]
    assert cells["reference diameter d"] == ["170 mm", "250 mm"]
    geometry = {r[0]: r[1] for r in _table(parsed, "Pair geometry (derived)")[0]}
    assert float(geometry["transverse contact ratio ε_α"]) == pytest.approx(1.563, abs=1e-3)
    contact = {r[0]: r[1:] for r in _table(parsed, "Contact and friction")[0]}
    assert contact["stiffness K"] == ["100000", "N/mm^1.5"]
    assert contact["dynamic coefficient μ_d"][0] == "0.05"
    results = {r[0]: r[1:] for r in _table(parsed, "Results of the steady window")[0]}
    assert results["dynamic factor F_max / F_static"][1] == "–"
    assert results["normal force, maximum (from the solver steps)"][1] == "N"
    manifest = json.loads((short_dir / "manifest.json").read_text())
    assert manifest["case_sha256"] in text
    assert "run.end_time=0.6" in text  # the overrides are shown
    # the modes simulate stored (speed drive: the gear against the prescribed pinion)
    modes = _table(parsed, "Modes of the linearised model")[0][1:]  # after the header row
    assert len(modes) == 1 and modes[0][3].startswith("mesh mode")
    assert float(modes[0][1]) == pytest.approx(281.2, abs=0.1)


def test_html_escapes_strings_from_the_case(short_dir, tmp_path):
    folder = tmp_path / "evil"
    shutil.copytree(short_dir, folder)
    man = json.loads((folder / "manifest.json").read_text())
    man["resolved_case"]["name"] = "<b>bold</b>"
    man["resolved_case"]["description"] = '<script>alert("x")</script> & <img src=x>'
    (folder / "manifest.json").write_text(json.dumps(man))
    text = build_report(folder).read_text()
    assert "<script>" not in text and "<img src=x>" not in text and "<b>bold" not in text
    assert "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &lt;img src=x&gt;" in text
    md = build_report(folder, fmt="md").read_text()
    assert "<script>" not in md and r"\<script\>" in md


def test_markdown_references_existing_figures(short_dir, md_report):
    path, text = md_report
    assert path == short_dir / "report.md"
    links = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert len(links) == len(list((short_dir / "figures").glob("*.png")))
    for link in links:
        assert link.startswith("figures/") and (path.parent / link).is_file()
    assert "| check | value | unit | limit | result | note | key |" in text
    for c in json.loads((short_dir / "analysis.json").read_text())["checks"]:
        assert c["name"].replace("_", r"\_") in text


def test_markdown_elsewhere_links_back_to_the_figures(short_dir, tmp_path):
    out = build_report(short_dir, fmt="md", out_file=tmp_path / "r.md")
    links = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", out.read_text())
    assert links and all((out.parent / link).resolve().is_file() for link in links)


def test_missing_analysis_asks_for_gearcli_analyze(short_dir, tmp_path):
    folder = tmp_path / "raw"
    shutil.copytree(short_dir, folder, ignore=shutil.ignore_patterns("report.*", "figures"))
    (folder / "analysis.json").unlink()
    with pytest.raises(ResultsError, match="run gearcli analyze"):
        build_report(folder)
    assert not (folder / "report.html").exists() and not (folder / "figures").exists()


def test_not_a_results_folder_and_bad_options(tmp_path, short_dir):
    with pytest.raises(ResultsError):
        build_report(tmp_path)
    with pytest.raises(ValueError, match="html, md"):
        build_report(short_dir, fmt="pdf")
    with pytest.raises(OutputError):
        build_report(short_dir, out_file=tmp_path / "no" / "such" / "report.html")


def test_errors_and_relief_add_a_figure(tmp_path):
    folder = write_run(tmp_path / "mods", analysed=True, overrides=SHORT + [
        "errors.runout.gear={eccentricity: 0.02}",
        "modifications.tip_relief.pinion={amount: 0.05, length: 6}"])
    text = build_report(folder).read_text()
    assert (folder / "figures" / "modifications.png").is_file()
    # geometry, speeds, force, mesh cycles, DTE, spectra, Campbell, order map, modifications
    assert text.count("data:image/png;base64") == 9
    rows, _ = _table(_parse(text), "Profile modifications and errors")
    assert {r[0] for r in rows[1:]} == {"pinion tip relief", "gear runout"}


# --- plotting functions on synthetic data ----------------------------------------------------
def test_spectra_mark_aliases_when_the_mesh_is_above_nyquist():
    fs, f_z = 200.0, 141.67
    freq = np.linspace(0.0, 100.0, 401)
    amp = np.full(freq.size, 1e-3)
    lines = {"force": {"1fz": SpectrumLine(expected_Hz=f_z, resolvable=False),
                       "2fz": SpectrumLine(expected_Hz=2 * f_z, resolvable=False)}}
    fig = plot_spectra(freq, {"force": ("force", "N", amp)}, lines, f_z, 2, fs)
    ax = fig.axes[0]
    assert ax.get_xlim() == (0.0, 100.0)  # never past Nyquist
    labels = {t.get_text() for t in ax.texts}
    assert {"1 f_z alias", "2 f_z alias"} <= labels
    xs = sorted(round(line.get_xdata()[0], 2) for line in ax.lines if line.get_linestyle() == "-.")
    assert xs == [58.33, 83.34]  # 200 - 141.67 and 2 x 141.67 - 200
    assert "Nyquist" in fig._suptitle.get_text()


def test_mesh_cycle_mean_averages_whole_cycles_only():
    t = np.arange(100) * 0.1
    v = np.sin(2 * np.pi * t / 1.0) + 3.0  # period = 10 samples
    tm, vm = plots.mesh_cycle_mean(t, v, 10.0)
    assert tm.size == vm.size == 91
    assert np.allclose(vm, 3.0, atol=1e-12)
    assert tm[0] == pytest.approx(0.45)


def test_force_figure_marks_the_true_maximum_and_the_static_line():
    t = np.linspace(0.0, 1.0, 1001)
    f = 1000.0 + 100.0 * np.sin(2 * np.pi * 50 * t)
    fig = plots.plot_force(t, f, 1000.0, 1500.0, 0.5, (0.2, 1.0), (0.48, 0.52), 50.0)
    title = fig._suptitle.get_text()
    assert "1.50 kN" in title and "1.50 × the static 1.00 kN" in title
    stars = [ln for ax in fig.axes for ln in ax.lines if ln.get_marker() == "*"]
    assert len(stars) == 2 and all(ln.get_ydata()[0] == pytest.approx(1.5) for ln in stars)


def test_no_order_map_for_a_start_up_transient(tmp_path):
    """A speed that reaches its final value within 2 % of the run is a start-up, not a run-up:
    the report has no order map (docs: report/figures.py)."""
    run = write_run(tmp_path / "run", ["drive.speed=STEP(time, 0, 0, 0.01, 3000)",
                                       "load.torque=STEP(time, 0, 0, 0.01, 4.5e5)",
                                       "run.end_time=0.5"], analysed=True)
    build_report(run, fmt="md")
    names = {p.stem for p in (run / "figures").glob("*.png")}
    assert "orders" not in names and {"speeds", "force", "spectra"} <= names


def test_results_rows_use_the_metric_registrys_labels(md_report):
    # keys the registry knows were labelled from their names ("force max t [s]")
    _, text = md_report
    assert "| time of the maximum force |" in text and "force max t" not in text


def test_zooms_use_the_dense_table_when_it_covers_the_span():
    """zoom.csv holds stretches at 128 points per nominal mesh period, with times rounded to 10
    digits; the report's spans come from the measured f_z, so no sample sits on their ends.
    Requiring one within 1e-9 s of each end made every force zoom fall back to the output
    samples (third adversarial run)."""
    from gearcli.report.figures import _zoom_of

    period = 1.0 / 141.7
    t = np.round(np.concatenate([np.linspace(1.0, 1.0 + 4 * period, 513),
                                 np.linspace(4.9, 5.0, 1812)]), 10)
    zoom = {"t_s": t, "force_total_N": np.ones_like(t), "load_torque_Nmm": np.ones_like(t),
            "omega2_rad_s": np.ones_like(t)}
    span = (1.0 + 0.5 * period + 1.234e-6, 1.0 + 3.5 * period - 2.1e-6)
    got = _zoom_of(zoom, span, 100.0)
    assert got is not None and got[0][0] >= span[0] and got[0][-1] <= span[1]
    assert len(got[0]) > 3 * 128 - 2
    assert _zoom_of(zoom, (1.0 + 3 * period, 4.95), 100.0) is None  # across the gap
    assert _zoom_of(zoom, (0.99, 1.0 + period), 100.0) is None  # starts before the table


def test_case_tables_show_tooth_form_settings_and_angles_in_degrees(tmp_path):
    # tip rounding was in no table (though "the tables show the values used") and the runout
    # phase printed in rad where the case takes degrees (fourth adversarial run)
    from typer.testing import CliRunner

    from gearcli.cli import app
    from tests.conftest import SEED

    out = tmp_path / "r"
    r = CliRunner().invoke(app, ["run", str(SEED), "-o", str(out), "-q", "--format", "md",
                                 "--set", "run.end_time=0.3", "--set",
                                 "gears.pinion.tip_rounding=1", "--set",
                                 "errors.runout.pinion={eccentricity: 0.01, phase: 30}"])
    assert r.exit_code in (0, 4), r.output
    text = (out / "report.md").read_text()
    assert "| tip rounding | 1 mm | 0 mm |" in text
    assert "| pinion runout | eccentricity = 0.01 mm, phase = 30 deg |" in text
