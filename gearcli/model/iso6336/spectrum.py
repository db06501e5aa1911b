"""A duty cycle (torque, speed, time share bins) rated by ISO 6336-6 (Palmgren–Miner).

docs/theory.md, "ISO 6336 rating", §4. Each bin i is rated as a single load (its own F_t and
speed, hence its own stresses, load factors and Z_v): it contributes n_i = 60 n_i L_h t_i q load
cycles (t_i its share of the life L_h) and, at the stress S_min σ_i, allows N_i cycles on the
gear's strength curve σ_G(N) (:func:`gearcli.model.iso6336.life.cycles_at_strength`). The damage
D = Σ n_i/N_i (ISO 6336-6, linear damage accumulation) is ≤ 1 for a gear that survives the
spectrum with the minimum safety. One bin with the rated load gives D = L_h/L_h(S_min), the
damage of :func:`gearcli.model.iso6336.rate.rate`.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass

from gearcli.model.iso6336.inputs import RatingInput
from gearcli.model.iso6336.life import cycles_at_strength, load_cycles, miner_damage
from gearcli.model.iso6336.rate import GearEvaluation, evaluate

__all__ = ["LoadBin", "GearDamage", "DutyCycleDamage", "duty_cycle_damage"]


@dataclass(frozen=True)
class LoadBin:
    """One bin of a load spectrum."""

    torque_Nm: float  #: pinion torque per mesh path [N·m]
    speed_rpm: float  #: pinion speed relative to the carrier [min⁻¹]
    time_share: float  #: share of the required life [-] (the shares sum to 1)


@dataclass(frozen=True)
class GearDamage:
    """Miner damage of one gear, in total and per bin."""

    name: str
    pitting: float  #: D_H [-]
    bending: float  #: D_F [-]
    pitting_per_bin: tuple[float, ...]
    bending_per_bin: tuple[float, ...]

    def to_dict(self) -> dict:
        def fin(x):
            return None if math.isinf(x) else x
        return {"name": self.name, "pitting": fin(self.pitting), "bending": fin(self.bending),
                "pitting_per_bin": [fin(x) for x in self.pitting_per_bin],
                "bending_per_bin": [fin(x) for x in self.bending_per_bin]}


@dataclass(frozen=True)
class DutyCycleDamage:
    pinion: GearDamage
    gear: GearDamage

    def to_dict(self) -> dict:
        return {"method": "ISO 6336-6 Palmgren-Miner", "pinion": self.pinion.to_dict(),
                "gear": self.gear.to_dict()}


def _bin_damage(ev: GearEvaluation, life_h: float, share: float, s_hmin: float,
                s_fmin: float) -> tuple[float, float]:
    n_i = load_cycles(ev.speed_rpm, life_h * share, ev.contacts_per_revolution)
    n_h = cycles_at_strength(ev.pitting_strength, s_hmin * ev.sigma_H_MPa, ev.n_static_H)
    n_f = cycles_at_strength(ev.bending_strength, s_fmin * ev.sigma_F_MPa, ev.n_static_F)
    return miner_damage([n_i], [n_h]), miner_damage([n_i], [n_f])


def duty_cycle_damage(inp: RatingInput, bins: Sequence[LoadBin]) -> DutyCycleDamage:
    """Palmgren–Miner damage of both gears over ``inp.life_h`` under the spectrum ``bins``
    (module notes). The torque and speed of ``inp`` are replaced by each bin's."""
    total = sum(b.time_share for b in bins)
    if not bins or abs(total - 1.0) > 1e-9:
        raise ValueError(f"the time shares of the duty cycle sum to {total:.12g}, not 1")
    per = {"pinion": ([], []), "gear": ([], [])}
    for b in bins:
        ev = evaluate(dataclasses.replace(inp, pinion_torque_Nm=b.torque_Nm,
                                          pinion_speed_rpm=b.speed_rpm))
        for g in (ev.pinion, ev.gear):
            d_h, d_f = _bin_damage(g, inp.life_h, b.time_share, inp.minimum_safety_pitting,
                                   inp.minimum_safety_bending)
            per[g.name][0].append(d_h)
            per[g.name][1].append(d_f)
    out = [GearDamage(name, sum(h), sum(f), tuple(h), tuple(f)) for name, (h, f) in per.items()]
    return DutyCycleDamage(out[0], out[1])
