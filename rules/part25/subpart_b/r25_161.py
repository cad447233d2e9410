"""§25.161 Trim — longitudinal trim in climb, level flight (cruise) and approach glide.

The paragraph's text could not be retrieved (docs/regulation-notes.md marks it unverified, from memory):
(c) the airplane must maintain longitudinal trim during climb at maximum continuous thrust at a speed not
more than 1.3 VSR1, during a glide (approach) at 1.3 VSR1, and in level flight at speeds up to VMO/MMO.
certkit trims every CG corner in each segment (one batch per configuration) and checks the elevator
needed against its design limits — the trim must be reachable with the longitudinal control.
"""

from __future__ import annotations

import math

import numpy as np

from certkit.conditions import CgCorners, ConditionSpace
from certkit.models.flight import control_limits
from certkit.registry import Criterion, Rule, rule
from certkit.results import Finding
from certkit.units import FT
from certkit_rules.part25.subpart_b.r25_103 import reference_stall_speed
from certkit_rules.part25.subpart_b.r25_121 import control_findings, oei_climb, trim_details

SEGMENTS = ("climb", "cruise", "approach")


@rule
class Trim(Rule):
    id = "25.161"
    symbol = "longitudinal-trim"
    title = "Trim"
    amendment = "25-38"
    requirement = """
        (Unverified, from memory.) The airplane must maintain longitudinal trim (c): in a climb with maximum
        continuous thrust at a speed not more than 1.3 VSR1; in a glide at 1.3 VSR1 (here the approach
        configuration on a −3° path); and in level flight at speeds up to VMO/MMO (here VC/MC, the cruise design
        speed). Trim is shown with the longitudinal control within its design range at each CG.
    """
    margin = "Elevator design limit − |trim elevator| on the side it is deflected (deg), at every CG corner and segment."
    references = ("25.103", "25.335(a)")
    requires = ("configurations.clean", "speeds.VC")
    criteria = {
        "climb_speed_over_vsr": Criterion(1.3, "", "14 CFR 25.161(c)(1) (unverified)", "climb speed, × VSR1 (flaps up)"),
        "glide_speed_over_vsr": Criterion(1.3, "", "14 CFR 25.161(c)(2) (unverified)", "glide speed, × VSR of the configuration"),
        "glide_path_deg": Criterion(-3.0, "deg", "standard −3° approach path (ICAO Annex 14 ILS glide slope)",
                                    "flight-path angle of the approach glide"),
        "cruise_altitude_ft": Criterion(35000.0, "ft", "14 CFR 25.161(c)(3) (unverified): level flight up to VMO/MMO",
                                        "cruise altitude where VC/MC is trimmed (also at sea level)"),
        "mct_over_takeoff_thrust": Criterion(
            0.96, "", "FAA TCDS E00049EN, GE90-90B: maximum continuous 90,580 lbf / takeoff 94,000 lbf",
            "maximum continuous over takeoff thrust of the engine model"),
    }
    conditions = ConditionSpace(loading=CgCorners(), extra=(("segment", SEGMENTS),),
                                note="climb: clean, MCT, 1.3 VSR1, sea level; cruise: clean, level, VC/MC at sea level and "
                                     "the cruise altitude; approach: approach configuration, −3° glide, 1.3 VSR, sea level")
    implementation = "partial"
    limitations = """
        §25.161(a), (b) (lateral/directional trim), (d) and (e) (engine-out trim) are not evaluated; the text of (c)
        is from memory. The stabiliser is fixed at its declared incidence, so the elevator carries the whole trim.
    """

    def evaluate(self, ctx, conditions, crit):
        out = []
        limits = control_limits(ctx.aircraft)
        climb = [c for c in conditions if c.get("segment") == "climb"]
        cruise = [c for c in conditions if c.get("segment") == "cruise"]
        glide = [c for c in conditions if c.get("segment") == "approach"]
        if climb:
            conds = [c.with_(configuration="clean", altitude=0.0, speed_kind="CAS", speed_name="1.3 VSR1",
                             speed=crit.climb_speed_over_vsr * reference_stall_speed(ctx, "clean", c.mass)[0],
                             thrust="maximum continuous") for c in climb]
            grads, batch, _ = oei_climb(ctx, conds, crit.mct_over_takeoff_thrust, engine_out=False)
            out += self._elevator(conds, batch, limits, "(c)(1) climb", gradients=grads)
        if cruise:
            h_cr = crit.cruise_altitude_ft * FT
            conds = []
            for h in (0.0, h_cr):
                v, mach_limited = ctx.design_speed_eas("VC", h)
                conds += [c.with_(configuration="clean", altitude=h, speed=float(v), speed_kind="EAS",
                                  speed_name="MC" if bool(mach_limited) else "VC", thrust="for level flight") for c in cruise]
            out += self._elevator(conds, ctx.trim(conds, kind="straight"), limits, "(c)(3) level flight")
        if glide:
            if "approach" not in ctx.aircraft.configurations:
                out += [Finding.not_evaluated(c, "(c)(2) glide", "needs configurations.approach") for c in glide]
            else:
                conds = [c.with_(configuration="approach", altitude=0.0, speed_kind="CAS", speed_name="1.3 VSR",
                                 speed=crit.glide_speed_over_vsr * reference_stall_speed(ctx, "approach", c.mass)[0],
                                 thrust="for the −3° path") for c in glide]
                batch = ctx.trim(conds, kind="straight", gamma=math.radians(crit.glide_path_deg))
                out += self._elevator(conds, batch, limits, "(c)(2) approach glide")
        return out

    @staticmethod
    def _elevator(conds, batch, limits, check, gradients=None):
        out = []
        for i, cond in enumerate(conds):
            r = batch.results[i]
            if not r.converged:
                out.append(Finding.not_evaluated(cond, f"{check} elevator within design limit",
                                                 f"trim did not converge (residual {r.residual_norm:.1e}); "
                                                 + "; ".join(m.message for m in r.limits_exceeded)))
                continue
            for f in control_findings(cond, check, r, limits):
                if "elevator" in f.check:
                    f.details.update(trim_details(r))
                    if gradients is not None:
                        f.details["climb_gradient"] = float(np.asarray(gradients)[i])
                    out.append(f)
        return out

    def evidence(self, ctx, findings, crit):
        from certkit.report.evidence_performance import margins_evidence

        return margins_evidence(findings, "§25.161 trim",
                                "Trims of each §25.161 condition: controls against their design limits.",
                                ("climb_gradient", "alpha_deg", "elevator_deg", "aileron_deg", "rudder_deg"))
