"""Conditions, findings and results.

A margin is signed so that **≥ 0 complies**; it carries its unit, and its normalised twin
(margin / |limit|) lets a design study compare rules. A finding that could not be computed is
``not_evaluated`` with the reason, never a pass.

A rule's status: ``fails`` when any finding fails; ``complies`` when every finding complies;
``complies_partial`` when every condition the rule computed complies but it does not evaluate some
sub-paragraphs (:attr:`certkit.engine.registry.Rule.unevaluated`, one ``not_evaluated`` finding each);
``not_evaluated`` when a condition the rule computes could not be evaluated, or nothing complies.
"""

from __future__ import annotations

import json
import math
import pickle
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Literal

import numpy as np

from certkit.engine.evidence import Table
from certkit.engine.results_json import (
    SCHEMA_VERSION,
    SIGNIFICANT_DIGITS,
    VOLATILE_KEY,
    Encoded,
    Rounded,
    RoundedRows,
    clean,
    compact,
    encode,
    round_rows,
)
from certkit.units import FT, KN, LB

Status = Literal["complies", "fails", "not_evaluated"]
COMPLIES: Status = "complies"
FAILS: Status = "fails"
NOT_EVALUATED: Status = "not_evaluated"
#: rule-level only: what was computed complies, something was not evaluated
COMPLIES_PARTIAL = "complies_partial"
#: how each status reads in the terminal and the report
STATUS_LABEL = {
    COMPLIES: "complies",
    COMPLIES_PARTIAL: "complies, partial",
    FAILS: "fails",
    NOT_EVALUATED: "not evaluated",
}
#: ``details`` key of the finding that stands for a sub-paragraph the rule does not evaluate
SCOPE_KEY = "not_evaluated_by_rule"


