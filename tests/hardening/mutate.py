"""Variants of the baseline aircraft file for the hardening tests: one value replaced by a YAML path."""

from __future__ import annotations

import copy
from functools import lru_cache

import yaml

from ..conftest import BASELINE


@lru_cache(maxsize=1)
def _baseline_data() -> dict:
    return yaml.safe_load(BASELINE.read_text(encoding="utf-8"))


def baseline_data() -> dict:
    """A fresh copy of the baseline file's plain data."""
    return copy.deepcopy(_baseline_data())


def with_value(path: str, value: object) -> dict:
    """The baseline data with the value at dotted ``path`` replaced (``mass.components.0.inertia.Iyy``)."""
    data = baseline_data()
    *parents, last = path.split(".")
    node = data
    for key in parents:
        node = node[int(key)] if isinstance(node, list) else node[key]
    node[int(last) if isinstance(node, list) else last] = value
    return data


def write_yaml(tmp_path, data: object, name: str = "aircraft.yaml"):
    path = tmp_path / name
    path.write_text(yaml.safe_dump(data, sort_keys=False, allow_unicode=True), encoding="utf-8")
    return path
