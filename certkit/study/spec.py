"""The study file: which aircraft, which design variables, which designs of experiments, what to record.

YAML read like the aircraft file (every value's line remembered, :mod:`certkit.aircraft.yaml_source`) and
validated with pydantic; every problem is reported at once with its YAML path and line (exit code 2).
Quantities are numbers in SI or strings with a unit ("1119 ft^2", "34.82 deg"), converted at load time, so
that a validated :class:`Study` holds SI floats only. ``certkit study schema`` prints the JSON Schema.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from fnmatch import fnmatchcase
from pathlib import Path
from typing import Annotated, Any, Literal, Union

import numpy as np
from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    ValidationError,
    ValidationInfo,
    WithJsonSchema,
    field_validator,
    model_validator,
)

from certkit.aircraft.pydantic_problems import Found, found_in, located
from certkit.aircraft.yaml_source import YamlSource, load_yaml
from certkit.errors import InputError, Problem, UserError
from certkit.units import DIMENSIONS, UnitError, to_si

SCHEMA_COMMAND = "certkit study schema"
ROLES = ("training", "validation")
_PERCENT = re.compile(r"^\s*(?:±|\+-|\+/-)\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(?:%|percent)\s*$")
_PATH = r"^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)+$"


def parse_quantity(value: object) -> tuple[float, str | None]:
    """A number (taken as SI) or a string with a unit of any known dimension → (SI float, dimension name).
    A bare number has no dimension (None); angles and plain ratios share the dimension name "angle"."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ValueError(f"expected a number or a string with a unit, got {type(value).__name__}")
    if not isinstance(value, str):
        return float(value), None
    for dimension in DIMENSIONS:
        try:
            return to_si(value, dimension), dimension
        except UnitError:
            continue
    raise ValueError(f"cannot read {value!r} as a number or a quantity with a unit")


def _si(value: object) -> object:
    if not isinstance(value, str):
        return value  # a number, or a wrong type that pydantic reports with its own words
    return parse_quantity(value)[0]


Quantity = Annotated[
    float,
    BeforeValidator(_si),
    WithJsonSchema(
        {
            "anyOf": [{"type": "number"}, {"type": "string"}],
            "description": 'a number in SI units or a string with a unit, e.g. "1119 ft^2", "34.82 deg"',
        }
    ),
]


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class Variable(_Model):
    """A design variable: an aircraft-file path, its baseline and its bounds (SI once validated)."""

    path: str = Field(pattern=_PATH, description="aircraft-file path, e.g. geometry.horizontal_tail.area")
    baseline: Quantity = Field(description="the baseline design's value")
    bounds: Annotated[
        tuple[float, float],
        WithJsonSchema(
            {
                "anyOf": [
                    {
                        "type": "array",
                        "minItems": 2,
                        "maxItems": 2,
                        "items": {"anyOf": [{"type": "number"}, {"type": "string"}]},
                    },
                    {"type": "string", "pattern": "^\\s*(±|\\+-|\\+/-)"},
                ],
                "description": '[lower, upper] (numbers in SI or strings with a unit), or "±20 %" of the baseline',
            }
        ),
    ]
    unit_label: str = Field(
        "", description="unit to show values in (default: the unit written for the baseline or bounds; empty for SI)"
    )

    @property
    def lower(self) -> float:
        return self.bounds[0]

    @property
    def upper(self) -> float:
        return self.bounds[1]

    @property
    def short(self) -> str:
        """The last words of the path, enough to tell the variables apart in tables and plots."""
        parts = self.path.split(".")
        return ".".join(parts[-2:]) if parts[-2] in ("elevator",) else parts[-1]

    @model_validator(mode="before")
    @classmethod
    def _units_agree(cls, data: object) -> object:
        """The baseline and the bounds written with units must all be of one dimension; the first unit written
        becomes the display unit."""
        if not isinstance(data, dict):
            return data
        written = [data.get("baseline")]
        if isinstance(data.get("bounds"), (list, tuple)):
            written += list(data["bounds"])
        dims: set[str] = set()
        label = ""
        for value in written:
            if isinstance(value, str) and not _PERCENT.match(value):
                try:
                    _, dim = parse_quantity(value)
                except ValueError:
                    continue  # reported on the field itself
                if dim is not None:
                    dims.add(dim)
                label = label or _unit_of(value)
        if len(dims) > 1:
            raise ValueError(f"baseline and bounds are written in units of different kinds ({', '.join(sorted(dims))})")
        if label and "unit_label" not in data:
            data = {**data, "unit_label": label}
        return data

    @field_validator("bounds", mode="before")
    @classmethod
    def _absolute(cls, value: object, info: ValidationInfo) -> object:
        """``"±P %"`` of the baseline → [lower, upper]; a pair of quantities → SI floats."""
        if isinstance(value, str):
            match = _PERCENT.match(value)
            if not match:
                raise ValueError('bounds must be [lower, upper] or a percentage of the baseline such as "±20 %"')
            if "baseline" not in info.data:
                raise ValueError("a ± percentage needs a valid baseline")
            base, p = info.data["baseline"], float(match.group(1)) / 100.0
            return tuple(sorted((base * (1.0 - p), base * (1.0 + p))))
        if isinstance(value, (list, tuple)):
            return tuple(_si(v) for v in value)
        return value

    @field_validator("bounds")
    @classmethod
    def _ordered(cls, value: tuple[float, float], info: ValidationInfo) -> tuple[float, float]:
        lower, upper = value
        if not lower < upper:
            raise ValueError(f"the lower bound ({lower:g}) must be below the upper bound ({upper:g}) (SI units)")
        base = info.data.get("baseline")
        if base is not None and not lower <= base <= upper:
            raise ValueError(f"the baseline ({base:g}) lies outside the bounds [{lower:g}, {upper:g}] (SI units)")
        return value


