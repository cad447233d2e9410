"""Safe YAML loading that remembers the line of every value.

Only plain data is built (``yaml.SafeLoader``: mappings, sequences, scalars); no object
construction. Each value's dotted path (``geometry.wing.area``, ``cg_envelope.vertices.3.mass``)
maps to its 1-based line so that validation messages can point into the file.
"""

from __future__ import annotations

import errno
import hashlib
import os
import stat
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from certkit.aircraft.number_range import scalars
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

    def values_by_path(self) -> dict[str, object]:
        """Every scalar of the file by dotted path (list items by index), as written (a date or other YAML scalar as
        text): what two runs compare to name the inputs that changed."""
        plain = (str, int, float, bool)
        return dict(
            sorted(
                (".".join(map(str, loc)), v if v is None or isinstance(v, plain) else str(v))
                for loc, v in scalars(self.data)
            )
        )

    def line_of(self, loc: tuple) -> int | None:
        """Line of ``loc``, or of its nearest existing parent (a missing key points at its parent)."""
        loc = tuple(loc)
        while loc:
            if loc in self.lines:
                return self.lines[loc]
            loc = loc[:-1]
        return self.lines.get((), 1)


#: PyYAML's binding of libyaml, when it was built with it: the same nodes, marks and data, ~10× faster
_C_LOADER = getattr(yaml, "CSafeLoader", None)

#: input limits: an aircraft file is tens of kilobytes, a few levels deep, a few thousand values
MAX_FILE_BYTES = 4 * 1024 * 1024
MAX_DEPTH = 32
MAX_NODES = 200_000


def _structure_problem(text: str, loader) -> tuple[str, int | None] | None:
    """A reason to refuse the document before any node is built, with its line: nesting deeper than
    :data:`MAX_DEPTH`, more than :data:`MAX_NODES` values once every alias is expanded (an "alias bomb" is refused
    from its event stream, without expanding it) or an alias inside the node it names (a recursive document).
    None when the document is within the limits (its syntax is checked by the parser afterwards)."""
    open_nodes: list[list] = []  # [anchor, expanded size so far] of each open collection
    sizes: dict[str, int] = {}
    total = 0
    for event in yaml.parse(text, Loader=loader):
        kind = type(event)
        if kind in (yaml.ScalarEvent, yaml.AliasEvent, yaml.SequenceStartEvent, yaml.MappingStartEvent):
            if kind is yaml.AliasEvent:
                if any(anchor == event.anchor for anchor, _ in open_nodes):
                    return (
                        f"the alias *{event.anchor} refers to a node that contains it (recursive data)",
                        event.start_mark.line + 1,
                    )
                size = sizes.get(event.anchor, 1)
            else:
                size = 1
            total += size
            if total > MAX_NODES:
                return (
                    f"more than {MAX_NODES:,} values once aliases are expanded (an aircraft file has a few "
                    "thousand): refused without expanding them"
                ), event.start_mark.line + 1
            if kind in (yaml.SequenceStartEvent, yaml.MappingStartEvent):
                open_nodes.append([event.anchor, 1])
                if len(open_nodes) > MAX_DEPTH:
                    return f"nested more than {MAX_DEPTH} levels deep", event.start_mark.line + 1
                continue
            if open_nodes:
                open_nodes[-1][1] += size
            if kind is yaml.ScalarEvent and event.anchor:
                sizes[event.anchor] = 1
        elif kind in (yaml.SequenceEndEvent, yaml.MappingEndEvent):
            anchor, size = open_nodes.pop()
            if anchor:
                sizes[anchor] = size
            if open_nodes:
                open_nodes[-1][1] += size
    return None


def _parse_with(loader_class, text: str) -> tuple[yaml.Node | None, object]:
    """The node tree (with line marks) and the data of the one document, parsed once."""
    loader = loader_class(text)
    try:
        node = loader.get_single_node()
        return node, (loader.construct_document(node) if node is not None else None)
    finally:
        loader.dispose()


def _parse(text: str, path: str = "<text>") -> tuple[yaml.Node | None, object]:
    """The document's node tree and data, after :func:`_structure_problem` let it through. libyaml parses when
    available; a document it rejects is parsed again by PyYAML's own parser, so that errors read as they always did."""
    refused = None
    for loader in dict.fromkeys((_C_LOADER or yaml.SafeLoader, yaml.SafeLoader)):  # libyaml stops at 1000 levels
        try:
            refused = _structure_problem(text, loader)
            break
        except yaml.YAMLError:
            continue  # a syntax error: reported below by the parser
    if refused is not None:
        raise InputError(path, [Problem("", refused[0], line=refused[1], file=path)])
    if _C_LOADER is not None:
        try:
            return _parse_with(_C_LOADER, text)
        except yaml.YAMLError:
            pass
    return _parse_with(yaml.SafeLoader, text)


