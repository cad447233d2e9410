"""Rule declaration, validation and discovery.

A rule is a class deriving from :class:`Rule`, decorated with :func:`rule`, in a module of the
built-in ``certkit_rules`` package (the repository's ``rules/`` folder), of a plugin package
registered under the entry-point group ``certkit.rules``, or of a user folder passed with
``--rules DIR``. Metadata is validated when the rule is declared (pluggy-style: fail early, name
the plugin and the field).
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import math
import pkgutil
import re
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from importlib.metadata import entry_points
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any, ClassVar, TypeVar

from certkit.errors import UserError

if TYPE_CHECKING:
    from certkit.engine.conditions import ConditionSpace
    from certkit.engine.context import Context
    from certkit.engine.results import Condition, Evidence, Finding, SimulationRun

RULE_ID = re.compile(r"^\d+\.\d+[a-z]?(\([a-zA-Z0-9]+\))*$")  # §25.125(b)(2)(i)(A): capitals at the fifth level
R = TypeVar("R", bound="Rule")
SYMBOL = re.compile(r"^[a-z][a-z0-9]*(-[a-z0-9]+)*$")
IMPLEMENTATION = ("implemented", "partial", "planned")
ENTRY_POINT_GROUP = "certkit.rules"


class PluginError(UserError):
    """Invalid rule metadata or a rule module that cannot be loaded."""


def exit_called(exc: SystemExit) -> str:
    """What a rule module did when it raised :class:`SystemExit` (``sys.exit``, ``exit()``): a rule ends nothing, it
    returns findings, so certkit never ends with the plugin's exit code (an exit 0 would read "all comply")."""
    return f"called sys.exit({exc.code!r}) (a rule must return findings or raise an exception, never end the program)"


#: what a criterion rests on, read from its source: ``regulation`` (the text of 14 CFR), ``unverified`` (text from
#: memory, a secondary copy or another authority's code, not checked against the CFR), ``data`` (published data: a
#: type certificate data sheet), ``project`` (a value certkit chose or assumed, its reading of the text) and
#: ``numerical`` (a numerical setting of the method, not a compliance criterion)
CRITERION_BASES = ("regulation", "unverified", "data", "project", "numerical")
_UNVERIFIED_WORDS = ("unverified", "secondary", "mirror", "from memory", "checked against cs")


@dataclass(frozen=True)
class Criterion:
    """A numeric criterion a rule applies, with its unit and where it comes from."""

    value: float | str | bool
    unit: str
    source: str
    description: str = ""

    @property
    def basis(self) -> str:
        """One of :data:`CRITERION_BASES`, from the words of :attr:`source` (``unverified``, ``secondary``, ``mirror``,
        ``from memory``; ``numerical choice``; ``project choice``, ``certkit …``; ``TCDS``; a CFR citation); a source
        that cites no CFR paragraph is a project choice."""
        text = self.source.lower()
        if any(word in text for word in _UNVERIFIED_WORDS):
            return "unverified"
        if "numerical choice" in text:
            return "numerical"
        if "project choice" in text or "certkit" in text or "assumption" in text:
            return "project"
        if "tcds" in text:
            return "data"
        return "regulation" if "cfr" in text or "§" in text else "project"


#: the kinds of loads a rule declares it produces (:class:`Loads`)
STATION_LOADS = "station"
HINGE_MOMENT = "hinge moment"
LOAD_KINDS = (STATION_LOADS, HINGE_MOMENT)


@dataclass(frozen=True)
class Loads:
    """Loads a rule computes beyond its findings, declared in :attr:`Rule.produces`. ``kind`` ``station``: the shear,
    bending and torsion at the load stations of ``surface`` (``wing``, ``horizontal_tail``, ``vertical_tail``), kept
    as the run's load envelopes (:meth:`certkit.engine.results.SimulationRun.envelopes`); ``hinge moment``: the
    deflection of the control surface ``surface`` (``elevator``) along the run's records with the flight state
    (Mach, dynamic pressure, angle of attack) its hinge moment follows from."""

    surface: str
    kind: str = STATION_LOADS


@dataclass(frozen=True)
class ModeResponses:
    """Rigid-body mode responses a rule offers (:attr:`Rule.offers`): each of its findings whose condition names a
    loading (CG corner) and a configuration and whose ``details[key]`` is a table {mode: row} holds, per mode of
    ``modes``, the row's quantities (``zeta``, ``wn_rad_s``, …) and its MIL-F-8785C levels (``level_<category>``).
    ``level(mode, configuration, zeta=, wn=, cap=)`` gives the level from the quantities (arrays allowed) as the
    row does, and ``level_margin(mode, configuration, level, zeta=, wn=, cap=)`` how far inside ``level`` they lie
    (≥ 0 there, continuous): a study derives levels from surrogates of the quantities with them."""

    modes: tuple[str, ...]
    key: str = "modes"
    level: Callable[..., Any] | None = None
    level_margin: Callable[..., Any] | None = None


