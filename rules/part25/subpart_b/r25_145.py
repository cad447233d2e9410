"""§25.145(b) Longitudinal control: flap and thrust changes without re-trimming.

Text ([CFR 2003]; the lead-in and (b)(1) verified against [CFR 1-1-19] p. 221, docs/regulation-notes.md): with the
landing gear
extended, no change in trim control, or exertion of more than 50 lbf control force, may be required for:
(1) power off, flaps retracted, trimmed at 1.3 VSR1: extend the flaps as rapidly as possible, keeping about
1.3 × the reference stall speed existing at each instant; (2) as (1), flaps extended then retracted; (3) as
(2) at go-around power or thrust; (4) power off, flaps retracted, trimmed at 1.3 VSR1: set go-around power or
thrust at the same airspeed; (5) as (4) with the flaps extended; (6) [not retrieved].

With a control-force model declared (``control_forces.elevator``, :mod:`certkit.models.control_force`) the 50 lbf
is evaluated: the force that holds the end trim with the trim device left at the start setting (zero force at
the start trim). Without one the force is not evaluated. In both cases certkit checks the premise under it: the
stabiliser (trim control) stays where it was, so the elevator must move
from its trim at the start of each manoeuvre to its trim at the end, and that change must fit in the elevator
authority left on that side of the start position (design limits). Each state is a steady trim at 1.3 VSR of
its configuration: idle ("power off") in the glide that idle thrust gives, go-around thrust in the climb it
gives (:func:`certkit_rules.part25.support.thrust_trims.trim_at_thrust`, the energy relation).
"""

from __future__ import annotations

import math

import numpy as np
from certkit_rules.part25.support.control_checks import trim_details
from certkit_rules.part25.support.reference_speeds import reference_stall_speed
from certkit_rules.part25.support.thrust_trims import operating_thrust, trim_at_thrust

from certkit.engine.conditions import CgCorners, ConditionSpace
from certkit.engine.evidence.performance import margins_evidence
from certkit.engine.registry import ControlCase, ControlResponses, Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.control_force import control_force_model, trim_state
from certkit.models.dynamics.trim import held_stabilizer
from certkit.models.flight import control_limits
from certkit.units import LBF

FLAPS = ("takeoff", "approach", "landing")
IDLE, GO_AROUND = "idle", "go-around"
_SRC = "14 CFR 25.145(b) (lead-in and (b)(1) verified, [CFR 1-1-19] p. 221; docs/regulation-notes.md)"


def manoeuvres(flap: str):
    """(paragraph, description, start state, end state) with a state (configuration, thrust)."""
    return (
        ("(b)(1)", f"extend flaps clean → {flap}, power off", ("clean", IDLE), (flap, IDLE)),
        ("(b)(2)", f"retract flaps {flap} → clean, power off", (flap, IDLE), ("clean", IDLE)),
        ("(b)(3)", f"retract flaps {flap} → clean, go-around thrust", (flap, GO_AROUND), ("clean", GO_AROUND)),
        ("(b)(5)", f"set go-around thrust, flaps {flap}", (flap, IDLE), (flap, GO_AROUND)),
    )


CLEAN_MANOEUVRES = (("(b)(4)", "set go-around thrust, flaps retracted", ("clean", IDLE), ("clean", GO_AROUND)),)


def control_responses() -> ControlResponses:
    """The elevator at the end of each change as a design response (``control.25.145(b).<change>.elevator``)."""
    plan = list(CLEAN_MANOEUVRES) + [m for f in FLAPS for m in manoeuvres(f)]
    return ControlResponses(
        tuple(
            ControlCase(
                f"{para} {what}",
                f"{para} elevator change",
                ("elevator",),
                ("end_{control}_deg",),
                (("manoeuvre", f"{para} {what}"),),
            )
            for para, what, _, _ in plan
        )
    )


