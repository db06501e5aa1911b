"""Reports of a results folder: figures (PNG + SVG) and one HTML or Markdown file.

Built only from the files simulate and analyze wrote (manifest, summary, time series, analysis,
spectrum), so a report can be rebuilt at any time without running anything again.
"""

from gearcli.report.build import build_report

__all__ = ["build_report"]
