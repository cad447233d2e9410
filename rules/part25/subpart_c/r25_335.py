"""§25.335 Design airspeeds (Amdt. 25-91). The selected design airspeeds are equivalent airspeeds.

One rule per sub-paragraph, each over its own conditions:
(a) VC ≥ VB + 1.32 U_ref; (b) VC/MC ≤ 0.8 VD/MD, or the Mach margin; (c) VA ≥ VS1·√n;
(d) VB ≥ VS1·√(n_g) with the gust load factor of the paragraph's formula.
"""

from __future__ import annotations

import numpy as np
from certkit_rules.part25.support.envelope_criteria import CN_OVER_CL
from certkit_rules.part25.support.gust import SOURCE as GUST_SOURCE
from certkit_rules.part25.support.gust import reference_gust_velocity
from certkit_rules.part25.support.reference_speeds import declared_eas

from certkit.atmosphere import RHO0, convert_speed, density
from certkit.engine.conditions import ConditionSpace, EnvelopeAltitudes, EnvelopeWeights
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.loads.vn_envelope import envelope, stall_line_speed
from certkit.models.performance.stall import stall_speed_eas
from certkit.units import G0

AMDT = "25-91"


def cn_max_clean(ctx, factor: float) -> float:
    """Maximum normal-force coefficient, flaps retracted: ``factor`` × declared clean CLmax."""
    return factor * ctx.aircraft.configurations["clean"].CLmax


def vs1(ctx, mass, factor: float):
    """1-g stall speed (EAS) flaps retracted, based on CNmax (§25.335(d)(1) definition of VS1)."""
    return stall_speed_eas(mass, ctx.aircraft.reference.area, cn_max_clean(ctx, factor))


def gust_load_factor(ctx, mass, h, vc_eas, uref, kg_a, kg_b):
    """n_g = 1 + K_g U_ref V_C a ρ₀ / (2 w), K_g = a_k μ/(b_k + μ), μ = 2w/(ρ c a g) (§25.335(d)(1),
    the paragraph's 498 constant written in SI). a = wing lift-curve slope at the Mach number of VC."""
    S, b = ctx.aircraft.reference.area, ctx.aircraft.reference.span
    w = mass * G0 / S
    mach = float(convert_speed(vc_eas, "EAS", "MACH", h))
    a = ctx.wing_lift_slope(min(mach, 0.95))
    mu = 2 * w / (density(h) * (S / b) * a * G0)
    kg = kg_a * mu / (kg_b + mu)
    return 1.0 + kg * RHO0 * uref * vc_eas * a / (2 * w), dict(K_g=float(kg), mu=float(mu), lift_slope=float(a))


@rule
class DesignCruisingSpeed(Rule):
    id = "25.335(a)"
    symbol = "design-cruising-speed"
    title = "Design cruising speed VC"
    amendment = AMDT
    requirement = """
        VC must be sufficiently greater than VB to provide for inadvertent speed increases in severe
        turbulence: VC may not be less than VB + 1.32 U_ref (U_ref of §25.341(a)(5)(i)), except at
        altitudes where VC is limited by Mach number (§25.335(a)(3), (d)(2)).
    """
    margin = "VC − (VB + 1.32 U_ref), m/s EAS, at each altitude where VC is not Mach-limited."
    references = ("25.341", "25.335(d)")
    requires = ("speeds.VC", "speeds.VB")
    criteria = {"gust_factor": Criterion(1.32, "", "14 CFR 25.335(a)(2)", "multiple of U_ref added to VB")}
    conditions = ConditionSpace(altitudes=EnvelopeAltitudes())
    limitations = "The relief 'VC need not exceed the maximum level speed at maximum continuous power' is not taken."

    def evaluate(self, ctx, conditions, crit):
        out = []
        for cond in conditions:
            h = cond.altitude
            vc, mach_limited = ctx.design_speed_eas("VC", h)
            if bool(mach_limited):
                out.append(
                    Finding.not_applicable(
                        cond,
                        "(a)(2) VC ≥ VB + 1.32 U_ref",
                        "VC is limited by MC at this altitude (§25.335(a)(3), (d)(2))",
                    )
                )
                continue
            limit = declared_eas(ctx, "VB", h) + crit.gust_factor * float(reference_gust_velocity(h))
            out.append(
                Finding.compare(
                    cond,
                    "(a)(2) VC ≥ VB + 1.32 U_ref",
                    float(vc),
                    limit,
                    at_least=True,
                    unit="m/s",
                    U_ref=float(reference_gust_velocity(h)),
                    U_ref_source=GUST_SOURCE,
                )
            )
        return out


