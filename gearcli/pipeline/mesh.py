"""`gearcli mesh`: quasi-static loaded tooth contact of the case's pair (model.ltca), no dynamics.

The same gaps (profile modifications, extended contact) and contact law as `simulate`, at the
case's static load (or a given one): loaded static transmission error, load sharing, pair and
mesh stiffness beside ISO 6336-1, and the Harris map on request.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gearcli.case.load import LoadedCase, load_case
from gearcli.errors import CaseError, GearcliError
from gearcli.model.gap import slot_layout
from gearcli.model.ltca import (
    LoadedMesh,
    LoadTooSmallError,
    harris_map,
    impact_law,
    loaded_mesh,
    single_pair_limit,
    tooth_law,
)
from gearcli.model.stiffness import IsoStiffness
from gearcli.pipeline.capabilities import not_included
from gearcli.pipeline.geometry import GeometryResult, run_geometry
from gearcli.pipeline.kernel_input import case_gap_tables
from gearcli.pipeline.mesh_faults import RevolutionColumns, faulted_revolution, revolution_summary
from gearcli.pipeline.mesh_input import (
    bore_notes,
    case_mesh,
    contact_stiffness,
    iso_stiffness,
    tooth_stiffness,
)
from gearcli.results.metrics import json_number
from gearcli.results.models import (
    FeCheck,
    HarrisMap,
    IsoResonance,
    MeshSharing,
    MeshSte,
    MeshStiffness,
    MeshSummary,
)

ARCSEC_PER_RAD = 180.0 / math.pi * 3600.0


@dataclass(frozen=True, repr=False)
class MeshAnalysis:
    """Quasi-static loaded tooth contact of a pair (`gearcli mesh`, :func:`gearcli.mesh`):
    :attr:`summary` STE [µm], mesh stiffness [N/mm] against ISO 6336-1 c′b and c_γα b, n_E1
    and K_v; :attr:`table` per pinion roll position (mesh.csv); ``notes`` what it leaves out."""

    source: LoadedCase  #: the case analysed
    name: str
    geometry: GeometryResult
    law: str  #: contact law of the pairs
    loaded: LoadedMesh
    iso: IsoStiffness
    harris: tuple[np.ndarray, np.ndarray] | None  #: loads [N], STE peak-to-peak [mm]
    notes: tuple[str, ...]  #: what the quasi-static model leaves out for this case
    fe: FeCheck | None = None  #: the tooth law against the FE model (``method="fe"``)
    #: with faults: stiffness and STE over one pinion revolution (pipeline/mesh_faults.py)
    revolution: RevolutionColumns | None = None
    #: the largest static force [N] with one pair alone somewhere in the cycle (+inf: a
    #: second pair never touches within the tables; model/ltca.single_pair_limit)
    single_pair_limit_N: float = math.nan
    #: the gap tables' cap [mm] (pipeline/kernel_input.case_gap_tables): no contact beyond it
    tables_cap_mm: float = math.nan

    @property
    def summary(self) -> MeshSummary:
        """The typed document of `gearcli mesh --json`."""
        return mesh_document(self)

    @property
    def table(self):
        """Per pinion roll position ``roll_mm``: STE, unloaded TE [µm], mesh stiffness [N/mm],
        pairs in contact, each pair's position [mm] and force [N] (mesh.csv), a DataFrame."""
        from gearcli.io.tables import columns_to_frame

        return columns_to_frame(mesh_table(self), "roll_mm")

    def document(self, units: str = "engineering") -> dict:
        """What `gearcli mesh --json` prints (its texts in the display ``units``)."""
        return mesh_document(self, units).to_dict()

    def __repr__(self) -> str:
        from gearcli.display_units import convert

        s = self.summary
        k, unit = convert(s.stiffness.mesh_mean_N_mm, "N/mm")  # engineering: N/µm
        return (f"<Mesh {self.name}: STE {s.ste.peak_to_peak_um:.3g} µm peak to peak, mean "
                f"stiffness {k:.4g} {unit}>")


