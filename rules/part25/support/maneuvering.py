"""The manoeuvring capability of §25.143(h) in constant-speed coordinated turns, shared by §25.143(h) (every row of
its table) and §25.107(g)(2) (VFTO gives the en-route row's capability) (regulation content, no rule here).

The paragraph's table (docs/regulation-notes.md marks it unverified — from memory, corroborated only by
EASA AMC 25.143(h), which names V2, V2 + XX, VFTO, VREF and "WAT-limited"):

    configuration   speed     bank in a coordinated turn   thrust
    takeoff         V2        30°                          asymmetric, WAT-limited
    takeoff         V2 + XX   40°                          all-engines-operating climb (takeoff thrust)
    en route        VFTO      40°                          asymmetric, WAT-limited
    landing         VREF      40°                          symmetric, for a −3° flight path

Each case is trimmed as a steady coordinated turn (``ctx.trim(kind="turn")``: zero sideslip, the bank
given, turn rate, α and the three controls solved for) — with the critical engine inoperative for the
asymmetric cases (the windmilling engine and the asymmetric thrust are in the flight model), in both
directions, at MTOW (MLW landing) and the forward, reference and aft CG. ``kind="oei"`` is not used: it trims
*straight* flight at a bank (|φ| ≤ 5°, §25.149), which at 30° needs a sideslip of some 36°. Where the table gives a
thrust rather than a path, the turn is trimmed at the flight-path angle that thrust gives
(:func:`certkit_rules.part25.support.thrust_trims.trim_at_thrust`, the energy relation sin γ = (T − D)/W of
Anderson, *Aircraft Performance and Design*, 1999, eq. 5.12, iterated on the thrust the trim needs). A case's
trims are memoised, so the two rules (run in one process) trim them once; each turn's findings are its controls
against their design limits and its lift coefficient against the stall-warning onset.
"""

from __future__ import annotations

import math

import numpy as np
from certkit_rules.part25.support.climb_checks import CGS
from certkit_rules.part25.support.control_checks import control_findings
from certkit_rules.part25.support.reference_speeds import declared_cas, stall_warning_cl
from certkit_rules.part25.support.thrust_trims import critical_engine, operating_thrust, trim_at_thrust
from certkit_rules.part25.support.turns import STEEPEST_PATH, least_lift_coefficient, turn_details

from certkit.engine.conditions import DesignWeight
from certkit.engine.registry import Criterion
from certkit.engine.results import Finding
from certkit.models.dynamics.trim import held_stabilizer
from certkit.models.flight import control_limits, stabilizer_trim
from certkit.units import FT, KN

CASES = ("takeoff V2", "takeoff V2+XX", "en route VFTO", "landing VREF")
UNVERIFIED = (
    "14 CFR 25.143(h) table (rows verified, GPO print 1-1-14 p. 385; footnotes not read, 'WAT-limited' per "
    "EASA AMC 25.143(h); docs/regulation-notes.md)"
)

#: the criteria of the en-route VFTO row (§25.107(g)(2) uses these alone)
EN_ROUTE_CRITERIA = {
    "bank_deg": Criterion(40.0, "deg", UNVERIFIED, "bank at V2 + XX, at VFTO and at VREF"),
    "wat_gradient_enroute": Criterion(
        0.012,
        "",
        "14 CFR 25.121(c) (two engines), the WAT limit of the VFTO case",
        "straight-flight climb gradient the asymmetric WAT-limited thrust gives at VFTO",
    ),
    "enroute_altitude_ft": Criterion(
        1500.0,
        "ft",
        "14 CFR 25.111 end of the takeoff path (25.121(c)), as for VFTO",
        "second altitude of the en-route case (also at sea level)",
    ),
    "mct_over_takeoff_thrust": Criterion(
        0.96,
        "",
        "FAA TCDS E00049EN, GE90-90B: maximum continuous 90,580 lbf / takeoff 94,000 lbf at SL static",
        "maximum continuous (en route, WAT-limited) over takeoff thrust of the engine model",
    ),
}

#: the criteria of every row of the table
MANEUVERING_CRITERIA = {
    "bank_v2_deg": Criterion(
        30.0, "deg", UNVERIFIED, "bank of the coordinated turn at V2, takeoff, critical engine inoperative"
    ),
    "bank_deg": EN_ROUTE_CRITERIA["bank_deg"],
    "v2_increment_kt": Criterion(
        10.0,
        "kt",
        UNVERIFIED + "; XX is the all-engines initial-climb speed, not stated in the notes: V2 + 10 kt "
        "assumed, override with the approved speed",
        "XX of V2 + XX (CAS)",
    ),
    "landing_path_deg": Criterion(-3.0, "deg", UNVERIFIED, "flight-path angle of the landing-configuration turn"),
    "wat_gradient_takeoff": Criterion(
        0.024,
        "",
        "14 CFR 25.121(b) (two engines), the WAT limit of the V2 case",
        "straight-flight climb gradient the asymmetric WAT-limited thrust gives at V2",
    ),
    **{k: v for k, v in EN_ROUTE_CRITERIA.items() if k != "bank_deg"},
}


