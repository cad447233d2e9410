"""The §25.331(b) balanced manoeuvres shared by §25.331(b) and §25.427(b) (regulation content, no rule here): the
envelope points of the condition space, their speeds and load factors (§25.333(b), §25.345(a)), the criteria and
the batched balanced states and loads, memoised in the context so that the rules evaluated in one process
(``run_with = "discrete-gust"``) balance once. Sources and verification status:
:mod:`certkit_rules.part25.subpart_c.r25_331b`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from certkit_rules.part25.support.envelope_criteria import CN_OVER_CL
from certkit_rules.part25.support.fuel_states import fuel_detail, fuel_state_table
from certkit_rules.part25.support.loads_conditions import refusal_findings, trimmed_batch
from certkit_rules.part25.support.out_of_trim import (
    MISTRIM_SECONDS,
    MISTRIMS,
    mistrim,
    mistrim_note,
    mistrim_rate,
    no_mistrim,
    out_of_trim_speed,
)
from certkit_rules.part25.support.stability_speeds import FLAP_ALTITUDE, flap_altitude_findings
from certkit_rules.part25.support.structural_checks import (
    SAFETY,
    beyond_mach_range,
    capability_finding,
    critical_state_finding,
    set_aside_finding,
)

from certkit.atmosphere import RHO0, convert_speed
from certkit.engine.conditions import CgCorners, ConditionSpace, EnvelopeAltitudes
from certkit.engine.registry import Criterion
from certkit.engine.results import Finding, LoadsRun
from certkit.models.flight import control_limits
from certkit.models.loads.balanced import ELEVATOR_ALONE, balanced_loads
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.response import LoadEnvelope, holds_flap_lift
from certkit.models.loads.vn_envelope import envelope
from certkit.units import G0, KN

SURFACES = ("wing", "horizontal_tail")
#: flaps-retracted points (§25.333(b) figure, letters A, D, E, F, H as docs/regulation-notes.md §1 reconstructs them)
CLEAN_POINTS = ("A", "VC at n+", "D", "E", "F", "H")
#: the §25.331(a)(2) out-of-trim conditions: the clean points at VC and VD (the §25.255 speeds, trimmed at cruise
#: speeds up to VMO/MMO), the stabiliser mistrimmed nose up and nose down
OUT_OF_TRIM_POINTS = ("VC at n+", "D", "E", "F")
FLAP_POINTS = ("VF at n flaps", "VF at 0")
NO_FLAP_STRIPS = (
    "the strip loads model cannot spread this configuration's flap lift on the wing (no flap declared in "
    "geometry.wing.flaps, or the aerodynamics are declared tables): its wing loads flaps extended are not computed"
)


@dataclass
class BalancedRun(LoadsRun):
    """The balanced manoeuvres: the balanced states (``state``: name → (n,)), the airplane's loads model and the
    right half tailplane's (aerodynamic, inertial) loads (``tail_parts``: (n, 3, S) each)."""

    state: dict = field(default_factory=dict)
    loads: object = None
    tail_parts: tuple = ()


@dataclass(frozen=True)
class BalancedPoints(ConditionSpace):
    """Every configuration of the aircraft: the flaps-retracted envelope points for ``clean``, the flap points for
    the others; each at every CG-envelope corner and altitude."""

    def expand(self, aircraft):
        out = []
        for cfg in aircraft.configurations:
            points = CLEAN_POINTS if cfg == "clean" else FLAP_POINTS
            out += ConditionSpace.expand(replace(self, configurations=(cfg,), extra=(("point", points),)), aircraft)
            if cfg == "clean" and mistrim_rate(aircraft) is not None:
                extra = (("point", OUT_OF_TRIM_POINTS), ("trim", tuple(MISTRIMS)))
                out += ConditionSpace.expand(replace(self, configurations=(cfg,), extra=extra), aircraft)
        return out

    def describe(self):
        return (
            "every corner of the weight–CG envelope; altitudes from the envelope minimum to the ceiling; clean: "
            f"points {', '.join(CLEAN_POINTS)}, and out of trim (§25.331(a)(2), with a declared stabiliser trim "
            f"rate) points {', '.join(OUT_OF_TRIM_POINTS)} with the stabiliser mistrimmed nose up and nose down; "
            f"each flap configuration: {', '.join(FLAP_POINTS)}. " + self.note
        )


