"""The §25.331(b) balanced manoeuvres shared by §25.331(b) and §25.427(b) (regulation content, no rule here): the
envelope points of the condition space, their speeds and load factors (§25.333(b), §25.345(a)), the criteria and
the batched balanced states and loads, memoised in the context so that the rules evaluated in one process
(``run_with = "discrete-gust"``) balance once. Sources and verification status: :mod:`certkit_rules.part25.subpart_c.r25_331b`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from certkit.atmosphere import convert_speed
from certkit.engine.conditions import CgCorners, ConditionSpace, EnvelopeAltitudes
from certkit_rules.part25.support.loads_conditions import refusal_findings, trimmed_batch
from certkit.models.flight import control_limits
from certkit.models.loads.balanced import balanced_states, linear_lift, steady_load_parts
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.response import LoadEnvelope
from certkit.models.loads.vn_envelope import envelope
from certkit.engine.registry import Criterion
from certkit.engine.results import Finding, LoadsRun
from certkit.units import KN
from certkit_rules.part25.support.envelope_criteria import CN_OVER_CL
from certkit_rules.part25.support.structural_checks import SAFETY, capability_finding

SURFACES = ("wing", "horizontal_tail")
#: flaps-retracted points (§25.333(b) figure, letters A, D, E, F, H as docs/regulation-notes.md §1 reconstructs them)
CLEAN_POINTS = ("A", "VC at n+", "D", "E", "F", "H")
FLAP_POINTS = ("VF at n flaps", "VF at 0")
NO_FLAP_STRIPS = ("the strip loads model has no flap deflection (clean lattice): the wing's lift increment of the "
                  "flaps is not distributed on its strips, so its loads flaps extended are not computed")


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
        return out

    def describe(self):
        return ("every corner of the weight–CG envelope; altitudes from the envelope minimum to the ceiling; clean: "
                f"points {', '.join(CLEAN_POINTS)}; each flap configuration: {', '.join(FLAP_POINTS)}. " + self.note)


#: the conditions of the balanced manoeuvres (§25.331(b); §25.427(b) splits their tail loads)
BALANCED_CONDITIONS = BalancedPoints(loading=CgCorners(), altitudes=EnvelopeAltitudes(),
                                     note="Speeds in EAS, VC and VD Mach-limited at altitude (A and H at most VC).")


def point_speed_and_load_factor(ctx, cond, crit) -> tuple[float, float, str]:
    """EAS (m/s), path-normal load factor and a note of the envelope point of ``cond``."""
    lf = ctx.aircraft.envelope.limit_load_factors
    point, h = cond.get("point"), cond.altitude
    if point in FLAP_POINTS:
        vfe = ctx.aircraft.speeds.VFE.get(cond.configuration)
        if vfe is None:
            raise LookupError(f"speeds.VFE.{cond.configuration} is not declared (the design flap speed)")
        v = float(convert_speed(vfe.value, vfe.kind, "EAS", h))
        n = float(lf.flaps_extended if lf.flaps_extended is not None else crit.flaps_load_factor)
        return v, (n if point == FLAP_POINTS[0] else 0.0), "declared VFE as the design flap speed VF"
    env = envelope(ctx, cond.mass, h, crit.cn_over_cl)
    table = {"A": (env.v_a, env.n_pos), "VC at n+": (env.v_c, env.n_pos), "D": (env.v_d, env.n_pos),
             "E": (env.v_d, 0.0), "F": (env.v_c, env.n_neg), "H": (env.v_h, env.n_neg)}
    v, n = table[point]
    note = ""
    if point in ("A", "H") and v > env.v_c:
        note = f"stall-line speed {v / KN:.1f} kn EAS above VC at this altitude: taken at VC"
        v = env.v_c
    # a speed below the stall line's (Mach-limited VC at altitude): the envelope's boundary there is the stall line
    stall_n = (v / env.vs1_pos) ** 2 if n > 0 else -((v / env.vs1_neg) ** 2)
    if abs(stall_n) < abs(n) * (1.0 - 1e-9):
        note = (note + "; " if note else "") + (f"{v / KN:.1f} kn EAS is below the stall line's speed at n = {n:g}: "
                                                f"the point is on the ±C_N,max line at n = {stall_n:.3f}")
        n = stall_n
    return float(v), float(n), note


#: the criteria that define the balanced states (shared by §25.427(b), which splits their tail loads)
BALANCED_RUN_CRITERIA = {
    "cn_over_cl": CN_OVER_CL["cn_over_cl"],
    "flaps_load_factor": Criterion(2.0, "", "14 CFR 25.345(a)(1) (wording checked against CS 25.345(a) only, "
                                   "docs/regulation-notes.md §3)", "positive limit load factor flaps extended, "
                                   "used when envelope.limit_load_factors.flaps_extended is not declared"),
    "convergence": Criterion(1e-8, "rad/s", "certkit numerical choice", "largest |α̇|, |q̇| of a balanced state"),
    **SAFETY,
}
BALANCE_CRITERIA = tuple(BALANCED_RUN_CRITERIA)
#: what the balanced manoeuvres need from the aircraft file
BALANCED_REQUIRES = ("speeds.VA", "speeds.VC", "speeds.VD", "envelope.limit_load_factors", "configurations.clean.CLmax",
                     "configurations.clean.CLmin", "geometry.horizontal_tail")


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
    for cfg, conds in by_cfg.items():
        entries, key_of, target, notes = [], {}, {}, {}
        for c in conds:
            try:
                v, n, note = point_speed_and_load_factor(ctx, c, crit)
            except LookupError as exc:
                findings += [Finding.not_evaluated(c, _check(c, s), str(exc)) for s in SURFACES]
                continue
            key = (c.loading, c.altitude, round(v, 6))
            if key not in key_of:
                key_of[key] = len(entries)
                entries.append(c.with_(speed=v, speed_kind="EAS", speed_name=None, point=None))
            target[c], notes[c] = (key_of[key], n), note
        if not entries:
            continue
        batch = trimmed_batch(ctx, entries)
        todo = list(target)
        rows, refined, refused = batch.distribute(todo, lambda c: target[c][0], [e.speed for e in entries])
        findings += refusal_findings(refused, lambda c: [_check(c, s) for s in SURFACES])
        if not rows.size:
            continue
        kept = [c for c in todo if target[c][0] not in dict(batch.failed)]
        n = np.array([target[c][1] for c in kept])
        model = linear_lift(batch.model.subset(rows))
        st = balanced_states(model, batch.x[rows], batch.u[rows], n, tol=float(crit.convergence))
        sl = steady_load_parts(loads, model, st.x, st.u, st.outputs, SURFACES)
        total = {s: a + i for s, (a, i) in sl.items()}
        if cfg != "clean":
            total["wing"] = np.full_like(total["wing"], np.nan)
        bad = ~st.converged
        for s in SURFACES:
            total[s][bad] = np.nan
        de = st.u[:, list(model.control_names).index("elevator")]
        tail_load = 2.0 * sl["horizontal_tail"][0][:, 0, 0]  # both halves' aerodynamic root shear
        wing_lift = 2.0 * sl["wing"][0][:, 0, 0]
        for i, c in enumerate(refined):
            details = dict(point=c.get("point"), n=round(float(n[i]), 3), V_kn_EAS=round(float(c.speed / KN), 1),
                           n_z_body=round(float(st.outputs.n_z[i]), 4), alpha_deg=round(float(np.degrees(st.alpha[i])), 3),
                           CL=round(float(st.outputs.CL[i]), 4), elevator_deg=round(float(np.degrees(de[i])), 3),
                           pitch_rate_deg_s=round(float(np.degrees(st.pitch_rate[i])), 3),
                           tail_balancing_load_kN=round(float(tail_load[i] / 1e3), 1),
                           wing_air_load_kN=round(float(wing_lift[i] / 1e3), 1), mach=round(float(st.outputs.mach[i]), 3))
            if not lim[0] <= de[i] <= lim[1]:
                details["elevator_note"] = (f"the balance needs {np.degrees(de[i]):.1f}° elevator, beyond the design "
                                            f"limits {np.degrees(lim[0]):.1f}…{np.degrees(lim[1]):.1f}°")
            if notes[kept[i]]:
                details["speed_note"] = notes[kept[i]]
            for s in SURFACES:
                check = _check(c, s)
                if bad[i]:
                    findings.append(Finding.not_evaluated(c, check, f"balanced state not found (residual "
                                                          f"{st.residual[i]:.2e})", **details))
                elif s == "wing" and cfg != "clean":
                    findings.append(Finding.not_evaluated(c, check, NO_FLAP_STRIPS, **details))
                else:
                    peaks = np.stack([total[s][i], total[s][i]])  # one state: min = max
                    findings.append(capability_finding(c, check, s, peaks, loads[s].station_names, caps[s],
                                                       crit.ultimate_factor, **details))
        parts.append(total)
        tail_parts.append(tuple(np.where(bad[:, None, None], np.nan, x) for x in sl["horizontal_tail"]))
        names = list(model.control_names)
        states.append({"n_z": st.outputs.n_z, "qbar": st.outputs.qbar, "mach": st.outputs.mach, "alpha": st.alpha,
                       "q_hat": st.pitch_rate * model.c / (2 * st.outputs.V),
                       **{k: st.u[:, names.index(k)] for k in names if ":" not in k}})
        labels += [c.label() for c in refined]
        done += refined
    if not parts:
        return BalancedRun(findings, reason="no condition could be balanced (see the findings)")
    hist = {s: np.concatenate([p[s] for p in parts])[None] for s in SURFACES}
    env = LoadEnvelope.from_histories(loads, hist, np.zeros(1), labels, keys=done)
    state = {k: np.concatenate([p[k] for p in states]) for k in states[0]}
    tail = tuple(np.concatenate([p[k] for p in tail_parts]) for k in (0, 1))
    return BalancedRun(findings, done, envelope=env, state=state, loads=loads, tail_parts=tail)


def _check(cond, surface: str) -> str:
    return f"(b) balanced manoeuvre, point {cond.get('point')}, {surface.replace('_', ' ')}"
