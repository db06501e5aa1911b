"""A small, safe parser for Adams-style time functions such as ``STEP(time, 0, 0, 1, 3000)``.

Nothing is ever evaluated by Python: a tokenizer and a recursive-descent parser build the exact
:class:`~gearcli.model.timefunction.PiecewisePolynomial` directly.

Grammar (names case-insensitive)::

    expr     := term (("+" | "-") term)*
    term     := unary (("*" | "/") unary)*         division by a constant only
    unary    := ("+" | "-") unary | power
    power    := atom (("^" | "**") unary)?          constant integer exponent 0..10
    atom     := NUMBER | "time" | "(" expr ")"
              | ("STEP" | "STEP5" | "RAMP") "(" "time" "," expr "," expr "," expr "," expr ")"

STEP, STEP5 and RAMP take ``(time, t0, h0, t1, h1)`` with constant ``t0 < t1``, ``h0``, ``h1``
(MSC Adams Solver function reference; RAMP is the clamped linear blend).
"""

from __future__ import annotations

import operator
import re
from dataclasses import dataclass

import numpy as np

from gearcli import guards
from gearcli.model.timefunction import PiecewisePolynomial

_FUNCTIONS = {
    "step": PiecewisePolynomial.step,
    "step5": PiecewisePolynomial.step5,
    "ramp": PiecewisePolynomial.ramp,
}
_ARGUMENTS = "(time, t0, h0, t1, h1)"
_MAX_EXPONENT = 10
_MAX_DEGREE = 20
_MAX_DEPTH = 50
MAX_LENGTH = guards.MAX_EXPRESSION_CHARS
_TOKEN = re.compile(
    r"\s*(?:(?P<number>(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)"
    r"|(?P<name>[A-Za-z_][A-Za-z0-9_]*)|(?P<op>\*\*|[-+*/^(),]))"
)
_EXPRESSION_HINT = re.compile(r"\btime\b|[A-Za-z_][A-Za-z0-9_]*\s*\(", re.IGNORECASE)


class ExpressionError(ValueError):
    """A malformed time expression; ``str(err)`` is one line ending in ``at column N``.

    Attributes
    ----------
    reason : str
        What was wrong and what was expected.
    column : int
        1-based column in the text.
    """

    def __init__(self, reason: str, column: int) -> None:
        self.reason = reason
        self.column = column
        super().__init__(f"{reason} at column {column}")


@dataclass(frozen=True)
class _Token:
    kind: str  # "number", "name", "op" or "end"
    text: str
    column: int


def _tokenize(text: str) -> list[_Token]:
    tokens, pos = [], 0
    while True:
        match = _TOKEN.match(text, pos)
        if match is None or match.end() == pos:
            rest = text[pos:]
            column = pos + len(rest) - len(rest.lstrip()) + 1
            if not rest.strip():
                return tokens + [_Token("end", "", column)]
            raise ExpressionError(
                f"unexpected character {rest.lstrip()[0]!r}; expected a number, `time`, "
                "STEP/STEP5/RAMP, an operator (+ - * / ^) or parentheses",
                column,
            )
        kind = match.lastgroup
        tokens.append(_Token(kind, match.group(kind), match.start(kind) + 1))
        pos = match.end()


def _describe(token: _Token) -> str:
    return "end of text" if token.kind == "end" else repr(token.text)


