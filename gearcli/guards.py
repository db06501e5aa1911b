"""Limits on user input, checked before any work is sized by it.

Every number here bounds how much a user value can make gearcli read, build, allocate or wait
for. The checks raise ordinary one-line errors (the caller locates them); nothing in this module
imports pint, numpy or pydantic, so the guards run before the expensive parsers see the input.

- :func:`read_bounded`: a case or study file (regular file, pipe or device) of at most
  :data:`MAX_INPUT_BYTES`, never blocking for more than :data:`READ_TIMEOUT_S` without data.
- :func:`check_unit_text`: a string on its way to pint (a quantity such as ``"10 mm"`` or a
  unit such as ``"N*m"``): bounded length and small, unchained powers (pint evaluates
  ``"9**9**9**9"`` with Python integers, which never ends).
- :func:`clip`: a user value or line shown in a message, cut to a readable length.
"""

from __future__ import annotations

import os
import re
import select
import stat
import time

#: Largest case or study file [bytes]; the seed case is 2.5 kB.
MAX_INPUT_BYTES = 1_000_000
#: Longest wait for the next bytes of a pipe or device given as the case file [s].
READ_TIMEOUT_S = 30.0
#: Most YAML nodes a document may expand to (aliases are counted at every use).
MAX_YAML_NODES = 100_000
#: Deepest nesting of YAML mappings and lists (a case is 5 levels deep).
MAX_YAML_DEPTH = 50
#: Longest string handed to the unit parser (quantities and units).
MAX_UNIT_CHARS = 200
#: Largest |exponent| of a power in a unit string ("mm^1.5", "s**-2").
MAX_UNIT_EXPONENT = 10
#: Longest time expression (``STEP(time, ...) + ...``) [characters].
MAX_EXPRESSION_CHARS = 2000
#: Longest user value or source line quoted in a message [characters].
MAX_QUOTE_CHARS = 80
#: Longest line of an error message [characters].
MAX_MESSAGE_LINE_CHARS = 1000
#: Most output rows (samples) of one run; each costs ~1 kB in memory (arrays, CSV text).
MAX_OUTPUT_ROWS = 1_000_000
#: Memory of one output row [bytes]: the kernel's ~45 columns as float64, the named copies
#: and the CSV text (~12 characters per value).
BYTES_PER_OUTPUT_ROW = 45 * (8 + 8 + 12)
#: Timeout of every network handshake (a Dask scheduler) [s].
NETWORK_TIMEOUT_S = 10.0


class InputTooLarge(ValueError):
    """Input beyond one of the limits of this module; ``str(err)`` says which and by how much."""


# --- files -----------------------------------------------------------------------------------
def read_bounded(path: str | os.PathLike, limit: int = MAX_INPUT_BYTES,
                 timeout_s: float | None = None) -> bytes:
    """The bytes of ``path``: a regular file, or a pipe / character device read as a stream.

    Raises
    ------
    InputTooLarge
        More than ``limit`` bytes (checked from the size of a regular file before reading,
        and while reading a stream).
    TimeoutError
        A stream gave no data for ``timeout_s`` (default :data:`READ_TIMEOUT_S`): a FIFO
        nobody writes to, a terminal.
    OSError
        Unreadable (the caller reports ``strerror``).
    """
    timeout_s = READ_TIMEOUT_S if timeout_s is None else timeout_s
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)  # a FIFO without a writer must not block
    try:
        st = os.fstat(fd)
        if stat.S_ISDIR(st.st_mode):
            raise IsADirectoryError(21, "Is a directory")
        if stat.S_ISREG(st.st_mode):
            if st.st_size > limit:
                raise InputTooLarge(too_large(st.st_size, limit))
            os.set_blocking(fd, True)
            return _read_all(fd, limit)
        # a character device (/dev/null, a terminal) at end of input reads empty: that is EOF;
        # a FIFO reads empty also before its writer has opened it
        return _read_stream(fd, limit, timeout_s, eof_on_empty=stat.S_ISCHR(st.st_mode))
    finally:
        os.close(fd)


def _read_all(fd: int, limit: int) -> bytes:
    chunks, size = [], 0
    while chunk := os.read(fd, 65536):
        size += len(chunk)
        if size > limit:  # the file grew while being read
            raise InputTooLarge(too_large(size, limit, at_least=True))
        chunks.append(chunk)
    return b"".join(chunks)


def _read_stream(fd: int, limit: int, timeout_s: float, eof_on_empty: bool = False) -> bytes:
    chunks, size = [], 0
    deadline = time.monotonic() + timeout_s
    poller = select.poll()
    poller.register(fd, select.POLLIN)
    while True:
        left = deadline - time.monotonic()
        if left <= 0.0:
            raise TimeoutError(f"no data for {timeout_s:g} s (a pipe nobody writes to?)")
        events = poller.poll(max(1, int(left * 1000)))
        if not events:
            continue
        try:
            chunk = os.read(fd, 65536)
        except BlockingIOError:
            continue
        if not chunk:
            if events[0][1] & select.POLLHUP or size or eof_on_empty:
                return b"".join(chunks)
            continue
        size += len(chunk)
        if size > limit:
            raise InputTooLarge(too_large(size, limit, at_least=True))
        chunks.append(chunk)
        deadline = time.monotonic() + timeout_s