NO_MISTRIM = no_mistrim("balanced manoeuvres")


#: the conditions of the balanced manoeuvres (§25.331(b); §25.427(b) splits their tail loads)
BALANCED_CONDITIONS = BalancedPoints(
    loading=CgCorners(),
    altitudes=EnvelopeAltitudes(),
    note="Speeds in EAS, VC and VD Mach-limited at altitude (A and H at most VC).",
)


def point_speed_and_load_factor(ctx, cond, crit) -> tuple[float, float, str]:
    """EAS (m/s), path-normal load factor and a note of the envelope point of ``cond``."""
    lf = ctx.aircraft.envelope.limit_load_factors
    point, h = cond.get("point"), cond.altitude
    if point in FLAP_POINTS:
        v, note = design_flap_speed(ctx, cond.configuration, h, crit)
        n = float(lf.flaps_extended if lf.flaps_extended is not None else crit.flaps_load_factor)
        return v, (n if point == FLAP_POINTS[0] else 0.0), note
    env = envelope(ctx, cond.mass, h, crit.cn_over_cl)
    table = {
        "A": (env.v_a, env.n_pos),
        "VC at n+": (env.v_c, env.n_pos),
        "D": (env.v_d, env.n_pos),
        "E": (env.v_d, 0.0),
        "F": (env.v_c, env.n_neg),
        "H": (env.v_h, env.n_neg),
    }
    v, n = table[point]
    note = ""
    if point in ("A", "H") and v > env.v_c:
        note = f"stall-line speed {v / KN:.1f} kn EAS above VC at this altitude: taken at VC"
        v = env.v_c
    # a speed below the stall line's (Mach-limited VC at altitude): the envelope's boundary there is the stall line
    stall_n = float(env.n_stall_pos(v)) if n > 0 else -((v / env.vs1_neg) ** 2)
    if abs(stall_n) < abs(n) * (1.0 - 1e-9):
        note = (note + "; " if note else "") + (
            f"{v / KN:.1f} kn EAS is below the stall line's speed at n = {n:g}: "
            f"the point is on the ±C_N,max line at n = {stall_n:.3f}"
        )
        n = stall_n
    return float(v), float(n), note


def design_flap_speed(ctx, configuration: str, h: float, crit) -> tuple[float, str]:
    """EAS (m/s) of the design flap speed VF of a flap configuration and a note: the larger of the declared placard
    VFE and the §25.335(e)(3) minimum — ``vf_takeoff_factor`` × VS1 at MTOW for the configuration named ``takeoff``,
    ``vf_landing_factor`` × VS1 at MLW for the others (approach and landing positions) — VS1 = √(2 W / (ρ₀ S CLmax))
    with the configuration's declared CLmax. Raises LookupError without a declared VFE."""
    ac = ctx.aircraft
    vfe = ac.speeds.VFE.get(configuration)
    if vfe is None:
        raise LookupError(f"speeds.VFE.{configuration} is not declared (the design flap speed)")
    placard = float(convert_speed(vfe.value, vfe.kind, "EAS", h))
    takeoff = configuration == "takeoff"
    mass = ac.mass.MTOW if takeoff else ac.mass.MLW
    clmax = ac.configurations[configuration].CLmax
    if mass is None or clmax is None:
        return placard, "declared VFE as VF (no MLW or CLmax to form the §25.335(e)(3) minimum)"
    factor = float(crit.vf_takeoff_factor if takeoff else crit.vf_landing_factor)
    vs1 = float(np.sqrt(2 * mass * G0 / (RHO0 * ac.reference.area * clmax)))
    minimum = factor * vs1
    if minimum > placard:
        return minimum, (
            f"VF = {factor:g} VS1 at {'MTOW' if takeoff else 'MLW'} = {minimum / KN:.1f} kn EAS "
            f"(§25.335(e)(3)), above the placard VFE {placard / KN:.1f} kn EAS"
        )
    return placard, (
        f"VF = the placard VFE {placard / KN:.1f} kn EAS, above the §25.335(e)(3) minimum "
        f"{factor:g} VS1 = {minimum / KN:.1f} kn EAS"
    )