@dataclass(frozen=True)
class ControlCase:
    """One case of :class:`ControlResponses`: the findings whose check text begins with ``check``, names a control of
    ``controls`` and whose condition holds the extras ``where`` give that control's deflection (deg) in the case —
    the finding's value, or the largest in magnitude of ``details[key.format(control=…)]`` over the keys of
    ``deflection``; ``name`` names the case in responses (``control.<rule id>.<name>.<control>``)."""

    name: str
    check: str
    controls: tuple[str, ...] = ("elevator", "aileron", "rudder")
    deflection: tuple[str, ...] = ()
    where: tuple[tuple[str, object], ...] = ()

    def deflections(self, finding: Finding) -> dict[str, float]:
        """control → deflection (deg) that ``finding`` reports for this case (empty when it is not one of its)."""
        if not finding.check.startswith(self.check) or any(finding.condition.get(k) != v for k, v in self.where):
            return {}
        out: dict[str, float] = {}
        for control in self.controls:
            if self.deflection:
                given = [finding.details.get(k.format(control=control)) for k in self.deflection]
                values = [float(v) for v in given if isinstance(v, (int, float)) and math.isfinite(v)]
                if values:
                    out[control] = max(values, key=abs)
            elif (
                control in finding.check
                and finding.unit == "deg"
                and finding.value is not None
                and math.isfinite(finding.value)
            ):
                out[control] = float(finding.value)
        return out


@dataclass(frozen=True)
class ControlResponses:
    """The control deflections a rule offers per named case (:class:`ControlCase`)."""

    cases: tuple[ControlCase, ...]


#: what a rule may offer in :attr:`Rule.offers`
RESPONSE_KINDS = (ModeResponses, ControlResponses)


class Criteria(dict[str, Any]):
    """The criteria in force for one run: the rule's defaults with the aircraft file's overrides."""

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None