@rule
class LongitudinalControlConfigurationChanges(Rule):
    id = "25.145(b)"
    offers = (control_responses(),)
    symbol = "longitudinal-control-configuration-changes"
    title = "Longitudinal control: flap and thrust changes without re-trimming"
    amendment = "25-84"
    requirement = """
        With the landing gear extended, no change in trim control, or more than 50 lbf control force, may be
        required when, from a trim at 1.3 VSR1, the flaps are extended or retracted (power off, and retracted at
        go-around thrust) keeping about 1.3 × the instantaneous VSR, or go-around thrust is set at constant
        speed with the flaps retracted or extended.
    """
    margin = """Elevator authority left on the side of the change at the start trim (design limit − start
        deflection) − |elevator change to the end trim| (deg), for every manoeuvre, flap setting and CG corner;
        ≥ 0: the change can be held without re-trimming. With control_forces.elevator: 50 lbf − |elevator force holding
        the end trim, trim device at its start setting| (lbf)."""
    references = ("25.103", "25.143", "25.161")
    requires = ("configurations.clean", "mass.MTOW")
    criteria = {
        "speed_over_vsr": Criterion(
            1.3,
            "",
            _SRC + ": (b)(1), (b)(4)",
            "trim speed, × VSR of the configuration flown (VSR1 clean, instantaneous VSR flaps out)",
        ),
        "control_force_lbf": Criterion(50.0, "lbf", _SRC + ": (b)", "largest control force (one hand, short term)"),
        "go_around_thrust_fraction": Criterion(
            1.0,
            "",
            _SRC + ": (b)(3)-(5) go-around power or thrust; the engine model's throttle-1 (takeoff) thrust "
            "taken as go-around thrust, as for §25.121(d)",
            "go-around thrust over the engine model's full thrust",
        ),
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        note="sea level; clean and each flap configuration (takeoff, approach, landing) at 1.3 VSR of "
        "the configuration; idle (power off) and go-around thrust",
    )
    implementation = "partial"
    limitations = """
        The 50 lbf limit needs control_forces.elevator (without it one not_evaluated finding per corner); the force
        is the steady one at the end trim (the flap-dependent downwash change at the tail is not modelled). Steady
        trims at the start and end
        of each manoeuvre (no transient, no pitch-rate or speed-change dynamics). The gear is as declared for each
        configuration (the clean configuration is gear up, (b) asks gear down; the gear's pitching moment is not
        modelled). A movable stabiliser (geometry.horizontal_tail.stabilizer) stays where the start trim set it — that
        is
        what "without re-trimming" means — and the elevator takes the change; without one the stabiliser is fixed at its
        declared incidence. (b)(6) is not evaluated (text not retrieved).
    """

    unevaluated = (("25.145(b)(6)", "not evaluated (text of (b)(6) not retrieved)"),)

    def evaluate(self, ctx, conditions, crit):
        ac = ctx.aircraft
        elevator = control_force_model(ac, "elevator")
        limits = control_limits(ac)
        lo, hi = limits["elevator"]
        known = lambda cfg: ctx.clmax(cfg) is not None or cfg in ac.speeds.VSR  # noqa: E731  (a VSR to fly 1.3 VSR at)
        flaps = [f for f in FLAPS if f in ac.configurations]
        unknown = [cfg for cfg in ("clean", *flaps) if not known(cfg)]
        trims, aims = {}, {}
        for cfg in ("clean", *flaps):
            if cfg not in unknown:
                states, aim = self._trim_states(ctx, conditions, cfg, crit)
                trims.update(states)
                aims.update(aim)
        out, held = [], {}
        for i, cond in enumerate(conditions):
            plan = list(CLEAN_MANOEUVRES) + [m for f in flaps for m in manoeuvres(f)]
            for para, what, start, end in plan:
                missing = [cfg for cfg in (start[0], end[0]) if cfg in unknown]
                if missing:
                    out.append(
                        Finding.not_evaluated(
                            cond.with_(configuration=end[0], manoeuvre=f"{para} {what}"),
                            f"{para} elevator change within the remaining authority",
                            "needs "
                            + " or ".join(
                                f"configurations.{c}.CLmax (or speeds.VSR.{c})" for c in dict.fromkeys(missing)
                            ),
                        )
                    )
                    continue
                if (start, end) not in held:
                    held[(start, end)] = held_trims(ctx, trims[start], trims[end], aims[end])
                ends = held[(start, end)]
                out.append(self._finding(cond, i, para, what, trims[start], ends, lo, hi))
                if elevator is not None:
                    out.append(force_finding(ctx, elevator, i, para, what, trims[start], ends, crit.control_force_lbf))
            if elevator is None:
                out.append(
                    Finding.not_evaluated(
                        cond.with_(configuration="clean"),
                        f"(b) control force ≤ {crit.control_force_lbf:g} lbf",
                        "no control-force model (control_forces.elevator: hinge moments and gearing, or artificial "
                        "feel): the "
                        "force is not computed; the elevator change against the remaining authority is checked instead",
                    )
                )
        return out

    @staticmethod
    def _trim_states(ctx, conditions, cfg, crit):
        """Idle and go-around trims of every condition in ``cfg`` at 1.3 VSR, in one batch per iteration."""
        states = (IDLE, GO_AROUND)
        conds = [
            c.with_(
                configuration=cfg,
                altitude=0.0,
                speed_kind="CAS",
                speed_name="1.3 VSR" + ("1" if cfg == "clean" else ""),
                speed=crit.speed_over_vsr * reference_stall_speed(ctx, cfg, c.mass)[0],
                thrust="idle (power off)" if s == IDLE else "go-around",
            )
            for s in states
            for c in conditions
        ]
        n = len(conditions)
        aim = np.concatenate(
            [
                operating_thrust(ctx, conds[:n], 0.0),
                operating_thrust(ctx, conds[n:], 1.0, crit.go_around_thrust_fraction),
            ]
        )
        results, gamma, residual = trim_at_thrust(ctx, conds, aim)
        return (
            {
                (cfg, s): [
                    (conds[k * n + i], results[k * n + i], float(gamma[k * n + i]), float(residual[k * n + i]))
                    for i in range(n)
                ]
                for k, s in enumerate(states)
            },
            {(cfg, s): aim[k * n : (k + 1) * n] for k, s in enumerate(states)},
        )

    @staticmethod
    def _finding(cond, i, para, what, start, end, lo, hi):
        (c0, r0, g0, _), (c1, r1, g1, res1) = start[i], end[i]
        here = c1.with_(manoeuvre=f"{para} {what}")
        check = f"{para} elevator change within the remaining authority"
        bad = [(label, r) for label, r in (("start", r0), ("end", r1)) if not r.converged]
        if bad:
            return Finding.not_evaluated(
                here,
                check,
                "; ".join(
                    f"{label} trim did not converge (residual {r.residual_norm:.1e})"
                    + "".join(f"; {m.message}" for m in r.limits_exceeded)
                    for label, r in bad
                ),
            )
        d0, d1 = r0.controls["elevator"], r1.controls["elevator"]
        change = d1 - d0
        authority = (hi - d0) if change >= 0 else (d0 - lo)
        message = "; ".join(m.message for m in r1.limits_exceeded if m.control == "elevator")
        return Finding.compare(
            here,
            check,
            abs(math.degrees(change)),
            math.degrees(authority),
            at_least=False,
            unit="deg",
            reason=message,
            start_state=f"{c0.configuration}, {c0.get('thrust')}, {c0.speed_name}",
            start_elevator_deg=round(math.degrees(d0), 3),
            start_flight_path_deg=round(math.degrees(g0), 3),
            end_flight_path_deg=round(math.degrees(g1), 3),
            start_speed_m_s=round(c0.speed, 3),
            end_thrust_residual=res1,
            direction="trailing edge down" if change >= 0 else "trailing edge up",
            **{f"end_{k}": v for k, v in trim_details(r1).items()},
        )

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.145(b) elevator to trim configuration and thrust changes",
            "Elevator change between the start and end trims of each flap/thrust change against the elevator "
            "authority left at the start trim.",
            (
                "direction",
                "start_elevator_deg",
                "end_elevator_deg",
                "start_flight_path_deg",
                "end_flight_path_deg",
                "start_speed_m_s",
            ),
            plot=True,
        )