@rule
class DesignDiveSpeed(Rule):
    id = "25.335(b)"
    symbol = "design-dive-speed"
    title = "Design dive speed VD/MD"
    amendment = AMDT
    requirement = """
        VD/MD must be selected so that VC/MC is not greater than 0.8 VD/MD, or so that the speed margin
        between VC/MC and VD/MD is the greater of the upset manoeuvre increase ((b)(1)) and the margin for
        atmospheric variations, instrument errors and production variations ((b)(2)), which at altitudes
        where MC is limited by compressibility is not less than 0.07 M (0.05 M with a rational analysis).
    """
    margin = """
        At each altitude: 0.8·VD − VC (m/s EAS) when that complies; otherwise, where VD is Mach-limited,
        the speed margin in Mach, (MD − M of VC at that altitude) − required margin. The better route is reported.
    """
    references = ("25.335(a)", "25.1505")
    requires = ("speeds.VD",)
    criteria = {
        "vc_over_vd_max": Criterion(0.8, "", "14 CFR 25.335(b)", "largest VC/VD (and MC/MD) ratio"),
        "mach_margin": Criterion(
            0.07, "", "14 CFR 25.335(b)(2)", "minimum MD − MC where MC is compressibility-limited"
        ),
        "mach_margin_floor": Criterion(
            0.05, "", "14 CFR 25.335(b)(2)", "never less than this, even with a rational analysis"
        ),
    }
    conditions = ConditionSpace(altitudes=EnvelopeAltitudes())
    limitations = "The upset-manoeuvre margin of (b)(1) is not simulated; the Mach-margin route uses (b)(2)."

    implementation = "partial"
    unevaluated = (
        (
            "25.335(b)(1)",
            "the upset-manoeuvre speed increase (20° nose-down upset from VC, 1.5 g recovery) is not "
            "simulated: only the 0.8 ratio and the (b)(2) Mach margin are checked",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        out = []
        for cond in conditions:
            h = cond.altitude
            vc, _ = ctx.design_speed_eas("VC", h)
            vd, vd_mach = ctx.design_speed_eas("VD", h)
            ratio = Finding.compare(
                cond, "(b) VC/MC ≤ 0.8 VD/MD", crit.vc_over_vd_max * float(vd), float(vc), at_least=True, unit="m/s"
            )
            if ratio.status == "complies" or not bool(vd_mach):
                out.append(ratio)
                continue
            m_c, m_d = (float(convert_speed(v, "EAS", "MACH", h)) for v in (vc, vd))
            required = max(crit.mach_margin, crit.mach_margin_floor)
            mach = Finding.compare(
                cond,
                "(b)(2) MD − M(VC) ≥ Mach margin",
                m_d - m_c,
                required,
                at_least=True,
                unit="Mach",
                M_C=m_c,
                M_D=m_d,
            )
            out.append(mach if (mach.normalized_margin or 0) >= (ratio.normalized_margin or 0) else ratio)
        return out


@rule
class DesignManeuveringSpeed(Rule):
    id = "25.335(c)"
    symbol = "design-maneuvering-speed"
    title = "Design maneuvering speed VA"
    amendment = AMDT
    requirement = """
        VA may not be less than VS1·√n, n the limit positive maneuvering load factor at VC and VS1 the
        stalling speed with flaps retracted, evaluated at the design weight and altitude under
        consideration. VA need not be more than VC or the speed at which the positive C_Nmax curve
        intersects the positive manoeuvre load factor line, whichever is less.
    """
    margin = "VA − min(VS1·√n, VC), m/s EAS, at every envelope weight and altitude."
    references = ("25.333", "25.337", "25.103")
    requires = ("speeds.VA", "speeds.VC", "configurations.clean.CLmax", "envelope.limit_load_factors")
    criteria = dict(CN_OVER_CL)
    conditions = ConditionSpace(loading=EnvelopeWeights(), altitudes=EnvelopeAltitudes())

    def evaluate(self, ctx, conditions, crit):
        n = ctx.aircraft.envelope.limit_load_factors.positive
        out = []
        for cond in conditions:
            h = cond.altitude
            v_s1 = float(vs1(ctx, cond.mass, crit.cn_over_cl))
            vc, _ = ctx.design_speed_eas("VC", h)
            # VS1·√n, or where the stall line of a C_N,max varying with Mach reaches n at this altitude (§25.335(c)(2))
            required = min(envelope(ctx, cond.mass, h, crit.cn_over_cl).v_a, float(vc))
            out.append(
                Finding.compare(
                    cond,
                    "(c) VA ≥ min(VS1·√n, VC)",
                    declared_eas(ctx, "VA", h),
                    required,
                    at_least=True,
                    unit="m/s",
                    VS1=v_s1,
                    n=n,
                    VC=float(vc),
                )
            )
        return out


@rule
class DesignSpeedMaximumGust(Rule):
    id = "25.335(d)"
    symbol = "design-speed-maximum-gust-intensity"
    title = "Design speed for maximum gust intensity VB"
    amendment = AMDT
    requirement = """
        VB may not be less than VS1·[1 + K_g U_ref V_C a / (498 w)]^½ (the 1-g stall speed times the root of
        the sharp-edged gust load factor at VC), with K_g = 0.88 μ/(5.3 + μ), μ = 2w/(ρ c a g). At altitudes
        where VC is limited by Mach number VB need not be greater than VC.
    """
    margin = "VB − VS1·√(n_g) (or − VC where VC is Mach-limited and smaller), m/s EAS."
    references = ("25.341", "25.335(a)")
    requires = ("speeds.VB", "speeds.VC", "configurations.clean.CLmax", "geometry.wing")
    criteria = {
        **CN_OVER_CL,
        "kg_a": Criterion(0.88, "", "14 CFR 25.335(d)(1)", "gust alleviation factor K_g = a μ/(b + μ): a"),
        "kg_b": Criterion(5.3, "", "14 CFR 25.335(d)(1)", "gust alleviation factor K_g = a μ/(b + μ): b"),
    }
    conditions = ConditionSpace(loading=EnvelopeWeights(), altitudes=EnvelopeAltitudes())
    limitations = (
        "a is the wing lift-curve slope (DATCOM/Polhamus) at the Mach number of VC, not the whole "
        "airplane's C_Nα; the vortex-lattice value replaces it when the aerodynamics model is wired in."
    )

    def evaluate(self, ctx, conditions, crit):
        out = []
        for cond in conditions:
            h = cond.altitude
            v_s1 = float(vs1(ctx, cond.mass, crit.cn_over_cl))
            vc, vc_mach = ctx.design_speed_eas("VC", h)
            n_g, info = gust_load_factor(
                ctx, cond.mass, h, float(vc), float(reference_gust_velocity(h)), crit.kg_a, crit.kg_b
            )
            required = v_s1 * np.sqrt(n_g)
            line = envelope(ctx, cond.mass, h, crit.cn_over_cl).stall_pos
            if line is not None:  # C_N,max varying with Mach: where the stall line at this altitude reaches n_g
                required = stall_line_speed(line, n_g, required)
            if bool(vc_mach):
                required = min(required, float(vc))
            out.append(
                Finding.compare(
                    cond,
                    "(d)(1) VB ≥ VS1·√n_g",
                    declared_eas(ctx, "VB", h),
                    required,
                    at_least=True,
                    unit="m/s",
                    VS1=v_s1,
                    n_g=float(n_g),
                    **info,
                )
            )
        return out
