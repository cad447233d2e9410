"""Safe YAML loading that remembers the line of every value.

Only plain data is built (``yaml.SafeLoader``: mappings, sequences, scalars); no object
construction. Each value's dotted path (``geometry.wing.area``, ``cg_envelope.vertices.3.mass``)
maps to its 1-based line so that validation messages can point into the file.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from certkit.errors import InputError, Problem


@dataclass
class YamlSource:
    path: str
    text: str
    data: object
    lines: dict[tuple, int] = field(default_factory=dict)

    @property
    def sha256(self) -> str:
        return hashlib.sha256(self.text.encode("utf-8")).hexdigest()

    def line_of(self, loc: tuple) -> int | None:
        """Line of ``loc``, or of its nearest existing parent (a missing key points at its parent)."""
        loc = tuple(loc)
        while loc:
            if loc in self.lines:
                return self.lines[loc]
            loc = loc[:-1]
        return self.lines.get((), 1)


class _UniqueKeyLoader(yaml.SafeLoader):
    """SafeLoader that rejects duplicate keys (PyYAML silently keeps the last one)."""


#: PyYAML's binding of libyaml, when it was built with it: the same nodes, marks and data, ~10× faster
_C_LOADER = getattr(yaml, "CSafeLoader", None)


def _parse(text: str) -> tuple[yaml.Node | None, object]:
    """The document's node tree (with line marks) and its data. libyaml parses when available; a document it
    rejects is parsed again by PyYAML's own parser, so that errors read as they always did."""
    if _C_LOADER is not None:
        try:
            return yaml.compose(text, Loader=_C_LOADER), yaml.load(text, Loader=_C_LOADER)
        except yaml.YAMLError:
            pass
    return yaml.compose(text, Loader=_UniqueKeyLoader), yaml.load(text, Loader=yaml.SafeLoader)


def _record(node: yaml.Node, loc: tuple, lines: dict, problems: list[Problem], path: str) -> None:
    lines[loc] = node.start_mark.line + 1
    if isinstance(node, yaml.MappingNode):
        seen: dict[object, int] = {}
        for key_node, value_node in node.value:
            key = key_node.value if isinstance(key_node, yaml.ScalarNode) else str(key_node.value)
            if key in seen:
                problems.append(Problem(".".join(map(str, loc + (key,))), f"duplicate key (first at line {seen[key]})",
                                        line=key_node.start_mark.line + 1, file=path))
            seen[key] = key_node.start_mark.line + 1
            _record(value_node, loc + (key,), lines, problems, path)
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            _record(item, loc + (i,), lines, problems, path)


def load_yaml(path: str | Path) -> YamlSource:
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(str(path), [Problem("", "file not found")]) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(str(path), [Problem("", f"cannot read the file: {exc}")]) from None
    try:
        node, data = _parse(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = mark.line + 1 if mark else None
        what = getattr(exc, "problem", None) or str(exc)
        raise InputError(str(path), [Problem("", f"not valid YAML: {what}", line=line, file=str(path))]) from None
    lines: dict[tuple, int] = {}
    problems: list[Problem] = []
    if node is not None:
        _record(node, (), lines, problems, str(path))
    if problems:
        raise InputError(str(path), problems)
    return YamlSource(str(path), text, data, lines)
