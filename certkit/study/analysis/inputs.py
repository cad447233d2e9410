"""What the analysis reads: a light view of the study definition and the cases of the study store.

The study definition (``certkit.study.spec.Study``) and the store's DataFrame are described in INTERFACES.md.
:func:`study_view` is the one adapter from that definition (a pydantic object, or the same fields as a mapping)
to the frozen dataclasses below; nothing else in the analysis touches the definition's own classes.

Analysis options live in the study file's optional ``analysis:`` mapping::

    analysis:
      r2_threshold: 0.9            # validation R² below which a surrogate is flagged (default 0.9)
      level_relaxation:            # accept a worse MIL-F-8785C level for some cases in the constrained stage
        - {responses: "level.*.cg2*.*", max_level: 2}
      uncertainty:                 # declared model uncertainty on surrogate outputs
        - {responses: "rule.25.331*", percent: 10, distribution: uniform}   # or normal (percent = 1 sigma)
      profiler: [constraint.range_margin_m]   # constraint responses shown in the profiler (default: all)
      gp_max_cases: 600            # Gaussian process fitted only up to this many training cases
"""

from __future__ import annotations

import fnmatch
import hashlib
import json
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np
import pandas as pd

from certkit.errors import UserError

VAR_PREFIX = "var:"
RESP_PREFIX = "resp:"
LEVEL_PREFIX = "level."


@dataclass(frozen=True)
class Variable:
    path: str
    lower: float
    upper: float
    baseline: float
    unit_label: str = ""

    @property
    def short(self) -> str:
        """The last words of the path, enough to tell the variables apart in plots."""
        parts = self.path.split(".")
        return ".".join(parts[-2:]) if parts[-2] in ("elevator",) else parts[-1]


@dataclass(frozen=True)
class Objective:
    response: str
    sense: str = "min"


@dataclass(frozen=True)
class Constraint:
    """Feasible where ``min <= value <= max`` (either bound may be absent)."""

    name: str
    response: str
    min: float | None = None
    max: float | None = None

    @property
    def is_level(self) -> bool:
        return self.response.startswith(LEVEL_PREFIX)

    def feasible(self, values: np.ndarray, max_override: float | None = None) -> np.ndarray:
        """Boolean mask of feasible values. A handling-quality level (an integer 1..4 predicted by a
        regression) counts as level L where the prediction is below L + 0.5; ``max_override`` replaces the
        declared maximum (the level relaxation)."""
        upper = self.max if max_override is None else max_override
        lo, hi = self.min, upper
        if self.is_level:
            lo = None if lo is None else lo - 0.5
            hi = None if hi is None else hi + 0.5
        ok = np.isfinite(values)
        if lo is not None:
            ok &= values >= lo
        if hi is not None:
            ok &= values <= hi
        return ok

    def describe(self) -> str:
        if self.min is not None and self.max is not None:
            return f"{self.min:g} ≤ {self.response} ≤ {self.max:g}"
        if self.min is not None:
            return f"{self.response} ≥ {self.min:g}"
        return f"{self.response} ≤ {self.max:g}"


@dataclass(frozen=True)
class LevelRelaxation:
    """Level constraints whose response matches ``pattern`` accept ``max_level`` in the constrained stage."""

    pattern: str
    max_level: int


@dataclass(frozen=True)
class Uncertainty:
    """Relative model uncertainty on the outputs of the surrogates of responses matching ``pattern``:
    value × (1 + δ), δ ~ U(−p, +p) for ``uniform`` or N(0, p²) for ``normal``, p = percent / 100."""

    pattern: str
    percent: float
    distribution: str = "uniform"


@dataclass(frozen=True)
class Options:
    r2_threshold: float = 0.9
    level_relaxation: tuple[LevelRelaxation, ...] = ()
    uncertainty: tuple[Uncertainty, ...] = ()
    profiler: tuple[str, ...] | None = None
    gp_max_cases: int = 600

    def relaxed_max(self, constraint: Constraint) -> float | None:
        """The maximum level the constrained stage accepts for ``constraint`` (None: the declared one)."""
        if not constraint.is_level:
            return None
        levels = [r.max_level for r in self.level_relaxation if fnmatch.fnmatchcase(constraint.response, r.pattern)]
        return float(max(levels)) if levels else None

    def uncertainty_for(self, response: str) -> Uncertainty | None:
        return next((u for u in self.uncertainty if fnmatch.fnmatchcase(response, u.pattern)), None)