@dataclass(frozen=True)
class Condition:
    """One point of a rule's condition space (§25.21(a): weight and CG, configuration, flight condition)."""

    loading: str | None = None  # CG-envelope corner or loading name
    mass: float | None = None  # kg
    x_cg: float | None = None  # m, airplane frame (aft of the nose)
    configuration: str | None = None
    altitude: float | None = None  # m
    speed: float | None = None  # m/s
    speed_kind: str | None = None  # EAS, CAS, TAS or MACH
    speed_name: str | None = None  # VC, VD, … when the speed is a declared one
    extra: tuple[tuple[str, object], ...] = ()

    def get(self, key: str, default: Any = None) -> Any:
        for name, value in reversed(self.extra):  # the last item of a name, as a dict of the items would hold
            if name == key:
                return value
        return default

    def with_(self, **changes: Any) -> "Condition":
        """This condition with fields changed; a name that is not a field sets (or replaces) an ``extra`` item."""
        fields = self.__dataclass_fields__
        extra = dict(self.extra)
        values = dict(self.__dict__)
        for key, value in changes.items():
            if key in fields:
                values[key] = value
            else:
                extra[key] = value
        values["extra"] = tuple(extra.items())
        return self.from_fields(values)

    def without(self, *keys: str) -> "Condition":
        """This condition without the ``extra`` items named ``keys``."""
        return self.from_fields({**self.__dict__, "extra": tuple((k, v) for k, v in self.extra if k not in keys)})

    @classmethod
    def from_fields(cls, values: dict[str, Any]) -> "Condition":
        """A condition of this type with the field ``values``, every field given in the fields' order (frozen, no
        ``__post_init__``: set as ``__init__`` would set them, without its cost)."""
        new = object.__new__(cls)
        new.__dict__.update(values)
        return new

    def refines(self, other: "Condition") -> bool:
        """True when this condition is ``other`` with more fields set (a rule that computes, say, the
        speed 1.3 VSR of a weight refines the scheduled condition of that weight)."""
        for name in ("loading", "mass", "x_cg", "configuration", "altitude", "speed", "speed_kind", "speed_name"):
            theirs = getattr(other, name)
            if theirs is not None and getattr(self, name) != theirs:
                return False
        mine = dict(self.extra)
        return all(k in mine and mine[k] == v for k, v in other.extra)

    def same_point(self, scheduled: "Condition") -> bool:
        """True when this condition (as a rule evaluated it, possibly refined) is the point ``scheduled`` of a rule's
        condition space whatever the airplane-dependent numbers (mass, CG, speed): the same loading, configuration,
        altitude, named speed and scheduled fields. It finds one airplane's condition among another's schedule."""
        if (self.loading, self.configuration) != (scheduled.loading, scheduled.configuration):
            return False
        if (self.altitude is None) != (scheduled.altitude is None):
            return False
        if (
            self.altitude is not None
            and scheduled.altitude is not None
            and abs(self.altitude - scheduled.altitude) > 1e-6
        ):
            return False
        if scheduled.speed_name is not None and self.speed_name != scheduled.speed_name:
            return False
        return all(item in self.extra for item in scheduled.extra)

    def as_dict(self) -> dict[str, object]:
        """JSON form (SI, with units in the key names)."""
        out: dict[str, object] = {}
        if self.loading is not None:
            out["loading"] = self.loading
        if self.mass is not None:
            out["mass_kg"] = round(self.mass, 3)
        if self.x_cg is not None:
            out["x_cg_m"] = round(self.x_cg, 4)
        if self.configuration is not None:
            out["configuration"] = self.configuration
        if self.altitude is not None:
            out["altitude_m"] = round(self.altitude, 2)
        if self.speed is not None:
            out["speed_m_s"] = round(self.speed, 4)
            out["speed_kind"] = self.speed_kind
        if self.speed_name is not None:
            out["speed_name"] = self.speed_name
        for k, v in self.extra:
            out[k] = v
        return out

    def label(self, numbers: bool = True) -> str:
        """Human label: ``fwd_mrw · 655,000 lb · CG 94.23 ft · clean · 0 ft · VC = 272.0 kn EAS · at 1.3 VSR``; the
        scheduled fields in words (:func:`field_words`). ``numbers`` False leaves out the mass and CG (the loading
        names them): the short form of a one-line cause."""
        parts = []
        if self.loading:
            parts.append(self.loading)
        if self.mass is not None and numbers:
            parts.append(f"{self.mass / LB:,.0f} lb")
        if self.x_cg is not None and numbers:
            parts.append(f"CG {self.x_cg / FT:.2f} ft")
        if self.configuration:
            parts.append(self.configuration)
        if self.altitude is not None:
            parts.append(f"{self.altitude / FT:,.0f} ft")
        if self.speed is not None:
            unit = "" if self.speed_kind == "MACH" else f" kn {self.speed_kind}"
            value = f"M {self.speed:.3f}" if self.speed_kind == "MACH" else f"{self.speed / KN:.1f}{unit}"
            parts.append(f"{self.speed_name + ' = ' if self.speed_name else ''}{value}")
        parts += [field_words(k, v) for k, v in self.extra]
        return " · ".join(parts) if parts else "whole airplane"


#: scheduled condition fields (``extra``) as a reviewer reads them: name → text with ``{}`` for the value
_FIELD_WORDS = {
    "speed_point": "at {}",
    "entry_speed": "entry at {}",
    "bank_deg": "{}° bank",
    "inoperative": "{} engine inoperative",
    "gust": "gust {}",
    "direction": "{}",
    "load_factor": "n = {}",
    "case": "{}",
    "point": "{}",
    "delta_isa_K": "ISA {:+g} °C",
}


def field_words(name: str, value: object) -> str:
    """A scheduled condition field in words: ``speed_point`` 1.3 VSR → "at 1.3 VSR", ``delta_isa_K`` 15 → "ISA +15
    °C"; a field not listed reads "name value" with underscores as spaces."""
    template = _FIELD_WORDS.get(name)
    if isinstance(value, float):
        value = round(value, 1) if abs(value) >= 1 else float(f"{value:.3g}")  # a label, not a record
    if template is None:
        return f"{name.replace('_', ' ')} {value}"
    try:
        return template.format(value)
    except (ValueError, TypeError):
        return f"{name.replace('_', ' ')} {value}"


