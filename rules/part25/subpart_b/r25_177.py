"""§25.177 Static lateral-directional stability.

Over every CG corner × (takeoff, cruise, landing) configuration × the speed range 1.13 VSR1 to the
configuration's maximum allowable speed, at sea level and 35,000 ft (clean only up there):

* (a), (b): the static derivatives about the CG (Cn_β > 0 weathercock stability, Cl_β < 0 dihedral effect);
* (c): straight steady sideslips (steady-heading trims) over the range the paragraph prescribes, up to the
  sideslip of the lesser of half the available rudder and 180 lbf of pedal force (the force only when the
  aircraft file declares ``control_forces.rudder``), found from a 5° trim and swept at ¼, ½, ¾ and all of
  it: rudder and aileron within their design limits and moving in the stable sense between every pair of
  points (the increments, so "substantially proportional" is read point by point; the ratio of the
  largest to the smallest local gradient is reported);
* (d): beyond that range, up to full rudder (or 180 lbf, or until full aileron ends the steady sideslip),
  more sideslip needs more rudder (and, with a force model, the pedal force does not reverse).
"""

from __future__ import annotations

import numpy as np
from certkit_rules.part25.support.stability_speeds import (
    FLAP_ALTITUDE,
    PHASES,
    by_configuration,
    refine_speeds,
    steady_flight_trims,
)

from certkit.engine.conditions import Altitudes, CgCorners, ConditionSpace, speed_as
from certkit.engine.evidence.stability import margin_matrix_evidence
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.control_force import control_force_model, trim_state
from certkit.models.flight import control_limits
from certkit.units import FT, LBF

SOURCE = "14 CFR 25.177, Amdt. 25-135 (verified, docs/regulation-notes.md)"
#: sweep of (c) and (d), fractions of the (c) range
FRACTIONS_C = (0.25, 0.5, 0.75, 1.0)
FRACTIONS_D = (1.25, 1.5, 1.75, 2.0)


def derivatives_at_cg(ctx, cond) -> tuple[float, float]:
    """(Cn_β, Cl_β) per radian about the condition's CG at its Mach number. The model's moments are about
    the reference point x_ref; the side force moves Cn_β by CY_β (x_cg − x_ref)/b (Etkin & Reid §2.4:
    M_cg = M_ref + r_ref × F, the reference point lying (x_cg − x_ref) ahead of the CG in body x)."""
    m = ctx.aero(cond.configuration).model
    mach = speed_as(cond, "MACH")
    cn = float(
        m.derivative("Cn_beta", mach)
        + m.derivative("CY_beta", mach) * (cond.x_cg - m.reference.x_ref) / m.reference.span
    )
    return cn, float(m.derivative("Cl_beta", mach))