class _Parser:
    def __init__(self, text: str) -> None:
        self.tokens = _tokenize(text)
        self.i = 0
        self.depth = 0

    @property
    def tok(self) -> _Token:
        return self.tokens[self.i]

    def take(self, *texts: str) -> _Token | None:
        """Consume and return the current token if it is one of the operators ``texts``."""
        if self.tok.kind == "op" and self.tok.text in texts:
            self.i += 1
            return self.tokens[self.i - 1]
        return None

    def expect(self, text: str, what: str) -> None:
        if self.take(text) is None:
            raise ExpressionError(f"expected {what}, got {_describe(self.tok)}", self.tok.column)

    def parse(self) -> PiecewisePolynomial:
        if self.tok.kind == "end":
            raise ExpressionError(
                "empty expression; expected a number or e.g. STEP(time, 0, 0, 1, 3000)", 1
            )
        result = self.expr()
        if self.tok.kind != "end":
            raise ExpressionError(
                f"unexpected {_describe(self.tok)} after a complete expression; expected an "
                "operator (+ - * / ^) or the end of the text",
                self.tok.column,
            )
        return result

    def expr(self) -> PiecewisePolynomial:
        result = self.term()
        while op := self.take("+", "-"):
            right = self.term()
            result = _apply(op, operator.add if op.text == "+" else operator.sub, result, right)
        return result

    def term(self) -> PiecewisePolynomial:
        result = self.unary()
        while op := self.take("*", "/"):
            right = self.unary()
            if op.text == "*":
                result = _apply(op, operator.mul, result, right)
            elif not right.is_constant:
                raise ExpressionError(
                    "division by a time-varying expression; only division by a constant is allowed",
                    op.column,
                )
            elif right(0.0) == 0.0:
                raise ExpressionError("division by zero", op.column)
            else:
                result = _apply(op, operator.truediv, result, right(0.0))
        return result

    def unary(self) -> PiecewisePolynomial:
        if op := self.take("+", "-"):
            operand = self.nested(self.unary)
            return operand if op.text == "+" else -operand
        return self.power()

    def power(self) -> PiecewisePolynomial:
        base = self.atom()
        if op := self.take("^", "**"):
            start = self.tok.column
            exponent = self.nested(self.unary)
            value = exponent(0.0) if exponent.is_constant else None
            if value is None or value != int(value) or not 0 <= value <= _MAX_EXPONENT:
                raise ExpressionError(
                    f"the exponent must be a constant integer from 0 to {_MAX_EXPONENT}", start
                )
            if base.max_degree * int(value) > _MAX_DEGREE:
                raise ExpressionError(f"polynomial degree above {_MAX_DEGREE}", op.column)
            base = _apply(op, operator.pow, base, int(value))
        return base

    def nested(self, rule):
        self.depth += 1
        if self.depth > _MAX_DEPTH:
            raise ExpressionError(f"expression nested more than {_MAX_DEPTH} deep", self.tok.column)
        try:
            return rule()
        finally:
            self.depth -= 1

    def atom(self) -> PiecewisePolynomial:
        tok = self.tok
        if tok.kind == "number":
            self.i += 1
            value = float(tok.text)
            if not np.isfinite(value):
                raise ExpressionError(f"number {tok.text} is out of range", tok.column)
            return PiecewisePolynomial.constant(value)
        if self.take("("):
            result = self.nested(self.expr)
            self.expect(")", "')' to close the parenthesis")
            return result
        if tok.kind == "name":
            self.i += 1
            name = tok.text.lower()
            if name == "time":
                return PiecewisePolynomial.identity()
            if name in _FUNCTIONS:
                return self.call(tok)
            if name in ("nan", "inf", "infinity"):
                raise ExpressionError(f"{tok.text!r} is not a finite number", tok.column)
            raise ExpressionError(
                f"unknown name {tok.text!r}; expected `time`, STEP, STEP5 or RAMP", tok.column
            )
        raise ExpressionError(
            f"expected a number, `time`, a function or '(', got {_describe(tok)}", tok.column
        )

    def call(self, name: _Token) -> PiecewisePolynomial:
        fname = name.text.upper()
        self.expect("(", f"'(' after {fname}")
        first = self.tok
        if not (first.kind == "name" and first.text.lower() == "time"):
            raise ExpressionError(
                f"the first argument of {fname} must be `time`, got {_describe(first)}",
                first.column,
            )
        self.i += 1
        args: list[tuple[PiecewisePolynomial, int]] = []
        while self.take(","):
            start = self.tok.column
            args.append((self.nested(self.expr), start))
        if self.tok.kind == "name":  # e.g. STEP(time, 0, 0, 1, 3000 deg/s)
            raise ExpressionError(
                f"unexpected {self.tok.text!r} in {fname}{_ARGUMENTS}: numbers in an expression "
                "are in the field's unit (or its 'unit' key), so write no units inside",
                self.tok.column,
            )
        self.expect(")", f"',' or ')' in {fname}{_ARGUMENTS}")
        if len(args) != 4:
            raise ExpressionError(
                f"{fname} takes 5 arguments {_ARGUMENTS}, got {len(args) + 1}", name.column
            )
        values = []
        for label, (arg, start) in zip(("t0", "h0", "t1", "h1"), args, strict=True):
            if not arg.is_constant:
                raise ExpressionError(
                    f"argument {label} of {fname} must be a constant, not a function of time",
                    start,
                )
            values.append(arg(0.0))
        t0, h0, t1, h1 = values
        if not t1 > t0:
            raise ExpressionError(
                f"{fname} needs t1 > t0, got t0 = {t0:g} and t1 = {t1:g}", name.column
            )
        return _apply(name, _FUNCTIONS[fname.lower()], t0, h0, t1, h1)


def _apply(op: _Token, function, *args) -> PiecewisePolynomial:
    """``function(*args)``, reporting overflow (non-finite coefficients) at ``op``."""
    try:
        return function(*args)
    except (ValueError, OverflowError):
        raise ExpressionError(f"the result of {op.text!r} is not finite", op.column) from None


def is_expression(text: str) -> bool:
    """Whether ``text`` is a time expression rather than a number or a quantity with units.

    True when it names the variable ``time`` or calls a function (a name followed by ``(``):
    ``"STEP(time, 0, 0, 1, 4.5e5)"``, ``"2*STEP(...)"``, ``"time*300"``, ``"sin(2)"`` (the
    last one then fails to parse with a clear message). False for numbers (``"450"``,
    ``"4.5e5"``, ``"1e5*4.5"``) and quantities, whose letters are units and whose
    parentheses group units: ``"450 N*m"``, ``"1e5 N/(mm^1.5)"``.
    """
    return isinstance(text, str) and _EXPRESSION_HINT.search(text) is not None


def parse_time_function(text: str) -> PiecewisePolynomial:
    """Parse a constant or Adams-style expression of ``time`` into a piecewise polynomial.

    Parameters
    ----------
    text : str
        E.g. ``"3000"``, ``"STEP(time, 0, 0, 1, 4.5e+05)"``, ``"2*STEP5(time,0,0,1,1) - 1"``.

    Returns
    -------
    PiecewisePolynomial
        The exact function, in the unit the numbers of ``text`` are written in.

    Raises
    ------
    ExpressionError
        With a one-line message naming what was expected and the 1-based column.
    """
    if not isinstance(text, str):
        raise ExpressionError(f"expected text, got {type(text).__name__}", 1)
    if len(text) > MAX_LENGTH:  # bounds the work: each term merges the breakpoints so far
        raise ExpressionError(f"expression of {len(text):,} characters; expected at most "
                              f"{MAX_LENGTH:,}", MAX_LENGTH + 1)
    with np.errstate(all="ignore"):
        return _Parser(text).parse()
