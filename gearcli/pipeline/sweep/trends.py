"""Trends of a finished sweep: the seed's Table 5 computed, plus plots (``trends.csv/.md``).

For each varied parameter and each trend metric, the (parameter, metric) pairs of the points
that isolate that parameter are reduced to one value per parameter level (mean over the other
parameters in a grid; the points varying it alone, plus the base point, in a one-at-a-time
design; every point in zip/lhs designs). Reported: the tested range, the metric at its ends,
the change from the lowest to the highest level (relative to the metric at the lowest level,
and as a ratio: a 7x rise is +600 %, x7.0), the Spearman rank correlation and a direction:
"increases" / "decreases" when |rho| >= 0.8, else "non-monotonic" (or "no effect" when the
metric moves by less than 0.1 % of its mean over the levels). The plots draw one line per
combination of the other parameters of a grid (at most MAX_LINES; more are drawn as the main
effect, labelled so), never an average across unrelated points as if it were a case.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from gearcli.io.files import record_outputs, save_figure, write_atomic
from gearcli.pipeline.sweep.design import MESH_FREQUENCY
from gearcli.pipeline.sweep.study import Study
from gearcli.plotting.text import plain
from gearcli.results import Summary, sweep_metrics

#: Metrics of the seed's Table 5 (field metadata "trend", gearcli/results/).
TREND_METRICS = sweep_metrics("trend")
TREND_COLUMNS = ("parameter", "metric", "points", "parameter_min", "parameter_max",
                 "metric_at_min", "metric_at_max", "change_percent", "ratio", "spearman_rho",
                 "direction")
#: Most lines (combinations of the other parameters) in one trend plot.
MAX_LINES = 8
#: Further metrics of the speed plot (field metadata "trend_plot").
PLOT_METRICS = sweep_metrics("trend_plot")
#: |Spearman rho| needed to call a trend monotonic.
MONOTONIC_RHO = 0.8
#: Relative changes below this [%] are "no effect".
NO_EFFECT_PERCENT = 0.1


def parameter_levels(df, study: Study, column: str, metric: str) -> tuple[np.ndarray, np.ndarray]:
    """(levels, metric per level) isolating the parameter ``column`` (see the module doc)."""
    ok = df[df["status"] == "ok"]
    if study.design == "grid":
        ok = _matched(ok, study, column, metric)
    if study.design == "one_at_a_time":
        varied = ok[ok["point"].isin(_points_varying(study, column))]
        base = ok[ok["point"] == 0]
        ok = varied if base.empty else _concat(varied, base)
    x = np.asarray(ok[column], dtype=object)
    y = np.asarray(ok[metric], dtype=object)
    keep = [_isnum(a) and _isnum(b) for a, b in zip(x, y, strict=True)]
    x = np.array([float(v) for v, k in zip(x, keep, strict=True) if k])
    y = np.array([float(v) for v, k in zip(y, keep, strict=True) if k])
    if x.size == 0:
        return x, y
    if study.design in ("grid", "one_at_a_time"):
        levels = np.unique(x)
        return levels, np.array([y[x == v].mean() for v in levels])
    order = np.argsort(x, kind="stable")
    return x[order], y[order]


def _matched(ok, study: Study, column: str, metric: str):
    """The grid's rows whose combination of the other parameters ran (with a number for
    ``metric``) at every level of ``column``: averages per level over unmatched combinations
    would mix the other parameters' effects into this one's (a failed or invalid point)."""
    import pandas as pd

    others = [p.column for p in study.parameters if p.column != column]
    numeric = (pd.to_numeric(ok[column], errors="coerce").notna()
               & pd.to_numeric(ok[metric], errors="coerce").notna())
    ok = ok[numeric]
    if not others or ok.empty:
        return ok
    levels = ok[column].nunique()
    return ok[ok.groupby(others, dropna=False)[column].transform("nunique") == levels]


def _concat(a, b):
    import pandas as pd

    return pd.concat([a, b])


def _points_varying(study: Study, column: str) -> list[int]:
    key = next(p.key for p in study.parameters if p.column == column)
    return [pt.index for pt in study.points
            if any(o.startswith(f"{key}=") or (key == MESH_FREQUENCY and
                                                o.startswith("drive.speed="))
                   for o in pt.overrides)]


def _isnum(v) -> bool:
    try:
        return v is not None and v != "" and math.isfinite(float(v))
    except (TypeError, ValueError):
        return False


def trend_rows(df, study: Study) -> list[dict]:
    from scipy.stats import spearmanr

    rows = []
    for p in study.parameters:
        for m in TREND_METRICS:
            if m not in df.columns:
                continue
            x, y = parameter_levels(df, study, p.column, m)
            row = {"parameter": p.column, "metric": m, "points": int(x.size)}
            if x.size >= 2 and np.ptp(x) > 0:
                first, last = float(y[0]), float(y[-1])
                change = 100.0 * (last - first) / abs(first) if first != 0.0 else math.nan
                ratio = last / first if first != 0.0 else math.nan
                spread = 100.0 * np.ptp(y) / (float(np.mean(np.abs(y))) or 1.0)
                # rounded: Spearman's rho of 5 levels is 0.8 exactly, which floating point
                # may give an ulp below
                rho = round(float(spearmanr(x, y).statistic), 12) if np.ptp(y) > 0 else 0.0
                if spread < NO_EFFECT_PERCENT or not math.isfinite(rho):
                    direction = "no effect"
                elif abs(rho) >= MONOTONIC_RHO:
                    direction = "increases" if rho > 0 else "decreases"
                else:
                    direction = "non-monotonic"
                row.update(parameter_min=float(x[0]), parameter_max=float(x[-1]),
                           metric_at_min=float(y[0]), metric_at_max=float(y[-1]),
                           change_percent=float(change), ratio=float(ratio), spearman_rho=rho,
                           direction=direction)
            else:
                levels = {float(v) for v in p.numbers if math.isfinite(v)}
                held = (" at one combination of the other parameters" if study.design == "grid"
                        and len(study.parameters) > 1 else "")
                row.update(direction="not varied (fewer than 2 numeric levels)"
                           if len(levels) < 2 else
                           f"no trend: fewer than 2 of its levels have a value{held} (failed "
                           "or invalid points, or a spectral line not resolved)")
            rows.append(row)
    return rows


def write_trends(folder: str | Path, study: Study, rows: list[dict],
                 units: str = "engineering") -> list[Path]:
    """Write trends.csv, trends.md and the plots (labels and values in the display ``units``,
    gearcli/display_units.py); returns the paths written."""
    import pandas as pd

    from gearcli.pipeline.sweep.run import summary_columns

    out = Path(folder)
    columns = summary_columns(study)
    df = pd.DataFrame([{c: r.get(c) for c in columns} for r in rows], columns=columns)
    for c in df.columns:
        if c not in ("status", "error", "cause", "warnings", "case_hash", "checks"):
            df[c] = pd.to_numeric(df[c], errors="coerce")
    trends = trend_rows(df, study)
    tdf = pd.DataFrame(trends, columns=list(TREND_COLUMNS))
    paths = [out / "trends.csv", out / "trends.md"]
    write_atomic(paths[0], tdf.to_csv(index=False, float_format="%.6g"), out)
    write_atomic(paths[1], _markdown(study, df, trends, units), out)
    for m in (*TREND_METRICS, *PLOT_METRICS):  # metrics the study left out: empty panels
        if m not in df.columns:
            df[m] = np.nan
    paths += _plots(out, study, df, units)
    record_outputs(out, [p.name for p in paths])
    return paths


def _counts(df) -> str:
    """"N points (design), n ok, m invalid, k failed": invalid = outside the model's validity
    (the run finished), failed = the run did not finish (an error)."""
    status = df["status"]
    return (f"{int((status == 'ok').sum())} ok, {int((status == 'invalid').sum())} invalid "
            f"(outside the model's validity), {int((status == 'failed').sum())} failed (the "
            "run did not finish)")


def _markdown(study: Study, df, trends: list[dict], units: str = "engineering") -> str:
    lines = [f"# Trends: {study.name}", "",
             f"{len(df)} points ({study.design}): {_counts(df)}. "
             "Change = metric at the highest level against the lowest (grids: the main effect, "
             "the mean over the other parameters; one-at-a-time: the others at their base); "
             f"direction from the Spearman rank correlation (|rho| >= {MONOTONIC_RHO}); "
             "values in display units (trends.csv: the stored units of its keys).", "",
             "| parameter | tested range | metric | at min | at max | change | direction |",
             "|---|---|---|---|---|---|---|"]
    for t in trends:
        label, k = metric_axis(t["metric"], units)
        if "change_percent" not in t:
            lines.append(f"| {t['parameter']} | — | {label} | — | — | — | "
                         f"{t['direction']} |")
            continue
        lines.append(f"| {t['parameter']} | {t['parameter_min']:.4g} … {t['parameter_max']:.4g}"
                     f" | {label} | {k * t['metric_at_min']:.4g} | {k * t['metric_at_max']:.4g} "
                     f"| {_change(t)} | {t['direction']} "
                     f"(rho {t['spearman_rho']:+.2f}) |")
    for status, title in (("invalid", "Invalid points (outside the model's validity)"),
                          ("failed", "Failed points (the run did not finish)")):
        bad = df[df["status"] == status]
        if len(bad):
            lines += ["", f"## {title}", ""]
            lines += [f"- point {int(r['point'])}: {r['error']}" for _, r in bad.iterrows()]
    lines += ["", "Plots: " + ", ".join(f"`{p}`" for p in _plot_names(study)), ""]
    return "\n".join(lines)


def metric_axis(metric: str, units: str = "engineering") -> tuple[str, float]:
    """(axis label "label [unit]", factor stored -> display unit) of a metric from its field
    metadata (gearcli/results/metrics.py) in the display ``units``."""
    from gearcli.results.metrics import METRICS, display

    if metric not in METRICS:
        return metric.replace("_", " "), 1.0
    label, value, unit = display(metric, 1.0, units)
    return (f"{label} [{unit}]" if unit not in ("", "–") else label), float(value)


def parameter_axis(p) -> str:
    """The axis label of a parameter: the gear-mesh frequency by name, else its key path and
    unit as the study gives it."""
    if p.key == MESH_FREQUENCY:
        return "gear-mesh frequency f_z [Hz]"
    return p.column


def _change(t: dict) -> str:
    if not math.isfinite(t.get("change_percent", math.nan)):
        return "— (zero at the lowest level)"
    return f"{t['change_percent']:+.1f} % (x{t['ratio']:.3g})"


def _plot_names(study: Study) -> list[str]:
    names = [f"trend_{_slug(p.column)}.png" for p in study.parameters]
    if any(p.key == MESH_FREQUENCY for p in study.parameters):
        names.append("speed_sweep.png")
    return names


def _slug(text: str) -> str:
    return "".join(c if c.isalnum() else "_" for c in text).strip("_")


def _plots(out: Path, study: Study, df, units: str = "engineering") -> list[Path]:
    paths = []
    for p in study.parameters:
        path = out / f"trend_{_slug(p.column)}.png"
        save_figure(trend_figure(study, df, p, units), path, 100, path.parent)
        paths.append(path)
    speed = next((p for p in study.parameters if p.key == MESH_FREQUENCY), None)
    if speed is not None:
        path = out / "speed_sweep.png"
        save_figure(speed_figure(study, df, speed, units), path, 100, path.parent)
        paths.append(path)
    return paths


def trend_figure(study: Study, df, p, units: str = "engineering"):
    """The trend figure of parameter ``p``: one panel per trend metric, a line per
    combination of the other parameters (:func:`_trend_lines`), broken (NaN) at the invalid
    and failed points, which are marked on the axis (:func:`_mark_bad_points`)."""
    # Figure objects, not pyplot: no backend is chosen for (or windows opened in) the caller's
    # process, e.g. a notebook calling gearcli.sweep
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 7), layout="constrained")
    axes = fig.subplots(2, 2)
    for ax, m in zip(axes.flat, TREND_METRICS, strict=True):
        label, k = metric_axis(m, units)
        lines = _trend_lines(df, study, p, m)
        for name, x, y in lines:
            ax.plot(x, k * np.asarray(y, float), "o-", ms=3, label=plain(name) if name else None)
        _mark_bad_points(ax, df, p.column)
        ax.set_xlabel(parameter_axis(p))
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    fig.suptitle(plain(f"{study.name}: effect of {parameter_axis(p)}"))
    return fig


def _mark_bad_points(ax, df, column: str) -> None:
    """Invalid points (outside the model's validity) as red crosses and failed ones (the run
    did not finish) as black pluses on the parameter axis, named in the legend."""
    for status, marker, color in (("invalid", "x", "tab:red"), ("failed", "+", "k")):
        bad = df[df["status"] == status]
        x = np.asarray(bad[column], dtype=float) if column in bad else np.array([])
        x = x[np.isfinite(x)]
        if x.size:
            ax.plot(x, np.full(x.size, 0.02), marker, color=color, ms=7, ls="none",
                    transform=ax.get_xaxis_transform(), label=f"{status} ({x.size} points)")


def _with_gaps(ok, bad, column: str, metric: str):
    """(x, y) of one line: the ok points' values and NaN at the other points' levels, sorted by
    ``column``, so that the line breaks where a point is invalid or failed."""
    x = np.concatenate([np.asarray(ok[column], float), np.asarray(bad[column], float)])
    y = np.concatenate([np.asarray(ok[metric], float), np.full(len(bad), np.nan)])
    keep = np.isfinite(x)
    x, y = x[keep], y[keep]
    order = np.argsort(x, kind="stable")
    x, y = x[order], y[order]
    if x.size:  # one value per level: a level with an ok value keeps it
        levels = np.unique(x)
        y = np.array([np.nanmean(y[x == v]) if np.isfinite(y[x == v]).any() else np.nan
                      for v in levels])
        x = levels
    return x, y


def _trend_lines(df, study: Study, p, metric: str):
    """(label, x, y) lines of one trend panel: a grid's combinations of the other parameters
    one line each (the metric at each level of ``p`` with the others fixed, NaN at the levels
    whose point is invalid or failed), or the main effect when there are more than MAX_LINES;
    other designs: parameter_levels, with NaN at the levels no ok point has."""
    others = [q.column for q in study.parameters if q is not p]
    if study.design != "grid" or not others:
        x, y = parameter_levels(df, study, p.column, metric)
        return [("", *_gaps_at_bad_levels(df, p.column, x, y))]
    ok = df[df["status"] == "ok"]
    groups = list(df.groupby(others, dropna=False))
    if len(groups) > MAX_LINES:
        x, y = parameter_levels(df, study, p.column, metric)
        return [(f"main effect (mean over {len(groups)} combinations)",
                 *_gaps_at_bad_levels(df, p.column, x, y))]
    lines = []
    for key, g in groups:
        key = key if isinstance(key, tuple) else (key,)
        label = ", ".join(f"{c} = {v:g}" if isinstance(v, int | float) else f"{c} = {v}"
                          for c, v in zip(others, key, strict=True))
        good = g[g["status"] == "ok"]
        if good.empty and not ok.empty:
            continue
        lines.append((label, *_with_gaps(good, g[g["status"] != "ok"], p.column, metric)))
    return lines


def summaries(df) -> list[Summary]:
    """The rows of a summary.csv table as typed documents: each row's metric cells that are
    fields of gearcli.results.Summary (the others: the field's default), read by field, not
    by column name."""
    return [Summary.from_document(cells) for cells in df.to_dict("records")]


def _gaps_at_bad_levels(df, column: str, x, y):
    """``(x, y)`` with NaN inserted at the levels of ``column`` that only invalid or failed
    points have (the line breaks there)."""
    bad = np.asarray(df.loc[df["status"] != "ok", column], dtype=float)
    extra = np.setdiff1d(bad[np.isfinite(bad)], np.asarray(x, float))
    if not extra.size:
        return np.asarray(x, float), np.asarray(y, float)
    xs = np.concatenate([np.asarray(x, float), extra])
    ys = np.concatenate([np.asarray(y, float), np.full(extra.size, np.nan)])
    order = np.argsort(xs, kind="stable")
    return xs[order], ys[order]


def speed_figure(study: Study, df, speed, units: str = "engineering"):
    """Dynamic factor and DTE standard deviation (in the display unit: µm) against f_z, one
    curve per combination of the other parameters, broken at the invalid and failed points
    (marked on the axis), with the mesh natural frequency f_n and f_n/2, f_n/3 marked."""
    from matplotlib.figure import Figure

    others = [p.column for p in study.parameters if p is not speed]
    groups = df.groupby(others, dropna=False) if others else [((), df)]
    fig = Figure(figsize=(9, 7), layout="constrained")
    axes = fig.subplots(2, 1, sharex=True)
    panels = [(axes[0], "dynamic_factor"), (axes[1], "dte_rms_mm")]
    f_ns = []
    for key, g in groups:
        key = key if isinstance(key, tuple) else (key,)
        label = ", ".join(f"{c} = {v:g}" for c, v in zip(others, key, strict=True)) or None
        good, bad = g[g["status"] == "ok"], g[g["status"] != "ok"]
        for ax, metric in panels:
            x, y = _with_gaps(good, bad, speed.column, metric)
            ax.plot(x, metric_axis(metric, units)[1] * y, "o-", ms=3, label=label)
        f_ns += [f for f in (p.mesh_natural_frequency_Hz for p in summaries(good))
                 if f is not None and math.isfinite(f)]
    for ax, metric in panels:
        _mark_bad_points(ax, df, speed.column)
        ax.set_ylabel(metric_axis(metric, units)[0])
    if f_ns:
        f_n = float(np.median(f_ns))
        for ax in axes:
            for k, style in ((1, "-"), (2, "--"), (3, ":")):
                ax.axvline(f_n / k, color="k", ls=style, lw=0.8,
                           label=f"f_n/{k} = {f_n / k:.0f} Hz" if k > 1 else
                           f"f_n = {f_n:.0f} Hz")
    axes[1].set_xlabel(parameter_axis(speed))
    for ax in axes:
        ax.grid(alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    fig.suptitle(plain(f"{study.name}: speed sweep"))
    return fig
