"""Read a gearcli results folder back (for analyze and report), refusing bad folders.

The one place where a stored summary.json is read by its keys: :func:`check_summary` refuses a
document without the entries later steps read (the fields marked ``required`` in
gearcli/results/, with the schema_version check), then it becomes a typed
:class:`gearcli.results.SummaryDocument`.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gearcli.errors import InvalidResultError, ResultsError
from gearcli.io.manifest import RESULTS_SCHEMA_VERSION
from gearcli.results import (
    AnalysisDocument,
    AnalysisMetrics,
    StoredMode,
    StressDocument,
    Summary,
    SummaryDocument,
)
from gearcli.results.rating_document import RatingDocument

FILES = ("manifest.json", "summary.json", "timeseries.csv")
#: The time series may also be Parquet (`gearcli simulate --format parquet`).
TIMESERIES = ("timeseries.csv", "timeseries.parquet")


@dataclass(frozen=True)
class StoredRun:
    folder: Path
    manifest: dict
    summary: SummaryDocument
    columns: dict[str, np.ndarray]

    def column(self, name: str) -> np.ndarray:
        return self.columns[name]


def check_folder(folder: str | Path) -> Path:
    """``folder`` as a Path when it is an existing folder, else a one-line ResultsError."""
    p = Path(folder)
    if not p.exists():
        raise ResultsError(f"{p}: not found; expected a results folder from gearcli simulate")
    if not p.is_dir():
        raise ResultsError(f"{p}: not a folder; expected a results folder from gearcli simulate")
    return p


def read_run(folder: str | Path) -> StoredRun:
    """Load manifest, summary and time series; every problem is a one-line ResultsError."""
    p = check_folder(folder)
    series = next((p / f for f in TIMESERIES if (p / f).is_file()), p / TIMESERIES[0])
    missing = [f for f in FILES[:2] + (series.name,) if not (p / f).is_file()]
    if missing:
        raise ResultsError(f"{p}: missing {', '.join(missing)}; expected a folder written by "
                           "gearcli simulate")
    manifest = read_json(p / "manifest.json")
    if not isinstance(manifest, dict) or manifest.get("gearcli_manifest") != 1:
        raise ResultsError(f"{p / 'manifest.json'}: not a gearcli manifest; expected a folder "
                           "written by gearcli simulate")
    if not isinstance(manifest.get("resolved_case"), dict):
        raise ResultsError(f"{p / 'manifest.json'}: no resolved_case mapping; expected a "
                           "manifest written by gearcli simulate")
    summary = read_json(p / "summary.json")
    if isinstance(summary, dict) and summary.get("status") == "invalid":
        raise InvalidResultError(
            f"{p}: the run is outside the model's validity "
            f"({summary.get('invalid_reason', 'no reason given')}); its numbers are not results "
            "(docs/theory.md §10.2)")
    if not isinstance(summary, dict) or summary.get("status") != "ok" or "rows" not in summary:
        raise ResultsError(f"{p / 'summary.json'}: incomplete summary; expected a finished "
                           "gearcli simulate run")
    check_summary(p / "summary.json", summary)
    if series.suffix == ".parquet":
        columns = read_parquet_columns(series, "t_s", summary["rows"])
    else:
        columns = read_columns(series, "t_s", summary["rows"])
    missing = [c for c in REQUIRED_COLUMNS if c not in columns]
    if missing:
        raise ResultsError(f"{series}: no {', '.join(missing)} column"
                           f"{'s' if len(missing) > 1 else ''}; expected a table written by "
                           "gearcli simulate (was it edited?)")
    return StoredRun(p, manifest, SummaryDocument.from_document(summary), columns)


#: Columns of timeseries.csv that analyze, stress and report read.
REQUIRED_COLUMNS = ("t_s", "omega1_rad_s", "omega2_rad_s", "delta_mm", "force_total_N",
                    "force_coast_N", "pairs_in_contact", "friction_power_mW",
                    "drive_torque_Nmm", "load_torque_Nmm")
_NUMBER, _OPTIONAL, _TEXT, _PAIR = "a number", "a number or null", "text", "two numbers"


def _kind(annotation: str) -> str:
    """What a field's annotation (gearcli/results/) asks of its stored value."""
    if annotation.startswith("tuple[float, float]"):
        return _PAIR
    if annotation == "str":
        return _TEXT
    return _OPTIONAL if "None" in annotation else _NUMBER