def run_mesh(source: str | Path | LoadedCase, overrides: list[str] | None = None,
             load_N: float | None = None, harris: bool = False, *, cycles: int = 2,
             points_per_cycle: int = 200, method: str = "pe") -> MeshAnalysis:
    """Loaded tooth contact of a case at its static normal force (or ``load_N`` [N]) over
    ``cycles`` mesh cycles; the Harris map (``harris``) at 20 loads from 0.1 to 2 times it,
    one mesh cycle each on the same roll grid (``points_per_cycle``); ``method`` "fe" adds
    the tooth law against the finite-element model at that force (pipeline/mesh_fe.py)."""
    if method not in ("pe", "fe"):
        raise CaseError(f"method {method!r:.40}: expected 'pe' or 'fe'")
    loaded = source if isinstance(source, LoadedCase) else load_case(source, overrides)
    case = loaded.case
    geo = run_geometry(loaded)
    g = geo.geometry
    mesh = case_mesh(case, geo)
    force = mesh.static_force_N if load_N is None else float(load_N)
    if not force > 0.0:
        raise loaded.error(("load", "torque"), "the static load is zero: give a load torque "
                           "or --load with a force > 0 N") if load_N is None else \
            CaseError(f"load_N (--load) {load_N!r}: expected a force > 0 N")
    tables, cap_mm = case_gap_tables(case, geo, mesh)
    slots = int(slot_layout(g, tables)["n_slots"])
    law_of_load = None
    if case.contact.law == "tooth":
        def law_of_load(f):  # the contact term is Weber's secant at the load (§4b)
            ps = tooth_stiffness(case, geo, tables.x_mm, f)
            return tooth_law(np.stack([ps.k_N_mm, ps.dk_dx_N_mm2]), tables.x_lo, tables.x_hi)
        law = law_of_load(force)
        law_name = "tooth compliance k(x) p"
    else:
        law = impact_law(contact_stiffness(case, geo), case.contact.exponent)
        law_name = f"IMPACT elastic part k p^{case.contact.exponent:g}"
    args = (tables.tables, tables.x_lo, tables.x_hi, g.p_b_mm, slots, law)
    try:
        result = loaded_mesh(*args, force, cycles=cycles, points_per_cycle=points_per_cycle,
                             cap_mm=cap_mm)
        harris = (harris_map(*args, force, law_of_load=law_of_load, cycles=1,
                             points_per_cycle=points_per_cycle, cap_mm=cap_mm)
                  if harris else None)  # the same roll grid: its row at the load is the STE
        limit = _single_pair_limit(args, law_of_load)
    except ValueError as exc:  # model.ltca: no equilibrium, or a deflection past the tables
        where = f"--load {load_N:g} N" if load_N is not None else f"{force:.6g} N"
        small = isinstance(exc, LoadTooSmallError)
        raise (loaded.error(("load", "torque"), f"{exc} at {where}; expected a load the teeth "
                            "can carry and the solver resolves") if load_N is None else
               CaseError(f"{where}: {exc}; expected a "
                         f"{'larger' if small else 'smaller'} load")) from None
    notes = not_included("mesh", case)
    notes += bore_notes(case, geo)
    iso = iso_stiffness(case, geo, force)
    revolution = None
    if case.faults:
        from gearcli.pipeline.kernel_input import linearised_mesh

        deflection = linearised_mesh(case, geo, mesh, tables).loaded_deflection_mm
        revolution = faulted_revolution(case, geo, result, deflection)
    return MeshAnalysis(loaded, loaded.name, geo, law_name, result, iso, harris, tuple(notes),
                        _fe_check(case, geo, force) if method == "fe" else None, revolution,
                        limit, cap_mm)


def _single_pair_limit(args, law_of_load) -> float:
    """model.ltca.single_pair_limit [N]. The tooth law's contact term is Weber's secant at the
    load (docs/theory.md §4b), so its limit F* is the root of h(F) = limit(law at F) − F,
    started from the law at the analysed force: one plain pass, then secant steps on h (each
    search near the last one's roll position; h' ≈ −1, so they converge fast) to 1e-8, so F*
    does not depend on the force it started from in the digits shown (plain passes stopped at
    1e-4 left the sixth digit to --load)."""
    f, u_star = single_pair_limit(*args)
    if law_of_load is None:
        return f
    prev: tuple[float, float] | None = None  # (F, h(F)) of the previous pass
    for _ in range(12):
        if not (math.isfinite(f) and f > 0.0):
            return f
        g, u_star = single_pair_limit(*args[:-1], law_of_load(f), near_mm=u_star)
        h = g - f
        if not (math.isfinite(g) and g > 0.0) or abs(h) <= 1e-8 * g:
            return g
        f_next = g if prev is None or h == prev[1] else f - h * (f - prev[0]) / (h - prev[1])
        prev, f = (f, h), f_next
    return g


def _fe_check(case, geo, force: float) -> FeCheck:
    """pipeline.mesh_fe.fe_check; without the optional extra one line naming it (exit 1)."""
    from gearcli.model.fe import FEUnavailableError
    from gearcli.pipeline.mesh_fe import fe_check

    try:
        return fe_check(case, geo, force)
    except FEUnavailableError as exc:
        raise GearcliError(str(exc)) from None


