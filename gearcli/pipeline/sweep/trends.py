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


def write_trends(folder: str | Path, study: Study, rows: list[dict]) -> list[Path]:
    """Write trends.csv, trends.md and the plots; returns the paths written."""
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
    write_atomic(paths[1], _markdown(study, df, trends), out)
    for m in (*TREND_METRICS, *PLOT_METRICS):  # metrics the study left out: empty panels
        if m not in df.columns:
            df[m] = np.nan
    paths += _plots(out, study, df)
    record_outputs(out, [p.name for p in paths])
    return paths


def _markdown(study: Study, df, trends: list[dict]) -> str:
    n_ok = int((df["status"] == "ok").sum())
    lines = [f"# Trends: {study.name}", "",
             f"{len(df)} points ({study.design}), {n_ok} ok, {len(df) - n_ok} failed. "
             "Change = metric at the highest level against the lowest (grids: the main effect, "
             "the mean over the other parameters; one-at-a-time: the others at their base); "
             f"direction from the Spearman rank correlation (|rho| >= {MONOTONIC_RHO}).", "",
             "| parameter | tested range | metric | at min | at max | change | direction |",
             "|---|---|---|---|---|---|---|"]
    for t in trends:
        if "change_percent" not in t:
            lines.append(f"| {t['parameter']} | — | {t['metric']} | — | — | — | "
                         f"{t['direction']} |")
            continue
        lines.append(f"| {t['parameter']} | {t['parameter_min']:.4g} … {t['parameter_max']:.4g}"
                     f" | {t['metric']} | {t['metric_at_min']:.4g} | {t['metric_at_max']:.4g} "
                     f"| {_change(t)} | {t['direction']} "
                     f"(rho {t['spearman_rho']:+.2f}) |")
    failed = df[df["status"] != "ok"]
    if len(failed):
        lines += ["", "## Failed points", ""]
        lines += [f"- point {int(r['point'])}: {r['error']}" for _, r in failed.iterrows()]
    lines += ["", "Plots: " + ", ".join(f"`{p}`" for p in _plot_names(study)), ""]
    return "\n".join(lines)


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


def _plots(out: Path, study: Study, df) -> list[Path]:
    # Figure objects, not pyplot: no backend is chosen for (or windows opened in) the caller's
    # process, e.g. a notebook calling gearcli.sweep
    from matplotlib.figure import Figure

    paths = []
    for p in study.parameters:
        fig = Figure(figsize=(10, 7), layout="constrained")
        axes = fig.subplots(2, 2)
        for ax, m in zip(axes.flat, TREND_METRICS, strict=True):
            lines = _trend_lines(df, study, p, m)
            for label, x, y in lines:
                ax.plot(x, y, "o-", ms=3, label=plain(label) if label else None)
            if any(label for label, _, _ in lines):
                ax.legend(fontsize=7)
            ax.set_xlabel(p.column)
            ax.set_ylabel(m)
            ax.grid(alpha=0.3)
        fig.suptitle(plain(f"{study.name}: effect of {p.column}"))
        path = out / f"trend_{_slug(p.column)}.png"
        save_figure(fig, path, 100, path.parent)
        paths.append(path)
    speed = next((p for p in study.parameters if p.key == MESH_FREQUENCY), None)
    if speed is not None:
        paths.append(_speed_plot(out, study, df, speed, Figure))
    return paths


def _trend_lines(df, study: Study, p, metric: str):
    """(label, x, y) lines of one trend panel: a grid's combinations of the other parameters
    one line each (the metric at each level of ``p`` with the others fixed), or the main
    effect when there are more than MAX_LINES; other designs: parameter_levels."""
    others = [q.column for q in study.parameters if q is not p]
    if study.design != "grid" or not others:
        x, y = parameter_levels(df, study, p.column, metric)
        return [("", x, y)]
    ok = df[df["status"] == "ok"]
    groups = list(ok.groupby(others, dropna=False))
    if len(groups) > MAX_LINES:
        x, y = parameter_levels(df, study, p.column, metric)
        return [(f"main effect (mean over {len(groups)} combinations)", x, y)]
    lines = []
    for key, g in groups:
        key = key if isinstance(key, tuple) else (key,)
        g = g.sort_values(p.column)
        label = ", ".join(f"{c} = {v:g}" if isinstance(v, int | float) else f"{c} = {v}"
                          for c, v in zip(others, key, strict=True))
        lines.append((label, g[p.column].to_numpy(float), g[metric].to_numpy(float)))
    return lines


def summaries(df) -> list[Summary]:
    """The rows of a summary.csv table as typed documents: each row's metric cells that are
    fields of gearcli.results.Summary (the others: the field's default), read by field, not
    by column name."""
    return [Summary.from_document(cells) for cells in df.to_dict("records")]


def _speed_plot(out: Path, study: Study, df, speed, Figure) -> Path:  # noqa: N803
    """Dynamic factor and DTE standard deviation against f_z, one curve per combination of
    the other parameters, with the mesh natural frequency f_n and f_n/2, f_n/3 marked, and the
    points outside the model's validity or failed as crosses on the axis."""
    ok = df[df["status"] == "ok"]
    others = [p.column for p in study.parameters if p is not speed]
    groups = ok.groupby(others, dropna=False) if others else [((), ok)]
    fig = Figure(figsize=(9, 7), layout="constrained")
    axes = fig.subplots(2, 1, sharex=True)
    f_ns = []
    for key, g in groups:
        g = g.sort_values(speed.column)
        key = key if isinstance(key, tuple) else (key,)
        label = ", ".join(f"{c} = {v:g}" for c, v in zip(others, key, strict=True)) or None
        points = summaries(g)
        axes[0].plot(g[speed.column], [s.dynamic_factor for s in points], "o-", ms=3,
                     label=label)
        axes[1].plot(g[speed.column], [s.dte_rms_mm for s in points], "o-", ms=3, label=label)
        f_ns += [s.mesh_natural_frequency_Hz for s in points
                 if s.mesh_natural_frequency_Hz is not None
                 and math.isfinite(s.mesh_natural_frequency_Hz)]
    for status, g in df[df["status"] != "ok"].groupby("status"):
        for ax in axes:  # no metrics to plot: a cross on the f_z axis says where
            ax.plot(g[speed.column], np.full(len(g), 0.02), "x", color="tab:red",
                    transform=ax.get_xaxis_transform(), label=f"{status} ({len(g)} points)")
    if f_ns:
        f_n = float(np.median(f_ns))
        for ax in axes:
            for k, style in ((1, "-"), (2, "--"), (3, ":")):
                ax.axvline(f_n / k, color="k", ls=style, lw=0.8,
                           label=f"f_n/{k} = {f_n / k:.0f} Hz" if k > 1 else
                           f"f_n = {f_n:.0f} Hz")
    axes[0].set_ylabel("dynamic factor")
    axes[1].set_ylabel("DTE standard deviation [mm]")
    axes[1].set_xlabel("gear-mesh frequency f_z [Hz]")
    for ax in axes:
        ax.grid(alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    fig.suptitle(plain(f"{study.name}: speed sweep"))
    path = out / "speed_sweep.png"
    save_figure(fig, path, 100, path.parent)
    return path
