"""The design structure's loop: Subpart C horizontal-tail loads → box sizing → mass, CG, inertia → loads again.

Iteration k evaluates the rules that compute horizontal-tail loads (``Rule.loads_surfaces``) on the airplane whose
tail group is the one sized at iteration k − 1 (at k = 0 the declared component, scaled with the planform area for a
changed tail), reduces their envelopes to the tail's limit loads (:mod:`certkit.design.tail_loads`), and sizes the
tail group for the union of the envelopes seen so far (so the structure carries every load the loop computed).
The sized group (box, secondary structure, elevator and actuators) replaces the tail's component in the mass table
and its box becomes the tail's declared structural capability at every station. The loop ends when the group mass
changes by less than the declared tolerance and the loads of the airplane carrying it stay within what it was
sized for; then the loads rules' results of that last iteration are final. A loop that does not converge within the
declared number of iterations raises :class:`SizingNotConverged` with its history — never a silent last value.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

from certkit.design.tail_loads import TailLoadEnvelope, tail_load_envelope
from certkit.design.variables import design_aircraft

TAIL_COMPONENT = "horizontal tail"
ACTUATOR_COMPONENT = "elevator actuators"


class SizingNotConverged(RuntimeError):
    """The sizing loop did not converge; ``history`` holds each iteration's mass (kg) and change."""

    def __init__(self, message: str, history: list[dict]):
        super().__init__(message)
        self.history = history


@dataclass
class LoopResult:
    aircraft: object
    ctx: object
    results: list
    history: list[dict]
    group: object
    envelope: TailLoadEnvelope
    oew_kg: float
    baseline_tail_kg: float
    seconds: float
    iteration_seconds: list[float] = field(default_factory=list)

    def responses(self) -> dict:
        g = self.group
        return {"sizing.ht_group_mass_kg": g.total_mass, "sizing.ht_structure_mass_kg": g.structure_mass,
                "sizing.ht_box_mass_kg": g.box_mass, "sizing.actuator_mass_kg": g.actuator_mass,
                "sizing.iterations": float(len(self.history)), "objective.OEW_kg": self.oew_kg}

    def details(self) -> dict:
        return {"history": self.history, "group": self.group.as_dict(), "envelope": self.envelope.as_dict(),
                "oew_kg": self.oew_kg, "baseline_tail_group_kg": self.baseline_tail_kg}


def _tail_component_index(data: dict) -> int:
    for i, c in enumerate(data["mass"]["components"]):
        if str(c.get("name", "")).strip().lower() == TAIL_COMPONENT:
            return i
    raise ValueError(f"the aircraft file has no mass component named {TAIL_COMPONENT!r} for the sized tail to replace")


def with_tail_group(data: dict, group, oew_kg: float) -> dict:
    """A copy of the aircraft data whose tail component, actuators, structural capability and OEW are the sized
    group's (SI numbers); the rest of the data is shared."""
    out = dict(data)
    mass = dict(data["mass"])
    comps = list(mass["components"])
    i = _tail_component_index(data)
    comps[i] = {**comps[i], **group.component(), "name": comps[i]["name"]}
    comps = [c for c in comps if str(c.get("name", "")).strip().lower() != ACTUATOR_COMPONENT]
    if group.actuator_mass > 0:
        comps.append(group.actuator_component(ACTUATOR_COMPONENT))
    mass["components"] = comps
    mass["OEW"] = oew_kg
    out["mass"] = mass
    structure = dict(data.get("structure") or {})
    structure["horizontal_tail"] = group.capabilities()
    out["structure"] = structure
    return out


def size_horizontal_tail_loop(source, settings, data, aircraft, rules, loaded_of) -> LoopResult:
    """Run the loop for the design (``data``/``aircraft`` with the settings applied); ``rules`` the registered rule
    classes, ``loaded_of(aircraft)`` wraps an aircraft as the engine's LoadedAircraft."""
    from certkit.context import Context
    from certkit.design.tail_group import declared_sizing, initial_group, size_tail_group
    from certkit.scheduler import evaluate_rule

    start = time.perf_counter()
    spec = declared_sizing(aircraft)
    loads_rules = [r for r in rules if "horizontal_tail" in r.loads_surfaces]
    if not loads_rules:
        raise ValueError("no registered rule computes horizontal-tail loads: the tail cannot be sized")
    base_oew = float(aircraft.mass.OEW)
    base_tail = float(aircraft.mass.components[_tail_component_index(data)].mass)
    group = initial_group(aircraft, spec)
    history: list[dict] = []
    seconds: list[float] = []
    union: TailLoadEnvelope | None = None
    previous_mass, ctx = None, None
    for k in range(spec.max_iterations):
        t = time.perf_counter()
        oew = base_oew - base_tail + group.total_mass - group.baseline_actuator_mass
        current = design_aircraft(source, settings, with_tail_group(data, group, oew))
        previous_ctx, ctx = ctx, Context(loaded_of(current))
        if previous_ctx is not None:
            ctx.share_aerodynamics(previous_ctx)  # same geometry, only the tail's mass data changed
        results = [evaluate_rule(r, ctx, evidence=False, keep_loads=True) for r in loads_rules]
        envelope = tail_load_envelope(results)
        within = union is not None and not envelope.exceeds(union)
        union = envelope.union(union)
        sized = size_tail_group(current, ctx, union, spec)
        change = None if previous_mass is None else sized.total_mass - group.total_mass
        seconds.append(time.perf_counter() - t)
        history.append({"iteration": k, "group_mass_kg": round(group.total_mass, 3),
                        "sized_mass_kg": round(sized.total_mass, 3), "change_kg": round(sized.total_mass - group.total_mass, 3),
                        "loads_within_sized": bool(within), "seconds": round(seconds[-1], 3)})
        if k > 0 and abs(sized.total_mass - group.total_mass) < spec.tolerance_kg and within:
            return LoopResult(current, ctx, results, history, group, union, oew, base_tail, time.perf_counter() - start, seconds)
        previous_mass, group = group.total_mass, sized
    raise SizingNotConverged(
        f"horizontal-tail sizing did not converge in {spec.max_iterations} iterations (tolerance "
        f"{spec.tolerance_kg:g} kg): " + "; ".join(f"#{h['iteration']} {h['group_mass_kg']:.1f} → {h['sized_mass_kg']:.1f} kg"
                                                  for h in history), history)
