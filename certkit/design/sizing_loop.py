"""The design structure's loop: Subpart C horizontal-tail loads → box sizing → mass, CG, inertia → loads again.

Iteration k evaluates the rules that declare horizontal-tail station loads or elevator hinge moments
(``Rule.produces``, :func:`sizing_rules`) on the airplane whose
tail group is the one sized at iteration k − 1 (at k = 0 the declared component, scaled with the planform area for a
changed tail), reduces their envelopes to the tail's limit loads (:mod:`certkit.design.tail_loads`), and sizes the
tail group for the union of the envelopes seen so far (so the structure carries every load the loop computed).
The sized group (box, secondary structure, elevator and actuators) replaces the tail's component in the mass table
and its box becomes the tail's declared structural capability at every station.

A changed design's first iterations evaluate near-critical conditions only — at first the declared airplane's (those
whose tail load or elevator hinge moment reaches :data:`START_FRACTION` of its largest), then those of the pass
before that come within :data:`FOLLOW_FRACTION` of its own envelope — until the group's mass moves by less
than the tolerance, or the next pass would move it by less than half of it as foreseen from the last two changes
(:func:`contraction`; the first such pass costs about a third of a full one and takes the mass most of the way, the
next ones, about a tenth each, the load–mass coupling's 5–15 kg); the later ones evaluate every condition. The loop
ends, after an iteration over every condition, when the group mass changes by less than the declared tolerance and
the loads of the airplane carrying it stay within what it was sized for (the box is sized for the envelope × (1 +
LOAD_ALLOWANCE)); then the loads rules' results of that last iteration are final. A loop
that does not converge within the declared number of iterations raises :class:`SizingNotConverged` with its
history — never a silent last value.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from certkit.design import baseline_store
from certkit.design.cg_envelope import follows_loading, loading_corners, with_loading_corners
from certkit.design.parallel import evaluate_rules
from certkit.design.tail_group import (
    declared_sizing,
    design_hinge_moment,
    hinge_critical_conditions,
    initial_group,
    size_tail_group,
)
from certkit.design.tail_loads import SURFACE, TailLoadEnvelope, near_critical_conditions, tail_load_envelope
from certkit.design.variables import Setting, design_aircraft
from certkit.engine.context import Context
from certkit.engine.registry import HINGE_MOMENT, Loads, producers
from certkit.engine.scheduler import evaluate_rule
from certkit.models.loads.model import airplane_loads
from certkit.models.structure.actuators import size_elevator_actuators

if TYPE_CHECKING:
    from certkit.aircraft import Aircraft, LoadedAircraft
    from certkit.aircraft.yaml_source import YamlSource
    from certkit.design.tail_group import TailGroup
    from certkit.engine.registry import Rule
    from certkit.engine.results import Condition, RuleResult

    #: wraps a design's aircraft for the engine
    LoadedOf = Callable[[Aircraft], LoadedAircraft]

TAIL_COMPONENT = "horizontal tail"
ACTUATOR_COMPONENT = "elevator actuators"
#: the box is sized for the load envelope × (1 + this): a load that grows by less between two iterations (the tail's
#: own mass changing its inertia relief: +1.6 % of the 75 %-span torsion for the baseline's +175 kg first step) is
#: still carried, so the loop need not run again for it (numerical choice; ~1 % of the tail group's mass)
LOAD_ALLOWANCE = 0.02
#: a design's loop starts from the declared airplane's near-critical conditions: those whose tail load (or elevator
#: hinge moment) reaches this fraction of the declared airplane's envelope somewhere (numerical choice: the loop's
#: later iterations evaluate every condition, so a point it misses costs an iteration, not a load)
START_FRACTION = 0.7
#: … and, per rule, the conditions within this fraction of the rule's own largest tail load somewhere (a changed tail
#: can make another rule's case critical: §25.349(a)'s 75 %-span torsion in one sampled design)
START_OWN_FRACTION = 0.9
#: (one such iteration takes the mass most of the way, so the loop goes on over every condition at once; only
#: iterations over every condition end it. The two fractions trade the cost of that first iteration against a third
#: one: on 23 designs of the seed study's benchmark sample, 0.85/0.95 left 10 designs needing a third iteration and
#: 0.7/0.9 six (the first iteration 0.49 → 0.54 s CPU, a design 3.75 → 3.61 s); 0.6/0.85 and 0.5/0.8 left the same six
#: and cost more. Those six need it for the load–mass coupling itself: a change of 6–16 kg, or loads beyond the box by
#: more than the allowance while the mass changes by < 5 kg. A converged design differs only within the tolerance.)
#: a near-critical pass after the first flies the conditions of the pass before whose loads or hinge moment reach this
#: fraction of that pass's envelope (numerical choice: the second pass only settles the load–mass coupling of the
#: cases that size the box, a few per cent; on the seed study's 50-case benchmark sample 0.9 halves that pass's cost
#: and leaves every record identical, 0.98 moves one envelope value by 6e-15)
FOLLOW_FRACTION = 0.9
#: the near-critical passes stop when the change they foresee for the next one is below this fraction of the loop's
#: mass tolerance (numerical choice: half, so that a ratio misjudged by a factor of two still ends within it)
FORESEEN = 0.5
#: the declared component that carries the baseline's elevator actuators (they are moved out of it, at their own
#: positions, so that the design's actuators replace them)
FLIGHT_CONTROLS = "flight controls"


class SizingNotConverged(RuntimeError):
    """The sizing loop did not converge; ``history`` holds each iteration's mass (kg) and change."""

    def __init__(self, message: str, history: list[dict[str, Any]]):
        super().__init__(message)
        self.history = history