def _unit_of(text: str) -> str:
    """The unit part of "1119 ft^2" → "ft^2"."""
    match = re.match(r"^\s*[-+]?(?:[0-9]*\.?[0-9]+)(?:[eE][-+]?[0-9]+)?\s*(.*?)\s*$", text)
    return match.group(1) if match else ""


class _Block(_Model):
    name: str = Field(pattern=r"^[A-Za-z0-9][A-Za-z0-9_.-]*$", description="block name (unique in the study)")
    role: Literal["training", "validation"] = Field("training", description="training data, or held-out validation")


class CcdBlock(_Block):
    """Face-centred central composite design (axial points on the faces, α = 1: three levels, inside the
    bounds), on a resolution-V two-level fraction unless ``fraction: full`` (NIST/SEMATECH e-Handbook §5.3.3.6.1)."""

    generator: Literal["ccd"]
    fraction: Literal["resolution-v", "full"] = Field(
        "resolution-v",
        description="factorial part: smallest fraction of resolution V or more (pydoe "
        "fracfact_by_res), or the full 2^k factorial",
    )
    center: int = Field(1, ge=0, description="centre points (repeats of one point count once)")


class BoxBehnkenBlock(_Block):
    """Box–Behnken design (Box & Behnken 1960; pydoe bbdesign): pairs of factors at ±1, the others at the centre."""

    generator: Literal["box-behnken"]
    center: int = Field(0, ge=0, description="centre points (repeats of one point count once)")


class LhsBlock(_Block):
    """Latin hypercube (scipy.stats.qmc.LatinHypercube), space-filling by default: ``random-cd`` lowers the
    centred L2-discrepancy by random coordinate swaps (Fang et al. 2002); ``lloyd`` relaxes towards a
    centroidal Voronoi tessellation; ``none`` keeps the plain random LHS."""

    generator: Literal["lhs"]
    n: int = Field(gt=0, description="number of points")
    seed: int = Field(ge=0, description="random seed (the same seed gives the same points)")
    criterion: Literal["random-cd", "lloyd", "none"] = Field("random-cd", description="space-filling criterion")


class RandomBlock(_Block):
    """Independent uniform points (numpy PCG64 generator); a larger ``n`` with the same seed keeps the first points."""

    generator: Literal["random"]
    n: int = Field(gt=0, description="number of points")
    seed: int = Field(ge=0, description="random seed (the same seed gives the same points)")


DesignBlock = Annotated[Union[CcdBlock, BoxBehnkenBlock, LhsBlock, RandomBlock], Field(discriminator="generator")]


class Objective(_Model):
    response: str = Field(description="response name, e.g. objective.block_fuel_kg")
    sense: Literal["min", "max"] = "min"


LEVEL_PREFIX = "level."


#: the word that makes a constraint's bound the baseline design's own value of its response
BASELINE = "baseline"


