"""Load cycles, life-factor S-N curves, the life at a minimum safety, Palmgren–Miner damage.

docs/theory.md, "ISO 6336 rating", §4.

Load cycles of a gear (ISO 6336-2/-3, "number of load cycles"): N_L = 60 n L_h q [-], n the
speed [min⁻¹] relative to the carrier where there is one, L_h the life [h], q the contacts per
revolution of the flank considered (a sun meshing with three planets: 3; an idler: 1 per mesh).

Life factors Z_NT (ISO 6336-2, Table 2) and Y_NT (ISO 6336-3, Table 3) are straight lines in
log-log coordinates between knees (N, factor); beyond the endurance knee they fall to 0.85 at
N_L = 10¹⁰ ("normal" material and lubrication) or stay at 1.0 ("optimum"); beyond 10¹⁰ they
stay at that value (the standard's curves end there):

============================================  =====================  ==========  ============
Z_NT                                          static                 endurance   long life
============================================  =====================  ==========  ============
St, V, GGG, GTS, Eh, IF, pitting permitted     1.6 at ≤ 6·10⁵, 1.3 at 10⁷   1.0 at 10⁹   0.85 | 1.0
St, V, GGG, GTS, Eh, IF, no pitting            1.6 at ≤ 10⁵          1.0 at 5·10⁷  0.85 | 1.0
GG, NT, NV                                    1.3 at ≤ 10⁵          1.0 at 2·10⁶  0.85 | 1.0
NV nitrocarburized                            1.1 at ≤ 10⁵          1.0 at 2·10⁶  0.85 | 1.0
============================================  =====================  ==========  ============

Y_NT: St, V, GGG, GTS 2.5 at ≤ 10⁴; Eh, IF 2.5 at ≤ 10³; GG, NT, NV 1.6 at ≤ 10³; NV
nitrocarburized 1.1 at ≤ 10³; all 1.0 at 3·10⁶ and 0.85 | 1.0 at 10¹⁰. ISO 6336-6 writes the
same lines inverted (its Annex, e.g. N = Z_NT^(−32.60…) 5·10⁷ below the knee of Eh, no pitting).

Influence factors that depend on N (Z_L, Z_v, Z_R, Z_W, Z_X; Y_δrelT, Y_RrelT, Y_X) are
interpolated the same way between their static value at the static knee and their reference
value at the endurance knee (ISO 6336-2/-3, Method B, limited life).

Palmgren–Miner (ISO 6336-6): a spectrum of stresses σ_i with n_i cycles has the damage
D = Σ n_i/N_i, N_i the cycles at which the strength curve σ_G(N)/S_min equals σ_i (N_i = ∞
where σ_i is below the curve's end, 0 where it exceeds the static strength).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from gearcli.model.iso6336.common import log_interpolate
from gearcli.model.iso6336.material import GREY_IRON_LIKE, NITRIDED, SURFACE_HARDENED, MaterialKind

__all__ = ["load_cycles", "LifeCurve", "pitting_life_curve", "bending_life_curve",
           "influence_at", "cycles_at_strength", "miner_damage", "LONG_LIFE_CYCLES"]

#: N_L = 10¹⁰, the end of the standard's life-factor curves.
LONG_LIFE_CYCLES = 1.0e10


def load_cycles(speed_rpm: float, life_h: float, contacts_per_revolution: float = 1.0) -> float:
    """N_L = 60 n L_h q [-]: speed n [min⁻¹] (relative to a carrier), life L_h [h], q contacts
    of the flank per revolution [-] (ISO 6336-2/-3, number of load cycles)."""
    return 60.0 * abs(speed_rpm) * life_h * contacts_per_revolution


@dataclass(frozen=True)
class LifeCurve:
    """A life-factor curve: flat to the static knee, log-log lines through the knees, flat
    beyond 10¹⁰."""

    n_static: float  #: static knee [cycles]
    f_static: float  #: factor at and below it [-]
    n_ref: float  #: endurance knee [cycles]
    n_mid: float | None = None  #: intermediate knee (Z_NT with pitting permitted: 10⁷)
    f_mid: float | None = None
    f_long: float = 0.85  #: factor at 10¹⁰ and beyond: 0.85 "normal", 1.0 "optimum"

    def knees(self) -> list[tuple[float, float]]:
        pts = [(self.n_static, self.f_static)]
        if self.n_mid is not None:
            pts.append((self.n_mid, self.f_mid))
        pts += [(self.n_ref, 1.0), (LONG_LIFE_CYCLES, self.f_long)]
        return pts

    def __call__(self, n: float) -> float:
        """Life factor at N = ``n`` load cycles [-]."""
        pts = self.knees()
        if n <= pts[0][0]:
            return pts[0][1]
        for (n0, f0), (n1, f1) in itertools.pairwise(pts):
            if n <= n1:
                return log_interpolate(n, n0, f0, n1, f1)
        return pts[-1][1]


def _life_group(kind: MaterialKind) -> str:
    """The row group of ISO 6336-2 Table 2 / ISO 6336-3 Table 3 a material belongs to."""
    kind = MaterialKind(kind)
    if kind is MaterialKind.NITROCARBURIZED:
        return "nitrocarburized"
    if kind in NITRIDED or kind in GREY_IRON_LIKE:
        return "nitrided_grey"
    return "surface" if kind in SURFACE_HARDENED else "through"


#: (static knee, static factor, endurance knee) per group; module notes.
_PITTING_KNEES = {"nitrocarburized": (1e5, 1.1, 2e6), "nitrided_grey": (1e5, 1.3, 2e6),
                  "surface": (1e5, 1.6, 5e7), "through": (1e5, 1.6, 5e7)}
_BENDING_KNEES = {"nitrocarburized": (1e3, 1.1, 3e6), "nitrided_grey": (1e3, 1.6, 3e6),
                  "surface": (1e3, 2.5, 3e6), "through": (1e4, 2.5, 3e6)}


def pitting_life_curve(kind: MaterialKind, pitting_permitted: bool = False,
                       optimum: bool = False) -> LifeCurve:
    """Z_NT curve of a material (ISO 6336-2, Table 2; module notes). ``optimum``: 1.0 beyond
    the endurance knee (optimum lubrication, material, manufacturing and experience);
    ``pitting_permitted``: the St, V, GGG, GTS, Eh, IF line through 1.3 at 10⁷ to 1.0 at 10⁹."""
    f_long = 1.0 if optimum else 0.85
    group = _life_group(kind)
    if pitting_permitted and group in ("surface", "through"):
        return LifeCurve(6e5, 1.6, 1e9, 1e7, 1.3, f_long=f_long)
    return LifeCurve(*_PITTING_KNEES[group], f_long=f_long)


def bending_life_curve(kind: MaterialKind, optimum: bool = False) -> LifeCurve:
    """Y_NT curve of a material (ISO 6336-3, Table 3; module notes)."""
    return LifeCurve(*_BENDING_KNEES[_life_group(kind)], f_long=1.0 if optimum else 0.85)


def influence_at(n: float, curve: LifeCurve, static_value: float, reference_value: float) -> float:
    """An influence factor at N load cycles [-]: ``static_value`` up to the curve's static knee,
    ``reference_value`` from its endurance knee, log-log interpolated between (ISO 6336-2/-3
    Method B, limited life)."""
    return log_interpolate(n, curve.n_static, static_value, curve.n_ref, reference_value)


def cycles_at_strength(strength: Callable[[float], float], stress: float,
                       n_static: float) -> float:
    """Load cycles N [-] at which a non-increasing strength curve σ_G(N) [N/mm²] equals
    ``stress`` [N/mm²] (bisection in log N to 1e-12 relative).

    0 when the stress exceeds the static strength σ_G(n_static); ``math.inf`` when it is at
    or below the strength at 10¹⁰ (the curves are flat beyond).
    """
    if stress > strength(n_static):
        return 0.0
    if stress <= strength(LONG_LIFE_CYCLES):
        return math.inf
    lo, hi = math.log(n_static), math.log(LONG_LIFE_CYCLES)
    while hi - lo > 1e-12 * abs(hi):
        mid = 0.5 * (lo + hi)
        if strength(math.exp(mid)) >= stress:
            lo = mid
        else:
            hi = mid
    return math.exp(0.5 * (lo + hi))


def miner_damage(cycles: Sequence[float], allowed_cycles: Sequence[float]) -> float:
    """Palmgren–Miner damage D = Σ n_i/N_i [-] (ISO 6336-6); N_i = ∞ adds nothing, N_i = 0
    with n_i > 0 makes D infinite."""
    d = 0.0
    for n, n_allowed in zip(cycles, allowed_cycles, strict=True):
        if n <= 0.0 or math.isinf(n_allowed):
            continue
        d += math.inf if n_allowed <= 0.0 else n / n_allowed
    return d