@dataclass(frozen=True)
class BaselineActuators:
    """The elevator actuators of the unmodified aircraft file, sized by the same method (their mass sits in the
    declared flight-controls component)."""

    mass: float
    centroid: tuple[float, float, float]
    hinge: dict[str, Any]
    ctx: Context | None = field(default=None, repr=False, compare=False)  # the declared aircraft's (its lattice)
    #: rule id → the declared airplane's near-critical conditions (None: all), where a design's loop starts
    critical: dict[str, list[Condition] | None] | None = field(default=None, repr=False, compare=False)


@dataclass
class LoopResult:
    aircraft: Aircraft
    ctx: Context
    results: list[RuleResult]
    history: list[dict[str, Any]]
    group: TailGroup
    envelope: TailLoadEnvelope
    oew_kg: float
    baseline_tail_kg: float
    baseline_actuators: BaselineActuators
    seconds: float
    iteration_seconds: list[float] = field(default_factory=list)
    aero_seconds: float = 0.0  # of which: lattice, aerodynamic and strip-loads models
    #: the weight–CG corners the design was evaluated at when they follow its loading (sizing.cg_envelope: loading)
    cg_corners: list[dict[str, Any]] | None = None

    def responses(self) -> dict[str, float | None]:
        g = self.group
        out = {
            "sizing.ht_group_mass_kg": g.total_mass,
            "sizing.ht_structure_mass_kg": g.structure_mass,
            "sizing.ht_box_mass_kg": g.box_mass,
            "sizing.actuator_mass_kg": g.actuator_mass,
            "sizing.iterations": float(len(self.history)),
            "objective.OEW_kg": self.oew_kg,
            "sizing.design_hinge_moment_Nm": g.hinge.get("design_hinge_moment_Nm"),
        }
        if g.actuators is not None:
            out["sizing.hydraulic_flow_m3_s"] = g.actuators.total_flow
        return out

    def details(self) -> dict[str, Any]:
        extra = {} if self.cg_corners is None else {"cg_envelope": self.cg_corners}
        return {
            **extra,
            "history": self.history,
            "group": self.group.as_dict(),
            "envelope": self.envelope.as_dict(),
            "oew_kg": self.oew_kg,
            "declared_tail_component_kg": self.baseline_tail_kg,
            "baseline_actuators": {
                "mass_kg": self.baseline_actuators.mass,
                "centroid_m": list(self.baseline_actuators.centroid),
                "hinge_moment": self.baseline_actuators.hinge,
            },
            "oew_basis": "declared OEW − declared horizontal-tail component + sized structure + sized elevator "
            "actuators − the baseline's elevator actuators (sized alike; inside the declared flight controls)",
        }


def _index(data: dict[str, Any], name: str) -> int | None:
    for i, c in enumerate(data["mass"]["components"]):
        if str(c.get("name", "")).strip().lower() == name:
            return i
    return None