#: the criteria that define the balanced states (shared by §25.427(b), which splits their tail loads)
BALANCED_RUN_CRITERIA = {
    "cn_over_cl": CN_OVER_CL["cn_over_cl"],
    "flaps_load_factor": Criterion(
        2.0,
        "",
        "14 CFR 25.345(a)(1) (wording checked against CS 25.345(a) only, docs/regulation-notes.md §3)",
        "positive limit load factor flaps extended, "
        "used when envelope.limit_load_factors.flaps_extended is not declared",
    ),
    "vf_takeoff_factor": Criterion(
        1.6,
        "",
        "14 CFR 25.335(e)(3)(i) (text recalled, not re-verified)",
        "VF ≥ this × VS1, flaps in the takeoff position, at the maximum takeoff weight",
    ),
    "vf_landing_factor": Criterion(
        1.8,
        "",
        "14 CFR 25.335(e)(3)(ii)-(iii) (text recalled, not re-verified)",
        "VF ≥ this × VS1, flaps in the approach or landing position, at the maximum landing weight",
    ),
    "convergence": Criterion(1e-8, "rad/s", "certkit numerical choice", "largest |α̇|, |q̇| of a balanced state"),
    "mistrim_seconds": MISTRIM_SECONDS,
    "flap_altitude_max": FLAP_ALTITUDE,
    **SAFETY,
}
BALANCE_CRITERIA = tuple(BALANCED_RUN_CRITERIA)
#: what the balanced manoeuvres need from the aircraft file
BALANCED_REQUIRES = (
    "speeds.VA",
    "speeds.VC",
    "speeds.VD",
    "envelope.limit_load_factors",
    "configurations.clean.CLmax",
    "configurations.clean.CLmin",
    "geometry.horizontal_tail",
)


def balanced_runs(ctx, conditions, crit) -> BalancedRun:
    """:func:`balanced_maneuvers` memoised on the conditions and the criteria that define them (§25.331(b) and
    §25.427(b), evaluated in one process, balance once)."""
    key = ("balanced_maneuvers", tuple(conditions), tuple((k, str(crit[k])) for k in BALANCE_CRITERIA))
    return ctx.memo(key, lambda: balanced_maneuvers(ctx, conditions, crit))