def wat_limited_thrust(ctx, conds, gradient: float, fraction: float, inoperative: str):
    """ "Asymmetric WAT-limited thrust" (§25.143(h) footnote, read with EASA AMC 25.143(h)): the operating engine's
    thrust that gives exactly the minimum §25.121 gradient in straight flight at zero sideslip with the critical
    engine out, capped at the thrust available (``fraction`` of takeoff thrust). Returns (thrust N, capped)."""
    available = operating_thrust(ctx, conds, 1.0, fraction, inoperative)
    batch = ctx.trim(conds, kind="sideslip", beta=0.0, gamma=math.atan(gradient), inoperative=inoperative)
    live = [e.name for e in ctx.aircraft.propulsion.engines if e.name != inoperative]
    needed = np.array([sum(r.thrust[e] for e in live) if r.converged else np.inf for r in batch.results])
    return np.minimum(needed, available), needed >= available


def case_spec(case: str, crit) -> dict:
    """The table's row ``case``: configuration, weight, speed, bank, engines and thrust (``crit`` holds the row's
    :data:`MANEUVERING_CRITERIA`)."""
    if case == "takeoff V2":
        return dict(
            config="takeoff",
            weight="MTOW",
            speed="V2",
            bank=crit.bank_v2_deg,
            oei=True,
            fraction=1.0,
            wat=crit.wat_gradient_takeoff,
            thrust="asymmetric WAT-limited thrust",
        )
    if case == "takeoff V2+XX":
        return dict(
            config="takeoff",
            weight="MTOW",
            speed="V2",
            increment=crit.v2_increment_kt,
            bank=crit.bank_deg,
            oei=False,
            fraction=1.0,
            thrust="takeoff thrust, all engines",
        )
    if case == "en route VFTO":
        return dict(
            config="clean",
            weight="MTOW",
            speed="VFTO",
            bank=crit.bank_deg,
            oei=True,
            fraction=crit.mct_over_takeoff_thrust,
            altitudes=(0.0, crit.enroute_altitude_ft * FT),
            wat=crit.wat_gradient_enroute,
            thrust="asymmetric WAT-limited thrust (at most MCT)",
        )
    if case == "landing VREF":
        return dict(
            config="landing",
            weight="MLW",
            speed="VREF",
            bank=crit.bank_deg,
            oei=False,
            fraction=None,
            thrust=f"all engines, for a {crit.landing_path_deg:g}° path",
            path=crit.landing_path_deg,
        )
    raise ValueError(f"no §25.143(h) case {case!r}")


def _turns(ctx, cond, spec):
    """The case's turn conditions (loadings × altitudes × directions), banks (rad) and trims, memoised."""
    ac = ctx.aircraft
    dead = critical_engine(ctx)
    dead_y = next(e.position.y for e in ac.propulsion.engines if e.name == dead)
    toward_dead = -1.0 if dead_y < 0 else 1.0  # positive bank is right wing down
    v = declared_cas(ctx, spec["speed"]) + spec.get("increment", 0.0) * KN
    name = spec["speed"] + (f" + {spec['increment']:g} kt" if spec.get("increment") else "")
    bank = math.radians(spec["bank"])
    directions = (
        (("toward the operating engine", -toward_dead), ("toward the inoperative engine", toward_dead))
        if spec["oei"]
        else (("right", 1.0),)
    )
    conds, banks = [], []
    for ld in DesignWeight(spec["weight"], CGS).loadings(ac):
        for h in spec.get("altitudes", (0.0,)):
            for label, sign in directions:
                conds.append(
                    cond.with_(
                        loading=ld.name,
                        mass=ld.mass,
                        x_cg=ld.x_cg,
                        configuration=spec["config"],
                        altitude=h,
                        speed=v,
                        speed_kind="CAS",
                        speed_name=name,
                        thrust=(f"critical engine ({dead}) inoperative, " if spec["oei"] else "") + spec["thrust"],
                        bank_deg=spec["bank"],
                        turn=label,
                    )
                )
                banks.append(sign * bank)
    banks_arr = np.array(banks)

    def compute():
        inop = dead if spec["oei"] else None
        # a movable stabiliser stays where the wings-level trim at the same speed and thrust set it; the elevator
        # pulls into the turn (held_stabilizer: None without one)
        movable = stabilizer_trim(ac) is not None
        capped = np.zeros(len(conds), dtype=bool)
        if spec["fraction"] is None:
            gamma = np.full(len(conds), math.radians(spec["path"]))
            held = held_stabilizer(ctx.trim(conds, kind="straight", gamma=gamma).results) if movable else None
            results = ctx.trim(conds, kind="turn", bank=banks_arr, gamma=gamma, stabilizer=held).results
            residual = np.zeros(len(conds))
        else:
            if "wat" in spec:
                aim, capped = wat_limited_thrust(ctx, conds, spec["wat"], spec["fraction"], inop)
            else:
                aim = operating_thrust(ctx, conds, 1.0, spec["fraction"], inop)
            held = held_stabilizer(trim_at_thrust(ctx, conds, aim, inoperative=inop)[0]) if movable else None
            results, gamma, residual = trim_at_thrust(
                ctx, conds, aim, kind="turn", bank=banks_arr, inoperative=inop, stabilizer=held
            )
        return results, gamma, residual, capped

    key = (
        "coordinated turns",
        tuple(sorted((k, v if not isinstance(v, tuple) else tuple(v)) for k, v in spec.items())),
        tuple((c.mass, c.x_cg, c.altitude) for c in conds),
        tuple(np.round(banks_arr, 9)),
    )
    return conds, banks_arr, ctx.memo(key, compute)