@dataclass(frozen=True)
class StudyView:
    name: str
    variables: tuple[Variable, ...]
    objectives: tuple[Objective, ...]
    constraints: tuple[Constraint, ...]
    options: Options = field(default_factory=Options)
    definition: Mapping[str, Any] = field(default_factory=dict)
    sha256: str = ""

    @property
    def bounds(self) -> np.ndarray:
        """(n_variables, 2) array of lower and upper bounds (SI)."""
        return np.array([[v.lower, v.upper] for v in self.variables], dtype=float)

    @property
    def baseline(self) -> np.ndarray:
        return np.array([v.baseline for v in self.variables], dtype=float)

    def analysed_responses(self) -> list[str]:
        """Responses the analysis fits surrogates for: objectives, constraints and profiled responses."""
        names = [o.response for o in self.objectives] + [c.response for c in self.constraints]
        names += list(self.options.profiler or ())
        return list(dict.fromkeys(names))

    def profiled_constraints(self) -> list[str]:
        if self.options.profiler is not None:
            return list(self.options.profiler)
        return list(dict.fromkeys(c.response for c in self.constraints))


def _get(obj: Any, name: str, default: Any = None) -> Any:
    if isinstance(obj, Mapping):
        return obj.get(name, default)
    return getattr(obj, name, default)


