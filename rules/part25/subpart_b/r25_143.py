"""§25.143(h) Controllability and manoeuvrability: manoeuvring capability in coordinated turns.

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
directions. ``kind="oei"`` is not used: it trims *straight* flight at a bank (|φ| ≤ 5°, §25.149), which at
30° needs a sideslip of some 36°. Where the table gives a thrust rather than a path, the turn is trimmed at
the flight-path angle that thrust gives (:func:`certkit_rules.part25.support.thrust_trims.trim_at_thrust`, the energy
relation sin γ = (T − D)/W of
Anderson, *Aircraft Performance and Design*, 1999, eq. 5.12, iterated on the thrust the trim needs).
The elevator, aileron and rudder of each trim are reported against their design limits.
"""

from __future__ import annotations

import math

import numpy as np
from certkit_rules.part25.support.climb_checks import CGS
from certkit_rules.part25.support.control_checks import control_findings
from certkit_rules.part25.support.reference_speeds import declared_cas, stall_warning_cl
from certkit_rules.part25.support.thrust_trims import critical_engine, operating_thrust, trim_at_thrust
from certkit_rules.part25.support.turns import STEEPEST_PATH, least_lift_coefficient, turn_details

from certkit.engine.conditions import ConditionSpace, DesignWeight
from certkit.engine.evidence.performance import margins_evidence
from certkit.engine.registry import ControlCase, ControlResponses, Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.dynamics.trim import held_stabilizer
from certkit.models.flight import control_limits, stabilizer_trim
from certkit.units import FT, KN

CASES = ("takeoff V2", "takeoff V2+XX", "en route VFTO", "landing VREF")
#: each case's control deflections as design responses (``control.25.143(h).<name>.<control>``), named after the
#: table's row: configuration, engines, speed and bank
CASE_RESPONSES = {
    "takeoff V2": "takeoff OEI V2 30deg",
    "takeoff V2+XX": "takeoff AEO V2+XX 40deg",
    "en route VFTO": "en route OEI VFTO 40deg",
    "landing VREF": "landing AEO VREF 40deg",
}
_UNVERIFIED = (
    "14 CFR 25.143(h) table (rows verified, GPO print 1-1-14 p. 385; footnotes not read, 'WAT-limited' per "
    "EASA AMC 25.143(h); docs/regulation-notes.md)"
)


def wat_limited_thrust(ctx, conds, gradient: float, fraction: float, inoperative: str):
    """ "Asymmetric WAT-limited thrust" (§25.143(h) footnote, read with EASA AMC 25.143(h)): the operating engine's
    thrust that gives exactly the minimum §25.121 gradient in straight flight at zero sideslip with the critical
    engine out, capped at the thrust available (``fraction`` of takeoff thrust). Returns (thrust N, capped)."""
    available = operating_thrust(ctx, conds, 1.0, fraction, inoperative)
    batch = ctx.trim(conds, kind="sideslip", beta=0.0, gamma=math.atan(gradient), inoperative=inoperative)
    live = [e.name for e in ctx.aircraft.propulsion.engines if e.name != inoperative]
    needed = np.array([sum(r.thrust[e] for e in live) if r.converged else np.inf for r in batch.results])
    return np.minimum(needed, available), needed >= available


