"""Study files for `gearcli sweep`: a base case, parameters over case key paths, a design.

A study file (YAML)::

    name: table5
    base: ../seed.yaml            # path relative to the study file, or an inline case mapping
    set:                          # overrides applied to every point (key.path: value)
      run.end_time: 3 s
    design: one_at_a_time         # grid (default) | zip | lhs | one_at_a_time | speed_curve
    parameters:                   # key path -> explicit list, or a range
      gears.module: [8, 10, 12]
      gears.face_width: {linspace: ["60 mm", "140 mm"], num: 5}
      contact.stiffness: {logspace: ["1e5 N/mm", "1e6 N/mm"], num: 4}
      mesh_frequency: {linspace: ["50 Hz", "1500 Hz"], num: 30}   # virtual: sets drive.speed
    samples: 50                   # lhs only: number of points
    seed: 1                       # lhs only
    metrics: [force_max_N, dynamic_factor]  # optional: columns kept (default: all)
    dataset: {signal: accel_m_s2} # optional: a labelled dataset (pipeline/dataset.py)
    checks:                       # optional: per-point limits, reported in the summary
      - {metric: dynamic_factor, max: 2.0}

Values with units are passed to the case as strings ("9.5 mm"); ranges keep the unit of their
first end. ``mesh_frequency`` is not a case key: it sets the final value of the drive-speed ramp
(``drive.speed`` written as "STEP(time, ...)" or as ``{function: "STEP(time, ...)", unit: ...}``,
kept in its unit; any other drive speed becomes that constant speed) so that the gear-mesh
frequency f_z = z1 n1 takes the given value.

``design: speed_curve`` takes the one parameter ``mesh_frequency`` (2 to 40 values) and runs the
speeds up and then down, each speed starting from the previous one's state
(gearcli/pipeline/speed_curve.py).

Every point is resolved (overrides applied, validated) before anything runs, so an unknown key,
an empty list or a wrong unit is one located error, and the case hash (sha256 of the resolved
case JSON) identifies the point for resuming.
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from gearcli import guards, units
from gearcli.case.keypaths import field_at
from gearcli.case.load import data_loc, validate_source
from gearcli.case.overrides import apply_overrides, check_path, text_name
from gearcli.case.schema import Case
from gearcli.case.types import checked_quantity
from gearcli.case.yamlsrc import Source, parse_source, read_source
from gearcli.errors import CaseError
from gearcli.pipeline.sweep.design import (
    MESH_FREQUENCY,
    SPEED_CURVE_METRICS,
    Parameter,
    check_design,
    design_points,
    design_size,
)

#: Without ``--yes``, studies with more points than this are refused.
MAX_POINTS = 1000
#: Studies with more points than this are refused even with ``--yes``.
MAX_POINTS_YES = 100_000
#: File types a study's ``base:`` may name.
CASE_SUFFIXES = (".yaml", ".yml", ".json")
_RAMP = re.compile(r"^\s*(STEP5?|RAMP)\s*\(\s*time\s*,([^,]+),([^,]+),([^,]+),([^,()]+)\)\s*$",
                   re.IGNORECASE)
_NUMBER_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Range(_Strict):
    """``{linspace: [start, stop], num: N}``, ``{logspace: ...}`` or ``{values: [...]}``;
    ``with`` holds overrides set together with the parameter (e.g. a tip relief's length);
    ``{value}`` in them stands for the parameter's value."""

    model_config = ConfigDict(extra="forbid", populate_by_name=True)
    linspace: list[float | str] | None = Field(None, min_length=2, max_length=2)
    logspace: list[float | str] | None = Field(None, min_length=2, max_length=2)
    values: list[Any] | None = None
    num: int | None = Field(None, ge=1, le=100_000)
    with_: dict[str, Any] = Field(default_factory=dict, alias="with")

    @model_validator(mode="after")
    def _one_kind(self):
        if sum(x is not None for x in (self.linspace, self.logspace, self.values)) != 1:
            raise ValueError("give exactly one of 'linspace', 'logspace' (with 'num') or "
                             "'values'")
        return self


class Check(_Strict):
    metric: str
    min: float | None = None
    max: float | None = None


class DatasetSpec(_Strict):
    """``dataset:``: the study is a labelled dataset (docs/theory.md, "Fault datasets"): each
    point's signals kept as Parquet, one labels table with the monitoring metrics of
    ``signal`` (a sensors-table column, or "te")."""

    signal: str = "accel_m_s2"

    @model_validator(mode="after")
    def _known_signal(self):
        from gearcli.pipeline.monitor import SIGNALS

        if self.signal not in SIGNALS:
            raise ValueError(f"signal {self.signal!r}: expected one of {', '.join(SIGNALS)}")
        return self


class StudyFile(_Strict):
    name: str | None = None
    description: str | None = None
    base: str | dict[str, Any]
    set: dict[str, Any] = Field(default_factory=dict)
    design: Literal["grid", "zip", "lhs", "one_at_a_time", "speed_curve"] = "grid"
    samples: int | None = Field(None, ge=1)
    seed: int | None = Field(None, ge=0)  # numpy's seeds are non-negative
    parameters: dict[str, list[Any] | Range] = Field(min_length=1)
    metrics: list[str] | None = Field(None, min_length=1)
    checks: list[Check] = Field(default_factory=list)
    dataset: DatasetSpec | None = None


@dataclass
class Point:
    """One resolved point: its index, its parameter values, the resolved case and its hash."""

    index: int
    values: dict[str, Any]  #: parameter column -> number (or text)
    overrides: list[str]
    case_json: str = ""
    case_hash: str = ""


@dataclass
class Study:
    name: str
    file: str
    design: str
    parameters: list[Parameter]
    points: list[Point]
    metrics: list[str] | None
    checks: list[Check]
    base_case_json: str
    base_values: dict[str, Any] = field(default_factory=dict)
    dataset: DatasetSpec | None = None

    @property
    def parameter_columns(self) -> list[str]:
        return [p.column for p in self.parameters]


def load_study(path: str | Path, allow_large: bool = False) -> Study:
    """Read, validate and resolve a study file; every input problem is a located CaseError."""
    src = read_source(path)
    return _build(src, Path(path).resolve().parent, text_name(Path(path).stem), allow_large)


def load_study_text(text: str, name: str = "<study>", folder: str | Path = ".",
                    allow_large: bool = False) -> Study:
    return _build(parse_source(text, name), Path(folder), Path(name).stem, allow_large)


def _build(src: Source, folder: Path, stem: str, allow_large: bool) -> Study:
    try:
        spec = StudyFile.model_validate(src.data)
    except ValidationError as exc:
        err = min(exc.errors(), key=lambda e: (e["type"] == "missing",  # a typo first, then
                                               -len(data_loc(tuple(e["loc"]), src.data))))
        loc = data_loc(tuple(err["loc"]), src.data)
        msg = err["msg"].removeprefix("Value error, ")
        if msg.startswith("Input should be "):  # pydantic's words, as the case's errors read
            msg = "expected " + msg.removeprefix("Input should be ").replace(
                "greater than or equal to", ">=").replace("less than or equal to", "<=")
        if err["type"] == "missing":
            msg = "missing required key"
        if err["type"] == "extra_forbidden":
            msg = "unknown key; expected one of: " + ", ".join(StudyFile.model_fields)
            if loc[:1] == ("gears",):  # a case file given to sweep
                msg += " (a case file? sweep takes a study: gearcli new --template study)"
        raise src.error(loc, msg) from None
    base_src = _base_source(spec, src, folder)
    fixed = [f"{k}={_yaml(v)}" for k, v in spec.set.items()]
    _check_keys(src, ("set",), spec.set)
    _check_keys(src, ("parameters",), spec.parameters)
    texts = dict(zip(spec.set, fixed, strict=True))
    for key, text in texts.items():  # errors name the study's set:, not the base file's line
        base_src.key_lines.pop(tuple(key.split(".")), None)
        base_src.overridden[tuple(key.split("."))] = text
    try:
        base_src.data = apply_overrides(base_src.data, fixed, Case)
        base = validate_source(base_src, stem)
    except CaseError as exc:
        key = next((k for k, t in texts.items() if exc.file == f"--set {t}"), None)
        raise CaseError(f"the base case is invalid: {exc}", file=src.file,
                        line=src.line_of(("base",) if key is None else ("set", key))) from None
    system = base_src.data.get("units") if isinstance(base_src.data, dict) else None
    params = [_parameter(src, key, spec.parameters[key], system) for key in spec.parameters]
    for key, spec_p in spec.parameters.items():
        if isinstance(spec_p, Range) and spec_p.with_:
            _check_keys(src, ("parameters", key, "with"), spec_p.with_)
    check_design(src, spec, params,
                 {k: v for k, v in spec.parameters.items() if isinstance(v, Range)})
    size = design_size(spec, params)  # before the design is built: it may be astronomical
    where = ("samples",) if spec.design == "lhs" else ("parameters",)
    if size > MAX_POINTS_YES:
        raise src.error(where, f"the {spec.design} has {size:,} points; expected at most "
                        f"{MAX_POINTS_YES:,} (even with --yes): split the study")
    if size > MAX_POINTS and not allow_large:
        raise src.error(where, f"the {spec.design} has {size} points "
                        f"(> {MAX_POINTS}); pass --yes to run it")
    _check_metrics(src, spec)
    if spec.dataset is not None and spec.design == "speed_curve":
        raise src.error(("dataset",), "a speed_curve runs one simulation per direction; "
                        "expected design grid, zip, lhs or one_at_a_time for a dataset")
    combos = design_points(spec, params)
    base_values = {p.column: _base_value(base_src.data, p, system) for p in params}
    points = []
    for i, combo in enumerate(combos):
        values = dict(base_values)
        overrides = []
        for p, j in combo:
            values[p.column] = p.numbers[j] if not math.isnan(p.numbers[j]) else p.values[j]
            overrides.append((p, p.values[j]))
        points.append(_resolve(src, base_src, i, values, overrides, stem))
    metrics = spec.metrics
    return Study(spec.name or stem, src.file, spec.design, params, points, metrics, spec.checks,
                 _canonical(base), base_values, spec.dataset)


def _check_metrics(src: Source, spec: StudyFile) -> None:
    """Kept metrics and the metrics of checks must exist (and checks must be kept); a speed
    curve's are what each of its levels measures (pipeline/speed_curve.py)."""
    from gearcli.pipeline.sweep.metrics import METRICS as POINT_METRICS

    known = SPEED_CURVE_METRICS if spec.design == "speed_curve" else POINT_METRICS
    which = "a speed curve measures: " if spec.design == "speed_curve" else ""
    for k, m in enumerate(spec.metrics or ()):
        if m not in known:
            raise src.error(("metrics", k), f"unknown metric '{m}'; expected one of "
                            f"({which or 'the metrics of a point'}): " + ", ".join(known))
    kept = spec.metrics or known
    for k, c in enumerate(spec.checks):
        if c.metric not in known:
            raise src.error(("checks", k, "metric"), f"unknown metric '{c.metric}'; expected "
                            f"one of ({which or 'the metrics of a point'}): " + ", ".join(known))
        if c.metric not in kept:
            raise src.error(("checks", k, "metric"), f"'{c.metric}' is not among the study's "
                            "metrics; add it to 'metrics' or drop the check")
        if c.min is None and c.max is None:
            raise src.error(("checks", k), "a check needs 'min' and/or 'max'")
        if c.min is not None and c.max is not None and not c.min <= c.max:
            raise src.error(("checks", k), f"min {c.min:g} > max {c.max:g}: no value passes; "
                            "expected min <= max")


def _yaml(value) -> str:
    return json.dumps(value) if not isinstance(value, str) else value


def _base_source(spec: StudyFile, src: Source, folder: Path) -> Source:
    if isinstance(spec.base, dict):
        import yaml

        text = yaml.safe_dump(spec.base, sort_keys=False)
        return parse_source(text, f"{src.file} (inline base)")
    path = folder / spec.base
    if not path.is_file():
        raise src.error(("base",), f"base case {str(path)!r} not found; expected a case file "
                        "path relative to the study file, or an inline case mapping")
    if path.suffix.lower() not in CASE_SUFFIXES:
        raise src.error(("base",), f"base case {str(path)!r}: expected a case file ending in "
                        + ", ".join(CASE_SUFFIXES))
    try:
        return read_source(path)
    except CaseError as exc:  # said without quoting the file: it is not known to be a case
        raise src.error(("base",), f"base case {str(path)!r}: {exc.message}") from None


def _check_keys(src: Source, where: tuple, mapping: dict) -> None:
    for key in mapping:
        if key == MESH_FREQUENCY and where == ("parameters",):
            continue
        path = tuple(key.split("."))
        try:
            check_path(path, Case, f"{key}=...")
        except CaseError as exc:
            msg = str(exc).split(": ", 1)[1] if ": " in str(exc) else str(exc)
            raise src.error((*where, key), msg) from None


def _split(value) -> tuple[float, str] | None:
    """(number, unit) of 12, "12", "12 mm"; None for anything else ("derived")."""
    if isinstance(value, bool):
        return None
    if isinstance(value, int | float):
        return float(value), ""
    if isinstance(value, str):
        m = _NUMBER_UNIT.match(value)
        if m:
            return float(m.group(1)), m.group(2)
    return None


def _default_unit(key: str, system: str | None = None) -> str:
    """The case-file unit of a bare number at ``key`` ('' for plain numbers and counts) in the
    base case's ``units:`` ``system`` (None: the Adams default; gearcli.units.UNIT_SYSTEMS)."""
    system = system if system in units.UNIT_SYSTEMS else None
    if key == MESH_FREQUENCY:
        return units.in_system(units.FREQUENCY, system).default
    field = field_at(Case, tuple(key.split(".")))
    metas = list(getattr(field, "metadata", ()))
    args = list(getattr(getattr(field, "annotation", None), "__args__", ()))
    while args:  # Length | None, SpeedFunction | None: the validator in the Annotated type
        arg = args.pop()
        metas += list(getattr(arg, "__metadata__", ()))
        args += list(getattr(arg, "__args__", ()))
    for meta in metas:
        func = getattr(meta, "func", None)
        dim = getattr(func, "dim", None) or getattr(func, "time_dim", None)
        if dim is not None:
            return units.in_system(dim, system).default
    return ""


def _to_unit(number: float, unit: str, target: str) -> float:
    if unit == target:
        return number
    for text in (unit, target):
        guards.check_unit_text(text, need_number=False)  # before pint sees it
    q = units.registry().Quantity(number, unit or "dimensionless")
    return float(q.to(target or "dimensionless").magnitude)


def _parameter(src: Source, key: str, spec, system: str | None = None) -> Parameter:
    """A parameter of the study; bare numbers in the unit of the base case's ``units:``
    ``system`` (:func:`_default_unit`)."""
    if isinstance(spec, Range):
        extra = tuple(f"{k}={_yaml(v)}" for k, v in spec.with_.items())
        if spec.values is not None:
            p = _parameter(src, key, spec.values, system)
            return Parameter(p.key, p.unit, p.values, p.numbers, extra=extra)
        p = _range(src, key, spec, system)
        return Parameter(p.key, p.unit, p.values, p.numbers, p.log, p.bounds, extra)
    loc = ("parameters", key)
    if isinstance(spec, list):
        if not spec:
            raise src.error(loc, "empty list; expected at least one value")
        parts = [_split(v) for v in spec]
        # a bare number's unit, as in the case file (none when no value is a number: time
        # functions as expressions or mappings carry their own)
        default = _default_unit(key, system) if any(parts) else ""
        unit = next((p[1] for p in parts if p and p[1]), default)
        numbers = []
        for i, (v, p) in enumerate(zip(spec, parts, strict=True)):
            try:
                numbers.append(_to_unit(p[0], p[1] or default, unit) if p else math.nan)
            except Exception:
                raise src.error((*loc, i), f"got {v!r}: wrong unit; expected a value in "
                                f"'{unit}' or a compatible unit") from None
        return Parameter(key, unit, tuple(spec), tuple(numbers))
    raise src.error(loc, "expected a list of values or a range mapping")


def _range(src: Source, key: str, spec: Range, system: str | None = None) -> Parameter:
    loc = ("parameters", key)
    kind = "linspace" if spec.linspace is not None else "logspace"
    ends = spec.linspace or spec.logspace
    parts = [_split(v) for v in ends]
    if not all(parts):
        raise src.error((*loc, kind), f"got {ends!r}; expected two numbers, optionally with "
                        "units, e.g. ['8 mm', '12 mm']")
    default = _default_unit(key, system)  # a bare end's unit, as in the case file
    unit = parts[0][1] or default
    try:
        lo, hi = parts[0][0], _to_unit(parts[1][0], parts[1][1] or default, unit)
        if unit:
            guards.check_unit_text(unit, need_number=False)
            units.registry().Quantity(1.0, unit)
    except Exception:
        raise src.error((*loc, kind), f"got {ends!r}: wrong or inconsistent units; both ends "
                        "need units of the same dimension") from None
    if not (math.isfinite(lo) and math.isfinite(hi)):  # numpy would fill the range with NaN
        raise src.error((*loc, kind), f"got {ends!r}; expected finite ends")
    if kind == "logspace" and (lo <= 0 or hi <= 0):
        raise src.error((*loc, kind), f"got {ends!r}; logspace needs positive ends")
    num = spec.num or 0
    if num:
        nums = np.linspace(lo, hi, num) if kind == "linspace" else np.geomspace(lo, hi, num)
    else:
        nums = np.array([lo, hi])
    numbers = tuple(float(f"{x:.12g}") for x in nums)
    values = tuple(f"{x:.12g} {unit}" if unit else x for x in numbers)
    return Parameter(key, unit, values, numbers, kind == "logspace", (lo, hi))


def _base_value(data: dict, p: Parameter, system: str | None = None):
    """The base case's value of a parameter, in the parameter's unit where it is a number (a
    bare number in the base case is in its ``units:`` ``system``: :func:`_default_unit`)."""
    if p.key == MESH_FREQUENCY:
        return None
    node: Any = data
    for part in p.key.split("."):
        node = node.get(part) if isinstance(node, dict) else None
    parts = _split(node) if node is not None else None
    if parts is None:
        return node
    try:
        return _to_unit(parts[0], parts[1] or _default_unit(p.key, system) or p.unit, p.unit)
    except Exception:
        return node


def _resolve(src: Source, base_src: Source, index: int, values: dict, overrides: list,
             stem: str) -> Point:
    texts, owner = [], {}
    for p, v in overrides:
        own = [_speed_override(src, base_src.data, overrides, v) if p.key == MESH_FREQUENCY
               else f"{p.key}={_yaml(v)}", *(t.replace("{value}", str(v)) for t in p.extra)]
        texts += own
        owner.update({t: p.key for t in own})
    point_src = copy.copy(base_src)
    point_src.key_lines = dict(base_src.key_lines)
    point_src.overridden = {}
    try:
        point_src.data = apply_overrides(base_src.data, texts, Case)
        for t in texts:
            point_src.overridden[tuple(t.partition("=")[0].split("."))] = t
        loaded = validate_source(point_src, stem)
    except CaseError as exc:
        key = next((k for t, k in owner.items() if exc.file == f"--set {t}"), None)
        loc = ("parameters", key) if key else ("parameters",)
        raise src.error(loc, f"point {index}: {exc}") from None
    case_json = _canonical(loaded)
    return Point(index, values, texts, case_json, hashlib.sha256(case_json.encode()).hexdigest())


def _canonical(loaded) -> str:
    """The resolved case as canonical JSON (sorted keys): what the case hash is taken of."""
    return json.dumps(json.loads(loaded.case.model_dump_json()), sort_keys=True)


def _speed_override(src: Source, data: dict, overrides: list, value) -> str:
    """``drive.speed=...`` giving the gear-mesh frequency ``value`` (f_z = z1 n1)."""
    teeth = next((v for p, v in overrides if p.key == "gears.pinion.teeth"), None)
    teeth = teeth or data.get("gears", {}).get("pinion", {}).get("teeth")
    try:
        f_z = checked_quantity(value, units.FREQUENCY)
        n1_deg_s = f_z / float(teeth) * 360.0
    except (units.UnitError, TypeError, ValueError) as exc:
        raise src.error(("parameters", MESH_FREQUENCY), f"got {value!r}: {exc}") from None
    if not f_z > 0.0:  # 0 Hz divided the speed curve's dwell (exit 3); < 0 is a reverse drive
        raise src.error(("parameters", MESH_FREQUENCY), f"got {value!r}; expected a mesh "
                        "frequency > 0 Hz (the pinion turns forward)")
    drive_type = next((v for p, v in overrides if p.key == "drive.type"), None)
    drive_type = drive_type or data.get("drive", {}).get("type", "speed")
    if drive_type == "torque":
        raise src.error(("parameters", MESH_FREQUENCY), "sets the pinion speed (drive.speed), "
                        "which a torque drive does not prescribe: expected a base case with "
                        "drive type 'speed' or 'shaft'")
    speed = data.get("drive", {}).get("speed")
    ramp = _ramp_to(speed, n1_deg_s, data.get("units"))
    return f"drive.speed={ramp}" if ramp else f"drive.speed={n1_deg_s:.12g} deg/s"


def _ramp_to(speed, n1_deg_s: float, system) -> str:
    """``speed`` (a case's drive.speed: "STEP(time, t0, h0, t1, h1)" or ``{function: ...,
    unit: ...}``) ramping to ``n1_deg_s`` [deg/s] instead of h1, in the form and unit it was
    written in (a mapping's ``unit``, else the unit of the case's bare numbers: its ``units:``
    system); "" when it is not such a ramp."""
    expression, unit = (speed.get("function"), speed.get("unit")) if isinstance(speed, dict) \
        else (speed, None)
    m = _RAMP.match(expression) if isinstance(expression, str) else None
    if m is None:
        return ""
    dim = units.ANGULAR_VELOCITY
    own = units.in_system(dim, system if system in units.UNIT_SYSTEMS else None)
    n1 = units.parse_quantity(f"{n1_deg_s!r} deg/s", dim) / units.unit_factor(
        str(unit or own.default), dim)
    name, t0, h0, t1, _ = m.groups()
    text = f"{name}(time,{t0.strip()},{h0.strip()},{t1.strip()},{n1:.12g})"
    return json.dumps({"function": text, "unit": unit}) if unit else text
