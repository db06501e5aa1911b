"""The pinion speed bands to avoid when a mesh harmonic is too near a mode: the remedy of a
failed resonance margin (`gearcli analyze`, `gearcli modal`; docs/theory.md, "Remedies of
failed checks")."""

from __future__ import annotations

from gearcli.results import Remedy, ResonanceMargin


def avoid_bands(pairs, margin_percent: float) -> list[tuple[float, float, str]]:
    """Pinion speed bands [rpm] to avoid: for each (excitation per pinion revolution, mode
    frequency [Hz], label) the speeds n1 where the excitation n1/60 × per_rev lies within
    ``margin_percent`` of the mode, f_n (1 ± m) × 60 / per_rev; lowest first."""
    m = margin_percent / 100.0
    return sorted(((f_n * (1.0 - m) * 60.0 / per_rev, f_n * (1.0 + m) * 60.0 / per_rev, label)
                   for per_rev, f_n, label in pairs if per_rev > 0.0 and f_n), key=lambda b: b[0])


def speed_bands(margins: tuple[ResonanceMargin, ...], margin_percent: float,
                teeth: int) -> list[tuple[float, float, str]]:
    """:func:`avoid_bands` of analyze's (harmonic, mode) pairs that violate the margin and
    have a resonant peak: the harmonic k f_z is k z1 excitations per pinion revolution."""
    return avoid_bands(((r.harmonic * teeth, r.mode_Hz,
                         f"{r.harmonic} x f_z near "
                         f"{'the mesh mode' if r.mode is None else f'mode {r.mode}'} at "
                         f"{r.mode_Hz:.1f} Hz")
                        for r in margins
                        if r.resonant_peak and r.margin_percent < margin_percent),
                       margin_percent)


def band_remedy(bands, margin_percent: float) -> Remedy | None:
    """The remedy naming the speed ``bands`` (:func:`avoid_bands`), or None without one."""
    if not bands:
        return None
    parts = [f"{lo:.0f}-{hi:.0f} rpm ({label})" for lo, hi, label in bands]
    return Remedy(kind="speed_band",
                  text=f"avoid pinion speeds {'; '.join(parts)} (±{margin_percent:g} % of "
                       "each mode)",
                  avoid_pinion_speed_rpm=tuple((lo, hi) for lo, hi, _ in bands))


def resonance_remedy(margins, margin_percent: float, teeth: int) -> Remedy | None:
    """The speed bands to avoid (:func:`speed_bands`), or None without a violated pair."""
    return band_remedy(speed_bands(margins or (), margin_percent, teeth), margin_percent)
