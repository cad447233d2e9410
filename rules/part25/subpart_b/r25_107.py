"""§25.107 Takeoff speeds (Amdt. 25-121 era text). Declared V1, VR, V2, VLOF against VSR, VMC, VMCG, VMU.

Each sub-check is its own finding, so the rule reports what it can: the VSR parts are evaluated from
§25.103's reference stall speed of the takeoff configuration at MTOW; the VMC parts use the declared VMC, or
where none is declared the VMCA that §25.149 computes (the basis is named in the finding); the VMCG part the
declared VMCG or the one §25.149(e) computes by simulation, against VEF (V1 less the speed gained over the
recognition interval after the critical engine's failure); the VMU part is ``not_evaluated`` until VMU is declared.
"""

from __future__ import annotations

import numpy as np
from certkit_rules.part25.support.ground_control import computed_vmcg
from certkit_rules.part25.support.minimum_control import computed_vmca
from certkit_rules.part25.support.reference_speeds import declared_cas, ratio_check, reference_stall_speed
from certkit_rules.part25.support.takeoff import failure_speed_at_v1

from certkit.engine.conditions import ConditionSpace, DesignWeight
from certkit.engine.evidence.performance import margins_evidence
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding

AMDT = "25-121"
TAKEOFF = "takeoff"


