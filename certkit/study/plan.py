"""The cases of a study and their keys.

A case is a pure function of (aircraft file content, variable values, certkit version, requested responses,
evaluator), so the content hash of those is its key: the same design asked twice — by two blocks, by a rerun,
by a later validation block — is one case, evaluated once.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from certkit import __version__
from certkit.errors import UserError
from certkit.study import doe
from certkit.study.spec import DesignBlock, Study

DEFAULT_EVALUATOR = "certkit.design.evaluate:evaluate_design"


def _sha256(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


@dataclass(frozen=True)
class CaseContext:
    """What every case of one study shares."""

    aircraft_path: str
    aircraft_sha256: str
    certkit_version: str
    responses: tuple[str, ...] | None
    evaluator: str

    @classmethod
    def of(cls, study: Study, evaluator: str = DEFAULT_EVALUATOR) -> "CaseContext":
        text = Path(study.aircraft).read_text(encoding="utf-8")
        return cls(study.aircraft, _sha256(text), __version__, tuple(study.responses) or None, evaluator)

    @property
    def digest(self) -> str:
        """Hash of everything but the values (the aircraft by content, not by path)."""
        return _sha256(json.dumps([self.aircraft_sha256, self.certkit_version, self.responses, self.evaluator]))

    def key(self, values: dict[str, float]) -> str:
        return _sha256(json.dumps([self.digest, sorted(values.items())]))


@dataclass(frozen=True)
class Case:
    key: str
    block: str
    role: str
    index: int  # position in its block
    values: dict[str, float]  # variable path → SI value


def cases_for_points(context: CaseContext, points: list[dict[str, float]], block: str, role: str) -> list[Case]:
    """One case per point (``{path: SI value}``); the same point twice is one case."""
    cases, seen = [], set()
    for i, point in enumerate(points):
        values = {path: float(value) for path, value in point.items()}
        key = context.key(values)
        if key not in seen:
            seen.add(key)
            cases.append(Case(key, block, role, i, values))
    return cases


def block_points(study: Study, block: DesignBlock) -> list[dict[str, float]]:
    """The block's points in SI, as {path: value} in the study's variable order."""
    try:
        values = doe.scale(doe.unit_points(block, len(study.variables)), study.variables)
    except ValueError as exc:  # e.g. a design the library cannot build for this many variables
        raise UserError(
            f"design block {block.name!r} ({block.generator}, {len(study.variables)} variables): {exc}"
        ) from None
    paths = study.variable_paths()
    return [dict(zip(paths, map(float, row))) for row in np.asarray(values)]


@dataclass(frozen=True)
class Plan:
    cases: list[Case]
    duplicates: dict[str, int]  # block → points already planned by an earlier block


def plan_study(study: Study, context: CaseContext) -> Plan:
    """Every block's cases in file order; a point an earlier block already has belongs to that block."""
    cases: list[Case] = []
    seen: set[str] = set()
    duplicates: dict[str, int] = {}
    for block in study.designs:
        for case in cases_for_points(context, block_points(study, block), block.name, block.role):
            if case.key in seen:
                duplicates[block.name] = duplicates.get(block.name, 0) + 1
                continue
            seen.add(case.key)
            cases.append(case)
    return Plan(cases, duplicates)
