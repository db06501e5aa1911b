"""The resonance map of `gearcli modal`: excitation orders (mesh harmonics, shaft orders),
their crossings with the natural frequencies (Campbell diagram) and the margins at a speed.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Order:
    """An excitation at ``per_rev`` events per pinion revolution (f = per_rev n1)."""

    name: str
    per_rev: float


def excitation_orders(z1: int, z2: int, harmonics: int) -> tuple[Order, ...]:
    """GMF harmonics k z1 (k = 1..N) and the shaft orders 1x pinion, 1x gear (= z1/z2)."""
    gmf = tuple(Order(f"{k}x GMF", float(k * z1)) for k in range(1, harmonics + 1))
    return (*gmf, Order("1x pinion", 1.0), Order("1x gear", z1 / z2))


@dataclass(frozen=True)
class Crossing:
    order: str
    mode: int
    frequency_Hz: float
    pinion_speed_rev_s: float  #: n1 at which order × n1 = f_mode


@dataclass(frozen=True)
class Margin:
    order: str
    mode: int
    excitation_Hz: float
    mode_Hz: float
    margin_percent: float  #: |f_exc − f_mode| / f_mode × 100
    has_peak: bool


def crossings(modes, orders) -> list[Crossing]:
    """Pinion speeds n1 [rev/s] where each order line meets each non-rigid mode."""
    return [Crossing(o.name, m.number, m.natural_frequency_Hz, m.natural_frequency_Hz / o.per_rev)
            for m in modes if not m.rigid for o in orders]


def margins(modes, orders, pinion_speed_rev_s: float) -> list[Margin]:
    """Margin [%] of every order at the pinion speed n1 [rev/s] to every non-rigid mode,
    nearest first."""
    out = [Margin(o.name, m.number, o.per_rev * pinion_speed_rev_s, m.natural_frequency_Hz,
                  abs(o.per_rev * pinion_speed_rev_s - m.natural_frequency_Hz)
                  / m.natural_frequency_Hz * 100.0, m.has_peak)
           for m in modes if not m.rigid for o in orders]
    return sorted(out, key=lambda x: x.margin_percent)