def _dump(obj: Any) -> Any:
    if hasattr(obj, "model_dump"):
        return obj.model_dump(mode="json")
    if isinstance(obj, Mapping):
        return {k: _dump(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_dump(v) for v in obj]
    return obj


def _number(value: Any, where: str, *, integer: bool = False, low: float | None = None) -> float:
    try:
        number = int(value) if integer else float(value)
    except (TypeError, ValueError):
        raise UserError(f"{where}: expected a number, got {value!r}") from None
    if integer and number != value:
        raise UserError(f"{where}: expected an integer, got {value!r}")
    if low is not None and number < low:
        raise UserError(f"{where}: expected at least {low:g}, got {value!r}")
    return number


def _options(raw: Any) -> Options:
    if raw is None:
        return Options()
    raw = _dump(raw)
    if not isinstance(raw, Mapping):
        raise UserError(f"analysis: expected a mapping of analysis options, got {raw!r}")
    known = {"r2_threshold", "level_relaxation", "uncertainty", "profiler", "gp_max_cases"}
    unknown = sorted(set(raw) - known)
    if unknown:
        raise UserError(f"analysis: unknown option(s) {', '.join(unknown)}; expected some of {', '.join(sorted(known))}")
    relax = []
    for i, item in enumerate(raw.get("level_relaxation") or []):
        where = f"analysis.level_relaxation[{i}]"
        if not isinstance(item, Mapping) or "responses" not in item or "max_level" not in item:
            raise UserError(f"{where}: expected {{responses: PATTERN, max_level: 1..3}}, got {item!r}")
        level = int(_number(item["max_level"], f"{where}.max_level", integer=True, low=1))
        if level > 3:
            raise UserError(f"{where}.max_level: MIL-F-8785C levels are 1, 2 or 3, got {level}")
        relax.append(LevelRelaxation(str(item["responses"]), level))
    unc = []
    for i, item in enumerate(raw.get("uncertainty") or []):
        where = f"analysis.uncertainty[{i}]"
        if not isinstance(item, Mapping) or "responses" not in item or "percent" not in item:
            raise UserError(f"{where}: expected {{responses: PATTERN, percent: X, distribution: uniform|normal}}, "
                            f"got {item!r}")
        dist = str(item.get("distribution", "uniform"))
        if dist not in ("uniform", "normal"):
            raise UserError(f"{where}.distribution: expected uniform or normal, got {dist!r}")
        unc.append(Uncertainty(str(item["responses"]), _number(item["percent"], f"{where}.percent", low=0.0), dist))
    threshold = _number(raw.get("r2_threshold", 0.9), "analysis.r2_threshold")
    if not threshold <= 1.0:
        raise UserError(f"analysis.r2_threshold: expected a value up to 1, got {threshold!r}")
    profiler = raw.get("profiler")
    return Options(r2_threshold=threshold, level_relaxation=tuple(relax), uncertainty=tuple(unc),
                   profiler=None if profiler is None else tuple(str(p) for p in profiler),
                   gp_max_cases=int(_number(raw.get("gp_max_cases", 600), "analysis.gp_max_cases", integer=True,
                                            low=0)))


def _bounds(v: Any) -> tuple[float, float]:
    """(lower, upper) of a variable: the study file's ``bounds`` pair (SI once validated) or lower/upper fields."""
    b = _get(v, "bounds")
    return (b[0], b[1]) if b is not None else (_get(v, "lower"), _get(v, "upper"))


def study_view(study: Any, sha256: str | None = None, analysis: Any = None) -> StudyView:
    """Adapter from the study definition (INTERFACES.md field names; a pydantic ``Study`` or a mapping with the
    same fields) to :class:`StudyView`. ``sha256`` identifies the study (the study file's hash); without it,
    the hash of the definition's canonical JSON is used. ``analysis``: the study file's ``analysis:`` mapping
    when the definition does not carry it."""
    variables = tuple(
        Variable(str(_get(v, "path")), *map(float, _bounds(v)), float(_get(v, "baseline")),
                 str(_get(v, "unit_label", "") or ""))
        for v in _get(study, "variables", []))
    if not variables:
        raise UserError("study: no design variables to analyse")
    for v in variables:
        if not v.upper > v.lower:
            raise UserError(f"variables.{v.path}: upper bound {v.upper!r} must exceed lower bound {v.lower!r}")
    objectives = tuple(Objective(str(_get(o, "response")), str(_get(o, "sense", "min") or "min"))
                       for o in _get(study, "objectives", []) or [])
    for o in objectives:
        if o.sense not in ("min", "max"):
            raise UserError(f"objectives.{o.response}.sense: expected min or max, got {o.sense!r}")
    constraints = tuple(
        Constraint(str(_get(c, "name") or _get(c, "response")), str(_get(c, "response")),
                   None if _get(c, "min") is None else float(_get(c, "min")),
                   None if _get(c, "max") is None else float(_get(c, "max")))
        for c in _get(study, "constraints", []) or [])
    definition = _dump(study)
    if sha256 is None:
        sha256 = hashlib.sha256(json.dumps(definition, sort_keys=True, default=str).encode()).hexdigest()
    return StudyView(name=str(_get(study, "name", "") or "study"), variables=variables, objectives=objectives,
                     constraints=constraints, options=_options(_get(study, "analysis") or analysis), definition=definition,
                     sha256=sha256)


@dataclass(frozen=True)
class Cases:
    """The store's cases split for the analysis: inputs X (n, n_variables, SI) per role, the responses, counts."""

    frame: pd.DataFrame
    x_columns: tuple[str, ...]

    def rows(self, role: str, status: str = "ok") -> pd.DataFrame:
        df = self.frame
        return df[(df["role"] == role) & (df["status"] == status)]

    def xy(self, role: str, response: str) -> tuple[np.ndarray, np.ndarray, int]:
        """Inputs and response values of the ``ok`` cases of ``role`` where the response was computed, and how
        many ``ok`` cases lacked it (NaN: not computed)."""
        rows = self.rows(role)
        column = RESP_PREFIX + response
        if column not in rows.columns:
            return np.empty((0, len(self.x_columns))), np.empty(0), len(rows)
        y = rows[column].to_numpy(dtype=float)
        keep = np.isfinite(y)
        return rows[list(self.x_columns)].to_numpy(dtype=float)[keep], y[keep], int((~keep).sum())

    def counts(self) -> pd.DataFrame:
        """Cases per block, role and status (the DoE summary)."""
        return (self.frame.groupby(["block", "role", "status"]).size().rename("cases").reset_index())

    def failed(self) -> pd.DataFrame:
        df = self.frame[self.frame["status"] == "failed"]
        return df[["key", "block", "role", "error"] + list(self.x_columns)]


def cases(frame: pd.DataFrame, view: StudyView) -> Cases:
    """Check that the store's frame carries every study variable and the bookkeeping columns."""
    needed = ["key", "block", "role", "status", "error"] + [VAR_PREFIX + v.path for v in view.variables]
    missing = [c for c in needed if c not in frame.columns]
    if missing:
        raise UserError(f"study store: column(s) {', '.join(missing)} missing; the store does not match the study "
                        f"definition (variables {', '.join(v.path for v in view.variables)})")
    return Cases(frame, tuple(VAR_PREFIX + v.path for v in view.variables))