def _required(cls) -> dict[str, str]:
    return {f.name: _kind(str(f.type)) for f in dataclasses.fields(cls)
            if f.metadata.get("required") and f.type != "bool"}


#: Entries of summary.json's "scalars" that analyze, stress and report read, by kind.
REQUIRED_SCALARS = _required(Summary)
#: Keys of each entry of scalars.modes (optional list; ``rigid_body`` is checked apart).
MODE_KEYS = _required(StoredMode)


def _is(value, kind: str) -> bool:
    number = isinstance(value, int | float) and not isinstance(value, bool)
    if kind == _NUMBER:
        return number and np.isfinite(value)
    if kind == _OPTIONAL:
        return value is None or (number and np.isfinite(value))
    if kind == _TEXT:
        return isinstance(value, str)
    return (isinstance(value, list) and len(value) == 2
            and all(_is(v, _NUMBER) for v in value))


def check_summary(path: Path, summary: dict) -> None:
    """Refuse a summary.json without the entries later steps read (a hand-edited or foreign
    file) with the first entry that is missing or of the wrong kind."""
    def bad(key: str, kind: str) -> ResultsError:
        return ResultsError(f"{path}: {key} missing or not {kind}; expected a summary written "
                            "by gearcli simulate (was it edited?)")

    version = summary.get("schema_version", RESULTS_SCHEMA_VERSION)  # absent: before versions
    if version != RESULTS_SCHEMA_VERSION:
        raise ResultsError(f"{path}: schema_version {version!r}; this gearcli reads "
                           f"{RESULTS_SCHEMA_VERSION} (rerun gearcli simulate)")
    rows = summary.get("rows")
    if not isinstance(rows, int) or isinstance(rows, bool) or rows < 1:
        raise bad("rows", "a positive integer")
    scalars = summary.get("scalars")
    if not isinstance(scalars, dict):
        raise bad("scalars", "a mapping")
    for key, kind in REQUIRED_SCALARS.items():
        if key not in scalars or not _is(scalars[key], kind):
            raise bad(f"scalars.{key}", kind)
    t0, t1 = scalars["window_s"]
    if not 0.0 <= t0 < t1:
        raise bad("scalars.window_s", "a window T0 < T1 (seconds from the start)")
    balance = scalars.get("energy_balance")
    if not isinstance(balance, dict) or not _is(balance.get("relative_residual"), _NUMBER):
        raise bad("scalars.energy_balance.relative_residual", _NUMBER)
    modes = scalars.get("modes", [])
    if not isinstance(modes, list):
        raise bad("scalars.modes", "a list")
    for i, mode in enumerate(modes):
        if not isinstance(mode, dict) or not isinstance(mode.get("rigid_body"), bool):
            raise bad(f"scalars.modes.{i}.rigid_body", "true or false")
        for key, kind in MODE_KEYS.items():
            if key not in mode or not _is(mode[key], kind):
                raise bad(f"scalars.modes.{i}.{key}", kind)
    warnings = summary.get("warnings", [])
    if not isinstance(warnings, list):
        raise bad("warnings", "a list")
    if not isinstance(summary.get("solver", {}), dict):
        raise bad("solver", "a mapping")


#: Non-numeric entries of analysis.json's metrics, by kind (the annotations of
#: gearcli.results.AnalysisMetrics); every other entry is a number or null.
_TEXT_METRICS = tuple(f.name for f in dataclasses.fields(AnalysisMetrics) if f.type == "str")
_LIST_METRICS = tuple(f.name for f in dataclasses.fields(AnalysisMetrics)
                      if str(f.type).startswith("tuple"))


