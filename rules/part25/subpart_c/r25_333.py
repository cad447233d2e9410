"""§25.333 Flight maneuvering envelope (Amdt. 25-86).

The strength requirements must be met at each combination of airspeed and load factor on and
within the representative maneuvering envelope (V–n diagram) of (b). This rule builds the envelope
per weight and altitude — stall lines from ±C_Nmax, corners A (VA-point, n₊), D (VD, n₊),
E (VD, 0), F (VC, n₋), H (negative stall, n₋) — checks that the declared speeds close it, and draws
it. The strength check on the envelope belongs to the loads rules (§25.331, §25.341 …).
"""

from __future__ import annotations

from certkit_rules.part25.support.envelope_criteria import CN_OVER_CL
from certkit_rules.part25.support.reference_speeds import declared_eas

from certkit.engine.conditions import ConditionSpace, EnvelopeAltitudes, EnvelopeWeights
from certkit.engine.evidence import Axis, Chart, Limit, Panel, Point, Series
from certkit.engine.registry import Rule, rule
from certkit.engine.results import Evidence, Finding
from certkit.models.loads.vn_envelope import envelope


@rule
class FlightManeuveringEnvelope(Rule):
    id = "25.333"
    symbol = "flight-maneuvering-envelope"
    title = "Flight maneuvering envelope (V–n diagram)"
    amendment = "25-86"
    requirement = """
        The strength requirements must be met at each combination of airspeed and load factor on and within
        the boundaries of the representative manoeuvring envelope: the stall lines of ±C_Nmax, the positive
        limit load factor from A to D, VD from D to E, the negative limit load factor from F (VC) back to the
        negative stall line at H, and the line E–F.
    """
    margin = """
        For each weight and altitude, three closure checks in m/s EAS: VA − V_A (the declared VA is at or
        above where the +C_Nmax line reaches n₊, or VC where that lies beyond it, §25.335(c)(3)), VC − V_H (the
        −C_Nmax line reaches n₋ before VC) and VD − VC (the envelope has a positive width). ≥ 0 complies.
    """
    references = ("25.335(c)", "25.337", "25.331", "25.1501")
    requires = (
        "speeds.VA",
        "speeds.VC",
        "speeds.VD",
        "configurations.clean.CLmax",
        "configurations.clean.CLmin",
        "envelope.limit_load_factors",
    )
    criteria = dict(CN_OVER_CL)
    conditions = ConditionSpace(loading=EnvelopeWeights(), altitudes=EnvelopeAltitudes())
    limitations = (
        "Strength on the envelope is checked by the loads rules; this rule defines the envelope and "
        "checks that the declared speeds close it."
    )

    implementation = "partial"
    unevaluated = (
        (
            "25.333(a)",
            "strength at each point of the envelope is not checked by this rule (the loads rules check "
            "their own points); the flaps-extended envelope of §25.345 is not drawn",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        out = []
        for cond in conditions:
            env = envelope(ctx, cond.mass, cond.altitude, crit.cn_over_cl)
            corners = {k: [round(v, 3), round(n, 3)] for k, (v, n) in env.corners().items()}
            va = declared_eas(ctx, "VA", cond.altitude)
            capped = {}
            if env.v_a > env.v_c:  # §25.335(c)(3): VA need not exceed VC (a C_N,max falling with Mach at altitude)
                capped = {"stall_line_at_n_plus": "beyond VC at this altitude: VA need not exceed VC (§25.335(c)(3))"}
            out.append(
                Finding.compare(
                    cond,
                    "A: +C_Nmax line reaches n₊ at or below VA",
                    va,
                    min(env.v_a, env.v_c),
                    at_least=True,
                    unit="m/s",
                    corners=corners,
                    **capped,
                )
            )
            out.append(
                Finding.compare(
                    cond, "H: −C_Nmax line reaches n₋ at or below VC", env.v_c, env.v_h, at_least=True, unit="m/s"
                )
            )
            out.append(Finding.compare(cond, "D–E: VD above VC", env.v_d, env.v_c, at_least=True, unit="m/s"))
        return out

    def evidence(self, ctx, findings, crit):
        conds = sorted(
            {f.condition for f in findings if f.condition.mass is not None}, key=lambda c: (c.altitude, c.mass)
        )
        if not conds:
            return []
        h0 = min(c.altitude for c in conds)
        sea = [c for c in conds if c.altitude == h0]
        picks = [sea[0], sea[-1]] if len(sea) > 1 else sea
        envs = [(c.loading or f"{c.mass:.0f} kg", envelope(ctx, c.mass, c.altitude, crit.cn_over_cl)) for c in picks]
        speeds = {
            name: declared_eas(ctx, name, h0) for name in ("VA", "VB", "VC", "VD") if getattr(ctx.aircraft.speeds, name)
        }
        series, corners = [], []
        for k, (label, env) in enumerate(envs):
            v, n = env.outline()
            series.append(Series(label, v, n, colour=k))
            corners += [Point(vc, nc, name, kind="corner", colour=k) for name, (vc, nc) in env.corners().items()]
        lf = ctx.aircraft.envelope.limit_load_factors
        limits = [Limit(value, name, axis="x", kind="reference") for name, value in speeds.items()] + [
            Limit(lf.positive, f"n = {lf.positive:g}"),
            Limit(lf.negative, f"n = {lf.negative:g}"),
        ]
        chart = Chart(
            Axis("equivalent airspeed", "m/s", "kn"), [Panel(Axis("load factor n", "g"), series, limits, corners)]
        )
        return [
            Evidence(
                "V–n manoeuvring envelope, lightest and heaviest weight, lowest altitude (speeds in kn EAS)",
                chart,
                "Stall lines from ±C_Nmax; corners A, D, E, F, H; declared speeds dashed; limit "
                "manoeuvring load factors (§25.337) dashed black.",
            )
        ]
