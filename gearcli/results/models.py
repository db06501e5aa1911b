"""The documents of `gearcli stress`, `gearcli modal` and `gearcli mesh`."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

from gearcli.results.fields import Document, metric_field


@dataclasses.dataclass(frozen=True, repr=False)  # Document's labelled repr
class Mode(Document):
    """One mode of the linearised model (the modal JSON's ``modes``)."""

    mode: int = metric_field("mode", 0)
    rigid_body: bool = metric_field("rigid_body", False)
    natural_frequency_Hz: float | None = metric_field("natural_frequency_Hz", None)
    damping_ratio: float | None = metric_field("damping_ratio", None)
    damped_frequency_Hz: float | None = metric_field("damped_frequency_Hz", None)
    undamped_frequency_Hz: float | None = metric_field("undamped_frequency_Hz", None)
    resonant_peak: bool = metric_field("resonant_peak", False)
    description: str = metric_field("description", "")
    shape: Mapping[str, float] = metric_field("shape", None)
    strain_energy_share: Mapping[str, float] = metric_field("strain_energy_share", None)
    kinetic_energy_share: Mapping[str, float] = metric_field("kinetic_energy_share", None)
    eigenvalues_1_s: tuple = metric_field("eigenvalues_1_s", ())  #: [[Re, Im], ...] [1/s]


@dataclasses.dataclass(frozen=True)
class Crossing(Document):
    """Where a mesh order meets a mode on the Campbell diagram."""

    order: str = metric_field("order", "")
    mode: int = metric_field("mode", 0)
    frequency_Hz: float = metric_field("frequency_Hz")
    pinion_speed_deg_s: float = metric_field("pinion_speed_deg_s")
    in_range: bool = metric_field("in_range", False)  #: inside the diagram's speed range


@dataclasses.dataclass(frozen=True)
class OrderMargin(Document):
    """A mesh order at the case speed against a mode."""

    order: str = metric_field("order", "")
    mode: int = metric_field("mode", 0)
    excitation_Hz: float = metric_field("excitation_Hz")
    mode_Hz: float = metric_field("mode_Hz")
    margin_percent: float = metric_field("margin_percent")
    resonant_peak: bool = metric_field("resonant_peak", False)


def _damping(key: str, label: str, unit: str):
    return metric_field(key, label=label, unit=unit)


@dataclasses.dataclass(frozen=True)
class Linearisation(Document):
    """The linearised model's mesh and dampers (the modal JSON's ``linearisation``): the mesh
    linearised at the static load (gearcli/pipeline/kernel_input.linearised_mesh), the motor
    curve and the quadratic load term at the case speed, friction off."""

    static_force_N: float = metric_field("static_force_N", metric="force_static_N")
    static_deflection_mm: float = metric_field("static_deflection_mm")
    pair_stiffness_N_mm: float = metric_field(
        "pair_stiffness_N_mm", label="pair stiffness k_pair (linearised), one pair",
        unit="N/mm")
    mesh_stiffness_N_mm: float = metric_field("mesh_stiffness_N_mm")
    #: None: the loaded mesh has no such zone (JSON null)
    single_pair_stiffness_N_mm: float | None = metric_field("single_pair_stiffness_N_mm")
    double_pair_stiffness_N_mm: float | None = metric_field("double_pair_stiffness_N_mm")
    mesh_damping_Ns_mm: float = _damping("mesh_damping_Ns_mm", "mesh damping c_mesh",
                                         "N*s/mm")
    motor_curve_damping_Nmms_rad: float = _damping(
        "motor_curve_damping_Nmms_rad", "motor curve, linearised c_m = |T|/ω0",
        "N*mm*s/rad")
    load_quadratic_damping_Nmms_rad: float = _damping(
        "load_quadratic_damping_Nmms_rad", "quadratic load term, linearised 2 c_q |ω_L|",
        "N*mm*s/rad")
    friction: str = metric_field("friction", "off", label="mesh friction in the linear model")


@dataclasses.dataclass(frozen=True)
class ModalDocument(Document):
    """`gearcli modal --json`: the linearised model, its :class:`Mode` s, the crossings of the
    mesh orders with them and the resonance-margin check."""

    schema_version: int = metric_field("schema_version", 0)
    case: str = metric_field("case", "")
    model: str = metric_field("model", "")
    drive: str = metric_field("drive", "")
    dofs: tuple[str, ...] = metric_field("dofs", ())
    shape_convention: str = metric_field("shape_convention", "")
    bodies: Mapping[str, float | None] = metric_field("bodies", {})
    linearisation: Linearisation = metric_field("linearisation", Linearisation(),
                                                nested=Linearisation)
    modes: tuple[Mode, ...] = metric_field("modes", (), nested=Mode)
    case_speed_deg_s: float | None = metric_field("case_speed_deg_s", None)
    speed_range_deg_s: tuple[float, float] = metric_field("speed_range_deg_s",
                                                          (math.nan, math.nan))
    orders_per_pinion_rev: Mapping[str, float] = metric_field("orders_per_pinion_rev", {})
    crossings: tuple[Crossing, ...] = metric_field("crossings", (), nested=Crossing)
    margins_at_case_speed: tuple[OrderMargin, ...] = metric_field(
        "margins_at_case_speed", (), nested=OrderMargin)
    #: each a :class:`gearcli.results.Check` as {name, value, limit, passed, checked, note}
    checks: tuple[Mapping[str, Any], ...] = metric_field("checks", ())
    passed: bool = metric_field("passed", True)


@dataclasses.dataclass(frozen=True)
class MeshSte(Document):
    """The loaded static transmission error over the analysed mesh cycles [µm]."""

    mean_um: float = metric_field("mean_um", metric="ste_mean_um")
    peak_to_peak_um: float = metric_field("peak_to_peak_um", metric="ste_peak_to_peak_um")
    peak_to_peak_arcsec: float = metric_field("peak_to_peak_arcsec",
                                              metric="ste_peak_to_peak_arcsec")
    harmonics_um: Mapping[str, float] = metric_field("harmonics_um", {})  #: "1fz": amplitude
    unloaded_te_peak_to_peak_um: float = metric_field("unloaded_te_peak_to_peak_um")


@dataclasses.dataclass(frozen=True)
class MeshStiffness(Document):
    """The mesh stiffness of the loaded contact against ISO 6336-1 [N/mm]."""

    mesh_mean_N_mm: float = metric_field("mesh_mean_N_mm")
    single_pair_zone_N_mm: float | None = metric_field("single_pair_zone_N_mm", None)
    double_pair_zone_N_mm: float | None = metric_field("double_pair_zone_N_mm", None)
    iso6336_single_pair_c_prime_b_N_mm: float = metric_field(
        "iso6336_single_pair_c_prime_b_N_mm")
    iso6336_mean_c_gamma_alpha_b_N_mm: float = metric_field("iso6336_mean_c_gamma_alpha_b_N_mm")


@dataclasses.dataclass(frozen=True)
class MeshSharing(Document):
    """How many pairs carry the load over the cycle, and up to which static force one pair
    alone carries it somewhere in the cycle (model/ltca.single_pair_limit; docs/theory.md §4b,
    "Corner contact"): above that force extended contact at the tip corners closes the
    single-pair zone. None: a second pair never touches within the gap tables (with extended
    contact: F* is above the contact model's range, not "any load"; ``single_pair_limit_note``
    says which)."""

    pairs_in_contact_min: int = metric_field("pairs_in_contact_min", 0)
    pairs_in_contact_max: int = metric_field("pairs_in_contact_max", 0)
    single_pair_share: float = metric_field("single_pair_share")
    single_pair_limit_N: float | None = metric_field("single_pair_limit_N", None)
    single_pair_limit_N_per_mm: float | None = metric_field("single_pair_limit_N_per_mm", None)
    #: why the limit is 0 or None ("" when it is a force)
    single_pair_limit_note: str = metric_field(
        "single_pair_limit_note", "", label="why the single-pair limit is not a force")


@dataclasses.dataclass(frozen=True)
class IsoResonance(Document):
    """ISO 6336-1 Method B resonance data of the pair (gearcli/pipeline/mesh_input.iso_dynamic)
    and, with a case speed, its resonance ratio and K_v."""

    reduced_mass_kg_mm: float = metric_field("reduced_mass_kg_mm")
    low_load_factor: float = metric_field("low_load_factor")
    c_prime_N_mm_um: float = metric_field("c_prime_N_mm_um")
    c_gamma_alpha_N_mm_um: float = metric_field("c_gamma_alpha_N_mm_um")
    line_load_N_mm: float = metric_field("line_load_N_mm")
    eps_gamma: float = metric_field("eps_gamma")
    resonance_speed_rpm: float = metric_field("resonance_speed_rpm")
    f_pb_eff_um: float = metric_field("f_pb_eff_um")
    f_f_eff_um: float = metric_field("f_f_eff_um")
    tip_relief_um: float = metric_field("tip_relief_um")
    tip_relief_source: str = metric_field("tip_relief_source", "")
    B_p: float = metric_field("B_p")
    B_f: float = metric_field("B_f")
    B_k: float = metric_field("B_k")
    pinion_speed_rpm: float | None = metric_field("pinion_speed_rpm", None, omit_none=True)
    resonance_ratio: float | None = metric_field("resonance_ratio", None, omit_none=True)
    k_v: float | None = metric_field("k_v", None, omit_none=True)
    speed_range: str | None = metric_field("speed_range", None, omit_none=True)


@dataclasses.dataclass(frozen=True)
class HarrisMap(Document):
    """STE peak to peak against the static force (`gearcli mesh --harris`); None where the
    load has no static equilibrium inside the contact tables (outside the model's range)."""

    force_N: tuple[float, ...] = metric_field("force_N", ())
    ste_peak_to_peak_um: tuple[float | None, ...] = metric_field("ste_peak_to_peak_um", ())


@dataclasses.dataclass(frozen=True)
class PeFe(Document):
    """One quantity by the tooth law (potential energy, PE) and by the FE model, and
    FE/PE − 1."""

    pe: float = metric_field("pe")
    fe: float = metric_field("fe")
    fe_over_pe_minus_1: float | None = metric_field("fe_over_pe_minus_1")  #: None: PE is 0


@dataclasses.dataclass(frozen=True)
class FeCheck(Document):
    """`gearcli mesh --method fe`: the tooth law against the finite-element model of the pair
    (docs/theory.md, "Finite-element check of the tooth compliance"), both with rigid-engagement
    load sharing and no profile modifications, at the case's line load and the FE's plane
    state."""

    line_load_N_mm: float = metric_field("line_load_N_mm")
    plane_strain: bool = metric_field("plane_strain", True)
    pitch_pair_stiffness_N_mm: PeFe = metric_field("pitch_pair_stiffness_N_mm", PeFe(),
                                                   nested=PeFe)
    mesh_mean_stiffness_N_mm: PeFe = metric_field("mesh_mean_stiffness_N_mm", PeFe(),
                                                  nested=PeFe)
    ste_peak_to_peak_um: PeFe = metric_field("ste_peak_to_peak_um", PeFe(), nested=PeFe)
    teeth_at_pitch_N_mm: PeFe = metric_field("teeth_at_pitch_N_mm", PeFe(), nested=PeFe)
    contact_at_pitch_N_mm: PeFe = metric_field("contact_at_pitch_N_mm", PeFe(), nested=PeFe)
    #: with the case's gaps (extended contact at the tip corners, modifications), same LTCA
    loaded_ste_peak_to_peak_um: PeFe = metric_field("loaded_ste_peak_to_peak_um", PeFe(),
                                                    nested=PeFe)
    #: share of the roll positions with one pair in contact, same LTCA
    single_pair_share: PeFe = metric_field("single_pair_share", PeFe(), nested=PeFe)
    fe_dofs: tuple[int, ...] = metric_field("fe_dofs", ())  #: model sizes (pinion, gear)
    cache_hits: int = metric_field("cache_hits", 0)  #: gear models read from the cache
    cache_misses: int = metric_field("cache_misses", 0)  #: gear models solved
    seconds: float = metric_field("seconds")  #: wall time of the FE part (reported only)
    note: str = metric_field("note", "")


@dataclasses.dataclass(frozen=True)
class FaultedRevolution(Document):
    """The faulted mesh over one pinion revolution (`gearcli mesh` of a case with faults;
    docs/theory.md, "Tooth faults"): stiffness and STE extremes against the healthy pair."""

    faults: tuple[str, ...] = metric_field("faults", ())  #: "kind gear tooth i"
    points: int = metric_field("points", 0)  #: roll positions over the revolution
    stiffness_min_N_mm: float = metric_field("stiffness_min_N_mm")
    stiffness_healthy_min_N_mm: float = metric_field("stiffness_healthy_min_N_mm")
    stiffness_largest_drop: float = metric_field("stiffness_largest_drop")  #: 1 − k_f/k [-]
    stiffness_largest_drop_at_roll_mm: float = metric_field("stiffness_largest_drop_at_roll_mm")
    ste_peak_to_peak_um: float = metric_field("ste_peak_to_peak_um")  #: where a pair carries
    ste_healthy_peak_to_peak_um: float = metric_field("ste_healthy_peak_to_peak_um")
    no_contact_share: float = metric_field("no_contact_share", 0.0)  #: share with k_f = 0 [-]


@dataclasses.dataclass(frozen=True, repr=False)  # Document's labelled repr
class MeshSummary(Document):
    """A quasi-static loaded contact analysis (`gearcli mesh --json`): the static normal force,
    the STE, the mesh stiffness against ISO 6336-1 and the ISO 6336-1 Method B data."""

    schema_version: int = metric_field("schema_version", 0)
    case: str = metric_field("case", "")
    contact_law: str = metric_field("contact_law", "")
    force_N: float = metric_field("force_N")
    mesh_cycles: int = metric_field("mesh_cycles", 0)
    ste: MeshSte = metric_field("ste", MeshSte(), nested=MeshSte)
    stiffness: MeshStiffness = metric_field("stiffness", MeshStiffness(), nested=MeshStiffness)
    sharing: MeshSharing = metric_field("sharing", MeshSharing(), nested=MeshSharing)
    iso6336_method_b: IsoResonance = metric_field("iso6336_method_b", IsoResonance(),
                                                  nested=IsoResonance)
    notes: tuple[str, ...] = metric_field("notes", ())
    harris: HarrisMap | None = metric_field("harris", None, omit_none=True, nested=HarrisMap)
    fe_check: FeCheck | None = metric_field("fe_check", None, omit_none=True, nested=FeCheck)
    #: with faults: the faulted stiffness and STE over one pinion revolution
    faulted_revolution: FaultedRevolution | None = metric_field(
        "faulted_revolution", None, omit_none=True, nested=FaultedRevolution)
