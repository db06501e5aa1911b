"""Plain typed inputs of an ISO 6336 rating (engineering units, documented per field).

docs/theory.md, "ISO 6336 rating". Built by the caller (a case file's ``rating:`` section, a
script, a test); nothing here reads files.
"""

from __future__ import annotations

from dataclasses import dataclass

from gearcli.model.iso6336.common import Edition
from gearcli.model.iso6336.material import MaterialKind, Quality

__all__ = ["GearInput", "RatingInput"]


@dataclass(frozen=True)
class GearInput:
    """One gear of the rated pair (external spur gear)."""

    teeth: int  #: z [-]
    face_width_mm: float  #: b [mm]
    profile_shift: float = 0.0  #: x [-]
    tip_diameter_mm: float | None = None  #: d_a [mm]; None: d + 2 m (h_aP* + x)
    material: MaterialKind = MaterialKind.CASE_HARDENED  #: ISO 6336-5 group
    quality: Quality = Quality.MQ  #: ISO 6336-5 quality grade
    surface_hardness: float | None = None  #: in the ISO 6336-5 row's scale (HV or HBW)
    sigma_h_lim_MPa: float | None = None  #: σ_Hlim [N/mm²]; None: ISO 6336-5 from hardness
    sigma_f_lim_MPa: float | None = None  #: σ_Flim [N/mm²]; None: ISO 6336-5 from hardness
    youngs_MPa: float = 206000.0  #: E [N/mm²]
    poisson: float = 0.3  #: ν [-]
    proof_stress_MPa: float | None = None  #: σ_0.2 [N/mm²] (St, V, GGG, GTS: notch sensitivity)
    brinell_hardness: float | None = None  #: HB [-] of a through-hardened gear (work hardening)
    flank_roughness_rz_um: float = 3.0  #: R_zH, flank mean roughness [µm]
    root_roughness_rz_um: float = 10.0  #: R_zF, root mean roughness [µm]
    base_pitch_deviation_um: float = 0.0  #: f_pb [µm] (transverse load factor, running-in)
    accuracy_grade: int = 6  #: ISO 1328 accuracy grade [-] (deep tooth factor)
    rim_thickness_mm: float | None = None  #: s_R below the root [mm]; None: solid gear
    idler: bool = False  #: both flanks loaded once per revolution (alternating bending)
    mean_stress_sensitivity: float | None = None  #: M [-] for Y_M (2019), None: by material
    root_stress_ratio: float | None = None  #: R [-] of reversed bending; None: −1.2 idler, else 0
    contacts_per_revolution: float = 1.0  #: load cycles of the flank per revolution [-]
    thickness_allowances_mm: tuple[float, float] = (0.0, 0.0)  #: (upper, lower) A_sn [mm]
    ball_diameter_mm: float | None = None  #: D_M [mm]; None: the next standard size

    def __post_init__(self):
        _positive(self, "teeth", "face_width_mm", "youngs_MPa", "contacts_per_revolution")
        if not 0.0 <= self.poisson < 0.5:
            raise ValueError(f"poisson {self.poisson:g} outside 0 … 0.5")


@dataclass(frozen=True)
class RatingInput:
    """A spur pair, its load and life: everything an ISO 6336 Method B rating needs."""

    module_mm: float  #: m [mm]
    pinion: GearInput  #: the gear of ``pinion_torque_Nm`` and ``pinion_speed_rpm``
    gear: GearInput
    pinion_torque_Nm: float  #: T1 per mesh path [N·m] (a planetary sun: total / planets)
    pinion_speed_rpm: float  #: n1 [min⁻¹], relative to the carrier where there is one
    life_h: float  #: required life L_h [h]
    pressure_angle_deg: float = 20.0  #: α [deg]
    centre_distance_mm: float | None = None  #: a_w [mm]; None: from x1 + x2 without backlash
    addendum_coefficient: float = 1.0  #: h_aP* [-] of the basic rack
    dedendum_coefficient: float = 1.25  #: h_fP* [-] of the tool (basic rack dedendum)
    root_radius_coefficient: float = 0.38  #: ρ_fP* [-] of the tool tip
    application_factor: float = 1.0  #: K_A [-]
    load_sharing_factor: float = 1.0  #: K_γ [-] (planets: the mesh load / mean mesh load)
    dynamic_factor: float = 1.0  #: K_v [-] (ISO 6336-1 Method B: gearcli.model.iso_kv)
    face_load_factor: float | None = None  #: K_Hβ [-]; None: Method C from the misalignments
    transverse_load_factor: float | None = None  #: K_Hα = K_Fα [-]; None: Method B
    mesh_stiffness_N_mm_um: float = 20.0  #: c_γα [N/(mm·µm)] (K_Hα; c_γβ = 0.85 c_γα for K_Hβ)
    shaft_misalignment_um: float = 0.0  #: f_sh [µm] (Method C K_Hβ)
    manufacturing_misalignment_um: float = 0.0  #: f_ma [µm] (Method C K_Hβ)
    viscosity_40_mm2_s: float = 220.0  #: lubricant ν40 [mm²/s]
    minimum_safety_pitting: float = 1.0  #: S_H,min [-]
    minimum_safety_bending: float = 1.0  #: S_F,min [-]
    pitting_permitted: bool = False  #: limited pitting permitted (Z_NT curve)
    optimum_long_life: bool = False  #: life factors stay 1.0 beyond the knee (else 0.85 at 1e10)
    edition: Edition = Edition.ISO2019  #: ISO 6336 edition followed where they differ

    def __post_init__(self):
        _positive(self, "module_mm", "pinion_torque_Nm", "pinion_speed_rpm", "life_h",
                  "application_factor", "load_sharing_factor", "dynamic_factor",
                  "mesh_stiffness_N_mm_um", "viscosity_40_mm2_s", "minimum_safety_pitting",
                  "minimum_safety_bending")
        object.__setattr__(self, "edition", Edition(self.edition))


def _positive(obj, *names: str) -> None:
    """ValueError naming the first field of ``names`` that is not > 0."""
    for name in names:
        if not getattr(obj, name) > 0:
            raise ValueError(f"{name} must be > 0, got {getattr(obj, name)!r}")
