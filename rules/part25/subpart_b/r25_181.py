"""§25.181 Dynamic stability, with the MIL-F-8785C Level of every rigid-body mode as a reference reading.

The modes are those of the linearised six-degree-of-freedom model about the trim of each condition
(``ctx.modes``): every CG corner × (takeoff, cruise, landing) × altitude band × three speeds from 1.13 VSR to the
configuration's maximum allowable speed. The trim is level flight, or, where the weight is beyond its level-flight
thrust ceiling at that altitude and speed, the steady descent at full thrust the airplane can hold there; each
finding says which (``flight``).
"""

from __future__ import annotations

import math

from certkit_rules.part25.support import handling_levels as hq
from certkit_rules.part25.support.stability_speeds import (
    FLAP_ALTITUDE,
    PHASES,
    SPEED_POINTS,
    by_configuration,
    flight_described,
    refine_speeds,
    steady_flight_trims,
)

from certkit.engine.conditions import Altitudes, CgCorners, ConditionSpace
from certkit.engine.evidence.stability import damping_frequency_chart, margin_matrix_evidence
from certkit.engine.registry import Criterion, ModeResponses, Rule, rule
from certkit.engine.results import Evidence, Finding
from certkit.models.dynamics.modes import load_factor_per_alpha
from certkit.units import FT, KN

MODES = ("short_period", "phugoid", "dutch_roll", "roll", "spiral")
#: how the short-period criterion reads each configuration's flight phase (MIL-F-8785C 1.5 flight-phase categories)
PHASE_READING = {
    "cruise": "B (en route: climb, cruise, descent), Level 1 ζ_sp ≥ 0.30",
    "terminal": "C (terminal: takeoff, approach, landing), Level 1 ζ_sp ≥ 0.35",
}


categories = hq.categories_of


def mode_levels(modes: dict, configuration: str, n_alpha: float | None = None) -> dict:
    """{mode: {ζ, ωn, eigenvalue, period, times to half and double, level per category, reason}} for the classical
    modes present; the short period's control anticipation parameter ω²/(n/α) ((rad/s²)/g, MIL-F-8785C 3.2.2.1.1)
    with the condition's n/α (g/rad)."""
    out = {}
    for name in MODES:
        m = modes.get(name)
        if m is None:
            continue
        q = hq.quantities(m)
        row = {
            "zeta": round(m.damping_ratio, 5),
            "wn_rad_s": round(m.natural_frequency, 5),
            "eigenvalue": [round(m.eigenvalue.real, 6), round(m.eigenvalue.imag, 6)],
            "tau_s": None if q["tau"] == float("inf") else round(float(q["tau"]), 3),
            "t_double_s": None if q["t_double"] == float("inf") else round(float(q["t_double"]), 2),
            "period_s": None if m.period is None else round(m.period, 3),
            "t_half_s": None if m.time_to_half is None else round(m.time_to_half, 3),
        }
        if name == "short_period" and n_alpha is not None and n_alpha > 0:
            row["cap"] = round(m.natural_frequency**2 / n_alpha, 5)
            row["n_alpha_g_rad"] = round(float(n_alpha), 4)
        for cat in categories(configuration):
            level, why = hq.level_of(name, m, cat, n_alpha if name == "short_period" else None)
            row[f"level_{cat}"] = level
            if why:
                row[f"level_{cat}_limited_by"] = why
        out[name] = row
    return out


