"""report.html in a real browser (issue 19): headless Chromium (Debian's chromium and
chromium-driver, installed by `make test` where missing) opens the report of a short seed run;
the test fails on any console error or broken image and saves a screenshot."""

from __future__ import annotations

import shutil

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import SEED

runner = CliRunner()
SHORT = ["--set", "run.end_time=0.4", "--set", "drive.speed=STEP(time, 0, 0, 0.1, 3000)",
         "--set", "load.torque=STEP(time, 0, 0, 0.1, 4.5e5)"]

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
pytestmark = pytest.mark.skipif(not (CHROMIUM and DRIVER),
                                reason="Debian's chromium and chromium-driver are not installed "
                                       "(make test installs them where it may)")


def test_report_renders_without_console_errors_or_broken_images(tmp_path):
    webdriver = pytest.importorskip("selenium.webdriver")
    from selenium.webdriver.chrome.service import Service

    out = tmp_path / "run"
    res = runner.invoke(app, ["run", str(SEED), "-o", str(out), "-q", *SHORT])
    assert res.exit_code in (0, 4), res.output
    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--window-size=1280,2000"):
        opts.add_argument(arg)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(DRIVER), options=opts)
    try:
        driver.set_page_load_timeout(60)
        driver.get((out / "report.html").resolve().as_uri())
        title = driver.title
        images = driver.execute_script(
            "return Array.from(document.images).map(i => [i.alt, i.complete, i.naturalWidth])")
        headings = driver.execute_script(
            "return Array.from(document.querySelectorAll('h2')).map(h => h.textContent)")
        errors = [e for e in driver.get_log("browser") if e.get("level") == "SEVERE"]
        driver.save_screenshot(str(out / "report-screenshot.png"))
    finally:
        driver.quit()
    assert title.startswith("gearcli report")
    assert not errors, errors
    assert len(images) >= 5  # speeds, force, mesh cycles, DTE, spectra
    broken = [alt for alt, complete, width in images if not complete or width == 0]
    assert not broken, broken
    assert {"Summary", "Case", "Results", "Checks", "Figures", "Provenance"} <= set(headings)
    assert (out / "report-screenshot.png").stat().st_size > 20_000