def check_analysis(path: Path, doc: dict) -> None:
    """Refuse an analysis.json whose entries the report cannot read (hand-edited, foreign):
    the first wrong entry, and the remedy (run gearcli analyze again)."""
    def bad(key: str, kind: str) -> ResultsError:
        return ResultsError(f"{path}: {key} is not {kind}; run gearcli analyze again (was the "
                            "file edited?)")

    def number(v) -> bool:
        return v is None or (isinstance(v, int | float) and not isinstance(v, bool))

    window = doc.get("window_s")
    if window is not None and not (isinstance(window, list) and len(window) == 2
                                   and all(number(v) and v is not None for v in window)):
        raise bad("window_s", "two numbers")
    metrics = doc["metrics"]
    if not isinstance(metrics, dict):
        raise bad("metrics", "a mapping")
    for key, value in metrics.items():
        if key in _TEXT_METRICS:
            ok = value is None or isinstance(value, str)
        elif key in _LIST_METRICS:
            ok = value is None or isinstance(value, list)
        else:
            ok = number(value)
        if not ok:
            raise bad(f"metrics.{key}", "text" if key in _TEXT_METRICS else
                      "a list" if key in _LIST_METRICS else "a number or null")
    if not isinstance(doc["checks"], list):
        raise bad("checks", "a list")
    for i, check in enumerate(doc["checks"]):
        if not (isinstance(check, dict) and isinstance(check.get("name"), str)
                and (isinstance(check.get("passed"), bool)
                     or (check.get("passed") is None and check.get("checked") is False))):
            raise bad(f"checks.{i}", "a check (name, value, limit, passed, note)")
    lines = doc.get("lines", {})
    if not isinstance(lines, dict) or not all(
            isinstance(v, dict) and all(isinstance(ln, dict) for ln in v.values())
            for v in lines.values()):
        raise bad("lines", "a mapping of signals to lines")
    if not isinstance(doc.get("warnings", []), list):
        raise bad("warnings", "a list")


def read_analysis(path: Path) -> AnalysisDocument:
    """analysis.json of `gearcli analyze` as its typed document; a file the report cannot
    read (hand-edited, foreign, another schema_version) is a one-line ResultsError."""
    doc = read_json(path, "run gearcli analyze again")
    if not isinstance(doc, dict) or "checks" not in doc or "metrics" not in doc:
        raise ResultsError(f"{path}: not an analysis of gearcli analyze; run it again")
    version = doc.get("schema_version", RESULTS_SCHEMA_VERSION)  # absent: before versions
    if version != RESULTS_SCHEMA_VERSION:
        raise ResultsError(f"{path}: schema_version {version!r}; this gearcli reads "
                           f"{RESULTS_SCHEMA_VERSION} (rerun gearcli analyze)")
    check_analysis(path, doc)
    try:
        return AnalysisDocument.from_document(doc)
    except (TypeError, AttributeError) as exc:
        raise ResultsError(f"{path}: unreadable analysis ({exc}); run gearcli analyze "
                           "again") from None


def _typed(cls, path: Path, doc: dict, what: str, command: str):
    """The stored ``doc`` of ``path`` as the document ``cls``, its schema_version checked; a
    document of another version or one it cannot read is a ResultsError saying to rerun
    `gearcli COMMAND`."""
    version = doc.get("schema_version", RESULTS_SCHEMA_VERSION)  # absent: before versions
    if version != RESULTS_SCHEMA_VERSION:
        raise ResultsError(f"{path}: schema_version {version!r}; this gearcli reads "
                           f"{RESULTS_SCHEMA_VERSION} (rerun gearcli {command})")
    try:
        return cls.from_document(doc)
    except (TypeError, AttributeError) as exc:
        raise ResultsError(f"{path}: unreadable {what} ({exc}); run gearcli {command} "
                           "again") from None


def read_stress(path: Path) -> StressDocument:
    """stress.json of `gearcli stress` as its typed document (the schema_version checked)."""
    doc = read_json(path, "run gearcli stress again")
    if not isinstance(doc, dict) or not all(isinstance(doc.get(k), dict)
                                            for k in ("static", "pinion", "gear")):
        raise ResultsError(f"{path}: not a stress.json of gearcli stress; run it again")
    return _typed(StressDocument, path, doc, "stress document", "stress")


def read_rating(path: Path) -> RatingDocument:
    """rating.json of `gearcli run` or `gearcli rate -o` as its typed document (the
    schema_version checked); a file the report cannot read is a one-line ResultsError."""
    doc = read_json(path, "run gearcli run again")
    if not isinstance(doc, dict) or not isinstance(doc.get("iso"), dict):
        raise ResultsError(f"{path}: not a rating.json of gearcli rate or run; run it again")
    return _typed(RatingDocument, path, doc, "rating", "run")


#: Most values (rows x columns) of a Parquet time series that are decoded: 2e8 float64 are
#: 1.6 GB, and the analysis holds about two more copies. A compressed file can expand ~2000x
#: (29 MB to 51 GB seen), so the size is read from the file's metadata before any decoding.
MAX_PARQUET_VALUES = 200_000_000