@dataclass
class Finding:
    """The outcome of one check at one condition."""

    condition: Condition
    check: str
    status: Status
    value: float | None = None
    limit: float | None = None
    margin: float | None = None
    unit: str = ""
    reason: str = ""
    details: dict[str, Any] = field(default_factory=dict)
    #: more details computed only when the finding is written (:meth:`as_dict`), placed before ``details``: a
    #: picklable callable returning a dict (a structural finding's per-station load table: a design study makes
    #: thousands of them per design and writes none)
    written_details: Callable[[], dict[str, Any]] | None = field(default=None, repr=False, compare=False)

    @property
    def has_number(self) -> bool:
        return self.value is not None or self.limit is not None or self.margin is not None

    @property
    def normalized_margin(self) -> float | None:
        if self.margin is None or self.limit is None:
            return None
        scale = abs(self.limit) if self.limit != 0 else 1.0
        return self.margin / scale

    @classmethod
    def compare(
        cls,
        condition: Condition,
        check: str,
        value: float,
        limit: float,
        *,
        at_least: bool,
        unit: str,
        reason: str = "",
        tolerance: float | None = None,
        **details: Any,
    ) -> "Finding":
        """A finding for ``value ≥ limit`` (``at_least``) or ``value ≤ limit``; margin ≥ 0 complies.

        ``unit``: the unit of value, limit and margin; a dimensionless one names its quantity ("ratio", "g" for a
        load factor, "C_L", "ζ" for a damping ratio), so that no margin is printed without a unit word.
        ``tolerance`` (in the margin's unit; default 1e-9 × |limit|) absorbs round-off when a value sits
        exactly on its limit, as declared speeds derived from each other do.
        """
        if not unit or unit == "1":
            raise ValueError(
                f"{check!r}: Finding.compare needs the unit of its value and limit (a dimensionless quantity names "
                "itself: 'ratio', 'g', 'C_L', 'ζ')"
            )
        value, limit = float(value), float(limit)
        if not (math.isfinite(value) and math.isfinite(limit)):
            return cls.not_evaluated(condition, check, f"non-finite value ({value}) or limit ({limit})")
        margin = value - limit if at_least else limit - value
        if tolerance is None:
            tolerance = 1e-9 * max(1.0, abs(limit))
        status: Status = COMPLIES if margin >= -tolerance else FAILS
        return cls(condition, check, status, value, limit, margin, unit, reason, details)

    @classmethod
    def not_applicable(cls, condition: Condition, check: str, reason: str, **details: Any) -> "Finding":
        """The paragraph does not apply at this condition (computed, not assumed): complies, no margin."""
        return cls(condition, check, COMPLIES, reason="not applicable: " + reason, details=details)

    @classmethod
    def not_evaluated(cls, condition: Condition, check: str, reason: str, **details: Any) -> "Finding":
        return cls(condition, check, NOT_EVALUATED, reason=reason, details=details)

    @classmethod
    def outside_scope(
        cls,
        paragraph: str,
        reason: str,
        *,
        condition: Condition | None = None,
        check: str | None = None,
        **details: Any,
    ) -> "Finding":
        """The ``not_evaluated`` finding of a sub-paragraph the rule does not evaluate, set apart from the rule's own
        checks (it does not make the rule not evaluated): whole-airplane by default, or at ``condition`` under its own
        ``check`` name with ``details`` (e.g. a comparison with a value the aircraft file does not declare)."""
        return cls(
            Condition() if condition is None else condition,
            f"§{paragraph} not evaluated" if check is None else check,
            NOT_EVALUATED,
            reason=reason,
            details={SCOPE_KEY: paragraph, **details},
        )

    def as_dict(self) -> dict[str, Any]:
        return {
            "condition": self.condition.as_dict(),
            **self._fields(),
            **({"details": details} if (details := self.all_details()) else {}),
        }

    def _fields(self) -> dict[str, Any]:
        """:meth:`as_dict` between the condition and the details."""
        return {
            "check": self.check,
            "value": self.value,
            "limit": self.limit,
            "margin": self.margin,
            "normalized_margin": self.normalized_margin,
            "unit": (self.unit or "1") if self.has_number else None,
            "status": self.status,
            "reason": self.reason,
        }

    def all_details(self) -> dict[str, Any]:
        """``details`` with the :attr:`written_details` before them."""
        return {**self.written_details(), **self.details} if self.written_details is not None else self.details

    def json_line(
        self, conditions: dict[int, tuple[str, int]], written: dict[str, Any] | None = None
    ) -> tuple[str, int]:
        """:meth:`as_dict` as results.json writes it (one compact line) and the count of its non-finite numbers, the
        same text as cleaning and encoding :meth:`as_dict`, made faster: the condition's text is kept in
        ``conditions`` (by object: a rule's findings share their conditions) and written details that come
        :class:`Rounded` are written as they are; ``written``: the :attr:`written_details` already computed."""
        key = id(self.condition)
        cond = conditions.get(key)
        if cond is None:
            data, n = clean(self.condition.as_dict())
            cond = conditions[key] = (compact(data), n)
        fields, count = clean(self._fields())
        count += cond[1]
        if written is None and self.written_details is not None:
            written = self.written_details()
        if type(written) is Rounded and written and not written.keys() & self.details.keys():
            details = compact(written)  # as it is; the other details after it
            if self.details:
                more, n = clean(self.details)
                details, count = details[:-1] + ", " + compact(more)[1:], count + n
        elif merged := (self.details if written is None else {**written, **self.details}):
            data, n = clean(merged)
            details, count = compact(data), count + n
        else:
            details = ""
        tail = f', "details": {details}}}' if details else "}"
        return '{"condition": ' + cond[0] + ", " + compact(fields)[1:-1] + tail, count