@rule
class ManeuveringCapability(Rule):
    id = "25.143(h)"
    offers = (ControlResponses(tuple(ControlCase(name, f"(h) {case} ") for case, name in CASE_RESPONSES.items())),)
    cost = 2  # relative evaluation time (orders work over --jobs processes)
    symbol = "maneuvering-capability"
    title = "Controllability: manoeuvring capability in coordinated turns"
    amendment = "25-140"  # (h) came with 25-108; the section was last amended by 25-140 (2014)
    requirement = """
        (Table rows verified against the GPO print; footnotes not read.) The manoeuvring capabilities in a
        constant-speed coordinated turn at
        forward CG must be free of stall warning or other characteristics that might interfere with normal
        manoeuvring: takeoff configuration, V2, 30° bank, asymmetric WAT-limited thrust; takeoff, V2 + XX (the
        all-engines initial-climb speed), 40°, all-engines climb thrust; en route, VFTO, 40°, asymmetric
        WAT-limited thrust; landing, VREF, 40°, symmetric thrust for a −3° flight path. certkit checks that
        each turn can be trimmed with the elevator, aileron and rudder within their design limits, at the
        forward, reference and aft CG, and that the lift coefficient it needs stays below the stall-warning onset
        (the declared one, or the latest §25.207(c) allows).
    """
    margin = """Each trim control's design limit on the side it is deflected − |deflection| (deg), for every
        case, CG and turn direction; a control beyond its limit fails with the trim's message. Stall warning: the
        warning-onset 1-g lift coefficient − the turn's CL = n W/(q S) (≥ 0: free of warning)."""
    references = ("25.107", "25.121", "25.125", "25.147")
    requires = ("mass.MTOW", "configurations.takeoff")
    criteria = {
        "bank_v2_deg": Criterion(
            30.0, "deg", _UNVERIFIED, "bank of the coordinated turn at V2, takeoff, critical engine inoperative"
        ),
        "bank_deg": Criterion(40.0, "deg", _UNVERIFIED, "bank at V2 + XX, at VFTO and at VREF"),
        "v2_increment_kt": Criterion(
            10.0,
            "kt",
            _UNVERIFIED + "; XX is the all-engines initial-climb speed, not stated in the notes: V2 + 10 kt "
            "assumed, override with the approved speed",
            "XX of V2 + XX (CAS)",
        ),
        "landing_path_deg": Criterion(-3.0, "deg", _UNVERIFIED, "flight-path angle of the landing-configuration turn"),
        "wat_gradient_takeoff": Criterion(
            0.024,
            "",
            "14 CFR 25.121(b) (two engines), the WAT limit of the V2 case",
            "straight-flight climb gradient the asymmetric WAT-limited thrust gives at V2",
        ),
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
    conditions = ConditionSpace(
        extra=(("case", CASES),),
        note="MTOW (takeoff and en-route cases) or MLW (landing case) at the forward, reference and aft CG; sea level "
        "(and 1500 ft en route); turns toward and away from the inoperative (critical) engine for the asymmetric cases",
    )
    implementation = "partial"
    limitations = """
        The footnotes of the (h) table were not read. Without a declared stall-warning onset the warning is taken at
        the latest speed §25.207(c) allows (VSR + the greater of 5 kn and 5 %, the stall identified at VSR), which
        is the most favourable reading for the turns; other characteristics that might interfere with normal
        manoeuvring (buffet) are not modelled. "WAT-limited" is read as MTOW at
        sea level (and 1500 ft en route) with the operating engine's thrust set so that straight flight climbs at
        exactly the §25.121(b) (V2) or §25.121(c) (VFTO) minimum gradient (at most takeoff or maximum continuous
        thrust). A movable stabiliser is trimmed in wings-level flight at the
        case's speed and thrust and held; the elevator pulls into the turn. Without one the stabiliser is fixed at its
        declared incidence and the elevator carries the whole trim. A coordinated turn is flown at zero sideslip.
    """

    unevaluated = (
        (
            "25.143(h)",
            "characteristics other than stall warning that might interfere with normal manoeuvring (buffet "
            "onset) are not evaluated",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        ac = ctx.aircraft
        limits = control_limits(ac)
        dead = critical_engine(ctx)
        dead_y = next(e.position.y for e in ac.propulsion.engines if e.name == dead)
        toward_dead = -1.0 if dead_y < 0 else 1.0  # positive bank is right wing down
        specs = {
            "takeoff V2": dict(
                config="takeoff",
                weight="MTOW",
                speed="V2",
                bank=crit.bank_v2_deg,
                oei=True,
                fraction=1.0,
                wat=crit.wat_gradient_takeoff,
                thrust="asymmetric WAT-limited thrust",
            ),
            "takeoff V2+XX": dict(
                config="takeoff",
                weight="MTOW",
                speed="V2",
                increment=crit.v2_increment_kt,
                bank=crit.bank_deg,
                oei=False,
                fraction=1.0,
                thrust="takeoff thrust, all engines",
            ),
            "en route VFTO": dict(
                config="clean",
                weight="MTOW",
                speed="VFTO",
                bank=crit.bank_deg,
                oei=True,
                fraction=crit.mct_over_takeoff_thrust,
                altitudes=(0.0, crit.enroute_altitude_ft * FT),
                wat=crit.wat_gradient_enroute,
                thrust="asymmetric WAT-limited thrust (at most MCT)",
            ),
            "landing VREF": dict(
                config="landing",
                weight="MLW",
                speed="VREF",
                bank=crit.bank_deg,
                oei=False,
                fraction=None,
                thrust=f"all engines, for a {crit.landing_path_deg:g}° path",
            ),
        }
        out = []
        for cond in conditions:
            spec = specs[cond.get("case")]
            out += self._case(ctx, cond, spec, limits, dead, toward_dead, crit)
        return out

    def _case(self, ctx, cond, spec, limits, dead, toward_dead, crit):
        ac = ctx.aircraft
        check = f"(h) {cond.get('case')}"
        missing = [
            p
            for p, ok in (
                (f"configurations.{spec['config']}", spec["config"] in ac.configurations),
                (f"speeds.{spec['speed']}", getattr(ac.speeds, spec["speed"]) is not None),
                (f"mass.{spec['weight']}", getattr(ac.mass, spec["weight"]) is not None),
            )
            if not ok
        ]
        if missing:
            return [Finding.not_evaluated(cond, f"{check} trim", "needs " + ", ".join(missing))]
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
        banks = np.array(banks)
        inop = dead if spec["oei"] else None
        # a movable stabiliser stays where the wings-level trim at the same speed and thrust set it; the elevator
        # pulls into the turn (held_stabilizer: None without one)
        movable = stabilizer_trim(ac) is not None
        if spec["fraction"] is None:
            gamma = np.full(len(conds), math.radians(crit.landing_path_deg))
            held = held_stabilizer(ctx.trim(conds, kind="straight", gamma=gamma).results) if movable else None
            results = ctx.trim(conds, kind="turn", bank=banks, gamma=gamma, stabilizer=held).results
            residual = np.zeros(len(conds))
        else:
            capped = np.zeros(len(conds), dtype=bool)
            if "wat" in spec:
                aim, capped = wat_limited_thrust(ctx, conds, spec["wat"], spec["fraction"], inop)
            else:
                aim = operating_thrust(ctx, conds, 1.0, spec["fraction"], inop)
            held = held_stabilizer(trim_at_thrust(ctx, conds, aim, inoperative=inop)[0]) if movable else None
            results, gamma, residual = trim_at_thrust(
                ctx, conds, aim, kind="turn", bank=banks, inoperative=inop, stabilizer=held
            )
        out = []
        for i, c in enumerate(conds):
            r = results[i]
            details = dict(
                turn_details(ctx, c, r, float(gamma[i]), float(banks[i])), thrust_residual=float(residual[i])
            )
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
                        f"(residual {r.residual_norm:.1e}){lift}"
                        + "".join(f"; {m.message}" for m in r.limits_exceeded),
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

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.143(h) manoeuvring capability",
            "Coordinated-turn trims: controls against their design limits.",
            (
                "bank_deg",
                "load_factor",
                "CL_over_CLmax",
                "flight_path_deg",
                "elevator_deg",
                "aileron_deg",
                "rudder_deg",
            ),
        )
