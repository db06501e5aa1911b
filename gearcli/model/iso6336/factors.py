"""ISO 6336-1 load factors of a spur pair: K_Hβ (Method C), K_Fβ, K_Hα and K_Fα (Method B).

docs/theory.md, "ISO 6336 rating", §1. Clauses are those of ISO 6336-1:2006; the 2019
edition keeps these relations for spur gears (its Method C for K_Hβ adds helix-modification
options not modelled here). K_v by Method B is :func:`gearcli.model.iso_kv.dynamic_factor`.

Running-in allowances (ISO 6336-1, running-in allowances y_β of the face load factor and y_α of
the transverse load factor; y_α = 160/σ_Hlim f_pb is eq. (75), 8.3.5.1, of the 2006 edition as
corrected by its Cor.1:2008):

==================  =========================================  ==============================
material group      y_β (helix, of F_βx)                        y_α (profile, of f_pb)
==================  =========================================  ==============================
St, V, GGG, GTS     320/σ_Hlim · F_βx, v ≤ 5 m/s: no limit;     160/σ_Hlim · f_pb, same
                    5 < v ≤ 10: ≤ 25600/σ_Hlim; v > 10:         v classes: ≤ 12800/σ_Hlim,
                    ≤ 12800/σ_Hlim                             ≤ 6400/σ_Hlim
GG                  0.55 F_βx (≤ 45 / 22 µm)                    0.275 f_pb (≤ 22 / 11 µm)
Eh, IF, NT, NV      0.15 F_βx ≤ 6 µm                            0.075 f_pb ≤ 3 µm
==================  =========================================  ==============================

A pair of different materials takes the mean of the two gears' allowances.
"""

from __future__ import annotations

import math

from gearcli.model.iso6336.material import GREY_IRON_LIKE, THROUGH_HARDENED, MaterialKind

__all__ = ["running_in_helix", "running_in_profile", "face_load_factor_method_c",
           "bending_face_load_factor", "transverse_load_factors"]


def _running_in(kind: MaterialKind, sigma_h_lim: float, deviation_um: float, v_m_s: float,
                coeffs: tuple) -> float:
    """Shared table lookup of :func:`running_in_helix` and :func:`running_in_profile`.

    ``coeffs`` = (St/V factor·σ_Hlim, its caps·σ_Hlim for 5 < v ≤ 10 and v > 10 m/s,
    GG factor, its caps [µm], Eh/IF/NT/NV factor, its cap [µm]).
    """
    through_k, through_caps, grey_k, grey_caps, hard_k, hard_cap = coeffs
    if kind in THROUGH_HARDENED:
        y, caps = through_k / sigma_h_lim * deviation_um, [c / sigma_h_lim for c in through_caps]
    elif kind in GREY_IRON_LIKE:
        y, caps = grey_k * deviation_um, grey_caps
    else:
        return min(hard_k * deviation_um, hard_cap)
    if v_m_s > 10.0:
        return min(y, caps[1])
    return min(y, caps[0]) if v_m_s > 5.0 else y


def running_in_helix(kind: MaterialKind, sigma_h_lim_MPa: float, f_beta_x_um: float,
                     v_m_s: float) -> float:
    """Running-in allowance y_β [µm] of one gear (ISO 6336-1:2006, face load factor,
    running-in allowance y_β).

    Parameters: material group; σ_Hlim [N/mm²]; initial equivalent misalignment F_βx [µm];
    pitch-line velocity v [m/s]. Table in the module notes (St/V: 320/σ_Hlim F_βx capped at
    25600/σ_Hlim for 5 < v ≤ 10 m/s and 12800/σ_Hlim above; Eh/IF/NT/NV: 0.15 F_βx ≤ 6 µm).
    """
    return _running_in(MaterialKind(kind), sigma_h_lim_MPa, f_beta_x_um, v_m_s,
                       (320.0, (25600.0, 12800.0), 0.55, (45.0, 22.0), 0.15, 6.0))


def running_in_profile(kind: MaterialKind, sigma_h_lim_MPa: float, f_pb_um: float,
                       v_m_s: float) -> float:
    """Running-in allowance y_α [µm] of one gear (ISO 6336-1:2006, 8.3.5.1, eq. (75)
    and the limits that follow it).

    Parameters: material group; σ_Hlim [N/mm²]; base pitch deviation f_pb [µm]; pitch-line
    velocity v [m/s]. St/V: y_α = 160/σ_Hlim f_pb (≤ 12800/σ_Hlim for 5 < v ≤ 10 m/s, ≤
    6400/σ_Hlim above); GG: 0.275 f_pb; Eh/IF/NT/NV: y_α = 0.075 f_pb ≤ 3 µm.
    """
    return _running_in(MaterialKind(kind), sigma_h_lim_MPa, f_pb_um, v_m_s,
                       (160.0, (12800.0, 6400.0), 0.275, (22.0, 11.0), 0.075, 3.0))