class Constraint(_Model):
    """Feasible when ``min <= response <= max`` (either side optional, SI units). A bound written ``baseline`` is the
    baseline design's value of the response ("no worse than the baseline"): the analysis reads it from the baseline
    design's case (evaluated once and kept in the store) before it uses the constraint
    (:meth:`Study.with_baseline_bounds`)."""

    name: str
    response: str = Field(description="response name, e.g. subcheck.25.111.elevator_fraction_of_travel.value")
    min: Quantity | None = None
    max: Quantity | None = None
    min_from_baseline: bool = Field(False, description="set by `min: baseline`: the bound is the baseline's value")
    max_from_baseline: bool = Field(False, description="set by `max: baseline`: the bound is the baseline's value")

    @model_validator(mode="before")
    @classmethod
    def _baseline_bounds(cls, data: Any) -> Any:
        if isinstance(data, dict):
            data = dict(data)
            for side in ("min", "max"):
                if isinstance(data.get(side), str) and data[side].strip().lower() == BASELINE:
                    data[side] = None
                    data[f"{side}_from_baseline"] = True
        return data

    @model_validator(mode="after")
    def _bounded(self) -> "Constraint":
        if self.min is None and self.max is None and not (self.min_from_baseline or self.max_from_baseline):
            raise ValueError("a constraint needs a min or a max (or both; `baseline` for the baseline's value)")
        if self.min is not None and self.max is not None and self.min > self.max:
            raise ValueError(f"min ({self.min:g}) is above max ({self.max:g})")
        return self

    @property
    def needs_baseline(self) -> bool:
        """A bound is the baseline's value and has not been read yet."""
        return (self.min_from_baseline and self.min is None) or (self.max_from_baseline and self.max is None)

    @property
    def is_level(self) -> bool:
        """A MIL-F-8785C handling-quality level (1 best) rather than a continuous quantity."""
        return self.response.startswith(LEVEL_PREFIX)

    def feasible(self, values: np.ndarray, max_override: float | None = None) -> np.ndarray:
        """Boolean mask of feasible values. A level (an integer 1..3, or a regression of it) counts as level L
        where the value is below L + 0.5; ``max_override`` replaces the declared maximum (level relaxation)."""
        if self.needs_baseline:
            raise ValueError(f"constraint {self.name!r}: its baseline bound has not been read (with_baseline_bounds)")
        lo, hi = self.min, self.max if max_override is None else max_override
        if self.is_level:
            lo = None if lo is None else lo - 0.5
            hi = None if hi is None else hi + 0.5
        values = np.asarray(values, dtype=float)
        ok: np.ndarray = np.isfinite(values)
        if lo is not None:
            ok &= values >= lo
        if hi is not None:
            ok &= values <= hi
        return ok

    def describe(self) -> str:
        def bound(value: float | None, relative: bool) -> str:
            if relative:
                return BASELINE if value is None else f"{value:g} (the baseline's)"
            return "" if value is None else f"{value:g}"

        lo, hi = bound(self.min, self.min_from_baseline), bound(self.max, self.max_from_baseline)
        has_lo, has_hi = self.min is not None or self.min_from_baseline, self.max is not None or self.max_from_baseline
        if has_lo and has_hi:
            return f"{lo} ≤ {self.response} ≤ {hi}"
        if has_lo:
            return f"{self.response} ≥ {lo}"
        return f"{self.response} ≤ {hi}"


class LevelRelaxation(_Model):
    """Level constraints whose response matches ``responses`` accept ``max_level`` in the constrained stage."""

    responses: str = Field(description="glob pattern of level constraint responses, e.g. level.*.cg2*.*")
    max_level: int = Field(ge=1, le=3, description="the worst MIL-F-8785C level accepted (1, 2 or 3)")

    @property
    def pattern(self) -> str:
        return self.responses


class Uncertainty(_Model):
    """Relative model uncertainty on the surrogate outputs of the constraint responses matching ``responses``:
    value × (1 + δ), δ ~ U(−p, +p) for ``uniform`` or N(0, p²) for ``normal``, p = percent / 100."""

    responses: str = Field(description="glob pattern of constraint responses, e.g. travel.*")
    percent: float = Field(ge=0, description="p in percent (one standard deviation for normal)")
    distribution: Literal["uniform", "normal"] = "uniform"

    @property
    def pattern(self) -> str:
        return self.responses


class AnalysisOptions(_Model):
    """Options of ``certkit study report`` (the study file's ``analysis:`` mapping)."""

    r2_threshold: float = Field(
        0.9, le=1.0, description="R² (cross-validated, or on validation) below which a surrogate is flagged"
    )
    level_relaxation: list[LevelRelaxation] = Field(default_factory=list)
    uncertainty: list[Uncertainty] = Field(default_factory=list)
    profiler: list[str] | None = Field(
        None, description="constraint responses shown in the profiler (default: every constraint's)"
    )
    gp_max_cases: int = Field(
        600,
        ge=0,
        description="a Gaussian process is fitted on at most this many training "
        "cases (a maximin subsample of them above it; 0: no Gaussian "
        "process)",
    )

    def relaxed_max(self, constraint: Constraint) -> float | None:
        """The maximum level the constrained stage accepts for ``constraint`` (None: the declared one)."""
        if not constraint.is_level:
            return None
        levels = [r.max_level for r in self.level_relaxation if fnmatchcase(constraint.response, r.responses)]
        return float(max(levels)) if levels else None

    def uncertainty_for(self, response: str) -> Uncertainty | None:
        return next((u for u in self.uncertainty if fnmatchcase(response, u.responses)), None)