@rule
class TakeoffSpeeds(Rule):
    id = "25.107"
    symbol = "takeoff-speeds"
    title = "Takeoff speeds"
    amendment = AMDT
    requirement = """
        VFTO may not be less than 1.18 VSR of the en-route configuration (g)(1).
        V2MIN may not be less than 1.13 VSR (two- and three-engine propeller airplanes, and turbojets without
        provisions for a significant reduction of the one-engine-inoperative power-on stall speed; 1.08 VSR for
        propeller airplanes with more than three engines and turbojets with such provisions) nor 1.10 VMC (b);
        V2 may not be less than V2MIN (c)(1). VEF may not be less than VMCG, V1 not less than VEF (a).
        VR may not be less than V1 nor 1.05 VMC (e)(1)(i)-(ii), and must give a VLOF of not less than
        110 % of VMU with all engines operating (e)(1)(iv).
    """
    margin = """
        Ratios less their factors (≥ 0 complies): V2/VSR − 1.13, V2/VMC − 1.10, VR/V1 − 1, VR/VMC − 1.05,
        VEF/VMCG − 1, VLOF/VMU − 1.10, VFTO/VSR − 1.18; VSR of the takeoff configuration (of the clean one for VFTO) at
        MTOW (§25.103), speeds CAS.
    """
    references = ("25.103", "25.111", "25.121(b)", "25.143(h)", "25.149")
    requires = ("speeds.V2", "configurations.takeoff")
    criteria = {
        "v2_over_vsr": Criterion(
            1.13,
            "",
            "14 CFR 25.107(b)(1)(ii)",
            "V2MIN/VSR, turbojet without power-on stall-speed reduction provisions "
            "(1.08 under (b)(2)(ii): override with the justification)",
        ),
        "v2_over_vmc": Criterion(1.10, "", "14 CFR 25.107(b)(3)", "V2MIN/VMC"),
        "vr_over_v1": Criterion(1.0, "", "14 CFR 25.107(e)(1)(i)", "VR may not be less than V1"),
        "vr_over_vmc": Criterion(1.05, "", "14 CFR 25.107(e)(1)(ii)", "VR/VMC"),
        "v1_over_vmcg": Criterion(
            1.0,
            "",
            "14 CFR 25.107(a)(1)-(2)",
            "VEF/VMCG, VEF ≥ VMCG (VEF from V1 less the recognition interval's speed gain)",
        ),
        "vfto_over_vsr": Criterion(
            1.18, "", "14 CFR 25.107(g)(1)", "VFTO/VSR, VSR of the en-route (clean) configuration"
        ),
        "vlof_over_vmu": Criterion(
            1.10,
            "",
            "14 CFR 25.107(e)(1)(iv) (text after 'not less than' unverified, docs/regulation-notes.md)",
            "VLOF/VMU, all engines operating",
        ),
    }
    conditions = ConditionSpace(
        loading=DesignWeight("MTOW", ("reference",)),
        configurations=(TAKEOFF,),
        altitudes=None,
        note="VSR from the declared trimmed CLmax is not CG-sensitive here, so the reference CG.",
    )
    limitations = """
        V2 ≥ VR + the increment to 35 ft (c)(2), VR giving V2 by 35 ft (e)(1)(iii) and the VR − 5 kt abuse case
        (e)(3) need the takeoff-path simulation of §25.111 and are not evaluated; the OEI VLOF ≥ 1.05 VMU part of
        (e)(1)(iv) is not separated from the all-engines one (one VLOF is declared).
    """

    implementation = "partial"
    unevaluated = (
        ("25.107(c)(2)", "V2 ≥ VR + the speed increment to 35 ft needs the §25.111(c)(2) takeoff path: not evaluated"),
        ("25.107(e)(1)(iii)", "VR allowing V2 to be reached by 35 ft (§25.111(c)(2)) not evaluated"),
        (
            "25.107(e)(1)(iv)",
            "VLOF ≥ 105 % VMU at the one-engine-inoperative thrust-to-weight ratio not evaluated "
            "(one VLOF is declared)",
        ),
        ("25.107(e)(3)", "the VR − 5 kt one-engine-inoperative takeoff distance case not evaluated"),
        (
            "25.107(g)(2)",
            "the §25.143(h) manoeuvring capability at VFTO is not judged here (§25.143(h) flies its turns)",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        out = []
        for cond in conditions:
            cond = cond.with_(altitude=0.0)
            vsr, source = reference_stall_speed(ctx, TAKEOFF, cond.mass)
            speeds = {n: declared_cas(ctx, n) for n in ("V1", "VR", "V2", "VMC", "VMCG", "VMU", "VLOF", "VFTO")}
            speeds["VSR"] = vsr
            speeds["VSR clean"], clean_source = reference_stall_speed(ctx, "clean", cond.mass)
            vmc_basis = "declared VMC"
            if speeds["VMC"] is None:
                speeds["VMC"] = computed_vmca(ctx)
                vmc_basis = "VMCA computed by §25.149 (no VMC declared)"
            out += [
                ratio_check(cond, "(b)(1), (c)(1) V2 ≥ 1.13 VSR", speeds, "V2", "VSR", crit.v2_over_vsr, basis=source),
                ratio_check(
                    cond, "(b)(3), (c)(1) V2 ≥ 1.10 VMC", speeds, "V2", "VMC", crit.v2_over_vmc, basis=vmc_basis
                ),
                ratio_check(cond, "(e)(1)(i) VR ≥ V1", speeds, "VR", "V1", crit.vr_over_v1),
                ratio_check(cond, "(e)(1)(ii) VR ≥ 1.05 VMC", speeds, "VR", "VMC", crit.vr_over_vmc, basis=vmc_basis),
                self._vef_check(ctx, cond, speeds, crit),
                ratio_check(cond, "(e)(1)(iv) VLOF ≥ 1.10 VMU", speeds, "VLOF", "VMU", crit.vlof_over_vmu),
                ratio_check(
                    cond.with_(configuration="clean"),
                    "(g)(1) VFTO ≥ 1.18 VSR (en route)",
                    speeds,
                    "VFTO",
                    "VSR clean",
                    crit.vfto_over_vsr,
                    basis=clean_source,
                ),
            ]
        return out

    @staticmethod
    def _vef_check(ctx, cond, speeds, crit):
        """(a) VEF ≥ VMCG: VEF the speed from which V1 is reached one recognition interval after the failure of the
        critical engine (the simulated takeoff's, at MTOW and the reference CG: V1 ≥ VEF by construction); VMCG the
        declared one, or where none is declared the highest §25.149(e) computes over the weight–CG corners."""
        check = "(a) VEF ≥ VMCG (V1 ≥ VEF)"
        basis = "declared VMCG"
        if speeds["VMCG"] is None:
            vmcg, corner, _ = computed_vmcg(ctx)
            if vmcg is None:
                return Finding.not_evaluated(cond, check, "needs speeds.VMCG (or what §25.149(e) needs to compute it)")
            speeds["VMCG"] = vmcg
            basis = f"VMCG computed by §25.149(e) (highest over the weight–CG corners: {corner}; no VMCG declared)"
        vef, vef_basis = failure_speed_at_v1(ctx, cond)
        if vef is None:
            return Finding.not_evaluated(cond, check, vef_basis)
        speeds["VEF"] = vef
        if not np.isfinite(speeds["VMCG"]):
            return Finding.compare(
                cond.with_(speed=vef, speed_kind="CAS", speed_name="VEF"),
                check,
                0.0,
                1.0,
                at_least=True,
                unit="ratio",
                VEF=vef,
                basis=basis,
                vef_basis=vef_basis,
                reason="§25.149(e) finds no VMCG on the runway (below VR)",
            )
        return ratio_check(cond, check, speeds, "VEF", "VMCG", crit.v1_over_vmcg, basis=f"{basis}; VEF: {vef_basis}")

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.107 takeoff speed ratios",
            "Declared takeoff speeds as ratios against their §25.107 factors.",
            ("V1", "VR", "V2", "VSR", "VMC", "VMCG", "VLOF", "VMU"),
        )
