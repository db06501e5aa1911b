"""Building blocks of the case-file schema: the section base class, the per-gear section
(:func:`pair`), and the one wording of a validation error (``PROBLEM; expected ALLOWED``)."""

from __future__ import annotations

import functools
from typing import Annotated

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, create_model


def compose(problem: str = "", expected: str = "") -> str:
    """The wording of every case error: what is wrong, then what is allowed.

    ``compose("2 entries", "one per tooth (21)")`` is "2 entries; expected one per tooth (21)";
    either part may be empty. The loader prefixes the file, line, key and value.
    """
    parts = [problem] if problem else []
    if expected:
        parts.append(f"expected {expected}")
    return "; ".join(parts)


class FieldError(ValueError):
    """A validation error about the key at ``loc`` (relative to the validated section): what
    is wrong (``problem``, may be empty when the value says it) and what is allowed."""

    def __init__(self, loc: tuple[str, ...], problem: str = "", expected: str = "") -> None:
        super().__init__(compose(problem, expected))
        self.loc = loc
        self.problem = problem
        self.expected = expected


class FieldErrors(ValueError):
    """Several :class:`FieldError` of one section, found by one validator (all are reported)."""

    def __init__(self, errors: list[FieldError]) -> None:
        super().__init__("; ".join(str(e) for e in errors))
        self.errors = errors


def raise_all(errors: list[FieldError]) -> None:
    """Raise the errors a validator found, if any: one as itself, several together."""
    if len(errors) == 1:
        raise errors[0]
    if errors:
        raise FieldErrors(errors)


def not_boolean(value: object) -> object:
    """Refuse a YAML boolean (true/false/yes/no/on/off) where a number is expected: pydantic's
    lax float reads true as 1.0, so ``contact.exponent: true`` would run as e = 1."""
    if isinstance(value, bool):
        raise ValueError(compose("a YAML boolean, not a number", "a number"))
    return value


#: A plain number (no unit): finite, and never a YAML boolean.
Coefficient = Annotated[float, BeforeValidator(not_boolean), Field(allow_inf_nan=False)]


class Section(BaseModel):
    """Base of every section: unknown keys are errors, values are immutable."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    def exactly_one(self, first: str, second: str):
        """``self`` when exactly one of the keys ``first`` and ``second`` is given, else a
        FieldError at ``first`` (for an ``after`` model validator)."""
        given = getattr(self, first) is not None
        if given == (getattr(self, second) is not None):
            raise FieldError((first,), "both given" if given else "missing",
                             f"exactly one of '{first}' and '{second}'")
        return self


@functools.cache
def pair(entry: type[BaseModel]) -> type[Section]:
    """The per-gear section of ``entry``: the pinion's and the gear's, each optional.

    ``pair(Relief)`` is the section ``ReliefPair`` (the name in the JSON Schema is the entry's
    ``pair_name``, default its class name, + "Pair"); one class per entry, made once.
    """
    name = getattr(entry, "pair_name", entry.__name__) + "Pair"
    return create_model(name, __base__=Section, __module__=entry.__module__,
                        pinion=(entry | None, None), gear=(entry | None, None))
