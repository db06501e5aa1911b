"""A study run into one pandas DataFrame: the grid/random sweep (pipeline/sweep/run.py, its
trends and, for a ``dataset:`` study, the labels table) or the speed curve
(pipeline/speed_curve.py). The body of ``gearcli.sweep``; the arguments are checked there."""

from __future__ import annotations

import contextlib
import tempfile
from pathlib import Path


def study_frame(spec, out, jobs, scheduler, force: bool, keep_timeseries: bool,
                timeseries_format: str, progress, point_timeout, units: str = "engineering"):
    """Run the loaded study ``spec`` into ``out`` (None: a temporary folder, removed after)
    and return its summary table; ``attrs`` as documented by :func:`gearcli.sweep`; the
    trend table and figures in the display ``units`` (gearcli/display_units.py)."""
    import pandas as pd

    from gearcli.pipeline.sweep.run import rows_as_table, run_study, summary_columns

    with contextlib.ExitStack() as stack:
        if out is None:
            out = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="gearcli-"))) / "s"
        from gearcli.pipeline.sweep.folder import study_lock

        stack.enter_context(study_lock(Path(out)))  # the whole study, trends included
        if spec.design == "speed_curve":
            from gearcli.io.outdir import check_target
            from gearcli.pipeline.speed_curve import run_speed_curve, write_speed_curve

            check_target(out, force)  # before the runs, not after
            curve = run_speed_curve(spec, jobs, scheduler, point_timeout=point_timeout)
            write_speed_curve(curve, out, force)
            df = pd.DataFrame(curve.table(), columns=curve.columns)
            df.attrs.update(kind="speed_curve", errors=list(curve.errors),
                            notes=list(curve.notes))
            return df
        from gearcli.pipeline.sweep.trends import write_trends

        if spec.dataset is not None:  # every point's signals as Parquet (pipeline/dataset.py)
            keep_timeseries, timeseries_format = True, "parquet"
        outcome = run_study(spec, Path(out), jobs, scheduler, keep_timeseries, force, progress,
                            timeseries_format=timeseries_format,
                            point_timeout=point_timeout)
        write_trends(Path(out), spec, outcome.rows, units)
        df = rows_as_table(outcome.rows, summary_columns(spec))
        df.attrs.update(kind="sweep", total=outcome.total, ran=outcome.ran,
                        skipped=outcome.skipped, failed=outcome.failed,
                        wall_time_s=outcome.wall_time_s, labels=None)
        if spec.dataset is not None:
            from gearcli.pipeline.dataset import write_dataset

            df.attrs["labels"] = write_dataset(Path(out), outcome.rows, spec.dataset.signal)
        return df
