"""§25.177 Static lateral-directional stability.

Two readings, each over every CG corner × (takeoff, cruise, landing) configuration × the speed range
1.13 VSR1 to the configuration's maximum allowable speed, at sea level and 35,000 ft (clean only up
there): the static derivatives about the CG (Cn_β > 0 weathercock stability, Cl_β < 0 dihedral effect)
and steady-heading sideslip trims at the criterion's sideslip angle, whose rudder and aileron must lie
within their design limits and in the stable sense (§25.177(c): control movements proportional to
sideslip in a stable sense).
"""

from __future__ import annotations

import numpy as np

from certkit.conditions import Altitudes, CgCorners, ConditionSpace, speed_as
from certkit.models.flight import control_limits
from certkit.registry import Criterion, Rule, rule
from certkit.results import Finding
from certkit.units import FT
from certkit_rules.part25.subpart_b.r25_171 import FLAP_ALTITUDE_SOURCE, PHASES, by_configuration, refine_speeds

UNVERIFIED = "§25.177 wording from memory (docs/regulation-notes.md marks it unverified)"


def derivatives_at_cg(ctx, cond) -> tuple[float, float]:
    """(Cn_β, Cl_β) per radian about the condition's CG at its Mach number. The model's moments are about
    the reference point x_ref; the side force moves Cn_β by CY_β (x_cg − x_ref)/b (Etkin & Reid §2.4:
    M_cg = M_ref + r_ref × F, the reference point lying (x_cg − x_ref) ahead of the CG in body x)."""
    m = ctx.aero(cond.configuration).model
    mach = speed_as(cond, "MACH")
    cn = float(m.derivative("Cn_beta", mach) + m.derivative("CY_beta", mach) * (cond.x_cg - m.reference.x_ref) / m.reference.span)
    return cn, float(m.derivative("Cl_beta", mach))