@dataclass
class Evidence:
    """A figure and/or a table attached to a rule result, as data (:mod:`certkit.engine.evidence`): ``figure`` a
    :class:`~certkit.engine.evidence.Chart`, :class:`~certkit.engine.evidence.Bars` or
    :class:`~certkit.engine.evidence.Heatmap`,
    ``table`` a :class:`~certkit.engine.evidence.Table` (a list of dicts is turned into one). The report draws the
    figure
    into ``svg`` (:func:`certkit.report.figures.render_evidence`)."""

    title: str
    figure: object = None
    caption: str = ""
    table: object = None
    svg: str = ""

    def __post_init__(self) -> None:
        if isinstance(self.figure, str):
            raise TypeError(f"evidence {self.title!r}: a figure is data (certkit.engine.evidence), not drawn SVG")
        if isinstance(self.table, list):
            self.table = Table.from_dicts(self.table)


@dataclass
class SimulationRun:
    """What a simulated rule computes, kept for its evidence and for the design layer (never written to
    results.json): its findings, the conditions it simulated (column i of every record is ``conditions[i]``), the
    batch's records (:class:`certkit.models.dynamics.simulate.SimulationResult`, None when the rule's histories are
    of another kind), where the paragraph considers them (``valid``, (n_t, n) booleans; None: everywhere), the
    conditions it could not simulate with each reason (``failed``: (label, reason)) and, when nothing was simulated,
    why (``reason``). Rules that keep more (load histories, gust replays) extend it."""

    findings: list[Finding]
    conditions: list[Condition] = field(default_factory=list)
    records: Any = None  # SimulationResult, or a rule's own kind of history
    valid: Any = None
    failed: list[tuple[str, str]] = field(default_factory=list)
    reason: str = ""

    @property
    def simulated(self) -> bool:
        """True when the run holds simulated conditions (False: only refusals, see :attr:`reason`)."""
        return bool(self.conditions)

    def envelopes(self) -> list[Any]:
        """The load envelopes (:class:`certkit.models.loads.response.LoadEnvelope`) the run computed, in the rule's
        order; none for a run that computes no loads."""
        return []

    def records_only(self) -> "SimulationRun":
        """The conditions, records and validity alone (what a design keeps of a run between processes)."""
        return SimulationRun([], self.conditions, self.records, self.valid)


@dataclass
class LoadsRun(SimulationRun):
    """A run that computes station loads: ``envelope`` over every simulated condition (None when nothing was
    simulated)."""

    envelope: object = None

    @property
    def simulated(self) -> bool:
        return self.envelope is not None

    def envelopes(self) -> list[Any]:
        return [] if self.envelope is None else [self.envelope]


def margin_key(f: Finding) -> float:
    """Sort key of an evaluated finding: its normalised margin, else its margin."""
    key = f.normalized_margin if f.normalized_margin is not None else f.margin
    return math.inf if key is None else key