def _tail_component_index(data: dict[str, Any]) -> int:
    i = _index(data, TAIL_COMPONENT)
    if i is None:
        raise ValueError(
            f"the aircraft file has no mass component named {TAIL_COMPONENT!r} for the sized tail to replace"
        )
    return i


def with_tail_group(
    data: dict[str, Any], aircraft: Aircraft, group: TailGroup, baseline: BaselineActuators, oew_kg: float
) -> dict[str, Any]:
    """A copy of the aircraft data whose tail component, actuators, structural capability and OEW are the sized
    group's (SI numbers); the baseline's actuators leave the flight-controls component at their own positions. The
    rest of the data is shared, not copied."""
    out = dict(data)
    mass = dict(data["mass"])
    comps = list(mass["components"])
    i = _tail_component_index(data)
    comps[i] = {**comps[i], **group.component(), "name": comps[i]["name"]}
    j = _index(data, FLIGHT_CONTROLS)
    if j is not None and group.actuator_mass > 0 and baseline.mass > 0:
        fc = aircraft.mass.components[j]
        m = fc.mass - baseline.mass
        if m <= 0:
            raise ValueError(
                f"the baseline's elevator actuators ({baseline.mass:.0f} kg) outweigh the declared "
                f"{FLIGHT_CONTROLS!r} component ({fc.mass:.0f} kg)"
            )
        cg = [(fc.mass * a - baseline.mass * b) / m for a, b in zip((fc.cg.x, fc.cg.y, fc.cg.z), baseline.centroid)]
        comps[j] = {**comps[j], "mass": m, "cg": {"x": cg[0], "y": cg[1], "z": cg[2]}}
    if group.actuator_mass > 0:
        comps.append(group.actuator_component(ACTUATOR_COMPONENT))
    mass["components"] = comps
    mass["OEW"] = oew_kg
    out["mass"] = mass
    structure = dict(data.get("structure") or {})
    structure["horizontal_tail"] = group.capabilities()
    out["structure"] = structure
    return out


_BASELINE: dict[str, BaselineActuators] = {}
#: no baseline actuators (an aircraft file without sizing.elevator_actuators; a loop's first iteration)
NO_ACTUATORS = BaselineActuators(0.0, (0.0, 0.0, 0.0), {})


@dataclass(frozen=True)
class SizingRules:
    """The rules the loop evaluates, as they declare it (``Rule.produces``): those producing horizontal-tail station
    loads or elevator hinge moments, in rule order, and the ids of the latter (the actuators' design cases)."""

    rules: tuple[type[Rule], ...]
    hinge: frozenset[str]

    def hinge_results(self, results: Iterable[RuleResult]) -> list[RuleResult]:
        return [r for r in results if r.id in self.hinge]


#: the loads a sizing pass reads (:func:`tail_load_envelope`, :func:`design_hinge_moment`): a near-critical pass
#: asks the rules for these only (``evaluate_rule`` ``wanted``); the full pass computes everything, its findings the
#: verdicts
SIZING_LOADS = frozenset({Loads(SURFACE), Loads("elevator", HINGE_MOMENT)})


def sizing_rules(rules: Sequence[type[Rule]]) -> SizingRules:
    tail = producers(rules, SURFACE)
    hinge = producers(rules, "elevator", HINGE_MOMENT)
    return SizingRules(tuple(r for r in rules if r in tail or r in hinge), frozenset(r.id for r in hinge))


def _baseline_value(
    base_aircraft: Aircraft, ctx: Context, results: list[RuleResult], chosen: SizingRules
) -> BaselineActuators:
    hinge = design_hinge_moment(ctx, chosen.hinge_results(results))
    act = size_elevator_actuators(base_aircraft, hinge["design_hinge_moment_Nm"])
    x, y, z = (float(v) for v in np.mean(act.positions, axis=0))
    start = critical_points(ctx, results, chosen, START_FRACTION, START_OWN_FRACTION)
    return BaselineActuators(act.total_mass, (x, y, z), hinge, ctx, start)


