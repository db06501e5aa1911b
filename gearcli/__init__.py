"""gearcli — dynamics of spur gear pairs from a YAML case file.

Layers (imports point downward only)::

    cli -> pipeline -> model -> core
    case (YAML -> validated objects), io, plotting, report: leaves used by pipeline/cli

Internal units are declared once in :mod:`gearcli.units` (mm, N, s, tonne, rad).
"""

__version__ = "0.1.0"

#: The public API (gearcli/api.py), imported on first use so that ``import gearcli`` stays
#: light (no numpy, numba, pandas) and changes nothing in the calling process.
_API = ("load_case", "geometry", "simulate", "analyze", "spectra_frame", "modal", "mesh",
        "stress", "rate", "sweep", "monitor",
        "Simulation", "Analysis", "Stress", "Modal", "Mesh", "Summary",
        "AnalysisMetrics", "GearStress", "Mode", "MeshSummary", "SCHEMA_VERSION")
__all__ = ["__version__", *_API]


def __getattr__(name: str):
    if name in _API:
        from gearcli import api

        return getattr(api, name)
    raise AttributeError(f"module 'gearcli' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)