#: what :meth:`RuleResult.__getstate__` sends computed with a result whose findings travel packed
SUMMARY = ("status", "headline_reason", "not_evaluated_reason", "critical", "worst_failure")


@dataclass
class RuleResult:
    id: str
    symbol: str
    title: str
    findings: list[Finding]
    evidence: list[Evidence] = field(default_factory=list)
    overrides: dict[str, Any] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    #: :meth:`to_json` as a worker process encoded it once the rule was evaluated (None: encoded when needed)
    encoded: str | None = field(default=None, repr=False, compare=False)
    #: the report's HTML section as the process that evaluated the rule rendered it (None: rendered when needed)
    section: str | None = field(default=None, repr=False, compare=False)
    #: the load envelopes a loads rule computed, kept when asked (:func:`certkit.engine.scheduler.evaluate_rule`)
    load_envelopes: list[Any] = field(default_factory=list, repr=False, compare=False)
    #: what the rule simulated (:class:`SimulationRun`) when the load envelopes are kept; never written to results.json
    run: SimulationRun | None = field(default=None, repr=False, compare=False)
    #: the rule's implementation status (``implemented``, ``partial``, ``planned``) and modelling limitations
    implementation: str = "implemented"
    limitations: str = ""
    #: (paragraph, reason) of each sub-paragraph the rule does not evaluate
    unevaluated: list[tuple[str, str]] = field(default_factory=list)
    #: the amendment the rule reflects, the paragraphs it cross-references, the criteria in force (name → value,
    #: unit, source, basis, description, overridden) — the rule's metadata for results.json and the report
    amendment: str = ""
    references: list[str] = field(default_factory=list)
    criteria: dict[str, Any] = field(default_factory=dict)
    #: wall time of the rule's evaluation, s (for the terminal; not in results.json, which is the same for every run)
    seconds: float | None = field(default=None, repr=False, compare=False)
    #: NaN or infinite numbers :meth:`to_json` wrote as null
    non_finite: int = field(default=0, repr=False, compare=False)
    #: False: once encoded, the result leaves its process without its findings (:meth:`__getstate__`), for a caller
    #: that reads only the summary, the encoded text and the report's section
    findings_travel: bool = field(default=True, repr=False, compare=False)

    def __getstate__(self) -> dict[str, Any]:
        """A result encoded for ``results.json`` (:attr:`encoded`, as a worker process sends it back) travels with its
        findings as one pickled block, read only when something asks for them (the CI formats, the API), and with
        what the terminal, the report's index and the exit code read of them (:data:`SUMMARY`): a check's
        coordinating process skips rebuilding thousands of findings it only writes as text. Without
        :attr:`findings_travel` the findings stay behind (reading them afterwards raises AttributeError)."""
        state = dict(self.__dict__)
        if self.encoded is not None and "findings" in state:
            state["_summary"] = {name: getattr(self, name) for name in SUMMARY}
            findings = state.pop("findings")
            state["_packed_findings"] = (
                pickle.dumps(findings, protocol=pickle.HIGHEST_PROTOCOL) if self.findings_travel else None
            )
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)

    if not TYPE_CHECKING:  # the findings are a field to type checkers; only an unpickled result reads them here

        def __getattr__(self, name):
            """The packed findings (:meth:`__getstate__`), rebuilt on first use."""
            packed = self.__dict__.get("_packed_findings") if name == "findings" else None
            if packed is None:
                if name == "findings" and "_summary" in self.__dict__:
                    raise AttributeError(f"the findings of {self.id} stayed in the process that evaluated it")
                raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
            self.findings = pickle.loads(packed)
            del self.__dict__["_packed_findings"], self.__dict__["_summary"]
            return self.findings

    @property
    def status(self) -> str:
        """``fails``, ``complies``, ``complies_partial`` or ``not_evaluated`` (module docstring)."""
        if "_summary" in self.__dict__:
            return str(self.__dict__["_summary"]["status"])
        statuses = {f.status for f in self.findings}
        if FAILS in statuses:
            return FAILS
        own = {f.status for f in self.findings if SCOPE_KEY not in f.details}
        if NOT_EVALUATED in own or COMPLIES not in own:
            return NOT_EVALUATED
        return COMPLIES_PARTIAL if NOT_EVALUATED in statuses else COMPLIES

    @property
    def headline_reason(self) -> str:
        """The reason to show when there is no critical finding: the first finding's, those of the rule's own
        computation before the sub-paragraphs it does not evaluate."""
        if "_summary" in self.__dict__:
            return str(self.__dict__["_summary"]["headline_reason"])
        own = [f for f in self.findings if SCOPE_KEY not in f.details]
        first = (own or self.findings)[:1]
        return first[0].reason if first else ""

    @property
    def not_evaluated_reason(self) -> str:
        """Why the rule (or the part it computes) was not evaluated: its first own ``not_evaluated`` finding's
        reason, else :attr:`headline_reason` ("no finding" without either)."""
        if "_summary" in self.__dict__:
            return str(self.__dict__["_summary"]["not_evaluated_reason"])
        own = [f for f in self.findings if f.status == NOT_EVALUATED and SCOPE_KEY not in f.details]
        return (own[0].reason if own else self.headline_reason) or "no finding"

    @property
    def critical(self) -> Finding | None:
        """The evaluated finding with the smallest normalised margin (the critical condition)."""
        if "_summary" in self.__dict__:
            critical: Finding | None = self.__dict__["_summary"]["critical"]
            return critical
        evaluated = [f for f in self.findings if f.margin is not None]
        if not evaluated:
            return None
        return min(evaluated, key=margin_key)

    @property
    def worst_failure(self) -> Finding | None:
        """The failing finding with the smallest normalised margin (else margin), or the first failing one when
        none has a margin; None when nothing fails."""
        if "_summary" in self.__dict__:
            worst: Finding | None = self.__dict__["_summary"]["worst_failure"]
            return worst
        failing = [f for f in self.findings if f.status == FAILS]
        with_margin = [f for f in failing if f.margin is not None]
        if with_margin:
            return min(with_margin, key=margin_key)
        return failing[0] if failing else None

    def as_dict(self) -> dict[str, Any]:
        return {**self._fields(), "findings": [f.as_dict() for f in self.findings]}

    def _fields(self) -> dict[str, Any]:
        """:meth:`as_dict` but the findings."""
        crit = self.critical
        return {
            "id": self.id,
            "symbol": self.symbol,
            "title": self.title,
            "status": self.status,
            "implementation": self.implementation,
            "amendment": self.amendment,
            "limitations": self.limitations,
            "unevaluated": [{"paragraph": p, "reason": r} for p, r in self.unevaluated],
            "min_margin": crit.margin if crit else None,
            "normalized_min_margin": crit.normalized_margin if crit else None,
            "unit": (crit.unit or "1") if crit else None,
            "critical_check": crit.check if crit else None,
            "critical_condition": crit.condition.as_dict() if crit else None,
            "references": list(self.references),
            "criteria": self.criteria,
            "overrides": self.overrides,
            "notes": self.notes,
        }

    def to_json(self) -> str:
        """:meth:`as_dict` as it stands in ``results.json`` (:mod:`certkit.engine.results_json`, at a rule's depth);
        counts the non-finite numbers written as null in :attr:`non_finite`."""
        data, count = clean(self._fields())
        assert isinstance(data, dict)
        conditions: dict[int, tuple[str, int]] = {}
        lines = []
        tables = [i for i, f in enumerate(self.findings) if type(f.written_details) is RoundedRows]
        written = dict(zip(tables, round_rows([self.findings[i].written_details for i in tables])))  # type: ignore[misc]
        for i, f in enumerate(self.findings):
            line, n = f.json_line(conditions, written.get(i))
            lines.append(Encoded(line))
            count += n
        self.non_finite = count
        return encode({**data, "findings": lines}, depth=2)


