"""Classical gear condition-monitoring metrics, one function each.

docs/theory.md, "Condition-monitoring signals", §5. Pure functions of arrays, no I/O. The
sources: Stewart (1977) for FM0 and FM4, Martin (1989) for M6A and M8A, Zakrajsek, Townsend &
Decker (1993, NASA TM-105950) for NA4 and the comparison of all of these on pitting data,
Zakrajsek, Handschuh & Decker (1994) for NB4, Swansson (1980) for the energy ratio, and the
review of Lebold, McClintic, Campbell, Byington & Maynard (2000), which fixes the
pre-processing of each (which signal, which components removed) and defines the sideband
level factor and sideband index.

With x̄ the mean of N samples x_i, the central moments are μ_k = (1/N) Σ_i (x_i − x̄)^k. A
constant signal (μ_2 = 0) gives NaN for every ratio that divides by it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from gearcli.model.monitoring.orders import mesh_orders_kept, order_spectrum

__all__ = ["rms", "peak_to_peak", "normalised_moment", "kurtosis", "crest_factor", "fm0", "fm4",
           "m6a", "m8a", "na4", "nb4", "energy_ratio", "sideband_level_factor",
           "sideband_index"]


def _array(x) -> np.ndarray:
    a = np.asarray(getattr(x, "values", x), dtype=float)
    if a.ndim != 1 or a.size < 2:
        raise ValueError("a 1-D signal of at least two samples is needed")
    return a


def _ratio(num: float, den: float) -> float:
    return num / den if den > 0.0 else math.nan


def rms(x) -> float:
    """Root mean square [signal unit]: RMS = √((1/N) Σ_i x_i²) (Lebold et al. 2000).

    Parameters
    ----------
    x : array [signal unit]
    """
    a = _array(x)
    return float(np.sqrt(np.mean(a * a)))


def peak_to_peak(x) -> float:
    """PP = max_i x_i − min_i x_i [signal unit]."""
    a = _array(x)
    return float(a.max() - a.min())


def normalised_moment(x, order: int) -> float:
    """Normalised central moment μ_k / μ_2^{k/2} [-].

    Equal to N^{k/2 − 1} Σ (x_i − x̄)^k / [Σ (x_i − x̄)²]^{k/2}, the form in which Stewart (1977),
    Martin (1989) and Zakrajsek et al. (1993) write FM4 (k = 4), M6A (k = 6), M8A (k = 8).

    Parameters
    ----------
    x : array [signal unit]
    order : int [-]
        k ≥ 2.
    """
    a = _array(x)
    d = a - a.mean()
    m2 = float(np.mean(d * d))
    return _ratio(float(np.mean(d**order)), m2 ** (order / 2.0))


def kurtosis(x) -> float:
    """Kurtosis [-]: N Σ (x_i − x̄)⁴ / [Σ (x_i − x̄)²]² = μ_4/μ_2² (Lebold et al. 2000).

    3 for Gaussian noise, 1.5 for a sinusoid; no bias correction (the population form).
    """
    return normalised_moment(x, 4)


def crest_factor(x) -> float:
    """Crest factor [-]: CF = max_i |x_i| / RMS (Lebold et al. 2000); √2 for a sinusoid."""
    a = _array(x)
    return _ratio(float(np.max(np.abs(a))), rms(a))


def fm0(tsa, mesh_orders: Sequence[int], n_mesh_harmonics: int | None = None) -> float:
    """FM0, the zero-order figure of merit [-] (Stewart 1977; Zakrajsek et al. 1993).

    FM0 = PP / Σ_{h=1}^{H} A_{h z}: the peak-to-peak of the TSA over the sum of the amplitudes
    of the mesh harmonics (for several meshes on the shaft, all their harmonics). 2 for a pure
    mesh tone; heavy wear or a broken tooth raises PP without raising the mesh harmonics.

    Parameters
    ----------
    tsa : SynchronousAverage or array [signal unit]
        One revolution.
    mesh_orders : sequence of int [-]
        z of each mesh on the shaft.
    n_mesh_harmonics : int or None [-]
        H; None: all at or below n/2.
    """
    a = _array(tsa)
    _, amp = order_spectrum(a)
    harmonics = mesh_orders_kept(mesh_orders, a.size, n_mesh_harmonics)
    return _ratio(peak_to_peak(a), float(amp[harmonics].sum()))


def fm4(difference) -> float:
    """FM4 [-]: the normalised kurtosis of the difference signal d (Stewart 1977; Zakrajsek
    et al. 1993), N Σ (d_i − d̄)⁴ / [Σ (d_i − d̄)²]². About 3 for a healthy gear (a Gaussian-like
    d); a defect on one or a few teeth makes d peaked and FM4 larger.

    Parameters
    ----------
    difference : array [signal unit]
        d (:func:`gearcli.model.monitoring.orders.difference_signal`).
    """
    return normalised_moment(difference, 4)


def m6a(difference) -> float:
    """M6A [-]: N² Σ (d_i − d̄)⁶ / [Σ (d_i − d̄)²]³ of the difference signal d (Martin 1989;
    Zakrajsek et al. 1993). 15 for Gaussian d."""
    return normalised_moment(difference, 6)


def m8a(difference) -> float:
    """M8A [-]: N³ Σ (d_i − d̄)⁸ / [Σ (d_i − d̄)²]⁴ of the difference signal d (Martin 1989;
    Zakrajsek et al. 1993). 105 for Gaussian d."""
    return normalised_moment(difference, 8)


def _kurtosis_over_reference_variance(x, reference: Sequence) -> float:
    """μ_4(x) / ((1/M) Σ_j μ_2(x_j))², x_j the M reference records."""
    a = _array(x)
    if len(reference) == 0:
        raise ValueError("at least one reference record is needed")
    variances = [float(np.var(_array(r))) for r in reference]
    d = a - a.mean()
    return _ratio(float(np.mean(d**4)), float(np.mean(variances)) ** 2)


def na4(residual, reference_residuals: Sequence) -> float:
    """NA4 [-]: kurtosis of the residual signal over the run-averaged variance (Zakrajsek,
    Townsend & Decker 1993).

    NA4 = N Σ_i (r_iM − r̄_M)⁴ / {(1/M) Σ_{j=1}^{M} [Σ_i (r_ij − r̄_j)²]}²
        = μ_4(r) / (mean_j μ_2(r_j))²

    In Zakrajsek et al. the M records are those of the run so far, the current one included,
    so NA4 grows while the damage grows instead of renormalising itself. gearcli passes the
    records to normalise by: the residuals of a baseline (healthy) run, or, for the original
    form, the run's own records 1 … M.

    Parameters
    ----------
    residual : array [signal unit]
        r of the record assessed (:func:`gearcli.model.monitoring.orders.residual_signal`).
    reference_residuals : sequence of arrays [signal unit]
        r_1 … r_M, the records whose mean variance normalises.
    """
    return _kurtosis_over_reference_variance(residual, reference_residuals)


def nb4(envelope, reference_envelopes: Sequence) -> float:
    """NB4 [-]: NA4's form applied to the narrow-band envelope (Zakrajsek, Handschuh & Decker
    1994; Lebold et al. 2000).

    NB4 = N Σ_i (E_iM − Ē_M)⁴ / {(1/M) Σ_{j=1}^{M} [Σ_i (E_ij − Ē_j)²]}², E the envelope of the
    TSA band-passed around the mesh frequency
    (:func:`gearcli.model.monitoring.orders.narrowband_envelope`).

    Parameters
    ----------
    envelope : array [signal unit]
    reference_envelopes : sequence of arrays [signal unit]
    """
    return _kurtosis_over_reference_variance(envelope, reference_envelopes)


def energy_ratio(difference, regular) -> float:
    """Energy ratio [-]: ER = RMS(d) / RMS(r_reg) (Swansson 1980; Lebold et al. 2000), d the
    difference signal, r_reg the regular signal; grows as energy moves from the regular mesh
    components into the rest.

    Parameters
    ----------
    difference, regular : arrays [signal unit]
    """
    return _ratio(rms(difference), rms(regular))


def _first_sidebands(tsa, mesh_order: int) -> float:
    _, amp = order_spectrum(tsa)
    if not 1 <= mesh_order < amp.size - 1:
        raise ValueError(f"mesh order {mesh_order} leaves no room for its sidebands")
    return float(amp[mesh_order - 1] + amp[mesh_order + 1])


def sideband_level_factor(tsa, mesh_order: int) -> float:
    """Sideband level factor [-] (Lebold et al. 2000): the sum of the first-order sideband
    amplitudes about the fundamental mesh order over the standard deviation of the TSA,

    SLF = (A_{z−1} + A_{z+1}) / σ(x̄),   σ² = μ_2 of the TSA.

    Parameters
    ----------
    tsa : SynchronousAverage or array [signal unit]
    mesh_order : int [-]
        z.
    """
    a = _array(tsa)
    return _ratio(_first_sidebands(a, mesh_order), float(np.std(a)))


def sideband_index(tsa, mesh_order: int) -> float:
    """Sideband index [signal unit] (Lebold et al. 2000): the mean amplitude of the first-order
    sidebands about the fundamental mesh order, SI = (A_{z−1} + A_{z+1}) / 2.

    Parameters
    ----------
    tsa : SynchronousAverage or array [signal unit]
    mesh_order : int [-]
        z.
    """
    return 0.5 * _first_sidebands(tsa, mesh_order)