def missing_for(ctx, spec) -> list[str]:
    """What the aircraft file lacks for the case (configuration, speed, weight)."""
    ac = ctx.aircraft
    return [
        p
        for p, ok in (
            (f"configurations.{spec['config']}", spec["config"] in ac.configurations),
            (f"speeds.{spec['speed']}", getattr(ac.speeds, spec["speed"]) is not None),
            (f"mass.{spec['weight']}", getattr(ac.mass, spec["weight"]) is not None),
        )
        if not ok
    ]


def turn_findings(ctx, cond, spec, check: str) -> list[Finding]:
    """The case's findings, each named ``check`` + what it judges: every turn's trim controls against their design
    limits and its lift coefficient against the stall-warning onset (a turn that cannot be trimmed: not evaluated,
    and failing on the stall warning where the least lift any such turn needs is already beyond it)."""
    missing = missing_for(ctx, spec)
    if missing:
        return [Finding.not_evaluated(cond, f"{check} trim", "needs " + ", ".join(missing))]
    limits = control_limits(ctx.aircraft)
    conds, banks, (results, gamma, residual, capped) = _turns(ctx, cond, spec)
    out = []
    for i, c in enumerate(conds):
        r = results[i]
        details = dict(turn_details(ctx, c, r, float(gamma[i]), float(banks[i])), thrust_residual=float(residual[i]))
        if "wat" in spec:
            details["wat_thrust_capped_at_available"] = bool(capped[i])
        cl_sw, basis = stall_warning_cl(ctx, c.configuration, c.mass)
        if not r.converged:
            lift = f"; the turn needs n = {details['load_factor']:.3f}, CL = {details['CL']:.2f}" + (
                f" ({details['CL_over_CLmax']:.0%} of CLmax: the model's lift near stall may not hold it)"
                if "CL_over_CLmax" in details
                else ""
            )
            out.append(
                Finding.not_evaluated(
                    c,
                    f"{check} trim",
                    f"coordinated-turn trim did not converge "
                    f"(residual {r.residual_norm:.1e}){lift}" + "".join(f"; {m.message}" for m in r.limits_exceeded),
                    **details,
                )
            )
            # the least lift the turn needs on any path: beyond the stall warning, the turn fails whatever the
            # trim would have found (the controls of a turn that cannot be flown stay unevaluated)
            least = least_lift_coefficient(ctx, c, float(banks[i]))
            if least > cl_sw:
                out.append(
                    Finding.compare(
                        c,
                        f"{check} free of stall warning",
                        least,
                        cl_sw,
                        at_least=False,
                        unit="C_L",
                        reason=f"the turn needs at least CL {least:.3f} (on a path as steep as "
                        f"{math.degrees(STEEPEST_PATH):.0f}°), beyond the stall-warning CL: no steady turn at this "
                        "speed and bank stays free of it",
                        stall_warning_CL=round(cl_sw, 4),
                        stall_warning_basis=basis,
                        **details,
                    )
                )
            continue
        for f in control_findings(c, check, r, limits):
            f.details.update(details)
            out.append(f)
        out.append(
            Finding.compare(
                c,
                f"{check} free of stall warning",
                details["CL"],
                cl_sw,
                at_least=False,
                unit="C_L",
                stall_warning_CL=round(cl_sw, 4),
                stall_warning_basis=basis,
                **details,
            )
        )
    return out
