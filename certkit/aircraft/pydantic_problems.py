"""Pydantic validation errors turned into located problems (YAML path, line, the value as written).

Shared by every YAML input validated with pydantic (the aircraft file, the study file).
"""

from __future__ import annotations

from pydantic import ValidationError

from certkit.aircraft.yaml_source import YamlSource
from certkit.errors import Problem
from certkit.units import si_reading

Found = tuple[tuple, str, object]  # (location, message, value)


def pydantic_messages(schema_command: str) -> dict[str, str]:
    """Plainer wording for pydantic's most common error types."""
    return {
        "missing": "required field is missing",
        "extra_forbidden": f"unknown field (check the spelling; `{schema_command}` lists the fields)",
    }


def found_in(
    err: ValidationError, prefix: tuple = (), schema_command: str = "certkit schema", data: object = None
) -> list[Found]:
    """Every error of ``err`` as (location below ``prefix``, message, value as written).

    With ``data`` (the raw data ``prefix`` starts from), pydantic's own steps in a location (``constrained-float``,
    ``literal['root', 'side_of_body']``, a model name: the members of a union) are dropped, so that the location is a
    YAML path; the errors of a union's members at one place become one message, and a member that matched the
    value's shape deeper (a list item, a mapping's field) speaks for the union alone. The value shown is the one in
    the file ("-5 lb"), with its SI reading when that is what the limit was compared with."""
    messages = pydantic_messages(schema_command)
    raw_root = _descend(data, prefix) if data is not None else None
    entries = []
    for e in err.errors(include_url=False):
        loc, tagged = (
            _yaml_path(raw_root, tuple(e["loc"]), keep_last=e["type"] == "missing")
            if data is not None
            else (tuple(e["loc"]), False)
        )
        message = messages.get(e["type"], e["msg"]).removeprefix("Value error, ")
        value = None if e["type"] == "missing" else e.get("input")
        if data is not None and e["type"] != "missing":
            written = raw_at(raw_root, loc, value)
            if isinstance(written, str) and e["type"] in _LIMIT_TYPES:
                si = si_reading(written)
                if si is not None:
                    message += f" (read as {si:.6g} in SI units)"
            value = written
        entries.append((prefix + loc, message, value, tagged))
    return _merge_union_members(entries)


#: pydantic error types that compare a value with a limit in SI units
_LIMIT_TYPES = ("greater_than", "greater_than_equal", "less_than", "less_than_equal")


def _descend(data: object, loc: tuple) -> object:
    for key in loc:
        try:
            data = data[key]
        except (KeyError, IndexError, TypeError):
            return None
    return data


def _yaml_path(raw: object, loc: tuple, keep_last: bool) -> tuple[tuple, bool]:
    """``loc`` without the steps that are not in ``raw`` (pydantic's union-member tags); whether any was dropped."""
    out, dropped = [], False
    for i, key in enumerate(loc):
        if isinstance(raw, dict) and key in raw:
            out.append(key)
            raw = raw[key]
        elif isinstance(raw, list) and isinstance(key, int) and 0 <= key < len(raw):
            out.append(key)
            raw = raw[key]
        elif keep_last and i == len(loc) - 1:
            out.append(key)
        else:
            dropped = True
    return tuple(out), dropped


def _merge_union_members(entries: list) -> list[Found]:
    """One problem per location; a union member's error at a location that another member's error goes below is
    dropped (the value has the other member's shape)."""
    locs = [loc for loc, *_ in entries]
    kept: dict[tuple, list] = {}
    for loc, message, value, tagged in entries:
        if tagged and any(len(other) > len(loc) and other[: len(loc)] == loc for other in locs):
            continue
        kept.setdefault(loc, [[], value])[0].append(message)
    found = []
    for loc, (msgs, value) in kept.items():
        msgs = list(dict.fromkeys(msgs))
        if "Input should be a finite number" in msgs:
            msgs = ["Input should be a finite number"]  # a NaN or infinity, whatever else the field takes
        if len(msgs) > 1 and all(m.startswith("Input should be ") for m in msgs):
            msgs = ["expected " + "; or ".join(m.removeprefix("Input should be ") for m in msgs)]
        found.append((loc, "; or ".join(msgs), value))
    return found


def split_path(path: str) -> tuple:
    """``"a.3.b"`` → ``("a", 3, "b")``."""
    return tuple(int(part) if part.isdigit() else part for part in path.split(".") if part)


def raw_at(data: object, loc: tuple, default: object) -> object:
    """The value as the user wrote it (``"460000 lb"``), when ``loc`` names a scalar."""
    for key in loc:
        try:
            data = data[key]
        except (KeyError, IndexError, TypeError):
            return default
    return data if isinstance(data, (str, int, float)) else default


def located(found: list[Found], source: YamlSource | None) -> list[Problem]:
    """Problems with the file and line of each location (the nearest existing parent's line for a missing key)."""
    return [
        Problem(
            ".".join(map(str, loc)),
            message,
            value,
            source.line_of(loc) if source else None,
            source.path if source else None,
        )
        for loc, message, value in found
    ]
