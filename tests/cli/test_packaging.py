"""What `pip install .` installs outside the Makefile's venv, and the project's metadata files.

The wheel is built offline from a copy of the sources (``pip wheel --no-deps
--no-build-isolation --no-index``: this environment's setuptools, which the ``test`` extra
requires, so nothing is downloaded and the worktree gets no build/ folder) and inspected as a
zip, never installed: every module of the package, the starter cases `gearcli new` reads, the
``py.typed`` marker, the ``gearcli`` console script, the version and the licence must be in it.
"""

import importlib.metadata
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
import yaml

import gearcli

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "gearcli"
#: setuptools 77 is the first to read pyproject's ``license = "MIT"`` (an SPDX expression)
SETUPTOOLS_MIN = 77


def _source_files(pattern: str) -> set[str]:
    return {p.relative_to(ROOT).as_posix() for p in PACKAGE.rglob(pattern)
            if "__pycache__" not in p.parts}


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> zipfile.ZipFile:
    try:
        major = int(importlib.metadata.version("setuptools").split(".")[0])
    except importlib.metadata.PackageNotFoundError:
        major = 0
    if major < SETUPTOOLS_MIN:
        pytest.skip(f"building the wheel offline needs setuptools >= {SETUPTOOLS_MIN} in this "
                    "environment (the 'test' extra installs it)")
    tmp = tmp_path_factory.mktemp("wheel")
    src, out = tmp / "src", tmp / "dist"
    src.mkdir()
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy2(ROOT / name, src / name)
    shutil.copytree(PACKAGE, src / "gearcli",
                    ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    env = {**os.environ, "PIP_NO_INDEX": "1", "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    done = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", str(src), "-w", str(out), "--no-deps",
         "--no-build-isolation", "--no-index", "-q"],
        capture_output=True, text=True, env=env, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    wheels = list(out.glob("gearcli-*.whl"))
    assert len(wheels) == 1, wheels
    with zipfile.ZipFile(wheels[0]) as zf:
        yield zf


@pytest.mark.slow
def test_the_wheel_holds_every_module_and_the_package_data(wheel):
    names = set(wheel.namelist())
    modules = _source_files("*.py")
    assert len(modules) > 50  # the package's own modules were found (not an empty glob)
    assert {n for n in names if n.endswith(".py")} == modules
    cases = _source_files("data/*.yaml")
    assert {"gearcli/data/pair.yaml", "gearcli/data/seed.yaml"} <= cases
    assert cases <= names
    for name in cases:  # the starter cases byte for byte
        assert wheel.read(name) == (ROOT / name).read_bytes(), name
    assert "gearcli/py.typed" in names


@pytest.mark.slow
def test_the_wheel_metadata_names_version_entry_point_and_licence(wheel):
    info = f"gearcli-{gearcli.__version__}.dist-info"
    metadata = wheel.read(f"{info}/METADATA").decode()
    assert f"\nVersion: {gearcli.__version__}\n" in metadata
    assert "\nLicense-Expression: MIT\n" in metadata
    assert wheel.read(f"{info}/licenses/LICENSE") == (ROOT / "LICENSE").read_bytes()
    entry_points = wheel.read(f"{info}/entry_points.txt").decode()
    assert "gearcli = gearcli.cli:main" in entry_points


def test_citation_file_is_cff_1_2_with_the_package_version():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0"
    for key in ("message", "title", "authors"):  # required by CFF 1.2.0
        assert cff[key], key
    assert all(a.get("name") or a.get("family-names") for a in cff["authors"])
    assert str(cff["version"]) == gearcli.__version__
    assert cff["license"] == "MIT"


def test_licence_and_changelog():
    assert (ROOT / "LICENSE").read_text(encoding="utf-8").startswith("MIT License\n")
    changelog = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert "## [Unreleased]" in changelog
    assert f"## [{gearcli.__version__}] - " in changelog


@pytest.mark.slow
def test_the_wheel_installed_into_a_clean_venv_runs_gearcli(wheel, tmp_path):
    """`pip install` of the wheel into a new venv (offline: its dependencies are reached through
    a path entry to this environment's site-packages, whose own gearcli, an editable install,
    is not loaded: path entries do not run .pth files) gives a `gearcli` that runs from the
    venv, not from the sources: --version, and `new`, which reads the bundled starter case."""
    import sysconfig

    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True,
                   timeout=300)
    python = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env.update(PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    done = subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install",
                           "--no-deps", "--no-index", "-q", wheel.filename],
                          capture_output=True, text=True, env=env, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    site = subprocess.run([str(python), "-c", "import sysconfig; "
                           "print(sysconfig.get_paths()['purelib'])"], capture_output=True,
                          text=True, check=True).stdout.strip()
    (Path(site) / "deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    run = {"cwd": tmp_path, "env": env, "capture_output": True, "text": True, "timeout": 300}
    where = subprocess.run([str(python), "-c", "import gearcli; print(gearcli.__file__)"], **run)
    assert where.stdout.strip().startswith(str(venv)), where.stdout + where.stderr
    version = subprocess.run([str(venv / "bin" / "gearcli"), "--version"], **run)
    assert version.returncode == 0 and version.stdout == f"gearcli {gearcli.__version__}\n"
    new = subprocess.run([str(venv / "bin" / "gearcli"), "new", "pair.yaml"], **run)
    assert new.returncode == 0, new.stderr
    assert (tmp_path / "pair.yaml").read_bytes() == (PACKAGE / "data" / "pair.yaml").read_bytes()
