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


def field_at(schema: type[BaseModel], loc: Loc) -> FieldInfo | None:
    """The schema field at key path ``loc`` from the model ``schema``; None when there is none."""
    model: type[BaseModel] | None = schema
    field = None
    for part in loc:
        if model is None or str(part) not in model.model_fields:
            return None
        field = model.model_fields[str(part)]
        model = model_in(field.annotation)
    return field


def allowed_keys(schema: type[BaseModel], loc: Loc) -> list[str]:
    """Field names of the section at key path ``loc`` from ``schema``; [] for a value or no key."""
    model: type[BaseModel] | None = schema
    for part in loc:
        field = model.model_fields.get(str(part)) if model is not None else None
        if field is None:
            return []
        model = model_in(field.annotation)
    return list(model.model_fields) if model is not None else []