def critical_points(
    ctx: Context, results: list[RuleResult], chosen: SizingRules, fraction: float, own_fraction: float = 1.0
) -> dict[str, list[Condition] | None]:
    """Rule id → the conditions of ``results`` whose tail load reaches ``fraction`` of their envelope (or
    ``own_fraction`` of the rule's own largest) or whose elevator hinge moment reaches ``fraction`` of the largest
    (None: all the rule's conditions). A design's loop starts on the declared airplane's at :data:`START_FRACTION` and
    :data:`START_OWN_FRACTION`; a near-critical pass after the first flies those of the pass before at
    :data:`FOLLOW_FRACTION`."""
    out = near_critical_conditions(results, fraction, own_fraction)
    for rid, conds in hinge_critical_conditions(ctx, chosen.hinge_results(results), fraction).items():
        loads = out.get(rid, [])
        out[rid] = None if conds is None or loads is None else loads + [c for c in conds if c not in loads]
    return out


def baseline_actuators(
    source: YamlSource, base_aircraft: Aircraft, rules: Sequence[type[Rule]], loaded_of: LoadedOf
) -> BaselineActuators:
    """The unmodified file's elevator actuators, sized from its own pitch manoeuvres, and its near-critical loads
    conditions (once per process and file; from the user's cache when a process computed them before:
    :mod:`certkit.design.baseline_store`, the value without its context)."""
    if source.sha256 not in _BASELINE:
        if base_aircraft.sizing is None or base_aircraft.sizing.elevator_actuators is None:
            value = NO_ACTUATORS
        else:
            chosen = sizing_rules(rules)
            key = baseline_store.entry_key(base_aircraft, chosen.rules)
            entries = baseline_store.store()
            stored = entries.load(key)
            if isinstance(stored, BaselineActuators):
                value = stored
            else:
                ctx = Context(loaded_of(base_aircraft))
                value = _baseline_value(
                    base_aircraft,
                    ctx,
                    [evaluate_rule(r, ctx, evidence=False, keep_loads=True) for r in chosen.rules],
                    chosen,
                )
                entries.save(key, replace(value, ctx=None))
        _remember(source, value)
    return _BASELINE[source.sha256]


def _remember(source: YamlSource, value: BaselineActuators) -> None:
    _BASELINE.clear()
    _BASELINE[source.sha256] = value


def contraction(history: Sequence[dict[str, Any]]) -> float:
    """The ratio of the last two mass changes of the loop's history (the contraction of the fixed-point iteration
    group mass → loads → sized mass); 1 (nothing foreseen) before two iterations or after a zero change."""
    if len(history) < 2 or history[-2]["change_kg"] == 0.0:
        return 1.0
    return min(abs(float(history[-1]["change_kg"]) / float(history[-2]["change_kg"])), 1.0)