@rule
class StaticLateralDirectionalStability(Rule):
    id = "25.177"
    cost = 2  # relative evaluation time (orders work over --jobs processes)
    symbol = "static-lateral-directional-stability"
    title = "Static lateral-directional stability"
    amendment = "25-135"  # verified text
    requirement = """
        (a) The static directional stability (the tendency to recover from a skid with the rudder free) must be
        positive for any landing gear and flap position and symmetric power condition, at speeds from 1.13 VSR1 up
        to VFE, VLE or VFC/MFC as appropriate. (b) The static lateral stability (the tendency to raise the low wing
        in a sideslip) may not be negative from 1.13 VSR1 to VMO/MMO. (c) In straight, steady sideslips over the
        range of sideslip angles appropriate to the operation of the airplane — at least up to the lesser of half
        the available rudder control input and a 180 lbf rudder force — the aileron and rudder control movements
        and forces must be substantially proportional to the angle of sideslip in a stable sense. (d) Beyond that,
        up to full rudder or 180 lbf, the rudder forces may not reverse and increased rudder deflection must be
        needed for increased sideslip.
    """
    margin = """
        Cn_β − 0 and 0 − Cl_β (per rad, about the CG at the condition's Mach); over the (c) sweep: design limit −
        |deflection| for rudder and aileron at the end of the range (deg), and the smallest increment gradient
        Δδr/Δβ, −Δδa/Δβ ≥ 0 (deg/deg; certkit signs: rudder TE left and right aileron TE down positive); over the
        (d) sweep: the smallest Δδr/Δβ ≥ 0 (and the smallest pedal-force increment ΔF/Δβ ≥ 0 with a force model).
    """
    references = ("25.171", "25.147")
    requires = ("configurations.clean.CLmax",)
    criteria = {
        "rudder_fraction": Criterion(
            0.5, "", SOURCE + " (c)(1)", "share of the available rudder that bounds the (c) range"
        ),
        "pedal_force_lbf": Criterion(
            180.0, "lbf", SOURCE + " (c)(2), (d)", "rudder force that bounds the (c) and (d) ranges"
        ),
        "reference_sideslip_deg": Criterion(
            5.0, "deg", "certkit numerical choice", "sideslip of the first trim, from which the (c) range is scaled"
        ),
        "low_speed_factor": Criterion(1.13, "", SOURCE + " (a), (b)", "low end of the speed range, multiple of VSR"),
        "flap_altitude_max": FLAP_ALTITUDE,
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        configurations=tuple(PHASES.values()),
        altitudes=Altitudes((0.0, 35000 * FT)),
        extra=(("speed_point", ("1.13 VSR", "max allowable", "VFC")),),
        note="Speeds in CAS: 1.13 VSR1, the maximum allowable speed (VMO/MMO clean, VFE/VLE "
        "extended) and, clean, VFC/MFC (declared, or the least §25.253(b) allows): (a) and "
        "(c) up to VFC/MFC, (b)(1) to VMO/MMO, (b)(2) beyond; flaps and gear only up to the "
        "flap altitude limit.",
    )
    limitations = """
        Rudder-free (a) and aileron-free (b) are read with the controls fixed; sideslip to the right only (the
        airplane is symmetric); the 180 lbf bound and the force reversal of (d) need control_forces.rudder (without
        it the range is bounded by the rudder deflection alone); the "limits found necessary for safe operation" of
        the proportionality factor are not numeric (the ratio of local gradients is reported); level flight at the
        power for level flight (the steady descent at full thrust where that needs more, its flight path in the
        finding's condition), not every symmetric power condition; without a declared VFC/MFC the top speed is the
        least §25.253(b) allows.
    """

    implementation = "partial"
    unevaluated = (
        (
            "25.177(a)",
            "rudder-free directional stability is read with the rudder fixed; not every symmetric power "
            "condition is flown",
        ),
        ("25.177(b)", "aileron-free lateral stability is read with the ailerons fixed"),
    )

    def evaluate(self, ctx, conditions, crit):
        refined, out = refine_speeds(ctx, conditions, crit.flap_altitude_max, crit.low_speed_factor, "(a)-(c)")
        limits = control_limits(ctx.aircraft)
        rudder_force = control_force_model(ctx.aircraft, "rudder")
        for _config, idx in by_configuration(refined).items():
            conds = [refined[i] for i in idx]
            for cond in conds:
                cn, cl = derivatives_at_cg(ctx, cond)
                out.append(Finding.compare(cond, "(a) Cn_β > 0 about the CG", cn, 0.0, at_least=True, unit="1/rad"))
                if cond.get("speed_point") != "VFC":
                    out.append(Finding.compare(cond, "(b) Cl_β < 0", cl, 0.0, at_least=False, unit="1/rad"))
                elif cl < 0:
                    out.append(
                        Finding.compare(
                            cond, "(b)(2) Cl_β < 0 between VMO/MMO and VFC/MFC", cl, 0.0, at_least=False, unit="1/rad"
                        )
                    )
                else:
                    out.append(
                        Finding.not_evaluated(
                            cond,
                            "(b)(2) Cl_β < 0 between VMO/MMO and VFC/MFC",
                            "negative effective dihedral above VMO/MMO: "
                            "(b)(2) accepts it if the divergence is gradual, easily recognizable and easily "
                            "controllable by "
                            "the pilot — qualitative, not assessed",
                            Cl_beta_per_rad=float(cl),
                        )
                    )
            out += self._sideslips(ctx, conds, crit, limits, rudder_force)
        return out

    def _trims(self, ctx, conds, betas):
        """Steady-heading sideslip trims of ``conds`` at ``betas`` (rad, per condition) in the steady flight the
        airplane can hold: level, or the steady descent at full thrust where level flight in the sideslip needs more
        (the flight path solved by the trim)."""
        return steady_flight_trims(ctx, conds, kind="sideslip", beta=betas)[0]

    def _sideslips(self, ctx, conds, crit, limits, rudder_force):
        n = len(conds)
        lo_r, hi_r = limits["rudder"]
        beta_ref = np.radians(crit.reference_sideslip_deg)
        first = self._trims(ctx, conds, np.full(n, beta_ref))
        # the (c) range: the sideslip of half the available rudder (and of 180 lbf), scaled from the reference trim
        # (steady-heading sideslip deflections are near-linear in β); its sweep then shows whether they are
        dr_ref = np.array([r.controls["rudder"] if r.converged else np.nan for r in first])
        available = np.where(dr_ref >= 0, hi_r, -lo_r)
        beta_c = beta_ref * crit.rudder_fraction * available / np.abs(dr_ref)
        bound = np.full(n, "half the available rudder", dtype=object)
        if rudder_force is not None:
            # the deflection 180 lbf holds (the force law's inverse: breakout and q-feel included), at the
            # reference trim's dynamic pressure and fin angle, in the sense of the reference rudder
            q, a, d = trim_state(ctx.aircraft, "rudder", first)
            d_f = rudder_force.deflection_at_force(np.sign(d) * crit.pedal_force_lbf * LBF, q, a)
            beta_f = beta_ref * np.abs(d_f) / np.abs(d)
            bound = np.where(beta_f < beta_c, f"{crit.pedal_force_lbf:g} lbf pedal force", bound)
            beta_c = np.minimum(beta_c, beta_f)
        fr = np.array(FRACTIONS_C + FRACTIONS_D)
        ok = np.isfinite(beta_c)
        rows = [(k, j) for k in np.flatnonzero(ok) for j in range(fr.size)]
        sweep = (
            self._trims(ctx, [conds[k] for k, _ in rows], np.array([fr[j] * beta_c[k] for k, j in rows]))
            if rows
            else []
        )
        at = {kj: sweep[m] for m, kj in enumerate(rows)}
        out = []
        for k, cond in enumerate(conds):
            check = "(c) steady sideslips"
            if not ok[k]:
                r = first[k]
                out.append(
                    Finding.not_evaluated(
                        cond,
                        check,
                        f"the {crit.reference_sideslip_deg:g}° sideslip trim did not "
                        f"converge (|r| = {r.residual_norm:.1e}) " + "; ".join(e.message for e in r.limits_exceeded),
                    )
                )
                continue
            pts = [at[(k, j)] for j in range(fr.size)]
            c_pts = pts[: len(FRACTIONS_C)]
            if not all(r.converged for r in c_pts):
                bad = next(r for r in c_pts if not r.converged)
                out.append(
                    Finding.not_evaluated(
                        cond,
                        check,
                        "a sideslip trim of the (c) range did not converge "
                        f"(|r| = {bad.residual_norm:.1e}) " + "; ".join(e.message for e in bad.limits_exceeded),
                    )
                )
                continue
            end = c_pts[-1]
            here = cond.with_(flight_path_deg=round(float(np.degrees(end.gamma)), 2)) if end.gamma < 0 else cond
            info = dict(sideslip_range_deg=round(float(np.degrees(beta_c[k])), 3), range_bound=str(bound[k]))
            for name in ("rudder", "aileron"):
                dlt = end.controls[name]
                lo, hi = limits[name]
                lim = hi if dlt >= 0 else lo
                out.append(
                    Finding.compare(
                        here,
                        f"{check}: {name} within design limit at the end of the range",
                        abs(np.degrees(dlt)),
                        abs(np.degrees(lim)),
                        at_least=False,
                        unit="deg",
                        reason="; ".join(e.message for e in end.limits_exceeded),
                        deflection_deg=float(np.degrees(dlt)),
                        bank_deg=float(np.degrees(end.phi)),
                        **info,
                    )
                )
            betas = np.concatenate([[0.0], fr[: len(FRACTIONS_C)] * beta_c[k]])
            for name, sign, label in (("rudder", 1.0, "δr"), ("aileron", -1.0, "−δa")):
                defl = np.concatenate([[0.0], [sign * r.controls[name] for r in c_pts]])
                grad = np.diff(defl) / np.diff(betas)
                out.append(
                    Finding.compare(
                        here,
                        f"{check}: {name} in the stable sense at every step (Δ{label}/Δβ ≥ 0)",
                        float(grad.min()),
                        0.0,
                        at_least=True,
                        unit="deg/deg",
                        gradients=[round(float(g), 4) for g in grad],
                        proportionality_ratio=round(float(grad.max() / grad.min()), 3) if grad.min() > 0 else None,
                        **info,
                    )
                )
            out += self._beyond(ctx, here, pts, fr, beta_c[k], limits, rudder_force, crit, info)
        return out

    def _beyond(self, ctx, cond, pts, fr, beta_c, limits, rudder_force, crit, info):
        """(d): from the end of the (c) range on, while the trims stay steady sideslips within full rudder and full
        aileron (and under 180 lbf with a force model), each increment of sideslip needs more rudder."""
        lo_r, hi_r = limits["rudder"]
        lo_a, hi_a = limits["aileron"]
        used = [(fr[len(FRACTIONS_C) - 1] * beta_c, pts[len(FRACTIONS_C) - 1])]
        for f, r in zip(fr[len(FRACTIONS_C) :], pts[len(FRACTIONS_C) :]):
            if (
                not r.converged
                or not (lo_r <= r.controls["rudder"] <= hi_r)
                or not (lo_a <= r.controls["aileron"] <= hi_a)
            ):
                break  # full rudder or full lateral control reached: no steady sideslip needs to be held beyond
            if rudder_force is not None:
                q, a, d = trim_state(ctx.aircraft, "rudder", [r])
                if abs(float(rudder_force.force(q, a, d)[0])) > crit.pedal_force_lbf * LBF:
                    break
            used.append((f * beta_c, r))
        check = "(d) beyond the (c) range: more rudder for more sideslip (Δδr/Δβ ≥ 0)"
        if len(used) < 2:
            return [
                Finding.not_applicable(
                    cond,
                    check,
                    "full rudder, full lateral control or the force bound is reached at the end of the (c) range",
                    **info,
                )
            ]
        b = np.array([u[0] for u in used])
        dr = np.array([u[1].controls["rudder"] for u in used])
        grad = np.diff(dr) / np.diff(b)
        out = [
            Finding.compare(
                cond,
                check,
                float(grad.min()),
                0.0,
                at_least=True,
                unit="deg/deg",
                largest_sideslip_deg=round(float(np.degrees(b[-1])), 3),
                gradients=[round(float(g), 4) for g in grad],
                **info,
            )
        ]
        if rudder_force is not None:
            q, a, d = trim_state(ctx.aircraft, "rudder", [u[1] for u in used])
            force = np.abs(rudder_force.force(q, a, d)) / LBF
            out.append(
                Finding.compare(
                    cond,
                    "(d) rudder force does not reverse (ΔF/Δβ ≥ 0)",
                    float((np.diff(force) / np.degrees(np.diff(b))).min()),
                    0.0,
                    at_least=True,
                    unit="lbf/deg",
                    forces_lbf=[round(float(x), 2) for x in force],
                    **info,
                )
            )
        return out

    def evidence(self, ctx, findings, crit):
        return margin_matrix_evidence(
            findings, "§25.177 static lateral-directional margins (normalised) over CG corners × configurations"
        )