def _record(node: yaml.Node, loc: tuple, lines: dict, problems: list[Problem], path: str) -> None:
    lines[loc] = node.start_mark.line + 1
    if isinstance(node, yaml.MappingNode):
        seen: dict[object, int] = {}
        for key_node, value_node in node.value:
            key = key_node.value if isinstance(key_node, yaml.ScalarNode) else str(key_node.value)
            if key in seen:
                problems.append(
                    Problem(
                        ".".join(map(str, loc + (key,))),
                        f"duplicate key (first at line {seen[key]})",
                        line=key_node.start_mark.line + 1,
                        file=path,
                    )
                )
            seen[key] = key_node.start_mark.line + 1
            _record(value_node, loc + (key,), lines, problems, path)
            lines[loc + (key,)] = seen[key]  # a section is where its key is, not its first value
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            _record(item, loc + (i,), lines, problems, path)


def read_regular_file(path: str | Path, limit: int) -> bytes:
    """Up to ``limit + 1`` bytes of a regular file. Anything else is refused with an :class:`OSError` before a byte is
    read: a FIFO (opened without waiting for a writer, which would block for ever), a device (``/dev/zero`` never
    ends), a socket."""
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    with os.fdopen(fd, "rb") as f:
        mode = os.fstat(fd).st_mode
        if stat.S_ISDIR(mode):
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR))
        if not stat.S_ISREG(mode):
            raise NotRegularFile(errno.EINVAL, f"not a regular file (a {_kind(mode)}); give the path of a file on disk")
        return f.read(limit + 1)


class NotRegularFile(OSError):
    """An input path that names a FIFO, a device or a socket."""


def _kind(mode: int) -> str:
    return (
        "named pipe (FIFO)"
        if stat.S_ISFIFO(mode)
        else "character device"
        if stat.S_ISCHR(mode)
        else "block device"
        if stat.S_ISBLK(mode)
        else "socket"
        if stat.S_ISSOCK(mode)
        else "special file"
    )


def _read(path: Path) -> str:
    """The file's text, refused beyond :data:`MAX_FILE_BYTES` (read no further) or when not a regular file."""
    try:
        raw = read_regular_file(path, MAX_FILE_BYTES)
    except FileNotFoundError:
        raise InputError(str(path), [Problem("", "file not found")]) from None
    except IsADirectoryError:
        raise InputError(str(path), [Problem("", "is a folder, not a file")]) from None
    except NotRegularFile as exc:
        raise InputError(str(path), [Problem("", exc.strerror)]) from None
    except OSError as exc:
        raise InputError(str(path), [Problem("", f"cannot read the file: {exc.strerror or exc}")]) from None
    if len(raw) > MAX_FILE_BYTES:  # also checked by source_from_text, but /dev/zero must not be read whole
        raise InputError(
            str(path),
            [Problem("", f"file larger than {MAX_FILE_BYTES // 1024**2} MB (an aircraft file is tens of kilobytes)")],
        )
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(
            str(path), [Problem("", f"not UTF-8 text (byte {exc.start}: {raw[exc.start : exc.start + 1]!r})")]
        ) from None


def load_yaml(path: str | Path) -> YamlSource:
    path = Path(path)
    return source_from_text(_read(path), path)


def source_from_text(text: str, path: str | Path = "<text>") -> YamlSource:
    """The :class:`YamlSource` of YAML ``text`` (``path`` names it in messages), within the limits above."""
    path = Path(path)
    if len(text) > MAX_FILE_BYTES:
        raise InputError(str(path), [Problem("", f"text larger than {MAX_FILE_BYTES // 1024**2} MB")])
    try:
        node, data = _parse(text, str(path))
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = mark.line + 1 if mark else None
        what = getattr(exc, "problem", None) or str(exc)
        raise InputError(str(path), [Problem("", f"not valid YAML: {what}", line=line, file=str(path))]) from None
    except (RecursionError, MemoryError, OverflowError, ValueError) as exc:  # the parser's own limits and numbers
        raise InputError(
            str(path),
            [Problem("", f"cannot read the YAML: {exc.__class__.__name__}: {str(exc)[:120]}", file=str(path))],
        ) from None
    lines: dict[tuple, int] = {}
    problems: list[Problem] = []
    if node is not None:
        _record(node, (), lines, problems, str(path))
    if problems:
        raise InputError(str(path), problems)
    return YamlSource(str(path), text, data, lines)