def too_large(size: int, limit: int, at_least: bool = False) -> str:
    more = "at least " if at_least else ""
    return (f"{more}{size:,} bytes; expected a case file of at most {limit:,} bytes "
            "(the seed case is 2.5 kB)")


# --- unit strings ----------------------------------------------------------------------------
_NUMBER = r"(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
#: A power operator and what follows it: a small number, optionally signed / in parentheses.
_POWER = re.compile(r"(\*\*|\^)\s*(\(\s*[-+]?\s*" + _NUMBER + r"\s*\)|[-+]?\s*" + _NUMBER
                    + r")?")
_LEADING_NUMBER = re.compile(r"^\s*\(?\s*[-+]?\s*(?:\d|\.\d)")
_NON_FINITE = re.compile(r"^\s*[-+]?\s*(?:nan|inf(?:inity)?)(?:\s|$)", re.IGNORECASE)


def check_unit_text(text: str, need_number: bool, example: str = "10 mm") -> None:
    """Refuse a string pint must not evaluate: too long, or with a large or chained power.

    ``need_number``: the string is a quantity ("10 mm"), so it must start with a number; a
    unit alone ("mm") would otherwise be read as 1 mm. ``example``: a quantity of the field's
    dimension for the messages.

    Raises
    ------
    ValueError
        One line starting with "expected" (pydantic shows it with the key and the value).
    """
    if len(text) > MAX_UNIT_CHARS:
        raise ValueError(f"expected a number with units of at most {MAX_UNIT_CHARS} "
                         f"characters, e.g. '{example}' (got {len(text):,} characters)")
    pos = 0
    while (m := _POWER.search(text, pos)) is not None:
        exponent = m.group(2)
        rest = text[m.end():].lstrip()
        if exponent is None or rest.startswith(("**", "^")) or _powered_group(text, m.start()):
            raise ValueError(f"expected units with plain powers such as 'mm^1.5' or "
                             f"'s**-2', not {clip(text[m.start():].strip())!r}")
        try:
            value = float(exponent.strip("() ").replace(" ", ""))
        except ValueError:  # pragma: no cover - the pattern only matches numbers
            value = float("inf")
        if not abs(value) <= MAX_UNIT_EXPONENT:
            raise ValueError(f"expected powers of at most {MAX_UNIT_EXPONENT} in units, got "
                             f"{clip(text[m.start():m.end()].strip())!r}")
        pos = m.end()
    if need_number and _NON_FINITE.match(text):  # "nan", "-inf mm": not a unit alone
        raise ValueError(f"expected a number with units, e.g. '{example}' (a finite number: "
                         "not NaN or infinity)")
    if need_number and not _LEADING_NUMBER.match(text):
        raise ValueError(f"expected a number with units, e.g. '{example}' (no number in front: "
                         "a unit alone is not a value)")


def _powered_group(text: str, op: int) -> bool:
    """Whether the power at ``op`` applies to a parenthesised group holding a power itself
    ("(9**9)**9"): nested powers multiply their exponents."""
    head = text[:op].rstrip()
    if not head.endswith(")"):
        return False
    depth = 0
    for i in range(len(head) - 1, -1, -1):
        depth += {")": 1, "(": -1}.get(head[i], 0)
        if depth == 0:
            return "**" in head[i:] or "^" in head[i:]
    return True  # unbalanced: pint refuses it anyway


# --- messages --------------------------------------------------------------------------------
def clip(text: str, limit: int = MAX_QUOTE_CHARS) -> str:
    """``text`` cut to ``limit`` characters, saying how much was left out."""
    if len(text) <= limit:
        return text
    keep = max(limit - 20, 10)
    return f"{text[:keep]}... ({len(text):,} chars)"


def clip_message(text: str) -> str:
    """An error message with every line cut to :data:`MAX_MESSAGE_LINE_CHARS`."""
    return "\n".join(clip(line, MAX_MESSAGE_LINE_CHARS) for line in text.split("\n"))


def output_rows_message(rows: int, what: str) -> str:
    """Why ``rows`` output samples are refused, with the memory they would take."""
    need = rows * BYTES_PER_OUTPUT_ROW
    return (f"{what} gives {rows:,.0f} output samples (~{_bytes(need)} in memory); expected at "
            f"most {MAX_OUTPUT_ROWS:,} (~{_bytes(MAX_OUTPUT_ROWS * BYTES_PER_OUTPUT_ROW)}): "
            "shorten run.end_time or lower run.output_rate / run.output_steps")


def _bytes(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if n < 1000.0 or unit == "PB":
            return f"{n:.3g} {unit}"
        n /= 1000.0
    return f"{n:.3g} EB"  # pragma: no cover