@dataclass
class RunResult:
    certkit_version: str
    aircraft_name: str
    source_sha256: str
    source_path: str
    created: str
    rules: list[RuleResult]
    models: dict[str, Any] = field(default_factory=dict)
    #: which rules ran: the --select/--ignore patterns, ``partial`` when they left registered rules out
    selection: dict[str, Any] = field(default_factory=dict)
    #: the options that change what is evaluated (rule folders, plugins) and the platform
    options: dict[str, Any] = field(default_factory=dict)
    environment: dict[str, Any] = field(default_factory=dict)
    #: what varies between identical runs: wall time of the evaluation (s) and the processes used
    duration_s: float | None = None
    jobs: int | None = None
    #: the aircraft file's values by dotted YAML path, as written (:meth:`YamlSource.values_by_path`): what
    #: ``certkit diff`` compares to name the inputs that changed
    inputs: dict[str, Any] = field(default_factory=dict)

    def summary(self) -> dict[str, int]:
        statuses = [r.status for r in self.rules]
        return {
            "rules": len(self.rules),
            "complies": statuses.count(COMPLIES),
            "complies_partial": statuses.count(COMPLIES_PARTIAL),
            "fails": statuses.count(FAILS),
            "not_evaluated": statuses.count(NOT_EVALUATED),
        }

    def as_dict(self, rules: object = None) -> dict[str, Any]:
        """The run as plain data (``results.json``); ``rules`` stands in for the list of rule dicts. The last key,
        ``run``, holds what varies between identical runs (time stamp, duration, processes)."""
        return {
            "schema_version": SCHEMA_VERSION,
            "certkit_version": self.certkit_version,
            "aircraft": {
                "name": self.aircraft_name,
                "source_sha256": self.source_sha256,
                "source": self.source_path,
                **({"inputs": self.inputs} if self.inputs else {}),
            },
            "selection": self.selection,
            "options": self.options,
            "environment": self.environment,
            "precision": {"significant_digits": SIGNIFICANT_DIGITS, "non_finite": None},
            "summary": self.summary(),
            "rules": [r.as_dict() for r in self.rules] if rules is None else rules,
            "models": {
                k: ({kk: vv for kk, vv in v.items() if kk != "svg"} if isinstance(v, dict) else v)
                for k, v in self.models.items()
            },
            VOLATILE_KEY: {"created": self.created, "duration_s": self.duration_s, "jobs": self.jobs},
        }

    def to_json(self) -> str:
        """``results.json`` (:mod:`certkit.engine.results_json`): each rule's part taken from :attr:`RuleResult.encoded`
        where a worker process already encoded it (the same text as encoding the whole at once)."""
        return "".join(self.json_chunks())

    def json_chunks(self) -> list[str]:
        """:meth:`to_json`'s text in consecutive pieces (the head's, then each rule's and its separator), for a writer
        that need not join a check's ten-odd megabytes into one string first."""
        parts = []
        non_finite = 0
        for r in self.rules:
            if r.encoded is None:
                r.encoded = r.to_json()
            parts.append(r.encoded)
            non_finite += r.non_finite
        cleaned, n_head = clean(self.as_dict(rules=_RULES_MARK))
        head = cleaned if isinstance(cleaned, dict) else {}
        non_finite += n_head
        if non_finite:  # strict JSON has no NaN or Infinity: null, and the reason said once
            head = {
                **{k: v for k, v in head.items() if k != VOLATILE_KEY},
                "non_finite_numbers": {
                    "count": non_finite,
                    "written_as": None,
                    "reason": "a computed value was NaN or infinite (not computable there); JSON has no such numbers",
                },
                VOLATILE_KEY: head[VOLATILE_KEY],
            }
        before, after = encode(head).split(json.dumps(_RULES_MARK), 1)
        if not parts:
            return [before, "[]", after]
        rules = [piece for p in parts for piece in (",\n    ", p)]
        rules[0] = "[\n    "
        return [before, *rules, "\n  ]", after]

    def exit_code(self) -> int:
        """0 every rule complies in full, 1 any fails, 3 nothing fails but something was not evaluated (a rule
        ``not_evaluated`` or ``complies_partial``); 2 is the CLI's for a user error."""
        s = self.summary()
        if s["fails"]:
            return 1
        if s["not_evaluated"] or s["complies_partial"]:
            return 3
        return 0


#: placeholder of the rules list while the rest of ``results.json`` is encoded
_RULES_MARK = "\x00certkit-rules\x00"


def json_default(obj: object) -> object:
    """JSON of numpy scalars and arrays (their values); anything else as its ``str``."""
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    return str(obj)
