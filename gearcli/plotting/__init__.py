"""Plotting: functions that take model or result objects and return a matplotlib Figure (Agg)."""
