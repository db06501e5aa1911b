"""Safe YAML loading that keeps the line of every key, for error messages.

Uses PyYAML's SafeLoader only (no arbitrary object construction). Duplicate keys, which YAML
parsers silently resolve by keeping the last one, are refused.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from gearcli import guards
from gearcli.errors import CaseError

Loc = tuple[str | int, ...]


@dataclass
class Source:
    """A loaded YAML document: its data, its text lines and the line of each key path."""

    file: str
    data: object
    lines: list[str]
    key_lines: dict[Loc, int] = field(default_factory=dict)
    overridden: dict[Loc, str] = field(default_factory=dict)  #: key path -> the --set text
    sha256: str = ""  #: of the bytes that were parsed (the manifest records it)

    def line_of(self, loc: Loc) -> int | None:
        """1-based line of the deepest existing key on ``loc``."""
        loc = tuple(loc)
        while loc:
            if loc in self.key_lines:
                return self.key_lines[loc]
            loc = loc[:-1]
        return self.key_lines.get((), None)

    def override_of(self, loc: Loc) -> str | None:
        """The --set text that set the value at ``loc``: its own, or that of a section or list
        it lies in (``--set faults=[...]`` sets ``faults.0.depth``); None when the file did."""
        parts = tuple(str(p) for p in loc)
        for n in range(len(parts), 0, -1):
            if parts[:n] in self.overridden:
                return self.overridden[parts[:n]]
        return None

    def text_of(self, line: int | None) -> str | None:
        if line is None or not 1 <= line <= len(self.lines):
            return None
        return self.lines[line - 1]

    def error(self, loc: Loc, message: str, value: object = None, has_value: bool = False):
        """A :class:`CaseError` located at ``loc`` (or at the --set option that set it)."""
        loc = tuple(loc)
        given = self.override_of(loc)
        if given is not None:
            return CaseError(
                message,
                file=f"--set {given}",
                path=".".join(str(p) for p in loc),
                value=value,
                has_value=has_value,
            )
        line = self.line_of(loc)
        file = self.file
        if loc and line == self.key_lines.get(()) and loc[:1] not in self.key_lines:
            # nothing on the key's path is in the file: no line to show; when --set options
            # were given they are what the file is checked with
            line = None
            if self.overridden:
                file += " with --set " + " ".join(self.overridden.values())
        return CaseError(
            message,
            file=file,
            line=line,
            path=".".join(str(p) for p in loc) or None,
            value=value,
            has_value=has_value,
            source_line=self.text_of(line),
        )


def read_source(path: str | Path) -> Source:
    """Read and parse a YAML case file; every failure is a :class:`CaseError`.

    The file may be a pipe (``<(...)``, ``/dev/stdin``); it is read once, at most
    :data:`gearcli.guards.MAX_INPUT_BYTES`, and the hash of exactly those bytes is kept.
    """
    p = Path(path)
    name = str(path)
    if not p.exists():
        raise CaseError("file not found; expected the path of a YAML case file", file=name)
    if p.is_dir():
        raise CaseError("is a directory; expected a YAML case file", file=name)
    try:
        raw = guards.read_bounded(p)
    except guards.InputTooLarge as exc:
        raise CaseError(f"too large: {exc}", file=name) from None
    except TimeoutError as exc:
        raise CaseError(f"cannot read ({exc}); expected a YAML case file", file=name) from None
    except OSError as exc:
        raise CaseError(
            f"cannot read ({exc.strerror}); expected a readable file", file=name
        ) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise CaseError(
            f"not UTF-8 text ({exc.reason}); expected a YAML case file", file=name
        ) from None
    src = parse_source(text, name)
    src.sha256 = hashlib.sha256(raw).hexdigest()
    return src


def parse_source(text: str, name: str = "<case>") -> Source:
    """Parse YAML text into a :class:`Source` (mapping at the top level).

    Bounded: at most :data:`gearcli.guards.MAX_YAML_DEPTH` levels and
    :data:`gearcli.guards.MAX_YAML_NODES` values, aliases counted at every use (a "billion
    laughs" document is refused before anything walks its expansion).
    """
    lines = text.splitlines()
    if not text.strip():
        raise CaseError("file is empty; expected a YAML mapping of case keys", file=name)
    if len(text) > guards.MAX_INPUT_BYTES:
        raise CaseError(f"too large: {guards.too_large(len(text), guards.MAX_INPUT_BYTES)}",
                        file=name)
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
        if node is not None:
            _check_size(node, name, lines)
        data = yaml.load(text, Loader=yaml.SafeLoader)  # noqa: S506 - SafeLoader
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
        line = mark.line + 1 if mark is not None else None
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise CaseError(
            f"invalid YAML ({problem}); expected a YAML mapping of case keys",
            file=name,
            line=line,
            source_line=lines[line - 1] if line and line <= len(lines) else None,
        ) from None
    except RecursionError:  # PyYAML's composer recurses once per level of nesting
        raise CaseError(f"nested too deeply; expected at most {guards.MAX_YAML_DEPTH} levels "
                        "of mappings and lists", file=name) from None
    except (ValueError, OverflowError) as exc:  # e.g. an integer of more than 4300 digits
        raise CaseError(f"invalid YAML value ({guards.clip(str(exc), 120)}); expected a YAML "
                        "mapping of case keys", file=name) from None
    if node is None or data is None:
        raise CaseError("file holds no data; expected a YAML mapping of case keys", file=name)
    src = Source(name, data, lines, sha256=hashlib.sha256(text.encode("utf-8")).hexdigest())
    if not isinstance(data, dict):
        line = node.start_mark.line + 1
        raise CaseError(
            f"the document is a YAML {type(data).__name__}; expected a mapping of case keys "
            "(gears:, contact:, drive:, ...)",
            file=name,
            line=line,
            source_line=src.text_of(line),
        )
    src.key_lines[()] = node.start_mark.line + 1
    _index(node, (), src)
    return src


def _check_size(root: yaml.Node, name: str, lines: list[str]) -> None:
    """Refuse a document nested deeper than MAX_YAML_DEPTH or expanding (through aliases) to
    more than MAX_YAML_NODES nodes. Iterative, and it stops at the limit: the expansion itself
    is never walked."""
    count = 0
    stack: list[tuple[yaml.Node, int]] = [(root, 1)]
    while stack:
        node, depth = stack.pop()
        count += 1
        line = node.start_mark.line + 1
        if count > guards.MAX_YAML_NODES:
            raise CaseError(
                f"the document expands to more than {guards.MAX_YAML_NODES:,} values (YAML "
                "aliases are counted at every use); expected a case file", file=name,
                line=line, source_line=guards.clip(lines[line - 1], 120)
                if line <= len(lines) else None)
        if depth > guards.MAX_YAML_DEPTH:
            raise CaseError(f"nested too deeply; expected at most {guards.MAX_YAML_DEPTH} "
                            "levels of mappings and lists", file=name, line=line)
        if isinstance(node, yaml.MappingNode):
            for key_node, value_node in node.value:
                stack.append((key_node, depth + 1))
                stack.append((value_node, depth + 1))
        elif isinstance(node, yaml.SequenceNode):
            stack.extend((item, depth + 1) for item in node.value)


def _index(node: yaml.Node, loc: Loc, src: Source) -> None:
    """Record the line of every key below ``node``; refuse duplicate keys."""
    if isinstance(node, yaml.MappingNode):
        seen: set = set()
        for key_node, value_node in node.value:
            key = str(key_node.value)  # complex keys are refused later by the schema
            child = (*loc, key)
            line = key_node.start_mark.line + 1
            if key in seen:
                src.key_lines[child] = line
                raise src.error(child, "duplicate key; each key may appear once per mapping")
            seen.add(key)
            src.key_lines[child] = line
            _index(value_node, child, src)
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            child = (*loc, i)
            src.key_lines[child] = item.start_mark.line + 1
            _index(item, child, src)