class Rule:
    """Base class of a rule. Subclasses set the class attributes and implement :meth:`evaluate`.

    Attributes
    ----------
    id, symbol, title
        Paragraph (``25.331(c)(2)``), kebab-case symbol, short title.
    amendment
        The amendment whose text the rule reflects (``25-141``).
    requirement
        What the regulation asks, in plain words.
    margin
        How the margin is formed and signed (≥ 0 complies).
    references
        Paragraphs the rule cross-references (shown as links in the report).
    requires
        Aircraft-file paths that must be present (``speeds.VMC``); a missing one makes the rule
        ``not_evaluated`` before any computation.
    criteria
        Numeric criteria with their source; overridable in the aircraft file's ``criteria``.
    conditions
        The :class:`~certkit.engine.conditions.ConditionSpace` the rule is evaluated over.
    implementation
        ``implemented``, ``partial`` (list what is not evaluated in ``unevaluated``) or ``planned``.
    limitations
        Free text: the modelling simplifications of what the rule does evaluate (rigid airplane, …).
    unevaluated
        ``(paragraph, reason)`` pairs: each sub-paragraph (or part of one) the rule does not evaluate.
        The scheduler turns each into a ``not_evaluated`` finding, so a partial rule never reads
        "complies"; a ``partial`` rule must list at least one, an ``implemented`` one none.
    cost
        Rough evaluation time relative to a trim-only rule (1); used only to start the heaviest
        rules first when ``--jobs`` spreads them over processes.
    run_with
        Optional key: rules with the same key are evaluated one after the other in one process, so
        that a computation they share through ``ctx.memo`` is done once (e.g. §25.341(a) and §25.349(b)
        share the gust runs).
    produces
        The loads the rule computes beyond its findings (:class:`Loads`: surface and kind), which a design sizes
        structure from (:func:`producers`).
    offers
        The responses its findings carry for a design record (:class:`ModeResponses`, :class:`ControlResponses`).
    """

    id: ClassVar[str]
    symbol: ClassVar[str]
    title: ClassVar[str]
    amendment: ClassVar[str]
    requirement: ClassVar[str]
    margin: ClassVar[str]
    references: ClassVar[tuple[str, ...]] = ()
    requires: ClassVar[tuple[str, ...]] = ()
    criteria: ClassVar[dict[str, Criterion]] = {}
    conditions: ClassVar["ConditionSpace"]
    implementation: ClassVar[str] = "implemented"
    limitations: ClassVar[str] = ""
    unevaluated: ClassVar[tuple[tuple[str, str], ...]] = ()
    origin: ClassVar[str] = "built-in"
    cost: ClassVar[float] = 1.0
    run_with: ClassVar[str] = ""
    produces: ClassVar[tuple[Loads, ...]] = ()
    offers: ClassVar[tuple[ModeResponses | ControlResponses, ...]] = ()
    #: the loads the caller of this evaluation wants (:func:`certkit.engine.scheduler.evaluate_rule` ``wanted``: a
    #: design loop's sizing passes want the horizontal tail's); None: everything the rule computes
    wanted: "frozenset[Loads] | None" = None

    def computes(self, surface: str, kind: str = STATION_LOADS) -> bool:
        """Does this evaluation compute ``kind`` loads of ``surface`` (and the findings on them)? Always, but for a
        caller that wants other loads only (:attr:`wanted`): the rule may then leave them out — a partial result, as
        an evaluation at selected conditions is, never a verdict."""
        return self.wanted is None or Loads(surface, kind) in self.wanted

    def evaluate(self, ctx: "Context", conditions: list["Condition"], criteria: Criteria) -> list["Finding"]:
        """Return findings for the conditions (any number per condition, each naming its condition)."""
        raise NotImplementedError

    def evidence(self, ctx: "Context", findings: list["Finding"], criteria: Criteria) -> list["Evidence"]:
        """Plots or tables for the report (optional). Called on the same instance as :meth:`evaluate`, so a
        rule may keep what it simulated on ``self`` for its plots."""
        return []

    @classmethod
    def documentation(cls) -> str:
        """The text ``certkit explain`` prints."""
        lines = [
            f"§{cls.id}  {cls.title}  [{cls.symbol}]",
            f"Amendment: {cls.amendment}    Implementation: {cls.implementation}",
            "",
            "Requirement",
            _indent(cls.requirement),
            "",
            "Criterion",
        ]
        for name, c in cls.criteria.items():
            unit = f" {c.unit}" if c.unit else ""
            lines.append(f"  {name} = {c.value}{unit} — {c.description} (source: {c.source})")
        lines += ["", "Conditions", _indent(cls.conditions.describe()), "", "Margin", _indent(cls.margin)]
        if cls.requires:
            lines += ["", "Needs", "  " + ", ".join(cls.requires)]
        if cls.references:
            lines += ["", "Cross-references", "  " + ", ".join(f"§{r}" for r in cls.references)]
        if cls.limitations:
            lines += ["", "Limitations", _indent(cls.limitations)]
        if cls.unevaluated:
            lines += ["", "Not evaluated"] + [f"  §{para}: {why}" for para, why in cls.unevaluated]
        return "\n".join(lines)


class SimulationRule(Rule):
    """A rule that evaluates one batched simulation run. Subclasses implement :meth:`simulate`, returning a
    :class:`certkit.engine.results.SimulationRun` (its findings and what it simulated); the run is kept on the instance
    (``self.run``) between :meth:`evaluate` and :meth:`evidence` (the scheduler calls both on one instance)."""

    run: "SimulationRun | None" = None

    def simulate(self, ctx: "Context", conditions: list["Condition"], criteria: Criteria) -> "SimulationRun":
        raise NotImplementedError

    def evaluate(self, ctx: "Context", conditions: list["Condition"], criteria: Criteria) -> list["Finding"]:
        run = self.simulate(ctx, conditions, criteria)
        self.run = run
        return run.findings


def _indent(text: str) -> str:
    return "\n".join("  " + line.strip() for line in inspect.cleandoc(text).splitlines())


_REQUIRED_TEXT = ("id", "symbol", "title", "amendment", "requirement", "margin")


