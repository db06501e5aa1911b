"""The report's "Rating (ISO 6336)" section: S_H and S_F per gear, the ISO column (K_v of the
case), the simulated column (K_v = the run's F_max/F_static) and the safeties of the run's
stress peaks side by side, with the minimum safeties and verdicts (rating.json of `gearcli
run`; docs/theory.md, "ISO 6336 rating")."""

from __future__ import annotations

from gearcli.case.schema import Case
from gearcli.report.tables import Table, fmt
from gearcli.results.rating import SAFETY_CHECKS
from gearcli.results.rating_document import RatingDocument

_ROLES = ("pinion", "gear")
_LIMITS = ("contact_fatigue_limit", "bending_fatigue_limit")


def missing_limits(case: Case | None) -> list[str]:
    """The fatigue limits the rating needs and the case does not give: per gear, its
    material's (else the case's) σ_Hlim, σ_Flim, unless rating.<gear>.material.hardness
    gives them (ISO 6336-5)."""
    if case is None:
        return ["the case"]
    out = []
    for role in _ROLES:
        mat = case.material_of(role)
        if getattr(case.rating, role).material.hardness is not None:
            continue
        out += [f"{role} {key}" for key in _LIMITS if getattr(mat, key) is None]
    return out


def rating_table(rating: RatingDocument) -> Table:
    """One row per gear and safety: ISO, simulated, minimum, verdict of each column."""
    iso, sim = rating.iso, rating.simulated
    peaks = sim.peaks if sim is not None else None
    rows, status = [], []
    for role in _ROLES:
        for s, lim, verdict in SAFETY_CHECKS:
            a = getattr(iso, role)
            b = getattr(sim, role) if sim is not None else None
            peak = getattr(getattr(peaks, role), s) if peaks is not None else None
            a_verdict, b_verdict = getattr(a, verdict), getattr(b, verdict, "–")
            rows.append((role, s, fmt(getattr(a, s)), fmt(getattr(b, s)) if b else "–",
                         "–" if peak is None else fmt(peak), fmt(getattr(a, lim)),
                         a_verdict, b_verdict))
            ok = a_verdict == "pass" and (b is None or b_verdict == "pass")
            status.append("pass" if ok else "fail")
    note = (f"ISO 6336 Method B ({rating.edition}); ISO column K_v: "
            f"{rating.load.dynamic_factor_source}; simulated column K_v = the run's "
            "F_max/F_static; stress peaks: σ_G over the run's peak stresses (gearcli stress, "
            "their positions starred on the stress figure) times √(K_A K_γ K_Hβ) resp. "
            "K_A K_γ K_Fβ Y_β Y_B Y_DT. Verdict: " + rating.verdict + "."
            # a run off its operating point has no simulated column (pipeline/run_rating)
            + "".join(f" {n[0].upper()}{n[1:]}." for n in rating.notes
                      if n.startswith("no simulated column")))
    return Table("Rating (ISO 6336): safety factors, ISO beside simulated",
                 ("gear", "safety", "ISO", "simulated", "simulated, stress peaks", "minimum",
                  "verdict ISO", "verdict simulated"), rows, note=note, status=status)


def missing_line(case: Case | None) -> str:
    """One line: why the report has no rating."""
    missing = missing_limits(case)
    if missing:
        return ("Not rated: the ISO 6336 rating needs the fatigue limits, missing here: "
                + ", ".join(missing) + " (material.contact_fatigue_limit and "
                "material.bending_fatigue_limit, or rating.<gear>.material.hardness).")
    return "Not rated: no rating.json in this folder (`gearcli run` writes it)."
