"""gearcli — dynamics of spur gear pairs from a YAML case file.

Layers (imports point downward only)::

    cli -> pipeline -> model -> core
    case (YAML -> validated objects), io, plotting, report: leaves used by pipeline/cli

Internal units are declared once in :mod:`gearcli.units` (mm, N, s, tonne, rad).
"""

import os as _os

# gearcli's linear algebra works on matrices of at most 16 x 16 (modal analysis): BLAS worker
# threads cannot help there, and on a 2-core machine their spin-waiting after each call took
# CPU from the compiled solver running next (bench/RESULTS.md). Set before numpy is imported;
# a value the user set wins.
for _name in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS"):
    _os.environ.setdefault(_name, "1")

__version__ = "0.1.0"