def validate_rule_class(cls: type, origin: str) -> None:
    """Raise :class:`PluginError` naming the plugin (origin) and the field when metadata is invalid."""
    name = getattr(cls, "__name__", repr(cls))
    where = f"rule {name} from {origin}"
    if not (isinstance(cls, type) and issubclass(cls, Rule)):
        raise PluginError(f"{where}: must be a subclass of certkit.engine.registry.Rule")
    for attr in _REQUIRED_TEXT:
        value = getattr(cls, attr, None)
        if not isinstance(value, str) or not value.strip():
            raise PluginError(f"{where}: field '{attr}' is missing or empty")
    if not RULE_ID.match(cls.id):
        raise PluginError(f"{where}: field 'id' = {cls.id!r} is not a paragraph id such as '25.331(c)(2)'")
    if not SYMBOL.match(cls.symbol):
        raise PluginError(f"{where}: field 'symbol' = {cls.symbol!r} must be kebab-case, e.g. 'checked-pitch-maneuver'")
    if cls.implementation not in IMPLEMENTATION:
        raise PluginError(f"{where}: field 'implementation' = {cls.implementation!r} must be one of {IMPLEMENTATION}")
    _validate_unevaluated(cls, where)
    if isinstance(cls.cost, bool) or not isinstance(cls.cost, (int, float)) or not cls.cost > 0:
        raise PluginError(f"{where}: field 'cost' = {cls.cost!r} must be a positive number (relative evaluation time)")
    if not isinstance(cls.run_with, str):
        raise PluginError(
            f"{where}: field 'run_with' = {cls.run_with!r} must be a string (a key shared with other rules)"
        )
    _validate_declarations(cls, where)
    for ref in cls.references:
        if not isinstance(ref, str) or not RULE_ID.match(ref):
            raise PluginError(f"{where}: field 'references' holds {ref!r}, not a paragraph id")
    for key, c in cls.criteria.items():
        if not isinstance(c, Criterion) or not c.source:
            raise PluginError(f"{where}: field 'criteria.{key}' must be a Criterion with a source")
    from certkit.engine.conditions import (  # deferred: `certkit rules` lists the rules without the physics
        ConditionSpace,
    )

    if not isinstance(getattr(cls, "conditions", None), ConditionSpace):
        raise PluginError(f"{where}: field 'conditions' must be a certkit.engine.conditions.ConditionSpace")
    if cls.evaluate is Rule.evaluate:
        raise PluginError(f"{where}: method 'evaluate' is not implemented")


def _validate_declarations(cls: type[Rule], where: str) -> None:
    """``produces`` holds :class:`Loads` of a known kind, ``offers`` response declarations."""
    if not isinstance(cls.produces, tuple) or not all(
        isinstance(p, Loads) and p.kind in LOAD_KINDS and p.surface for p in cls.produces
    ):
        raise PluginError(
            f"{where}: field 'produces' = {cls.produces!r} must be a tuple of certkit.engine.registry.Loads "
            f"(a surface and a kind among {LOAD_KINDS})"
        )
    if not isinstance(cls.offers, tuple) or not all(isinstance(o, RESPONSE_KINDS) for o in cls.offers):
        raise PluginError(
            f"{where}: field 'offers' = {cls.offers!r} must be a tuple of "
            + " or ".join(k.__name__ for k in RESPONSE_KINDS)
        )


def producers(rules: Sequence[type[Rule]], surface: str, kind: str = STATION_LOADS) -> list[type[Rule]]:
    """The rules of ``rules`` that declare they produce ``kind`` loads of ``surface`` (:attr:`Rule.produces`)."""
    return [r for r in rules if Loads(surface, kind) in r.produces]


def _validate_unevaluated(cls: type[Rule], where: str) -> None:
    """``unevaluated`` holds (paragraph id, reason) pairs and agrees with ``implementation``."""
    entries = cls.unevaluated
    if not isinstance(entries, tuple):
        raise PluginError(f"{where}: field 'unevaluated' must be a tuple of (paragraph, reason) pairs")
    for entry in entries:
        if not (
            isinstance(entry, tuple)
            and len(entry) == 2
            and isinstance(entry[0], str)
            and RULE_ID.match(entry[0])
            and isinstance(entry[1], str)
            and entry[1].strip()
        ):
            raise PluginError(f"{where}: field 'unevaluated' holds {entry!r}, not a (paragraph id, reason) pair")
    if cls.implementation == "partial" and not entries:
        raise PluginError(
            f"{where}: implementation 'partial' needs the sub-paragraphs it does not evaluate in 'unevaluated'"
        )
    if cls.implementation == "implemented" and entries:
        raise PluginError(
            f"{where}: lists sub-paragraphs in 'unevaluated' but declares implementation 'implemented' "
            "(declare 'partial')"
        )


def rule(cls: type[R]) -> type[R]:
    """Class decorator declaring a rule; validates its metadata at import time."""
    validate_rule_class(cls, cls.__module__)
    cls.__certkit_rule__ = True  # type: ignore[attr-defined]  # the mark discovery reads (_rules_in_module)
    return cls


def _rules_in_module(module: ModuleType, origin: str) -> list[type[Rule]]:
    found: list[type[Rule]] = []
    for _, obj in inspect.getmembers(module, inspect.isclass):
        declared = obj.__dict__.get("__certkit_rule__") and obj.__module__ == module.__name__
        if declared and issubclass(obj, Rule):
            obj.origin = origin
            found.append(obj)
    return found