def face_load_factor_method_c(line_load_N_mm: float, c_gamma_beta_N_mm_um: float,
                              f_sh_um: float, f_ma_um: float, y_beta_um: float | None = None,
                              f_h_beta_um: float = 0.0,
                              kinds: tuple[MaterialKind, MaterialKind] | None = None,
                              sigma_h_lim_MPa: tuple[float, float] | None = None,
                              v_m_s: float = 0.0) -> tuple[float, float, float]:
    """Face load factor K_Hβ [-] by Method C (ISO 6336-1:2006, clause 7 Method C;
    F_βx is eq. (53), 7.5.2.3, as corrected by Cor.1:2008, here without helix modification).

    Parameters
    ----------
    line_load_N_mm : F_m/b = F_t K_A K_γ K_v / b [N/mm]
    c_gamma_beta_N_mm_um : mesh stiffness c_γβ = 0.85 c_γα [N/(mm·µm)]
    f_sh_um : component of the mesh misalignment from shaft and body deformation f_sh [µm]
    f_ma_um : manufacturing and assembly misalignment f_ma [µm]
    y_beta_um : running-in allowance y_β [µm]; None: mean of the two gears'
        :func:`running_in_helix` (needs ``kinds``, ``sigma_h_lim_MPa``, ``v_m_s``)
    f_h_beta_um : helix slope deviation f_Hβ [µm] for the minimum F_βx,min

    Returns
    -------
    (K_Hβ [-], F_βx [µm], F_βy [µm]) with
    F_βx = max(1.33 f_sh + f_ma, F_βx,min), F_βx,min = max(0.005 F_m/b, 0.5 f_Hβ) (no helix
    modification: B1 = B2 = 1), F_βy = F_βx − y_β, and
    K_Hβ = 1 + c_γβ F_βy / (2 F_m/b) when that is ≤ 2, else √(2 c_γβ F_βy / (F_m/b)).
    """
    f_beta_x = max(1.33 * f_sh_um + f_ma_um, 0.005 * line_load_N_mm, 0.5 * f_h_beta_um)
    if y_beta_um is None:
        if kinds is None or sigma_h_lim_MPa is None:
            raise ValueError("y_β not given: give both gears' material kinds and σ_Hlim")
        y_beta_um = 0.5 * sum(running_in_helix(k, s, f_beta_x, v_m_s)
                              for k, s in zip(kinds, sigma_h_lim_MPa, strict=True))
    f_beta_y = max(f_beta_x - y_beta_um, 0.0)
    k = 1.0 + c_gamma_beta_N_mm_um * f_beta_y / (2.0 * line_load_N_mm)
    if k > 2.0:
        k = math.sqrt(2.0 * c_gamma_beta_N_mm_um * f_beta_y / line_load_N_mm)
    return k, f_beta_x, f_beta_y


def bending_face_load_factor(k_h_beta: float, face_width_mm: float,
                             tooth_height_mm: float) -> float:
    """K_Fβ = K_Hβ^N_F [-], N_F = (b/h)² / (1 + b/h + (b/h)²)
    (ISO 6336-1:2006, face load factor for tooth root stress K_Fβ).

    b the face width [mm] (the smaller of the pair), h the tooth height [mm] (h_a + h_f); b/h
    is taken as at least 3 (ISO: "use b/h = 3 when b/h < 3").
    """
    r = max(face_width_mm / tooth_height_mm, 3.0)
    n_f = r * r / (1.0 + r + r * r)
    return k_h_beta ** n_f


def transverse_load_factors(eps_alpha: float, c_gamma_alpha_N_mm_um: float, f_pb_um: float,
                            y_alpha_um: float, line_load_N_mm: float,
                            z_eps: float) -> tuple[float, float]:
    """Transverse load factors (K_Hα, K_Fα) [-] by Method B (ISO 6336-1:2006, 8.3).

    Parameters
    ----------
    eps_alpha : transverse contact ratio ε_α = ε_γ (spur) [-]
    c_gamma_alpha_N_mm_um : mesh stiffness c_γα [N/(mm·µm)]
    f_pb_um : base pitch deviation f_pb [µm] (the larger of the pair)
    y_alpha_um : running-in allowance y_α [µm] (:func:`running_in_profile`)
    line_load_N_mm : F_tH/b = F_t K_A K_γ K_v K_Hβ / b [N/mm]
    z_eps : contact ratio factor Z_ε [-] (upper limit of K_Hα)

    Notes
    -----
    ε_γ ≤ 2: K = ε_γ/2 (0.9 + 0.4 c_γα (f_pb − y_α)/(F_tH/b)); ε_γ > 2:
    K = 0.9 + 0.4 √(2(ε_γ − 1)/ε_γ) c_γα (f_pb − y_α)/(F_tH/b). Limits: 1 ≤ K_Hα ≤
    ε_γ/(ε_α Z_ε²), 1 ≤ K_Fα ≤ ε_γ/(ε_α Y_ε) with Y_ε = 0.25 + 0.75/ε_α.
    """
    eg = eps_alpha
    term = c_gamma_alpha_N_mm_um * (f_pb_um - y_alpha_um) / line_load_N_mm
    k = eg / 2.0 * (0.9 + 0.4 * term) if eg <= 2.0 else (
        0.9 + 0.4 * math.sqrt(2.0 * (eg - 1.0) / eg) * term)
    y_eps = 0.25 + 0.75 / eps_alpha
    k_h = min(max(k, 1.0), eg / (eps_alpha * z_eps * z_eps))
    k_f = min(max(k, 1.0), eg / (eps_alpha * y_eps))
    return k_h, k_f