def balanced_maneuvers(ctx, conditions, crit) -> BalancedRun:
    """Balanced states and loads of every condition (batched per configuration); findings, envelope, states."""
    findings, parts, labels, done, states, tail_parts = [], [], [], [], [], []
    by_cfg: dict[str, list] = {}
    for c in conditions:
        by_cfg.setdefault(c.configuration, []).append(c)
    loads = airplane_loads(ctx)  # the lattice is shared by every configuration
    caps = {s: declared_capabilities(ctx, s) for s in SURFACES}
    lim = control_limits(ctx.aircraft)["elevator"]
    if "clean" in by_cfg and mistrim_rate(ctx.aircraft) is None:
        findings.append(Finding.outside_scope("25.331(a)(2)", NO_MISTRIM))
    for cfg, conds in by_cfg.items():
        stops = {k: v for k, v in control_limits(ctx.aircraft, False, cfg).items() if k in ("elevator", "stabilizer")}
        entries: list = []
        key_of: dict = {}
        target, notes, reference = {}, {}, {}
        for c in conds:
            high = flap_altitude_findings(ctx, c, float(crit.flap_altitude_max), [_check(c, s) for s in SURFACES])
            if high:
                findings += high
                continue
            try:
                v, n, note = point_speed_and_load_factor(ctx, c, crit)
            except LookupError as exc:
                findings += [Finding.not_evaluated(c, _check(c, s), str(exc)) for s in SURFACES]
                continue
            target[c], notes[c] = (_entry(entries, key_of, c, v), n), note
            if c.get("trim") is not None:  # trimmed at the speed up to VMO/MMO (§25.255(a)), then mistrimmed
                reference[c] = _entry(entries, key_of, c, min(v, out_of_trim_speed(ctx, c.altitude or 0.0)))
        if not entries:
            continue
        batch = trimmed_batch(ctx, entries)
        todo = list(target)
        rows, refined, refused = batch.distribute(todo, lambda c: target[c][0], [e.speed for e in entries])  # noqa: B023  (called within this iteration)
        findings += refusal_findings(refused, lambda c: [_check(c, s) for s in SURFACES])
        if not rows.size:
            continue
        kept = [c for c in todo if target[c][0] not in dict(batch.failed)]
        mis = mistrimmed_entries(ctx, batch, rows, kept, reference, cfg, crit)
        findings += [
            Finding.not_evaluated(refined[i], _check(kept[i], s), why) for i, why in mis.refused for s in SURFACES
        ]
        rows, kept, refined = rows[mis.keep], [kept[i] for i in mis.keep], [refined[i] for i in mis.keep]
        if not rows.size:
            continue
        n = np.array([target[c][1] for c in kept])
        wing_held = cfg == "clean" or holds_flap_lift(loads, batch.model)
        # the wing in each fuel state of §25.343 at the condition's weight (linear in each tank's fuel), clean only
        state_names, fuel = fuel_state_table(ctx.aircraft, [c.mass for c in kept])
        bl = balanced_loads(
            loads,
            batch.model.subset(rows),
            batch.x[rows],
            mis.u[mis.keep],
            n,
            stops,
            SURFACES,
            tol=float(crit.convergence),
            fuel=fuel,
            wing=wing_held,
            retrim=np.array([c.get("trim") is None for c in kept]),
        )
        model, st, scheme, sl, total, wing_states = bl.model, bl.state, bl.scheme, bl.parts, bl.total, bl.wing_states
        bad = ~st.converged
        de = st.u[:, list(model.control_names).index("elevator")]
        ds = st.u[:, list(model.control_names).index("stabilizer")] if "stabilizer" in stops else None
        tail_load = 2.0 * sl["horizontal_tail"][0][:, 0, 0]  # both halves' aerodynamic root shear
        wing_lift = 2.0 * sl["wing"][0][:, 0, 0]
        for i, c in enumerate(refined):
            details = dict(
                point=c.get("point"),
                n=round(float(n[i]), 3),
                V_kn_EAS=round(float(c.speed / KN), 1),
                n_z_body=round(float(st.outputs.n_z[i]), 4),
                alpha_deg=round(float(np.degrees(st.alpha[i])), 3),
                CL=round(float(st.outputs.CL[i]), 4),
                elevator_deg=round(float(np.degrees(de[i])), 3),
                pitch_rate_deg_s=round(float(np.degrees(st.pitch_rate[i])), 3),
                tail_balancing_load_kN=round(float(tail_load[i] / 1e3), 1),
                wing_air_load_kN=round(float(wing_lift[i] / 1e3), 1),
                mach=round(float(st.outputs.mach[i]), 3),
            )
            if not lim[0] <= de[i] <= lim[1]:
                details["elevator_note"] = (
                    f"the balance needs {np.degrees(de[i]):.1f}° elevator, beyond the design "
                    f"limits {np.degrees(lim[0]):.1f}…{np.degrees(lim[1]):.1f}°"
                )
            if notes[kept[i]]:
                details["speed_note"] = notes[kept[i]]
            if scheme[i] != ELEVATOR_ALONE:
                details["stabilizer_deg"] = round(float(np.degrees(ds[i])), 3)
                details["pitch_trim"] = PITCH_TRIM_NOTES[scheme[i]]
            if c.get("trim") is not None:
                j = mis.keep[i]
                details["stabilizer_deg"] = round(float(np.degrees(ds[i])), 3)
                details["pitch_trim"] = mistrim_note(
                    c.get("trim"), mis.trim_speed[j], mis.moved[j], bool(mis.limited[j]), "the elevator balances"
                )
            past_stop = beyond_stops(st.u[i], model.control_names, stops)
            beyond_mach = beyond_mach_range(loads, float(st.outputs.mach[i]))
            for s in SURFACES:
                check = _check(c, s)
                if beyond_mach:
                    findings.append(
                        set_aside_finding(
                            c,
                            check,
                            beyond_mach,
                            np.stack([wing_states[:, i]] * 2, axis=1) if s == "wing" else np.stack([total[s][i]] * 2),
                            loads[s].station_names,
                            **details,
                        )
                    )
                elif past_stop and not bad[i]:
                    findings.append(beyond_stop_finding(c, check, past_stop, **details))
                elif bad[i]:
                    findings.append(
                        Finding.not_evaluated(
                            c, check, f"balanced state not found (residual {st.residual[i]:.2e})", **details
                        )
                    )
                elif s == "wing" and not wing_held:
                    findings.append(Finding.not_evaluated(c, check, NO_FLAP_STRIPS, **details))
                elif s == "wing":
                    peaks = np.stack([wing_states[:, i], wing_states[:, i]], axis=1)  # one state each: min = max
                    findings.append(
                        critical_state_finding(
                            c,
                            check,
                            s,
                            peaks,
                            loads[s].station_names,
                            caps[s],
                            crit.ultimate_factor,
                            lambda j, i=i, names=state_names, fuel=fuel: fuel_detail(
                                names[i], fuel[i], loads["wing"].tank_names, j
                            ),
                            **details,
                        )
                    )
                else:
                    peaks = np.stack([total[s][i], total[s][i]])  # one state: min = max
                    findings.append(
                        capability_finding(
                            c, check, s, peaks, loads[s].station_names, caps[s], crit.ultimate_factor, **details
                        )
                    )
        parts.append({"wing": wing_states, "horizontal_tail": total["horizontal_tail"]})
        tail_parts.append(tuple(np.where(bad[:, None, None], np.nan, x) for x in sl["horizontal_tail"]))
        names = list(model.control_names)
        states.append(
            {
                "n_z": st.outputs.n_z,
                "qbar": st.outputs.qbar,
                "mach": st.outputs.mach,
                "alpha": st.alpha,
                "q_hat": st.pitch_rate * model.c / (2 * st.outputs.V),
                **{k: st.u[:, names.index(k)] for k in names if ":" not in k},
            }
        )
        labels += [c.label() for c in refined]
        done += refined
    if not parts:
        return BalancedRun(findings, reason="no condition could be balanced (see the findings)")
    # the fuel states as the envelope's "time" axis (the tail's loads do not depend on the wing's fuel)
    wing = np.concatenate([p["wing"] for p in parts], axis=1)
    tail = np.concatenate([p["horizontal_tail"] for p in parts])
    hist = {"wing": wing, "horizontal_tail": np.broadcast_to(tail, wing.shape[:1] + tail.shape)}
    env = LoadEnvelope.from_histories(loads, hist, np.zeros(wing.shape[0]), labels, keys=done)
    state = {k: np.concatenate([p[k] for p in states]) for k in states[0]}
    tail = tuple(np.concatenate([p[k] for p in tail_parts]) for k in (0, 1))
    return BalancedRun(findings, done, envelope=env, state=state, loads=loads, tail_parts=tail)


