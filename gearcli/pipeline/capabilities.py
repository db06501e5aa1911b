"""Which command models which feature of a case: the one table, and the notes made from it.

A case may carry features that not every command models: friction, runout, single pitch
deviations, tip/root relief, tooth faults. :data:`MODELLED` says, per command, which of them it
includes; :func:`not_included` turns that into the notes a command prints (and stores) for the
features the case uses and the command leaves out. A new feature or command is one entry here
(docs/theory.md §11: what each command computes).

- ``simulate`` (and ``run``, ``stress``, the speed curve and sweeps, which read its runs): every
  feature, in the time-domain model.
- ``mesh``: the quasi-static loaded contact of the healthy, error-free pair: relief only.
- ``modal``: linearised at the mean loaded mesh stiffness of the healthy pair (relief enters that
  mean), friction off.
- ``rate``: ISO 6336 of the healthy pair; relief enters through ISO 6336-1's K_v (C_a), the
  pitch deviation only as ISO's f_pb of ``rating:``, not the case's per-tooth list.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from gearcli.case.schema import Case

__all__ = ["FEATURES", "MODELLED", "Feature", "used_features", "not_included"]


@dataclass(frozen=True)
class Feature:
    name: str
    label: str  #: how a note names it
    used: Callable[[Case], bool]  #: whether a case has it
    why: str  #: why leaving it out matters, and where it is modelled
    #: command -> its own ``why``, where the general one would not say what it does instead
    why_for: Mapping[str, str] = field(default_factory=dict)


def _has_pair(pair) -> bool:
    return bool(pair.pinion or pair.gear)


FEATURES = (
    Feature("friction", "friction", lambda c: bool(c.friction.enabled),
            "it shifts the normal force by the friction moments, ~mu of it; simulate includes "
            "it"),
    Feature("runout_pitch", "runout, pitch and profile slope deviations",
            lambda c: _has_pair(c.errors.runout) or _has_pair(c.errors.pitch_deviation)
            or _has_pair(c.errors.profile_slope_deviation),
            "they vary over whole revolutions; simulate includes them"),
    Feature("relief", "tip and root relief",
            lambda c: _has_pair(c.modifications.tip_relief)
            or _has_pair(c.modifications.root_relief),
            "simulate and mesh include them"),
    Feature("faults", "tooth faults",
            lambda c: bool(c.faults),
            "the healthy pair is used; simulate includes them (docs/theory.md, Tooth faults)",
            {"modal": "the modes are linearised at the healthy pair's mean mesh stiffness; a "
                      "fault changes one tooth's stiffness once per revolution, which simulate "
                      "includes (docs/theory.md, Tooth faults)",
             "mesh": "the tables are the healthy pair's; the faulted mesh stiffness and STE "
                     "over one pinion revolution are shown beside them (faulted_revolution); "
                     "simulate includes them (docs/theory.md, Tooth faults)"}),
)

#: command -> the features it models (names of :data:`FEATURES`)
MODELLED: dict[str, frozenset[str]] = {
    "simulate": frozenset(f.name for f in FEATURES),
    "mesh": frozenset({"relief"}),
    "modal": frozenset({"relief"}),
    "rate": frozenset({"relief"}),  # through ISO 6336-1's K_v (C_a), pipeline/rating.py
}


def used_features(case: Case) -> tuple[Feature, ...]:
    """The features of :data:`FEATURES` that ``case`` uses, in table order."""
    return tuple(f for f in FEATURES if f.used(case))


def not_included(command: str, case: Case) -> list[str]:
    """One note per feature ``case`` uses that ``command`` does not model:
    "<label> is not included (<why>)"."""
    have = MODELLED[command]
    notes = []
    for f in used_features(case):
        if f.name not in have:
            verb = "are" if f.label.endswith("s") else "is"
            notes.append(f"{f.label} {verb} not included ({f.why_for.get(command, f.why)})")
    return notes
