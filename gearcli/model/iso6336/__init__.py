"""ISO 6336 Method B load-capacity rating of a spur gear pair (docs/theory.md, "ISO 6336 rating").

Pure functions and frozen dataclasses, one job per module:

=================  ==========================================================================
``common``         editions, the factor row of the rating document, involute helpers
``factors``        ISO 6336-1 load factors: K_Hβ (Method C), K_Fβ, K_Hα/K_Fα (Method B)
``pitting``        ISO 6336-2 contact stress, influence factors and safety S_H
``bending``        ISO 6336-3 root stress (Method B closed form), influence factors, S_F
``material``       ISO 6336-5 allowable stress numbers σ_Hlim, σ_Flim by material and quality
``life``           load cycles, life-factor S-N curves, life at the minimum safety,
                   ISO 6336-6 Palmgren–Miner damage
``inspection``     span W_k, ball diameter, dimension over balls M_dK, chordal thickness
``rate``           the rating document of a pair from plain typed inputs
``spectrum``       a duty cycle (torque, speed, time share bins) rated by ISO 6336-6
``editions``       the edition-dependent factors under ISO 6336:2006 and :2019 side by side
=================  ==========================================================================

K_v by Method B is :mod:`gearcli.model.iso_kv` (a number here). Units: mm, N, N/mm² (MPa), µm
for deviations and roughness, min⁻¹ for speeds, h for lives — each stated per argument.
"""