#: how the balance holds its pitching moment when the elevator alone would pass its stop
PITCH_TRIM_NOTES = {
    1: "stabiliser retrimmed, elevator at its 1 g trim (the elevator alone would pass its stop)",
    2: "elevator at its stop, stabiliser retrimmed (neither alone holds the balance)",
}


def beyond_stops(u, control_names, stops) -> tuple[str, float, float] | None:
    """The first pitch control of a balanced state ``u`` beyond its control-system stop: (name, deflection, the
    stop passed) in radians; None within every stop."""
    names = list(control_names)
    for name in ("stabilizer", "elevator"):
        if name in stops and name in names:
            d, (lo, hi) = float(u[names.index(name)]), stops[name]
            if not lo <= d <= hi:
                return name, d, hi if d > hi else lo
    return None


def beyond_stop_finding(cond, check: str, past: tuple[str, float, float], **details) -> Finding:
    """The finding of a balanced state that needs a pitch control beyond its control-system stop, after the
    stabiliser (if movable) was retrimmed (:func:`certkit.models.loads.balanced.balanced_within_stops`): the
    airplane cannot hold the condition, which fails; margin in degrees, the stop − the deflection needed. Its loads
    stay in the envelope (conservative for sizing)."""
    name, needed, stop = past
    word = "stabiliser" if name == "stabilizer" else name
    what = (
        f"the balance needs {np.degrees(needed):+.1f}° {word}, beyond its control-system stop {np.degrees(stop):+.1f}°"
    )
    if name == "stabilizer":
        what += " with the elevator at its stop"
    return Finding.compare(
        cond,
        f"{check}: {word} within its stop",
        abs(np.degrees(needed)),
        abs(np.degrees(stop)),
        at_least=False,
        unit="deg",
        reason=what,
        **details,
    )


