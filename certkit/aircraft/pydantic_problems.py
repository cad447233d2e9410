"""Pydantic validation errors turned into located problems (YAML path, line, the value as written).

Shared by every YAML input validated with pydantic (the aircraft file, the study file).
"""

from __future__ import annotations

from pydantic import ValidationError

from certkit.aircraft.yaml_source import YamlSource
from certkit.errors import Problem

Found = tuple[tuple, str, object]  # (location, message, value)


def pydantic_messages(schema_command: str) -> dict[str, str]:
    """Plainer wording for pydantic's most common error types."""
    return {
        "missing": "required field is missing",
        "extra_forbidden": f"unknown field (check the spelling; `{schema_command}` lists the fields)",
    }


def found_in(err: ValidationError, prefix: tuple = (), schema_command: str = "certkit schema") -> list[Found]:
    """Every error of ``err`` as (location below ``prefix``, message, value given)."""
    messages = pydantic_messages(schema_command)
    found = []
    for e in err.errors(include_url=False):
        message = messages.get(e["type"], e["msg"])
        message = message.removeprefix("Value error, ")
        found.append((prefix + tuple(e["loc"]), message, None if e["type"] == "missing" else e.get("input")))
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
        Problem(".".join(map(str, loc)), message, value,
                source.line_of(loc) if source else None, source.path if source else None)
        for loc, message, value in found
    ]