def size_horizontal_tail_loop(
    source: YamlSource,
    settings: list[Setting],
    data: dict[str, Any],
    aircraft: Aircraft,
    base_aircraft: Aircraft,
    rules: Sequence[type[Rule]],
    loaded_of: LoadedOf,
    jobs: int = 1,
) -> LoopResult:
    """Run the loop for the design (``data``/``aircraft`` with the settings applied; ``base_aircraft`` the file as
    declared); ``rules`` the registered rule classes, ``loaded_of(aircraft)`` wraps an aircraft for the engine;
    ``jobs`` processes share the loads rules of an iteration (:mod:`certkit.design.parallel`)."""
    start = time.perf_counter()
    spec = declared_sizing(aircraft)
    chosen = sizing_rules(rules)
    loads_rules = list(chosen.rules)
    if not loads_rules:
        raise ValueError("no registered rule computes horizontal-tail loads: the tail cannot be sized")
    if aircraft.mass.OEW is None:
        raise ValueError("mass.OEW: the sized tail group replaces its share of the declared OEW")
    base_oew = float(aircraft.mass.OEW)
    declared = aircraft.mass.components[_tail_component_index(data)]
    group = initial_group(aircraft, base_aircraft, declared)
    history: list[dict[str, Any]] = []
    seconds: list[float] = []
    aero_seconds = 0.0
    union: TailLoadEnvelope | None = None
    same_geometry = all(st.path.split(".")[0] in ("mass", "sizing", "structure", "criteria") for st in settings)
    known = _BASELINE.get(source.sha256)
    if known is None and settings:  # without settings, iteration 0 flies the declared airplane: sized from it below
        known = baseline_actuators(source, base_aircraft, rules, loaded_of)
    ctx = (
        known.ctx if same_geometry and known is not None else None
    )  # the declared lattice serves an unchanged geometry
    base_act = known
    # a changed design's first iteration flies the declared airplane's near-critical points, the next ones every
    # condition until the mass settles with the loads inside the sized box (only that ends the loop)
    partial = bool(settings) and known is not None and known.critical is not None
    start_points = known.critical if partial and known is not None else None
    for k in range(spec.max_iterations):
        t = time.perf_counter()
        # iteration 0 carries no sized actuators, so the baseline's are not moved out yet (none may be known)
        moved = base_act if base_act is not None else NO_ACTUATORS
        actuators = group.actuator_mass - moved.mass if k > 0 else 0.0
        oew = base_oew - declared.mass + group.structure_mass + actuators
        current_data = with_tail_group(data, aircraft, group, moved, oew)
        current = design_aircraft(source, settings, current_data)
        if follows_loading(current):  # the corners the design's own loading reaches (certkit.design.cg_envelope)
            corners = loading_corners(current, aircraft)
            current = design_aircraft(source, settings, with_loading_corners(current_data, corners))
        previous_ctx, ctx = ctx, Context(loaded_of(current))
        if previous_ctx is not None:
            ctx.share_aerodynamics(previous_ctx)  # same geometry, only the tail's mass data changed
        t_aero = time.perf_counter()
        ctx.aero("clean"), airplane_loads(ctx)  # lattice, aerodynamic and strip-loads models (timed apart)
        aero_seconds += time.perf_counter() - t_aero
        if k == 0 and same_geometry and known is not None and known.ctx is None and known is not NO_ACTUATORS:
            # the baseline came from the user's cache, without its context: this design's lattice (the declared
            # geometry's) serves the process's next designs of the same geometry, as the declared airplane's would
            _BASELINE[source.sha256] = replace(known, ctx=ctx)
        results = evaluate_rules(
            loads_rules,
            ctx,
            jobs,
            evidence=False,
            keep_loads=True,
            select=start_points if partial else None,
            wanted=SIZING_LOADS if partial else None,
        )
        if base_act is None:  # iteration 0 of an unchanged geometry flies the declared airplane: its actuators
            base_act = _baseline_value(base_aircraft, ctx, results, chosen)
            _remember(source, base_act)
        envelope = tail_load_envelope(results)
        within = union is not None and not envelope.exceeds(union, rtol=LOAD_ALLOWANCE)
        union = envelope.union(union)
        sized = size_tail_group(current, ctx, union, chosen.hinge_results(results), allowance=LOAD_ALLOWANCE)
        change = sized.total_mass - group.total_mass
        seconds.append(time.perf_counter() - t)
        history.append(
            {
                "iteration": k,
                "group_mass_kg": round(group.total_mass, 3),
                "sized_mass_kg": round(sized.total_mass, 3),
                "change_kg": round(change, 3),
                "loads_within_sized": bool(within),
                "conditions": "near-critical" if partial else "all",
            }
        )
        if partial:
            # the near-critical passes go on while the group's mass would still move by more than the tolerance (each
            # costs a third of a full pass); a full pass follows at the mass they settle on. After two passes the
            # next change is foreseen from the last two (a fixed-point iteration contracts by about their ratio), so
            # a pass that would only confirm the mass is not flown
            partial = (
                abs(change) >= spec.tolerance_kg and abs(change * contraction(history)) >= FORESEEN * spec.tolerance_kg
            )
            if partial:  # the next pass flies the points that set this pass's envelope and hinge moment
                skipped: dict[str, list[Condition] | None] = {
                    rid: [] for rid, conds in (start_points or {}).items() if conds == []
                }
                start_points = {**skipped, **critical_points(ctx, results, chosen, FOLLOW_FRACTION)}
        elif k > 0 and abs(change) < spec.tolerance_kg and within:
            for r in results:
                r.run = None  # the simulations are not needed any more
            return LoopResult(
                current,
                ctx,
                results,
                history,
                group,
                union,
                oew,
                declared.mass,
                base_act,
                time.perf_counter() - start,
                seconds,
                aero_seconds,
                corners if follows_loading(current) else None,
            )
        group = sized
    raise SizingNotConverged(
        f"horizontal-tail sizing did not converge in {spec.max_iterations} iterations (tolerance "
        f"{spec.tolerance_kg:g} kg): "
        + "; ".join(
            f"#{h['iteration']} {h['group_mass_kg']:.1f} → {h['sized_mass_kg']:.1f} kg"
            f"{'' if h['loads_within_sized'] else ' (loads grew)'}"
            for h in history
        ),
        history,
    )