def _no_analysis(value: object) -> object:
    return {} if value is None else value


class Study(_Model):
    """A design study: variables with bounds, designs of experiments, and what each case records."""

    model_config = ConfigDict(extra="forbid", frozen=True, json_schema_extra={"title": "certkit study file"})

    name: str = Field("", description="study name (default: the file name)")
    aircraft: str = Field(
        description="the base aircraft file, relative to the study file (held as an absolute path once loaded)"
    )
    variables: list[Variable] = Field(min_length=1)
    designs: list[DesignBlock] = Field(min_length=1)
    responses: list[str] = Field(
        default_factory=list,
        description="response names or glob patterns each case "
        "records (e.g. objective.*, rule.*.margin); empty = every response",
    )
    objectives: list[Objective] = Field(default_factory=list)
    constraints: list[Constraint] = Field(default_factory=list)
    analysis: Annotated[AnalysisOptions, BeforeValidator(_no_analysis)] = Field(
        default_factory=AnalysisOptions,
        description="options of `certkit study report` (see docs/design-studies.md)",
    )

    def variable_paths(self) -> list[str]:
        return [v.path for v in self.variables]

    def requested(self, response: str) -> bool:
        """True when ``response`` is matched by one of the study's response patterns (every one if none)."""
        return not self.responses or any(fnmatchcase(response, p) for p in self.responses)

    @property
    def bounds(self) -> np.ndarray:
        """(n_variables, 2) array of lower and upper bounds (SI)."""
        return np.array([[v.lower, v.upper] for v in self.variables], dtype=float)

    @property
    def baseline(self) -> np.ndarray:
        return np.array([v.baseline for v in self.variables], dtype=float)

    @property
    def needs_baseline(self) -> bool:
        """Some constraint's bound is the baseline's value and has not been read yet."""
        return any(c.needs_baseline for c in self.constraints)

    def with_baseline_bounds(self, values: dict[str, float | None]) -> "Study":
        """The study with every ``baseline`` bound set to the baseline design's value of its response (``values``:
        response → that value); a value the baseline's case does not give is an error naming the constraint."""
        constraints = []
        for i, c in enumerate(self.constraints):
            if not c.needs_baseline:
                constraints.append(c)
                continue
            value = values.get(c.response)
            if value is None or not np.isfinite(value):
                raise UserError(
                    f"study {self.name}: constraints[{i}] ({c.name}): its bound is the baseline's value of "
                    f"{c.response}, which the baseline design's case does not give (got {value}; expected a finite "
                    "value: the response is recorded and the baseline's case evaluates it)"
                )
            update = {side: float(value) for side in ("min", "max") if getattr(c, f"{side}_from_baseline")}
            constraints.append(c.model_copy(update=update))
        return self.model_copy(update={"constraints": constraints})

    def allowed_max(self, constraint: Constraint, stage: str = "constrained") -> float | None:
        """The constraint's maximum as a stage of the analysis takes it: a level's relaxed maximum
        (:meth:`AnalysisOptions.relaxed_max`), at most Level 1 in the preferred stage; else the declared one."""
        if not constraint.is_level:
            return constraint.max
        relaxed = self.analysis.relaxed_max(constraint)
        upper = constraint.max if relaxed is None else relaxed
        if stage == "preferred":
            upper = 1.0 if upper is None else min(upper, 1.0)
        return upper

    def holds(self, constraint: Constraint, values: np.ndarray, stage: str = "constrained") -> np.ndarray:
        """Where ``values`` of ``constraint``'s response meet it as a stage of the analysis judges, up to the stage's
        :meth:`allowed_max`."""
        return constraint.feasible(values, self.allowed_max(constraint, stage))

    def analysed_responses(self) -> list[str]:
        """Responses the analysis fits surrogates for: objectives, constraints and profiled responses."""
        names = [o.response for o in self.objectives] + [c.response for c in self.constraints]
        names += list(self.analysis.profiler or ())
        return list(dict.fromkeys(names))

    def profiled_constraints(self) -> list[str]:
        if self.analysis.profiler is not None:
            return list(self.analysis.profiler)
        return list(dict.fromkeys(c.response for c in self.constraints))


