"""The aircraft file: loading, validation with YAML lines, and the JSON Schema.

``load_aircraft(path)`` returns a :class:`LoadedAircraft` or raises :class:`InputError` listing
every problem of the file at once (YAML path, line, value, expectation).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pydantic import TypeAdapter, ValidationError

from certkit.aircraft.consistency import consistency_problems
from certkit.aircraft.model import Aircraft
from certkit.aircraft.number_range import extreme_numbers
from certkit.aircraft.pydantic_problems import found_in, located, pydantic_messages, raw_at, split_path
from certkit.aircraft.yaml_source import YamlSource, load_yaml
from certkit.errors import InputError, Problem

__all__ = ["Aircraft", "LoadedAircraft", "load_aircraft", "validate_aircraft_data", "json_schema"]


@dataclass(frozen=True)
class LoadedAircraft:
    model: Aircraft
    path: str
    sha256: str
    source: YamlSource

    @property
    def name(self) -> str:
        return self.model.name


#: a section's validator by its name (building one costs as much as validating the section)
_ADAPTERS: dict[str, TypeAdapter[Any]] = {}


def _adapter(name: str, annotation: Any) -> TypeAdapter[Any]:
    """The validator of the section ``name`` (its field annotation on :class:`Aircraft`), built once per process."""
    if name not in _ADAPTERS:
        _ADAPTERS[name] = TypeAdapter(annotation)
    return _ADAPTERS[name]


def validate_aircraft_data(data: object, source: YamlSource | None = None) -> Aircraft:
    """Validate plain data section by section, then the relations between sections; raise an
    :class:`InputError` with every problem found."""
    path = source.path if source else "<data>"
    if not isinstance(data, dict):
        raise InputError(
            path, [Problem("", "the file must be a mapping of sections (name:, reference:, ...)", type(data).__name__)]
        )
    found = []
    sections: dict[str, object] = {}
    fields = Aircraft.model_fields
    found += [
        ((key,), pydantic_messages("certkit schema")["extra_forbidden"], None) for key in data if key not in fields
    ]
    for name, info in fields.items():
        if name not in data:
            if info.is_required():
                found.append(((name,), "required section is missing", None))
            else:  # a default section takes part in the relations (the default 'clean' configuration...)
                sections[name] = info.get_default(call_default_factory=True)
            continue
        try:
            sections[name] = _adapter(name, info.annotation).validate_python(data[name])
        except ValidationError as err:
            found += found_in(err, (name,), data=data)
        extreme = extreme_numbers(data[name], (name,))
        if extreme:  # reported once per place; the section's relations are not checked with such numbers
            sections.pop(name, None)
            reported = {loc for loc, _, _ in found}
            found += [f for f in extreme if f[0] not in reported]
    found += [
        (split_path(p.path), p.message, raw_at(data, split_path(p.path), p.value))
        for p in consistency_problems(sections)
    ]
    if found:
        raise InputError(path, located(found, source))
    try:
        return Aircraft.model_validate(data)
    except ValidationError as err:  # a relation the section models check together (none today): still located
        raise InputError(path, located(found_in(err, data=data), source)) from None


def load_aircraft(path: str | Path) -> LoadedAircraft:
    source = load_yaml(path)
    model = validate_aircraft_data(source.data, source)
    return LoadedAircraft(model=model, path=str(path), sha256=source.sha256, source=source)


def json_schema() -> dict:
    schema = Aircraft.model_json_schema()
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "certkit aircraft file"
    return schema