def held_trims(ctx, start, end, end_aim):
    """The end trims of a change "without re-trimming": on an airplane with a movable stabiliser the end states
    trimmed again with the stabiliser held where each start trim set it (the elevator takes the change; memoised by
    the context, so each pair is trimmed once); the end trims as they are otherwise."""
    held = held_stabilizer([s[1] for s in start])
    if held is None:
        return end
    conds = [e[0] for e in end]
    results, gamma, residual = trim_at_thrust(ctx, conds, end_aim, stabilizer=held)
    return [(c, r, float(g), float(res)) for c, r, g, res in zip(conds, results, gamma, residual)]


def force_finding(ctx, elevator, i, para, what, start, end, limit_lbf):
    """(b) control force: the elevator force (lbf) that holds the end trim with the trim device left at its start
    setting (:mod:`certkit.models.control_force`: the start trim holds zero force), against ``limit_lbf``."""
    (_, r0, _, _), (c1, r1, _, _) = start[i], end[i]
    here = c1.with_(manoeuvre=f"{para} {what}")
    check = f"{para} control force ≤ {limit_lbf:g} lbf without re-trimming"
    if not (r0.converged and r1.converged):
        return Finding.not_evaluated(
            here, check, "start or end trim did not converge (see the elevator-change finding)"
        )
    q0, a0, d0 = trim_state(ctx.aircraft, "elevator", [r0])
    q1, a1, d1 = trim_state(ctx.aircraft, "elevator", [r1])
    pull = float(-elevator.force(q1, a1, d1, trim=(d0, a0))[0] / LBF)
    return Finding.compare(
        here,
        check,
        abs(pull),
        limit_lbf,
        at_least=False,
        unit="lbf",
        direction="pull" if pull >= 0 else "push",
        pull_force_lbf=round(pull, 2),
        force_model=elevator.kind,
        start_elevator_deg=round(math.degrees(d0[0]), 3),
        end_elevator_deg=round(math.degrees(d1[0]), 3),
    )