_MIN_FACTORS = {"ccd": 2, "box-behnken": 3}


def relation_problems(study: Study) -> list[Found]:
    """What each field alone cannot tell: duplicates, designs the number of variables does not allow,
    objectives and constraints on responses the study does not record."""
    found: list[Found] = []

    def unique(items: Sequence[BaseModel], field: str, section: str) -> None:
        seen: dict[str, int] = {}
        for i, item in enumerate(items):
            value = getattr(item, field)
            if value in seen:
                found.append(((section, i, field), f"duplicate (first at {section}.{seen[value]})", value))
            seen.setdefault(value, i)

    unique(study.variables, "path", "variables")
    unique(study.designs, "name", "designs")
    unique(study.constraints, "name", "constraints")
    for i, block in enumerate(study.designs):
        need = _MIN_FACTORS.get(block.generator, 1)
        if len(study.variables) < need:
            found.append(
                (
                    ("designs", i, "generator"),
                    f"{block.generator} needs at least {need} variables (the study has {len(study.variables)})",
                    block.generator,
                )
            )
    responses: tuple[tuple[str, Sequence[Objective | Constraint]], ...] = (
        ("objectives", study.objectives),
        ("constraints", study.constraints),
    )
    for section, items in responses:
        for i, item in enumerate(items):
            if not study.requested(item.response):
                found.append(
                    ((section, i, "response"), "not recorded: no pattern of `responses:` matches it", item.response)
                )
    found += _analysis_problems(study)
    return found


def _analysis_problems(study: Study) -> list[Found]:
    """Analysis options that would silently do nothing: an uncertainty or relaxation pattern matching no
    constraint (a level constraint for a relaxation), a profiled response the study does not record."""
    found: list[Found] = []
    options = study.analysis
    responses = [c.response for c in study.constraints]
    levels = [c.response for c in study.constraints if c.is_level]
    for i, u in enumerate(options.uncertainty):
        if not any(fnmatchcase(r, u.responses) for r in responses):
            found.append(
                (
                    ("analysis", "uncertainty", i, "responses"),
                    "matches no constraint's response (the uncertainty applies to constraints)",
                    u.responses,
                )
            )
    for i, r in enumerate(options.level_relaxation):
        if not any(fnmatchcase(name, r.responses) for name in levels):
            found.append(
                (
                    ("analysis", "level_relaxation", i, "responses"),
                    "matches no level constraint's response",
                    r.responses,
                )
            )
    for i, name in enumerate(options.profiler or ()):
        if not study.requested(name):
            found.append((("analysis", "profiler", i), "not recorded: no pattern of `responses:` matches it", name))
    return found


def _without_tag(loc: tuple[str | int, ...]) -> tuple[str | int, ...]:
    """pydantic puts the discriminating tag in an error's location (designs.2.lhs.seed): not a YAML path."""
    if len(loc) > 2 and loc[0] == "designs" and loc[2] in _GENERATORS:
        return loc[:2] + loc[3:]
    return loc


_GENERATORS = ("ccd", "box-behnken", "lhs", "random")


def validate_study(data: object, source: YamlSource | None = None, base_dir: Path | None = None) -> Study:
    """Validate plain data; raise :class:`InputError` with every problem (path and line when ``source`` is
    given). The aircraft path is resolved against ``base_dir`` and must name an existing file."""
    path = source.path if source else "<data>"
    if not isinstance(data, dict):
        raise InputError(
            path,
            [
                Problem(
                    "", "the study file must be a mapping (aircraft:, variables:, designs:, ...)", type(data).__name__
                )
            ],
        )
    try:
        study = Study.model_validate(data)
    except ValidationError as err:
        found = [
            (_without_tag(loc), message, value) for loc, message, value in found_in(err, schema_command=SCHEMA_COMMAND)
        ]
        raise InputError(path, located(found, source)) from None
    found = relation_problems(study)
    aircraft = Path(study.aircraft).expanduser()
    if not aircraft.is_absolute():
        aircraft = (base_dir or Path.cwd()) / aircraft
    if not aircraft.is_file():
        found.append((("aircraft",), f"aircraft file not found ({aircraft})", study.aircraft))
    if found:
        raise InputError(path, located(found, source))
    return study.model_copy(update={"aircraft": str(aircraft.resolve())})


def load_study(path: str | Path) -> Study:
    """Read and validate a study file; the name defaults to the file's stem."""
    source = load_yaml(path)
    study = validate_study(source.data, source, Path(path).resolve().parent)
    return study if study.name else study.model_copy(update={"name": Path(path).stem})


def json_schema() -> dict[str, Any]:
    schema = Study.model_json_schema()
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    return schema