def _iso_resonance(res: MeshAnalysis) -> IsoResonance:
    """ISO 6336-1 Method B resonance speed n_E1 and the case's resonance ratio N = n1/n_E1
    with its K_v (the case's deviations: mesh_input.iso_deviations; gearcli/model/iso_kv.py)."""
    from gearcli.model.iso_kv import dynamic_factor
    from gearcli.pipeline.mesh_input import iso_dynamic, kv_arguments

    iso = iso_dynamic(res.source.case, res.geometry)
    speed = res.geometry.pinion_speed_rad_s
    if speed:
        n1 = abs(speed) * 30.0 / math.pi
        ratio = n1 / iso.resonance_speed_rpm
        kv = dynamic_factor(ratio, **kv_arguments(iso))
        iso = dataclasses.replace(iso, pinion_speed_rpm=n1, resonance_ratio=ratio,
                                  k_v=float(kv.k_v), speed_range=str(kv.range_name))
    return iso


def _limit_note(res: MeshAnalysis, units: str) -> str:
    """Why the single-pair limit is not a force: 0, or +inf (rigid engagement: no contact
    outside the path; extended: a second pair's first touch is past the gap tables' cap, the
    contact model's range, so F* lies above the force of that deflection, not at "any load").
    The cap is quoted in the display ``units`` (gearcli/display_units.py: mm or m)."""
    from gearcli.display_units import convert

    limit = res.single_pair_limit_N
    if limit == 0.0:
        return "no load (two or more pairs everywhere, unloaded too)"
    if math.isfinite(limit):
        return ""
    if res.source.case.contact.engagement == "rigid":
        return "any load (rigid engagement: no contact outside the path)"
    cap, unit = convert(res.tables_cap_mm, "mm", units)
    return (f"above the model's range (a second pair touches past {cap:.3g} {unit}, "
            "the gap tables' end)")


def _sharing(res: MeshAnalysis, units: str) -> MeshSharing:
    """Pairs in contact over the cycle and the single-pair limit (force and per face width;
    its note's text in the display ``units``)."""
    g = res.geometry.geometry
    lm, limit = res.loaded, res.single_pair_limit_N
    finite = math.isfinite(limit)
    return MeshSharing(
        pairs_in_contact_min=int(lm.pairs_in_contact.min()),
        pairs_in_contact_max=int(lm.pairs_in_contact.max()),
        single_pair_share=float(np.mean(lm.pairs_in_contact == 1)),
        single_pair_limit_N=json_number(limit) if finite else None,
        single_pair_limit_N_per_mm=json_number(limit / g.narrow_face_width_mm)
        if finite else None,
        single_pair_limit_note=_limit_note(res, units))


def mesh_document(res: MeshAnalysis, units: str = "engineering") -> MeshSummary:
    """The typed document of a mesh analysis (its JSON: ``.to_dict()``; internal units, names
    carry units; the quantities inside its texts, such as the single-pair limit's note, in the
    display ``units``, gearcli/display_units.py)."""
    lm, g = res.loaded, res.geometry.geometry
    to_arcsec = ARCSEC_PER_RAD / g.pinion.r_b_mm  # δ along the LoA -> pinion angle
    harm = lm.ste_harmonics_mm(3)
    from gearcli.io.manifest import RESULTS_SCHEMA_VERSION

    harris = None
    if res.harris is not None:
        loads, ptp = res.harris  # NaN: outside the contact model's range (null in JSON)
        harris = HarrisMap(tuple(loads.tolist()),
                           tuple(json_number(1e3 * float(p)) for p in ptp))
    return MeshSummary(
        schema_version=RESULTS_SCHEMA_VERSION, case=res.name, contact_law=res.law,
        force_N=lm.force_N, mesh_cycles=lm.cycles,
        ste=MeshSte(
            mean_um=1e3 * float(lm.ste_mm.mean()),
            peak_to_peak_um=1e3 * lm.ste_peak_to_peak_mm,
            peak_to_peak_arcsec=lm.ste_peak_to_peak_mm * to_arcsec,
            harmonics_um={f"{k + 1}fz": 1e3 * float(a) for k, a in enumerate(harm)},
            unloaded_te_peak_to_peak_um=1e3 * float(np.ptp(lm.unloaded_te_mm))),
        stiffness=MeshStiffness(
            mesh_mean_N_mm=float(lm.mesh_stiffness_N_mm.mean()),
            single_pair_zone_N_mm=json_number(lm.zone_stiffness_N_mm(1)),
            double_pair_zone_N_mm=json_number(lm.zone_stiffness_N_mm(2)),
            iso6336_single_pair_c_prime_b_N_mm=res.iso.pair_stiffness_N_mm,
            iso6336_mean_c_gamma_alpha_b_N_mm=res.iso.mesh_stiffness_N_mm),
        sharing=_sharing(res, units),
        iso6336_method_b=_iso_resonance(res),
        notes=tuple(res.notes), harris=harris, fe_check=res.fe,
        faulted_revolution=None if res.revolution is None else revolution_summary(
            res.revolution, res.source.case))