def builtin_rules() -> list[type[Rule]]:
    import certkit_rules  # deferred: cycle and layer: the rules import this module; discovery loads them by name

    rules = []
    for info in pkgutil.walk_packages(certkit_rules.__path__, prefix="certkit_rules."):
        module = importlib.import_module(info.name)
        rules += _rules_in_module(module, "built-in")
    return rules


def plugin_rules() -> list[type[Rule]]:
    rules = []
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        origin = f"plugin '{ep.name}' ({ep.value}) of {ep.dist.name if ep.dist else 'an installed package'}"
        try:
            obj = ep.load()
        except PluginError:
            raise
        except SystemExit as exc:
            raise PluginError(f"{origin}: {exit_called(exc)} while being loaded") from None
        except Exception as exc:
            raise PluginError(f"{origin}: cannot be loaded: {exc.__class__.__name__}: {exc}") from None
        if inspect.ismodule(obj):
            rules += _rules_in_module(obj, origin)
        else:
            for cls in obj if isinstance(obj, (list, tuple)) else [obj]:
                validate_rule_class(cls, origin)
                cls.origin = origin
                rules.append(cls)
    return rules


def folder_rules(folder: str | Path) -> list[type[Rule]]:
    folder = Path(folder)
    if not folder.is_dir():
        raise UserError(f"--rules {folder}: not a folder")
    rules = []
    for path in sorted(folder.glob("*.py")):
        if path.name.startswith("_"):
            continue
        name = f"certkit_user_rules.{path.stem}_{abs(hash(str(path.resolve()))) % 10**8}"
        spec = importlib.util.spec_from_file_location(name, path)
        if spec is None or spec.loader is None:
            raise PluginError(f"{path}: cannot be loaded as a Python module")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        except PluginError as exc:
            raise PluginError(f"{path}: {exc}") from None
        except SystemExit as exc:
            raise PluginError(f"{path}: {exit_called(exc)} while being loaded") from None
        except Exception as exc:
            raise PluginError(f"{path}: cannot be loaded: {exc.__class__.__name__}: {exc}") from None
        rules += _rules_in_module(module, f"user folder {folder}")
    return rules


@dataclass(frozen=True)
class DiscoveryOptions:
    rules_dirs: tuple[str, ...] = ()
    plugins: bool = True


def discover(options: DiscoveryOptions = DiscoveryOptions()) -> list[type[Rule]]:
    """All rules, sorted by paragraph; duplicate ids are an error naming both origins."""
    rules = builtin_rules()
    if options.plugins:
        rules += plugin_rules()
    for folder in options.rules_dirs:
        rules += folder_rules(folder)
    by_id: dict[str, type[Rule]] = {}
    for cls in rules:
        if cls.id in by_id and by_id[cls.id] is not cls:
            raise PluginError(
                f"rule id {cls.id} is declared twice: by {by_id[cls.id].origin} "
                f"({by_id[cls.id].__name__}) and by {cls.origin} ({cls.__name__})"
            )
        by_id[cls.id] = cls
    return sorted(by_id.values(), key=lambda c: paragraph_key(c.id))


def paragraph_key(rule_id: str) -> tuple[int, int, str, str]:
    """Sort key: 25.21 < 25.103 < 25.331(c)(1) < 25.331(c)(2)."""
    head, _, tail = rule_id.partition("(")
    part, _, para = head.partition(".")
    num = re.match(r"(\d+)([a-z]?)", para)
    if num is None:
        raise ValueError(f"{rule_id!r} is not a paragraph id such as '25.331(c)(2)'")
    return (int(part), int(num.group(1)), num.group(2), tail)


def select(rules: list[type[Rule]], select: tuple[str, ...] = (), ignore: tuple[str, ...] = ()) -> list[type[Rule]]:
    """``--select``/``--ignore`` by id prefix, as ruff does (``25.1`` selects 25.103 … 25.181,
    ``25.331`` selects 25.331(c)(1) and (c)(2)) or by symbol. A pattern matching nothing is an error."""

    def matches(cls: type[Rule], pattern: str) -> bool:
        return pattern == cls.symbol or cls.id.startswith(pattern)

    for pattern in select + ignore:
        if not any(matches(c, pattern) for c in rules):
            raise UserError(f"no rule matches {pattern!r} (see `certkit rules` for ids and symbols)")
    chosen = [c for c in rules if not select or any(matches(c, p) for p in select)]
    return [c for c in chosen if not any(matches(c, p) for p in ignore)]
