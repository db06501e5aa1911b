"""Display units: one setting for tables, figures and reports (docs/theory.md §1).

Files keep their unit-suffixed internal units (``force_N``, ``delta_mm``, ``omega1_rad_s``,
summary.json's ``_deg_s`` speeds); what a person reads is converted here, to one of

``engineering`` (default)
    shaft speeds in rpm, lengths in mm and deflections (transmission error, static deflection)
    in µm, torques in N·m, mesh stiffness in N/µm (ISO 6336-1's c′ is per mm of face width in
    N/(mm·µm)), stresses in MPa, masses in kg, energies in J;
``si``
    coherent SI: rad/s, m, N·m, N/m, kg, J; stresses stay in MPa (ISO 6336's unit) in both.

The command line sets it once with ``gearcli --units si ...`` (or ``GEARCLI_UNITS=si``);
library functions take ``units=`` and default to engineering.
"""

from __future__ import annotations

import math

SYSTEMS = ("engineering", "si")
DEFAULT = "engineering"

#: stored (internal) unit -> ((engineering unit, factor), (SI unit, factor)); display value =
#: stored value * factor. Units not listed are displayed as stored (Hz, s, N, W, %, –).
_TABLE: dict[str, tuple[tuple[str, float], tuple[str, float]]] = {
    "deg/s": (("rpm", 1.0 / 6.0), ("rad/s", math.pi / 180.0)),
    "rad/s": (("rpm", 30.0 / math.pi), ("rad/s", 1.0)),
    "rpm": (("rpm", 1.0), ("rad/s", math.pi / 30.0)),
    "mm": (("mm", 1.0), ("m", 1e-3)),
    "µm": (("µm", 1.0), ("m", 1e-6)),
    "mm/s": (("mm/s", 1.0), ("m/s", 1e-3)),
    "N*mm": (("N·m", 1e-3), ("N·m", 1e-3)),
    "N/mm": (("N/µm", 1e-3), ("N/m", 1e3)),
    "N/mm (line load)": (("N/mm", 1.0), ("N/m", 1e3)),  # a force per face width, not a stiffness
    "N*s/mm": (("N·s/mm", 1.0), ("N·s/m", 1e3)),
    "N*mm/rad": (("N·m/rad", 1e-3), ("N·m/rad", 1e-3)),
    "N*mm*s/rad": (("N·m·s/rad", 1e-3), ("N·m·s/rad", 1e-3)),
    "N*mm*s^2/rad^2": (("N·m·s²/rad²", 1e-3), ("N·m·s²/rad²", 1e-3)),
    "N/mm^2": (("MPa", 1.0), ("MPa", 1.0)),  # stresses: MPa in both (the ISO 6336 unit)
    "t": (("kg", 1e3), ("kg", 1e3)),
    "t*mm^2": (("kg·m²", 1e-3), ("kg·m²", 1e-3)),
    "t/mm^3": (("kg/m³", 1e12), ("kg/m³", 1e12)),
    "mJ": (("J", 1e-3), ("J", 1e-3)),
    "fraction": (("%", 100.0), ("%", 100.0)),
    # ISO 6336-1's own units of c', c_gamma_alpha (per face width) and m_red (per face width)
    "N/(mm·µm)": (("N/(mm·µm)", 1.0), ("N/m²", 1e9)),
    "kg/mm": (("kg/mm", 1.0), ("kg/m", 1e3)),
}
#: Deflections are stored in mm but read in µm by engineers (a transmission error of 0.0084 mm
#: is "8.4 µm"): ``fine=True`` selects this row instead of "mm".
_FINE_LENGTH = (("µm", 1e3), ("m", 1e-3))


def check_system(system: str) -> str:
    """``system`` when it is one of :data:`SYSTEMS`, else a ValueError naming them."""
    if system not in SYSTEMS:
        raise ValueError(f"units {system!r}: expected one of {', '.join(SYSTEMS)}")
    return system


def unit_and_factor(unit: str, system: str = DEFAULT, fine: bool = False) -> tuple[str, float]:
    """(display unit, factor) of a stored ``unit``: display value = stored value * factor."""
    row = _FINE_LENGTH if fine and unit == "mm" else _TABLE.get(unit)
    if row is None:
        return unit, 1.0
    return row[SYSTEMS.index(check_system(system))]


def convert(value, unit: str, system: str = DEFAULT, fine: bool = False):
    """(value in the display unit, display unit); lists and tuples elementwise, None and text
    as they are."""
    shown, factor = unit_and_factor(unit, system, fine)
    return _scale(value, factor), shown


def _scale(value, factor: float):
    if factor == 1.0 or value is None or isinstance(value, bool | str):
        return value
    if isinstance(value, list | tuple):
        return [_scale(v, factor) for v in value]
    if isinstance(value, int | float):
        return value * factor
    return value


def speed_label(system: str = DEFAULT) -> str:
    """The unit shaft speeds are shown in: "rpm" or "rad/s"."""
    return unit_and_factor("rad/s", system)[0]


def speed_from_rad_s(omega_rad_s, system: str = DEFAULT):
    """Shaft speeds [rad/s] (numbers or numpy arrays) in the display unit."""
    return omega_rad_s * unit_and_factor("rad/s", system)[1]
