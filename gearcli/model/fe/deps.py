"""The optional finite-element libraries, imported only when an FE model is built.

scikit-fem (Gustafsson & McBain 2020) assembles and solves the elasticity problem; the
``triangle`` package (Shewchuk's Triangle) generates the quality triangular mesh. Both come
with the optional extra ``fe`` (``pip install gearcli[fe]``); without it the FE functions
raise :class:`FEUnavailableError` with one line that names the extra.
"""

from __future__ import annotations

import importlib
from types import ModuleType

__all__ = ["FEUnavailableError", "require"]


class FEUnavailableError(ImportError):
    """The optional extra ``fe`` (scikit-fem, triangle) is not installed."""


def require() -> tuple[ModuleType, ModuleType]:
    """(skfem, triangle), or :class:`FEUnavailableError` naming the missing extra."""
    try:
        skfem = importlib.import_module("skfem")
        triangle = importlib.import_module("triangle")
    except ImportError as exc:
        raise FEUnavailableError(
            f"the finite-element tooth model needs the optional extra 'fe' "
            f"(pip install 'gearcli[fe]'): {exc.name or exc} is not installed"
        ) from None
    return skfem, triangle