def check_parquet_size(path: Path, rows: int, limit: int | None = None) -> None:
    """Refuse, from its metadata alone, a Parquet table larger than ``limit`` values or with
    another row count than summary.json's ``rows``."""
    import pyarrow.parquet as pq

    try:
        meta = pq.ParquetFile(path).metadata
    except Exception as exc:  # pyarrow's errors: ArrowInvalid, OSError, ...
        raise ResultsError(f"{path}: unreadable Parquet ({exc}); expected a table written by "
                           "gearcli") from None
    limit = MAX_PARQUET_VALUES if limit is None else limit
    values = meta.num_rows * meta.num_columns
    if values > limit:
        raise ResultsError(f"{path}: {meta.num_rows:,} rows x {meta.num_columns} columns = "
                           f"{values:,} values; expected at most {limit:,} (the memory the "
                           "analysis may take); simulate with a lower run.output_rate")
    if meta.num_rows != rows:
        raise ResultsError(f"{path}: {meta.num_rows:,} rows, but summary.json says {rows:,}; "
                           "the file is truncated or was edited")


def read_parquet_columns(path: Path, key: str, rows: int) -> dict[str, np.ndarray]:
    """The float64 columns of a Parquet time series, checked like :func:`read_columns`
    (its size first, from the metadata: :func:`check_parquet_size`)."""
    from gearcli.io.tables import parquet_to_columns

    check_parquet_size(path, rows)
    try:
        columns = parquet_to_columns(path)
    except Exception as exc:  # pyarrow's errors: ArrowInvalid, OSError, ...
        raise ResultsError(f"{path}: unreadable Parquet ({exc}); expected a table written by "
                           "gearcli") from None
    if key not in columns:
        raise ResultsError(f"{path}: no {key} column; expected a table written by gearcli")
    if any(c.shape != (rows,) or not np.all(np.isfinite(c)) for c in columns.values()):
        raise ResultsError(f"{path}: not {rows} finite rows per column, as summary.json says; "
                           "the file is truncated or was edited")
    return columns


def case_has_faults(folder: str | Path) -> bool:
    """Whether the run in ``folder`` was simulated with ``faults:`` (its manifest's resolved
    case), read without the time series; False for a folder without a readable manifest (the
    commands that read the run say what is wrong with it)."""
    try:
        manifest = read_json(Path(folder) / "manifest.json")
    except ResultsError:
        return False
    case = manifest.get("resolved_case") if isinstance(manifest, dict) else None
    return isinstance(case, dict) and bool(case.get("faults"))


def read_json(path: Path, remedy: str = "expected gearcli output"):
    """A JSON file of a results folder; unreadable -> ResultsError saying ``remedy``."""
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError, RecursionError) as exc:
        raise ResultsError(f"{path}: unreadable JSON ({exc}); {remedy}") from None


def read_columns(path: Path, key: str, rows: int | None = None) -> dict[str, np.ndarray]:
    """A CSV table written by gearcli (header of names, finite numbers) as named columns.

    ``key`` must be one of the columns; ``rows``, when given, is the expected row count (a
    shorter file was truncated).
    """
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise ResultsError(f"{path}: unreadable ({exc})") from None
    lines = text.splitlines()
    if not lines:
        raise ResultsError(f"{path}: empty; expected a table written by gearcli")
    names = lines[0].split(",")
    if key not in names:
        raise ResultsError(f"{path}: no {key} column; expected a table written by gearcli")
    if rows is not None and (len(lines) - 1 != rows or not text.endswith("\n")):
        raise ResultsError(f"{path}: {len(lines) - 1} rows, summary.json says {rows}; the file "
                           "is truncated or was edited")
    try:
        data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    except ValueError as exc:
        raise ResultsError(f"{path}: malformed row ({exc}); expected numbers") from None
    if data.shape[1] != len(names) or not np.all(np.isfinite(data)):
        raise ResultsError(f"{path}: malformed rows (wrong column count or non-finite values)")
    return {n: data[:, i] for i, n in enumerate(names)}


def window_mask(t_s, t0_s: float, t1_s: float):
    """The samples of a stored run inside the window [t0, t1] [s]. The CSV keeps times to 10
    significant digits (core/csvtext.py), so a sample on the window's edge may be stored up to
    5e-10 of its value away: the edges get that much room, and CSV and Parquet copies of a run
    select the same samples."""
    room = 1e-9 * max(abs(t0_s), abs(t1_s), 1e-3)
    return (t_s >= t0_s - room) & (t_s <= t1_s + room)
