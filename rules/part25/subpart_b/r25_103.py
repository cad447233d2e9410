"""§25.103 Stall speed (Amdt. 25-108/25-121). The reference stall speed VSR of each configuration.

VSR is a calibrated airspeed defined by the applicant and may not be less than a 1-g stall speed.
certkit computes the 1-g stall speed from the configuration's declared trimmed 1-g CLmax and the
weight, V = √(2W / (ρ₀ S CLmax)) (EAS; equal to CAS at sea level, where the stall is evaluated),
and checks a declared ``speeds.VSR.<configuration>`` against it. The other Subpart B rules take
their VSR from :func:`reference_stall_speed`: the declared value where given (scaled with √W from
the configuration's reference weight), else the computed 1-g stall speed.
"""

from __future__ import annotations

import math

from certkit_rules.part25.support.reference_speeds import computed_stall_speed, reference_stall_speed, reference_weight

from certkit.engine.conditions import ConditionSpace, EnvelopeWeights, cg_limits_at
from certkit.engine.evidence.performance import margins_evidence
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import NOT_EVALUATED, Finding
from certkit.units import KN

AMDT = "25-121"


def _weights(ctx, configuration: str) -> list[tuple[str, float, float]]:
    """(loading name, kg, forward CG) at which ``configuration`` is used."""
    env_max = max(v.mass for v in ctx.aircraft.cg_envelope.vertices)
    if configuration == "clean":
        return [(ld.name, ld.mass, ld.x_cg) for ld in EnvelopeWeights().loadings(ctx.aircraft)]
    name, mass = reference_weight(ctx, configuration)
    fwd, _ = cg_limits_at(ctx.aircraft, min(mass, env_max))
    return [(f"{name} forward", mass, fwd)]


@rule
class StallSpeed(Rule):
    id = "25.103"
    symbol = "reference-stall-speed"
    title = "Stall speed VSR"
    amendment = AMDT
    requirement = """
        The reference stall speed VSR is a calibrated airspeed defined by the applicant; it may not be
        less than a 1-g stall speed, VCLMAX/√nZW, obtained in the (c) manoeuvre (deceleration not more
        than 1 kt/s from a trim speed between 1.13 and 1.3 VSR, engines idle, the CG giving the highest
        VSR). With a stick pusher, VSR is at least 2 kt or 2 % above the pusher speed (d).
    """
    margin = """
        Declared VSR − 1-g stall speed (m/s CAS at sea level) for each configuration at the weights where
        it is used (takeoff and clean at MTOW, clean also at every envelope weight, approach and landing at
        MLW); ≥ 0 complies. Without a declared VSR there is nothing to compare: the finding is not_evaluated
        and carries the computed 1-g stall speed, which the other Subpart B rules then use as VSR.
    """
    references = ("25.107", "25.121", "25.125", "25.143", "25.145")
    requires = ("mass.MTOW",)
    criteria = {
        "load_factor": Criterion(
            1.0, "", "14 CFR 25.103(a)", "normal load factor nZW at which the 1-g stall speed is taken"
        ),
    }
    conditions = ConditionSpace(
        configurations=("clean", "takeoff", "approach", "landing"),
        note="Weights per configuration: MTOW for takeoff, MLW for approach and landing, "
        "every envelope weight for clean; forward CG (declared CLmax is the trimmed value).",
    )
    limitations = """
        CLmax is the declared trimmed 1-g value (taken at the forward CG); the (c) deceleration manoeuvre,
        the nZW correction and the stick-pusher margin (d) are not simulated.
    """

    implementation = "partial"
    unevaluated = (
        (
            "25.103(c)",
            "the 1-g stall manoeuvre (trim at 1.13–1.3 VSR, deceleration ≤ 1 kt/s, nZW-corrected CL first "
            "maximum) is not simulated: the declared trimmed CLmax stands for it",
        ),
        (
            "25.103(d)",
            "stick-pusher margin (VSR ≥ the pusher speed + 2 kt or 2 %) not evaluated: no pusher speed in "
            "the aircraft file",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        out = []
        for cond in conditions:
            cfg = cond.configuration
            check = f"(a) VSR {cfg} ≥ 1-g stall speed"
            if ctx.clmax(cfg) is None:
                out.append(Finding.not_evaluated(cond, check, f"needs configurations.{cfg}.CLmax"))
                continue
            declared = ctx.aircraft.speeds.VSR.get(cfg)
            for name, mass, x_cg in _weights(ctx, cfg):
                v_1g = computed_stall_speed(ctx, cfg, mass) * math.sqrt(crit.load_factor)
                here = cond.with_(loading=name, mass=mass, x_cg=x_cg, altitude=0.0)
                if declared is None:
                    out.append(
                        Finding(
                            here.with_(speed=v_1g, speed_kind="CAS", speed_name="VSR"),
                            check,
                            NOT_EVALUATED,
                            value=v_1g,
                            unit="m/s",
                            reason=f"no declared speeds.VSR.{cfg} to compare with the 1-g stall speed "
                            f"({v_1g / KN:.1f} kn CAS from CLmax {ctx.clmax(cfg):g}): a VSR is a flight-test "
                            "value, and one derived from the declared CLmax would compare the model with itself; "
                            "the other rules use that computed speed as VSR",
                            details={"CLmax": ctx.clmax(cfg)},
                        )
                    )
                    continue
                vsr, source = reference_stall_speed(ctx, cfg, mass)
                out.append(
                    Finding.compare(
                        here.with_(speed=vsr, speed_kind="CAS", speed_name="VSR"),
                        check,
                        vsr,
                        v_1g,
                        at_least=True,
                        unit="m/s",
                        CLmax=ctx.clmax(cfg),
                        VSR_source=source,
                    )
                )
        return out

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.103 reference stall speeds",
            "VSR of each configuration and weight against the 1-g stall speed from the declared CLmax.",
            ("CLmax",),
        )