def _entry(entries: list, key_of: dict, c, v: float) -> int:
    """The position in ``entries`` of the 1 g trim of ``c``'s loading and altitude at EAS ``v``, added if new."""
    key = (c.loading, c.altitude, round(v, 6))
    if key not in key_of:
        key_of[key] = len(entries)
        plain = c.with_(speed=v, speed_kind="EAS", speed_name=None, point=None)
        entries.append(plain if c.get("trim") is None else plain.with_(trim=None))
    return key_of[key]


def _check(cond, surface: str) -> str:
    if cond.get("trim") is not None:
        return f"(a)(2) out-of-trim balanced manoeuvre, point {cond.get('point')}, {surface.replace('_', ' ')}"
    return f"(b) balanced manoeuvre, point {cond.get('point')}, {surface.replace('_', ' ')}"


@dataclass
class MistrimmedEntries:
    """The entry controls of a configuration's balanced conditions (``u``, (n, nc)): the 1 g trim's at the condition's
    speed, and for an out-of-trim condition the stabiliser of the 1 g trim at its reference speed (``trim_speed``,
    m/s EAS) moved by the mistrim (``moved``, rad; ``limited`` where the trim limit stopped it) with that trim's
    elevator; ``keep``: the conditions with an entry; ``refused``: (index, reason) of those whose reference speed did
    not trim."""

    u: np.ndarray
    keep: np.ndarray
    refused: list
    trim_speed: np.ndarray
    moved: np.ndarray
    limited: np.ndarray


def mistrimmed_entries(ctx, batch, rows, kept, reference, configuration: str, crit) -> MistrimmedEntries:
    """The §25.331(a)(2) out-of-trim entries of ``kept`` (batch ``rows``; ``reference``: condition → its reference
    entry): 3 s (``mistrim_seconds``) of the declared trim rate, nose up or nose down, within the configuration's
    stabiliser trim limits ("except as limited by stops in the trim system", §25.255(a)(1))."""
    n = len(kept)
    u = batch.u[rows].copy()
    trim_speed, moved, limited = np.full(n, np.nan), np.zeros(n), np.zeros(n, dtype=bool)
    refused, keep = [], []
    out = [i for i, c in enumerate(kept) if c.get("trim") is not None]
    if out:
        names = list(batch.model.control_names)
        js, je = names.index("stabilizer"), names.index("elevator")
        pos, failed = {int(e): k for k, e in enumerate(batch.index)}, dict(batch.failed)
        for i in out:
            e = reference[kept[i]]
            if e not in pos:
                refused.append((i, f"no 1 g trim at the out-of-trim reference speed (VMO/MMO): {failed.get(e, '')}"))
                continue
            ref = batch.u[pos[e]]
            u[i, js], limited[i] = mistrim(ctx, float(ref[js]), kept[i].get("trim"), configuration, crit)
            u[i, je], moved[i] = ref[je], u[i, js] - ref[js]
            trim_speed[i] = batch.conditions[pos[e]].speed
    gone = {i for i, _ in refused}
    keep = np.array([i for i in range(n) if i not in gone], dtype=int)
    return MistrimmedEntries(u, keep, refused, trim_speed, moved, limited)
