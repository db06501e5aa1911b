"""Order spectrum of a TSA, and its regular, residual, difference and narrow-band signals.

docs/theory.md, "Condition-monitoring signals", §3–§4. Pure functions of arrays, no I/O.

The TSA x̄_k (k = 0 … n−1) covers one revolution, so its discrete Fourier transform
X_m = Σ_k x̄_k e^{−2πi m k/n} has one line per shaft order m = 0 … n/2 (cycles per revolution).
The signals below keep or remove whole orders by setting X_m to zero and transforming back,
which is exact for a record of whole revolutions (no window, no leakage). For a shaft whose
gear has z teeth (the mesh order z of that shaft):

=================  ============================================================================
shaft orders       m = 1 … K (K = ``n_shaft_orders``)
mesh harmonics     m = h z, h = 1 … H (H = ``n_mesh_harmonics``; default all below n/2)
sidebands          m = h z ± s, s = 1 … S (S = ``n_sidebands``), 0 < m ≤ n/2
regular signal     shaft orders + mesh harmonics + sidebands (Swansson 1980; Lebold et al. 2000)
residual signal    x̄ − mean − shaft orders − mesh harmonics (Zakrajsek et al. 1993, NA4)
difference signal  x̄ − mean − regular (Zakrajsek et al. 1993, FM4: S = 1)
=================  ============================================================================

so that x̄ = mean + regular + difference exactly. The mean (order 0) is in none of them.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
from scipy.signal import hilbert

from gearcli.model.monitoring.angle import AngleSignal

__all__ = ["order_spectrum", "order_amplitude", "mesh_orders_kept", "keep_orders",
           "regular_signal", "residual_signal", "difference_signal", "sideband_table",
           "narrowband_envelope", "DEFAULT_SHAFT_ORDERS", "DEFAULT_SIDEBANDS"]

#: K: shaft orders 1 and 2 (once and twice per revolution: runout, ovality, misalignment).
DEFAULT_SHAFT_ORDERS = 2
#: S: first-order sidebands, as in Zakrajsek et al. (1993)'s difference signal.
DEFAULT_SIDEBANDS = 1


def _values(tsa) -> np.ndarray:
    if isinstance(tsa, AngleSignal) and tsa.n_revolutions != 1:
        raise ValueError("order signals need one revolution: average the angle signal first "
                         "(time_synchronous_average)")
    x = np.asarray(getattr(tsa, "values", tsa), dtype=float)
    if x.ndim != 1 or x.size < 4:
        raise ValueError("a TSA of at least 4 samples (one revolution) is needed")
    return x


def order_spectrum(tsa) -> tuple[np.ndarray, np.ndarray]:
    """Single-sided amplitude order spectrum of one revolution.

    A_0 = |X_0|/n, A_m = 2|X_m|/n for 0 < m < n/2, A_{n/2} = |X_{n/2}|/n (n even), so a
    component a cos(m θ + φ) has A_m = a.

    Parameters
    ----------
    tsa : SynchronousAverage or array [signal unit]
        One revolution, n samples at θ_k = 2π k/n.

    Returns
    -------
    orders : int array [-]
        m = 0 … ⌊n/2⌋ [cycles per revolution].
    amplitudes : array [signal unit]
        A_m.
    """
    x = _values(tsa)
    n = x.size
    amp = np.abs(np.fft.rfft(x)) / n
    amp[1:] *= 2.0
    if n % 2 == 0:
        amp[-1] /= 2.0
    return np.arange(amp.size), amp


def order_amplitude(tsa, order: int) -> float:
    """A_m [signal unit] of one order m (0 ≤ m ≤ n/2), see :func:`order_spectrum`."""
    _, amp = order_spectrum(tsa)
    if not 0 <= order < amp.size:
        raise ValueError(f"order {order} is outside 0 … {amp.size - 1}")
    return float(amp[order])


def mesh_orders_kept(mesh_orders: Sequence[int], n_samples: int,
                     n_mesh_harmonics: int | None = None) -> list[int]:
    """The mesh harmonics h z [-] (h = 1 … H) of each mesh order z that lie at or below n/2.

    Parameters
    ----------
    mesh_orders : sequence of int [-]
        z of each mesh on the shaft (the teeth of the shaft's gear in that mesh).
    n_samples : int [-]
        n, samples per revolution of the TSA.
    n_mesh_harmonics : int or None [-]
        H; None: every harmonic at or below n/2.
    """
    nyquist = n_samples // 2
    out: list[int] = []
    for z in mesh_orders:
        if z < 1:
            raise ValueError("a mesh order (tooth count) must be a positive integer")
        h_max = nyquist // z if n_mesh_harmonics is None else int(n_mesh_harmonics)
        out.extend(h * z for h in range(1, h_max + 1) if h * z <= nyquist)
    return sorted(set(out))


def _order_set(n: int, mesh_orders: Sequence[int], n_mesh_harmonics: int | None,
               n_shaft_orders: int, n_sidebands: int) -> set[int]:
    nyquist = n // 2
    harmonics = mesh_orders_kept(mesh_orders, n, n_mesh_harmonics)
    kept = {m for m in range(1, int(n_shaft_orders) + 1) if m <= nyquist}
    kept.update(harmonics)
    for m in harmonics:
        for s in range(1, int(n_sidebands) + 1):
            kept.update(o for o in (m - s, m + s) if 0 < o <= nyquist)
    return kept


def keep_orders(tsa, orders: Iterable[int]) -> np.ndarray:
    """The part of one revolution made of the given shaft orders only [signal unit].

    y_k = (1/n) Σ_{m ∈ M} (X_m e^{2πi m k/n} + conj.), M the given orders (0 ≤ m ≤ n/2).
    """
    x = _values(tsa)
    spec = np.fft.rfft(x)
    mask = np.zeros(spec.size, dtype=bool)
    for m in orders:
        if not 0 <= m < spec.size:
            raise ValueError(f"order {m} is outside 0 … {spec.size - 1}")
        mask[m] = True
    return np.fft.irfft(np.where(mask, spec, 0.0), n=x.size)


def regular_signal(tsa, mesh_orders: Sequence[int], *, n_mesh_harmonics: int | None = None,
                   n_shaft_orders: int = DEFAULT_SHAFT_ORDERS,
                   n_sidebands: int = DEFAULT_SIDEBANDS) -> np.ndarray:
    """Regular signal [signal unit]: shaft orders 1 … K, mesh harmonics h z and their sidebands
    h z ± 1 … S of the TSA (module table; Swansson 1980 via Lebold et al. 2000, the energy
    ratio's "regular meshing components").

    Parameters
    ----------
    tsa : SynchronousAverage or array [signal unit]
    mesh_orders : sequence of int [-]
        z of each mesh on the shaft.
    n_mesh_harmonics : int or None [-]
        H; None: all at or below n/2.
    n_shaft_orders : int [-]
        K.
    n_sidebands : int [-]
        S, sidebands each side of every mesh harmonic.
    """
    x = _values(tsa)
    return keep_orders(x, _order_set(x.size, mesh_orders, n_mesh_harmonics, n_shaft_orders,
                                     n_sidebands))


def residual_signal(tsa, mesh_orders: Sequence[int], *, n_mesh_harmonics: int | None = None,
                    n_shaft_orders: int = DEFAULT_SHAFT_ORDERS) -> np.ndarray:
    """Residual signal [signal unit]: the TSA without its mean, shaft orders 1 … K and mesh
    harmonics h z; the sidebands stay (Zakrajsek, Townsend & Decker 1993, NA4's residual: the
    synchronous average with the shaft frequency and its harmonics and the primary meshing
    frequency and its harmonics removed). Parameters as :func:`regular_signal`.
    """
    x = _values(tsa)
    removed = _order_set(x.size, mesh_orders, n_mesh_harmonics, n_shaft_orders, 0) | {0}
    return keep_orders(x, set(range(x.size // 2 + 1)) - removed)


def difference_signal(tsa, mesh_orders: Sequence[int], *, n_mesh_harmonics: int | None = None,
                      n_shaft_orders: int = DEFAULT_SHAFT_ORDERS,
                      n_sidebands: int = DEFAULT_SIDEBANDS) -> np.ndarray:
    """Difference signal [signal unit]: the TSA without its mean and its regular signal
    (:func:`regular_signal`), i.e. without shaft orders, mesh harmonics and S sidebands each
    side (Zakrajsek, Townsend & Decker 1993, FM4's difference signal: the synchronous average
    with the regular meshing components removed, i.e. the shaft frequency and its harmonics,
    the primary meshing frequency and its harmonics and their first-order sidebands; S = 1).
    Parameters as :func:`regular_signal`.
    """
    x = _values(tsa)
    removed = _order_set(x.size, mesh_orders, n_mesh_harmonics, n_shaft_orders,
                         n_sidebands) | {0}
    return keep_orders(x, set(range(x.size // 2 + 1)) - removed)


def sideband_table(tsa, mesh_order: int, n_sidebands: int = 3,
                   n_mesh_harmonics: int | None = None) -> np.ndarray:
    """Order-spectrum amplitudes around each mesh harmonic [signal unit].

    Row h − 1 holds A_{h z + s} for s = −S … S (column s + S): the mesh harmonic h z in the
    middle column, its shaft-order sidebands either side. Orders outside 0 … n/2 are NaN.

    Parameters
    ----------
    tsa : SynchronousAverage or array [signal unit]
    mesh_order : int [-]
        z, the mesh order of the shaft (teeth of its gear).
    n_sidebands : int [-]
        S.
    n_mesh_harmonics : int or None [-]
        H; None: all at or below n/2.

    Returns
    -------
    array (H, 2S + 1) [signal unit]
    """
    _, amp = order_spectrum(tsa)
    harmonics = mesh_orders_kept([mesh_order], 2 * (amp.size - 1), n_mesh_harmonics)
    table = np.full((len(harmonics), 2 * n_sidebands + 1), np.nan)
    for row, m in enumerate(harmonics):
        for col, s in enumerate(range(-n_sidebands, n_sidebands + 1)):
            if 0 <= m + s < amp.size:
                table[row, col] = amp[m + s]
    return table


def narrowband_envelope(tsa, mesh_order: int, *, harmonic: int = 1,
                        half_width_orders: int | None = None) -> np.ndarray:
    """Envelope of the TSA band-passed around a mesh harmonic [signal unit].

    b = the orders m with |m − h z| ≤ w (m ≥ 1) of the TSA; e_k = |b_k + i H[b]_k|, H the
    Hilbert transform (the magnitude of the analytic signal), as for NB4 (Zakrajsek, Handschuh
    & Decker 1994; Lebold et al. 2000). The band includes the mesh harmonic, so a steady mesh
    tone gives a constant envelope and an amplitude modulation shows as its variation.

    Parameters
    ----------
    tsa : SynchronousAverage or array [signal unit]
    mesh_order : int [-]
        z.
    harmonic : int [-]
        h, the mesh harmonic at the band's centre.
    half_width_orders : int or None [-]
        w; None: ⌊(z − 1)/2⌋, every order nearer to h z than to a neighbouring harmonic.
    """
    x = _values(tsa)
    w = (mesh_order - 1) // 2 if half_width_orders is None else int(half_width_orders)
    centre = harmonic * mesh_order
    nyquist = x.size // 2
    if centre + w >= nyquist:
        raise ValueError(f"band {centre} ± {w} reaches the Nyquist order {nyquist}")
    band = keep_orders(x, range(max(1, centre - w), centre + w + 1))
    return np.abs(hilbert(band))
