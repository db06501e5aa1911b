"""gearcli — dynamics of spur gear pairs from a YAML case file.

Layers (imports point downward only)::

    cli -> pipeline -> model -> core
    case (YAML -> validated objects), io, plotting, report: leaves used by pipeline/cli

Internal units are declared once in :mod:`gearcli.units` (mm, N, s, tonne, rad).
"""

__version__ = "0.1.0"
