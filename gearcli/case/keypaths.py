"""Key paths (``gears.pinion.teeth``) in a case schema: walk the pydantic models key by key.

Shared by the loader (did-you-mean lists, limits of quantity fields) and by ``--set``
overrides and study files (refusing unknown keys before validation).
"""

from __future__ import annotations

from pydantic import BaseModel
from pydantic.fields import FieldInfo

from gearcli.case.yamlsrc import Loc


def model_in(annotation) -> type[BaseModel] | None:
    """The pydantic model class in a field annotation (``Gear``, ``Gear | None``, ...), or None."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in getattr(annotation, "__args__", ()):
        found = model_in(arg)
        if found is not None:
            return found
    return None


def models_in(annotation) -> list[type[BaseModel]]:
    """Every pydantic model class in a field annotation (the members of a union: a fault's
    kinds), in order."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    return [m for arg in getattr(annotation, "__args__", ()) for m in models_in(arg)]


def _tags(model: type[BaseModel]) -> set[str]:
    """The names pydantic gives a union member in an error's location: its class name and, in
    a tagged union, its ``kind`` ("RootCrackFault", "root_crack")."""
    kind = model.model_fields.get("kind")
    return {model.__name__, *(getattr(kind.annotation, "__args__", ()) if kind else ())}


def _walk(schema: type[BaseModel], loc: Loc):
    """(models, field) at key path ``loc``: the candidate models of the section there and the
    field itself. A list index is passed over; a union member's name in pydantic's location
    ("spall" of ``faults.0.spall.width``) narrows the union to it; otherwise the first member
    with the key is taken. (None, None) when the path has no such key."""
    models: list[type[BaseModel]] = [schema]
    field = None
    for part in loc:
        if isinstance(part, int) or any(c in str(part) for c in "[]()"):  # index, validator
            continue
        tagged = [m for m in models if str(part) in _tags(m)]
        if tagged and not any(str(part) in m.model_fields for m in models):
            models = tagged
            continue
        model = next((m for m in models if str(part) in m.model_fields), None)
        if model is None:
            return None, None
        field = model.model_fields[str(part)]
        models = models_in(field.annotation)
    return models, field


def field_at(schema: type[BaseModel], loc: Loc) -> FieldInfo | None:
    """The schema field at key path ``loc`` from the model ``schema`` (a list's index passed
    over, a union narrowed by pydantic's member names: :func:`_walk`); None when there is
    none."""
    return _walk(schema, loc)[1]


def allowed_keys(schema: type[BaseModel], loc: Loc) -> list[str]:
    """Field names of the section at key path ``loc`` from ``schema`` (:func:`_walk`; in a
    union the first member's); [] for a value or no key."""
    models, _ = _walk(schema, loc)
    return list(models[0].model_fields) if models else []
