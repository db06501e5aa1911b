"""`gearcli mesh` of a case with ``faults:``: the faulted mesh stiffness and static
transmission error over one pinion revolution (docs/theory.md, "Tooth faults": "The faulted
revolution in `gearcli mesh`").

The stiffness is :func:`gearcli.model.faults.factors.revolution_stiffness` (the tooth law's
pair stiffness of every pair on the path at its rigid-kinematics position, times the faults'
factors; pinion roll s1 = r_b1 θ1 from t = 0, tooth 0 at the pitch point at s1 = 0). The STE
adds to the healthy loaded STE of `gearcli mesh` at the same mesh phase the compliance the
faults add at the static force F:

    STE_f(s1) = STE(s1 mod p_b) + F (1/k_f(s1) − 1/k(s1))                  [mm]

exact for linear pairs all in contact at zero gap (no relief, no separation), first order
about the healthy loaded state otherwise. Where no pair carries (k_f = 0: a missing tooth
where it would carry alone) the STE is undefined (NaN): the pair separates until the next
pair's extended contact takes the load, which only `simulate` follows.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gearcli.case.schema_faults import fault_records
from gearcli.model.faults import is_void
from gearcli.results.models import FaultedRevolution

#: Points per base pitch of the revolution (the kernel's factor table has 200 as well).
POINTS_PER_PITCH = 200


@dataclass(frozen=True)
class RevolutionColumns:
    """The faulted revolution, columns per pinion roll s1 [mm] from t = 0 (mesh_faults.csv)."""

    s1_mm: np.ndarray
    k_faulted_N_mm: np.ndarray
    k_healthy_N_mm: np.ndarray
    ste_faulted_mm: np.ndarray
    ste_healthy_mm: np.ndarray

    def columns(self) -> dict[str, np.ndarray]:
        return {"roll_s1_mm": self.s1_mm, "mesh_stiffness_faulted_N_mm": self.k_faulted_N_mm,
                "mesh_stiffness_healthy_N_mm": self.k_healthy_N_mm,
                "ste_faulted_um": 1e3 * self.ste_faulted_mm,
                "ste_healthy_um": 1e3 * self.ste_healthy_mm}


def faulted_revolution(case, geo, loaded_mesh, deflection_mm: float) -> RevolutionColumns | None:
    """The faulted stiffness and STE over one pinion revolution (module docstring); None when
    the case has no fault of nonzero size. ``loaded_mesh``: the healthy model.ltca.LoadedMesh
    of `gearcli mesh`; ``deflection_mm``: the static deflection per pair (a spall's depth
    against it, docs/theory.md "Tooth faults")."""
    from gearcli.model.faults.factors import revolution_stiffness
    from gearcli.pipeline.mesh_input import tooth_stiffness

    faults = fault_records(case.faults)
    if not faults or all(is_void(f) for f in faults):
        return None
    g = geo.geometry
    rev = revolution_stiffness(g, lambda x: tooth_stiffness(case, geo, x), faults,
                               points_per_pitch=POINTS_PER_PITCH, deflection_mm=deflection_mm)
    lm = loaded_mesh
    # the mesh phase of both: the distance of a pair from C, mod p_b (slot 0 at x_lo + u);
    # one mesh cycle of the loaded STE (it repeats)
    first = lm.roll_mm < lm.roll_mm[0] + g.p_b_mm
    phase_lm = np.mod(lm.pair_x_mm[first, 0] - (g.C_mm - g.A_mm), g.p_b_mm)
    order = np.argsort(phase_lm)
    ste_h = np.interp(np.mod(rev.s1_mm, g.p_b_mm), phase_lm[order], lm.ste_mm[first][order],
                      period=g.p_b_mm)
    with np.errstate(divide="ignore", invalid="ignore"):
        added = lm.force_N * (1.0 / rev.k_mesh_N_mm - 1.0 / rev.healthy_N_mm)
    ste_f = np.where(rev.k_mesh_N_mm > 0.0, ste_h + added, np.nan)
    return RevolutionColumns(rev.s1_mm, rev.k_mesh_N_mm, rev.healthy_N_mm, ste_f, ste_h)


def revolution_summary(rev: RevolutionColumns, case) -> FaultedRevolution:
    """mesh.json's ``faulted_revolution``: extremes of the faulted revolution."""
    ok = np.isfinite(rev.ste_faulted_mm)
    ste = rev.ste_faulted_mm[ok]
    drop = 1.0 - rev.k_faulted_N_mm / rev.k_healthy_N_mm
    faults = tuple(f"{f.kind} {f.gear} tooth {f.tooth}" for f in case.faults)
    return FaultedRevolution(
        faults=faults, points=int(rev.s1_mm.size),
        stiffness_min_N_mm=float(rev.k_faulted_N_mm.min()),
        stiffness_healthy_min_N_mm=float(rev.k_healthy_N_mm.min()),
        stiffness_largest_drop=float(drop.max()),
        stiffness_largest_drop_at_roll_mm=float(rev.s1_mm[int(np.argmax(drop))]),
        ste_peak_to_peak_um=1e3 * float(np.ptp(ste)) if ste.size else float("nan"),
        ste_healthy_peak_to_peak_um=1e3 * float(np.ptp(rev.ste_healthy_mm)),
        no_contact_share=float(1.0 - ok.mean()))