@rule
class StaticLateralDirectionalStability(Rule):
    id = "25.177"
    symbol = "static-lateral-directional-stability"
    title = "Static lateral-directional stability"
    amendment = "25-135"
    requirement = """
        (a) The static directional stability (the tendency to recover from a skid with the rudder free) must be
        positive for any landing gear and flap position and symmetric power condition, at speeds from 1.13 VSR1 up
        to VFE, VLE or VFC/MFC as appropriate. (b) The static lateral stability (the tendency to raise the low wing
        in a sideslip) may not be negative over the same range. (c) In straight, steady sideslips the aileron and
        rudder control movements must be substantially proportional to the sideslip angle in a stable sense, over
        the range of sideslip angles appropriate to the operation of the airplane.
    """
    margin = """
        Cn_β − 0 and 0 − Cl_β (per rad, about the CG at the condition's Mach); in the steady-heading sideslip at
        the criterion's angle: design limit − |deflection| for rudder and aileron (deg), and the sense
        δr/β ≥ 0, −δa/β ≥ 0 (deg/deg; certkit signs: rudder TE left and right aileron TE down positive).
    """
    references = ("25.171", "25.147")
    requires = ("configurations.clean.CLmax",)
    criteria = {
        "sideslip_deg": Criterion(10.0, "deg", "project choice for the 'range of sideslip angles appropriate to the "
                                  "operation of the airplane' of §25.177(c): a 30 kt crosswind at about 170 kt "
                                  "(1.3 VSR0 class) needs atan(30/170) = 10°; " + UNVERIFIED,
                                  "steady-heading sideslip angle of the trims (wind from the right)"),
        "low_speed_factor": Criterion(1.13, "", "§25.177(a),(b): from 1.13 VSR1 (" + UNVERIFIED + ")",
                                      "low end of the speed range, multiple of VSR"),
        "descent_deg": Criterion(3.0, "deg", "project choice: a descent at reduced power where level flight at 10° "
                                 "sideslip needs more than full thrust (§25.177(a): symmetric power conditions)",
                                 "flight-path angle of the sideslip trims that cannot be held level"),
        "flap_altitude_max": Criterion(6096.0, "m", FLAP_ALTITUDE_SOURCE, "highest altitude of flap configurations"),
    }
    conditions = ConditionSpace(loading=CgCorners(), configurations=tuple(PHASES.values()),
                                altitudes=Altitudes((0.0, 35000 * FT)),
                                extra=(("speed_point", ("1.13 VSR", "max allowable")),),
                                note="Speeds in CAS; flaps and gear only up to the flap altitude limit.")
    limitations = """
        Rudder-free (a) is read with the rudder fixed (no hinge-moment model); sideslip to the right only (the
        airplane is symmetric); control forces (§25.177(c)/(d) 180 lbf) need a control-force model the aircraft
        file does not have; level flight at the power for level flight, not every symmetric power condition.
    """

    def evaluate(self, ctx, conditions, crit):
        refined, out = refine_speeds(ctx, conditions, crit.flap_altitude_max, crit.low_speed_factor, "(a)-(c)")
        limits = control_limits(ctx.aircraft)
        beta = np.radians(crit.sideslip_deg)
        for config, idx in by_configuration(refined).items():
            conds = [refined[i] for i in idx]
            results = list(ctx.trim(conds, kind="sideslip", beta=beta).results)
            # where level flight needs more than full thrust, the sideslip is held in a shallow descent (§25.177
            # asks for symmetric power conditions, not level flight)
            short = [k for k, r in enumerate(results) if any(e.control == "throttle" and e.limit > 0 for e in r.limits_exceeded)]
            if short:
                retry = ctx.trim([conds[k] for k in short], kind="sideslip", beta=beta, gamma=-np.radians(crit.descent_deg))
                for k, r in zip(short, retry.results):
                    results[k] = r
            for cond, res in zip(conds, results):
                cn, cl = derivatives_at_cg(ctx, cond)
                out.append(Finding.compare(cond, "(a) Cn_β > 0 about the CG", cn, 0.0, at_least=True, unit="1/rad"))
                out.append(Finding.compare(cond, "(b) Cl_β < 0", cl, 0.0, at_least=False, unit="1/rad"))
                check = f"(c) {crit.sideslip_deg:g}° steady-heading sideslip"
                if not res.converged:
                    out.append(Finding.not_evaluated(cond, check, f"sideslip trim did not converge (|r| = {res.residual_norm:.1e}) "
                                                     + "; ".join(e.message for e in res.limits_exceeded)))
                    continue
                reason = "; ".join(lim.message for lim in res.limits_exceeded)
                bank = float(np.degrees(res.phi))
                if res.gamma < 0:
                    cond = cond.with_(flight_path_deg=round(float(np.degrees(res.gamma)), 2))
                for name in ("rudder", "aileron"):
                    d = res.controls[name]
                    lo, hi = limits[name]
                    lim = hi if d >= 0 else lo
                    out.append(Finding.compare(cond, f"{check}: {name} within design limit", abs(np.degrees(d)),
                                               abs(np.degrees(lim)), at_least=False, unit="deg", reason=reason,
                                               deflection_deg=float(np.degrees(d)), bank_deg=bank))
                out.append(Finding.compare(cond, f"{check}: rudder in the stable sense (δr/β ≥ 0)",
                                           res.controls["rudder"] / beta, 0.0, at_least=True, unit="deg/deg"))
                out.append(Finding.compare(cond, f"{check}: aileron in the stable sense (−δa/β ≥ 0)",
                                           -res.controls["aileron"] / beta, 0.0, at_least=True, unit="deg/deg"))
        return out

    def evidence(self, ctx, findings, crit):
        from certkit.report.evidence_stability import margin_matrix_evidence

        return margin_matrix_evidence(findings, "§25.177 static lateral-directional margins (normalised) over CG corners × configurations")