def mesh_table(res: MeshAnalysis):
    """Per roll position: STE, mesh stiffness, pairs in contact and the force per slot, as
    columns with units in their names (for CSV)."""
    lm = res.loaded
    cols = {"roll_mm": lm.roll_mm, "ste_um": 1e3 * lm.ste_mm,
            "unloaded_te_um": 1e3 * lm.unloaded_te_mm,
            "mesh_stiffness_N_mm": lm.mesh_stiffness_N_mm,
            "pairs_in_contact": lm.pairs_in_contact.astype(float)}
    for j in range(lm.pair_force_N.shape[1]):
        cols[f"pair{j}_x_mm"] = lm.pair_x_mm[:, j]
        cols[f"pair{j}_force_N"] = lm.pair_force_N[:, j]
    return cols


def save_mesh_plot(res: MeshAnalysis, path: str | Path, units: str = "engineering") -> None:
    """The figure of :func:`gearcli.plotting.mesh.plot_mesh` in the display ``units``
    (gearcli/display_units.py), written atomically."""
    from gearcli.display_units import unit_and_factor
    from gearcli.io.files import save_figure
    from gearcli.plotting.mesh import plot_mesh

    lm = res.loaded
    te_unit, k_te = unit_and_factor("mm", units, fine=True)
    k_unit, k_k = unit_and_factor("N/mm", units)
    harris = None if res.harris is None else (res.harris[0], k_te * res.harris[1])
    fig = plot_mesh(lm.roll_mm, k_te * lm.ste_mm, k_te * lm.unloaded_te_mm, lm.pair_force_N,
                    k_k * lm.mesh_stiffness_N_mm, force_N=lm.force_N,
                    iso_single=k_k * res.iso.pair_stiffness_N_mm,
                    iso_mean=k_k * res.iso.mesh_stiffness_N_mm,
                    te_unit=te_unit, stiffness_unit=k_unit,
                    title=f"{res.name}: loaded contact at {lm.force_N:.0f} N ({res.law}); "
                          f"STE {lm.ste_peak_to_peak_mm * k_te:.3g} {te_unit} "
                          "peak-to-peak",
                    harris=harris, single_pair_limit_N=res.single_pair_limit_N)
    save_figure(fig, path, 150)


def save_revolution_plot(res: MeshAnalysis, path: str | Path,
                         units: str = "engineering") -> None:
    """The faulted revolution's figure (plotting.mesh_faults.plot_revolution), written
    atomically; the analysis must have ``revolution``."""
    from gearcli.display_units import unit_and_factor
    from gearcli.io.files import save_figure
    from gearcli.plotting.mesh_faults import plot_revolution

    rev, g = res.revolution, res.geometry.geometry
    te_unit, k_te = unit_and_factor("mm", units, fine=True)
    k_unit, k_k = unit_and_factor("N/mm", units)
    faults = ", ".join(f"{f.kind} {f.gear} tooth {f.tooth}" for f in res.source.case.faults)
    fig = plot_revolution(rev.s1_mm / g.p_b_mm, k_k * rev.k_faulted_N_mm,
                          k_k * rev.k_healthy_N_mm, k_te * rev.ste_faulted_mm,
                          k_te * rev.ste_healthy_mm, k_unit, te_unit,
                          f"{res.name}: one pinion revolution with {faults} at "
                          f"{res.loaded.force_N:.0f} N")
    save_figure(fig, path, 150)


def write_mesh(res: MeshAnalysis, folder: str | Path, force: bool,
               overrides: list[str] | None = None, units: str = "engineering",
               doc: dict | None = None) -> Path:
    """mesh.json (``doc``, the caller's :func:`mesh_document` when it has it), mesh.csv,
    mesh.png (in the display ``units``) and manifest.json in ``folder``, all or nothing
    (io.outdir.atomic_dir)."""
    import json

    from gearcli.io.files import write_atomic
    from gearcli.io.manifest import manifest
    from gearcli.io.outdir import atomic_dir
    from gearcli.io.tables import columns_to_csv

    case_json = json.loads(res.source.case.model_dump_json())
    with atomic_dir(folder, force) as tmp:
        write_atomic(tmp / "mesh.json",
                     json.dumps(doc or mesh_document(res, units).to_dict(), indent=2) + "\n")
        write_atomic(tmp / "mesh.csv", columns_to_csv(mesh_table(res)))
        save_mesh_plot(res, tmp / "mesh.png", units)
        if res.revolution is not None:  # faults: the faulted revolution, its table and figure
            write_atomic(tmp / "mesh_faults.csv", columns_to_csv(res.revolution.columns()))
            save_revolution_plot(res, tmp / "mesh_faults.png", units)
        provenance = manifest(res.source.source, case_json, overrides)
        write_atomic(tmp / "manifest.json", json.dumps(provenance, indent=2) + "\n")
    return Path(folder)
