"""Figures of `gearcli monitor` (docs/theory.md, "Condition-monitoring signals"): each shaft's
order spectrum with the mesh harmonics and their shaft-order sidebands, and its TSA drawn tooth
by tooth with the faulted teeth marked. Pure: arrays in, a matplotlib Figure out (Agg canvas,
never shown)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["ShaftAverage", "plot_order_sidebands", "plot_tsa_teeth"]

FAULT_COLOUR = "#c0392b"


@dataclass(frozen=True)
class ShaftAverage:
    """One shaft's TSA as the figures need it."""

    shaft: str  #: "pinion" or "gear"
    teeth: int  #: z
    first_tooth: int  #: the tooth at the pitch point at TSA index 0
    tsa: np.ndarray  #: one revolution [signal unit]
    faulted_teeth: tuple[int, ...] = ()
    n_revolutions: int = 0


def _figure(rows: int, height: float):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10.0, height * rows), layout="constrained")
    return fig, [fig.add_subplot(rows, 1, k + 1) for k in range(rows)]


def plot_order_sidebands(shafts: list[ShaftAverage], signal_label: str, n_harmonics: int = 3,
                         n_sidebands: int = 3) -> Figure:
    """Per shaft, the TSA's order spectrum A_m (docs/theory.md monitoring §3) up to
    (H + ½) z: the mesh harmonics h z (dark), their sidebands h z ± 1 … S (orange: the shaft's
    own order spacing, where a fault on this shaft's gear shows) and the rest (grey)."""
    from gearcli.model.monitoring.orders import order_spectrum

    fig, axes = _figure(len(shafts), 3.0)
    for ax, s in zip(axes, shafts, strict=True):
        orders, amp = order_spectrum(np.asarray(s.tsa, float))
        top = min(int((n_harmonics + 0.5) * s.teeth), orders.size - 1)
        m, a = orders[1:top + 1], amp[1:top + 1]
        mesh = (m % s.teeth == 0)
        near = np.minimum(m % s.teeth, s.teeth - m % s.teeth)
        side = ~mesh & (near <= n_sidebands) & (m > s.teeth - n_sidebands - 1)
        rest = ~mesh & ~side
        ax.vlines(m[rest], 0, a[rest], color="0.6", lw=0.8)
        ax.vlines(m[side], 0, a[side], color="tab:orange", lw=1.6,
                  label=f"sidebands h z ± 1 … {n_sidebands}")
        ax.vlines(m[mesh], 0, a[mesh], color="k", lw=2.0, label="mesh harmonics h z")
        ax.set_yscale("symlog", linthresh=max(float(a.max()) * 1e-4, 1e-300))
        faults = (f"; faulted teeth {', '.join(map(str, s.faulted_teeth))}"
                  if s.faulted_teeth else "")
        ax.set_title(f"{s.shaft} ({s.teeth} teeth): order spectrum of the TSA of "
                     f"{s.n_revolutions} revolution(s){faults}", fontsize=10, loc="left")
        ax.set_xlabel(f"order [per {s.shaft} revolution]")
        ax.set_ylabel(f"amplitude [{signal_label}]")
        ax.legend(fontsize=8, loc="upper right")
        ax.grid(alpha=0.3)
    return fig


def plot_tsa_teeth(shafts: list[ShaftAverage], signal_label: str) -> Figure:
    """Per shaft, the TSA and its difference signal (monitoring §4) over one revolution against
    the tooth at the pitch point: x = k is tooth k's pitch-point passage, each tooth's
    segment (k − ½, k + ½) shaded alternately, the faulted teeth's segments red."""
    from gearcli.model.monitoring.orders import difference_signal

    fig, axes = _figure(2 * len(shafts), 2.4)
    for k, s in enumerate(shafts):
        x = np.asarray(s.tsa, float)
        n, z = x.size, s.teeth
        pos = s.first_tooth + np.arange(n) * z / n  # tooth index at the pitch point
        diff = difference_signal(x, [z])
        for ax, y, what in ((axes[2 * k], x - x.mean(), "TSA − mean"),
                            (axes[2 * k + 1], diff, "difference signal")):
            for tooth in range(s.first_tooth, s.first_tooth + z):
                faulted = tooth % z in s.faulted_teeth
                if faulted or tooth % 2 == 0:
                    ax.axvspan(tooth - 0.5, tooth + 0.5, lw=0,
                               color=FAULT_COLOUR if faulted else "0.93",
                               alpha=0.35 if faulted else 1.0)
                if faulted:
                    ax.text(tooth, 1.0, f"tooth {tooth % z}", color=FAULT_COLOUR, ha="center",
                            va="bottom", fontsize=8, transform=ax.get_xaxis_transform())
            ax.plot(np.append(pos, pos[0] + z), np.append(y, y[0]), lw=0.9, color="k")
            ax.set_xlim(s.first_tooth - 0.5, s.first_tooth + z - 0.5)
            step = max(1, z // 25)
            ticks = np.arange(s.first_tooth, s.first_tooth + z, step)
            ax.set_xticks(ticks, [str(t % z) for t in ticks], fontsize=7)
            ax.set_ylabel(f"[{signal_label}]")
            ax.set_title(f"{s.shaft}: {what}, one revolution tooth by tooth", fontsize=10,
                         loc="left")
        axes[2 * k + 1].set_xlabel(f"{s.shaft} tooth at the pitch point")
    return fig