@rule
class DynamicStability(Rule):
    id = "25.181"
    cost = 3  # relative evaluation time (orders work over --jobs processes)
    symbol = "dynamic-stability"
    title = "Dynamic stability"
    amendment = "25-108"
    requirement = """
        (a) Any short-period oscillation, not including combined lateral-directional oscillations, occurring between
        1.13 VSR and the maximum allowable speed appropriate to the configuration must be heavily damped with the
        primary controls free and fixed. (b) Any combined lateral-directional oscillation (Dutch roll) occurring in
        that speed range must be positively damped with controls free, and controllable with normal use of the
        primary controls without exceptional piloting skill.
    """
    margin = """
        ζ_sp − ζ_sp,min (short period, "heavily damped" read as MIL-F-8785C's Level 1 minimum of the flight phase's
        category: 0.30 for the clean configuration (category B, en route), 0.35 with flaps (category C, terminal)) and
        ζ_dr − ζ_dr,min (Dutch roll,
        "positively damped": ζ_dr > 0), dimensionless, at every condition. The MIL-F-8785C Level of every mode
        (short period, phugoid, Dutch roll, roll, spiral) is reported in the details and the evidence; it is not a
        Part 25 requirement and does not set the status.
    """
    references = ("25.171", "25.103")
    offers = (ModeResponses(MODES, level=hq.damping_level, level_margin=hq.damping_level_margin),)
    requires = ("configurations.clean.CLmax", "speeds.VMO")
    criteria = {
        "short_period_damping_min_cruise": Criterion(
            0.30,
            "",
            "MIL-F-8785C 3.2.2.1.2 Table IV, Level 1 category B minimum (" + hq.SOURCE + ")",
            "short-period damping ratio read as 'heavily damped' (§25.181(a) gives no number) in the en-route "
            "configuration: cruise, climb and descent are category B flight phases",
        ),
        "short_period_damping_min_terminal": Criterion(
            0.35,
            "",
            "MIL-F-8785C 3.2.2.1.2 Table IV, Level 1 category C minimum (" + hq.SOURCE + ")",
            "short-period damping ratio read as 'heavily damped' with flaps or gear extended: takeoff, approach and "
            "landing are category C (terminal) flight phases",
        ),
        "dutch_roll_damping_min": Criterion(
            0.0,
            "",
            "§25.181(b) 'positively damped' (verified, Amdt. 25-108; docs/regulation-notes.md)",
            "Dutch-roll damping ratio (> 0: the oscillation decays)",
        ),
        "low_speed_factor": Criterion(
            1.13, "", "§25.181(a),(b): from 1.13 VSR", "low end of the speed range, multiple of VSR"
        ),
        "flap_altitude_max": FLAP_ALTITUDE,
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        configurations=tuple(PHASES.values()),
        altitudes=Altitudes((0.0, 20000 * FT, 37000 * FT)),
        extra=(("speed_point", SPEED_POINTS),),
        note="Speeds in CAS, level flight at the power for level flight (beyond the level-flight thrust "
        "ceiling, the steady descent at full thrust); flaps only up to the flap altitude limit.",
    )
    implementation = "partial"
    limitations = """
        Controls-fixed modes only: no hinge-moment or control-system model, so 'controls free' (§25.181(a)(1), (b)) is
        read with the controls fixed. Rigid airplane. Controllability of the Dutch roll by normal use of the
        controls is not assessed. The MIL-F-8785C numbers are unverified secondary values (handling_levels.py).
        The airplane model's lateral derivatives are the vortex lattice's at zero angle of attack: Cl_β and Cn_p do not
        grow with the lift coefficient (at approach lift the lattice's own are within 2 % of the 747's, the model's
        Cl_β is 0.55 of it and its Cn_p about zero), which makes the Dutch roll's damping optimistic at high lift;
        no stability augmentation (yaw damper) is modelled (docs/baseline-sources.md §16).
    """

    unevaluated = (
        ("25.181(a)", "the short period with the primary controls free is not evaluated (controls fixed only)"),
        (
            "25.181(b)",
            "the Dutch roll with controls free, and its controllability by normal use of the controls, are"
            " not evaluated (controls fixed only)",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        refined, out = refine_speeds(ctx, conditions, crit.flap_altitude_max, crit.low_speed_factor, "(a), (b) modes")
        for config, idx in by_configuration(refined).items():
            conds = [refined[i] for i in idx]
            trims, stops = steady_flight_trims(ctx, conds)
            modes_of = dict(zip(range(len(conds)), ctx.modes(conds)))
            n_alpha = dict(enumerate(load_factor_per_alpha(ctx.linearization(conds))))
            held = [i for i, s in enumerate(stops) if s is not None]
            if held:  # beyond the level-flight ceiling: the modes of the steady descent (climb) at the throttle stop
                held_conds, held_throttle = [conds[i] for i in held], [stops[i] for i in held]
                modes_of.update(zip(held, ctx.modes(held_conds, throttle=held_throttle)))
                n_alpha.update(zip(held, load_factor_per_alpha(ctx.linearization(held_conds, throttle=held_throttle))))
            for i, cond in enumerate(conds):
                modes, res = modes_of[i], trims[i]
                flight = flight_described(res, stops[i])
                path = {} if stops[i] is None else {"flight_path_deg": math.degrees(res.gamma)}
                if modes is None:
                    out.append(
                        Finding.not_evaluated(
                            cond,
                            "(a), (b) modes",
                            f"trim in {flight} did not converge "
                            f"(|r| = {res.residual_norm:.1e}) " + "; ".join(e.message for e in res.limits_exceeded),
                        )
                    )
                    continue
                levels = mode_levels(modes, config, float(n_alpha[i]))
                phase = "cruise" if hq.CATEGORY.get(config, "B") == "B" else "terminal"
                for name, check, key in (
                    ("short_period", "(a) short period heavily damped", f"short_period_damping_min_{phase}"),
                    ("dutch_roll", "(b) Dutch roll positively damped", "dutch_roll_damping_min"),
                ):
                    m = modes.get(name)
                    if m is None:
                        out.append(
                            Finding.not_evaluated(
                                cond,
                                check,
                                f"no {name.replace('_', ' ')} mode identified among the eigenvalues",
                                modes=levels,
                                flight=flight,
                                **path,
                            )
                        )
                        continue
                    out.append(
                        Finding.compare(
                            cond,
                            check,
                            m.damping_ratio,
                            crit[key],
                            at_least=True,
                            unit="ζ",
                            natural_frequency_rad_s=m.natural_frequency,
                            modes=levels,
                            flight=flight,
                            **path,
                            **({"category": PHASE_READING[phase]} if name == "short_period" else {}),
                        )
                    )
        return out

    def evidence(self, ctx, findings, crit):
        points, worst = [], {}
        for f in findings:
            if not f.check.startswith("(a)") or "modes" not in f.details:
                continue
            c = f.condition
            cat = categories(c.configuration)[-1]
            for mode, row in f.details["modes"].items():
                level = row[f"level_{cat}"]
                points.append({"mode": mode, "zeta": row["zeta"], "wn": row["wn_rad_s"], "level": level})
                key = (c.loading, c.configuration, mode)
                if key not in worst or (level, -row["zeta"]) > (worst[key]["level"], -worst[key]["zeta"]):
                    worst[key] = {
                        "corner": c.loading,
                        "configuration": c.configuration,
                        "mode": mode,
                        "category": cat,
                        "level": level,
                        "zeta": row["zeta"],
                        "wn_rad_s": row["wn_rad_s"],
                        "tau_s": row["tau_s"],
                        "t_double_s": row["t_double_s"],
                        "altitude_ft": round(c.altitude / FT),
                        "speed_kn_cas": round(c.speed / KN, 1),
                        "limited_by": row.get(f"level_{cat}_limited_by", ""),
                    }
        boundaries = [
            ("SP L1 A/C 0.35", 0.35, "short_period"),
            ("SP L1 B 0.30", 0.30, "short_period"),
            ("SP L3 0.15", 0.15, "short_period"),
            ("DR L1 A 0.19", 0.19, "dutch_roll"),
            ("DR L1 B/C 0.08", 0.08, "dutch_roll"),
            ("DR L2 0.02", 0.02, "dutch_roll"),
            ("PH L1 0.04", 0.04, "phugoid"),
        ]
        out = []
        if points:
            out.append(
                Evidence(
                    "Modes over CG corners × configurations × speeds × altitudes, with MIL-F-8785C levels",
                    damping_frequency_chart(points, boundaries),
                    caption=(
                        "Damping ratio and natural frequency of the oscillatory modes, coloured by MIL-F-8785C Class "
                        "III "
                        "Level (category C with flaps, B clean); dotted lines are the damping boundaries "
                        "(Table IV short period, Table VI Dutch roll, 3.2.1.2 phugoid; unverified values). "
                        "The table lists, per corner, configuration and mode, the worst condition."
                    ),
                    table=sorted(worst.values(), key=lambda r: (r["mode"], r["configuration"], r["corner"])),
                )
            )
            out.append(
                Evidence("MIL-F-8785C level boundaries used (Class III)", caption=hq.SOURCE, table=hq.table_rows())
            )
        return out + margin_matrix_evidence(
            findings, "§25.181 damping margins (normalised) over CG corners × configurations"
        )
