"""Minimum control speeds in the air (§25.149(b)-(c) VMCA, §25.149(f) VMCL): the search shared by the rules that need
them (§§25.107, 25.125, 25.149), memoised on the Context.

Search (:func:`vmca_search`): every (inoperative engine, bank) row of the rule is solved in the same trim
batch at each step (a trim batch costs about the same for 4 rows as for 1). The control usage
u = max(|δr|/δr_lim, |δa|/δa_lim) of a straight OEI trim is nearly linear in 1/V² (the asymmetric thrust
moment over the dynamic pressure), so VMCA — the root of u − 1 — is found from 1.2 VSR by a first step
V·√u (at most ±15 %), then a secant in s = 1/V², kept inside the bracket of speeds known above and below
(bisection in 1/V² when the secant leaves it). Each iterate is one trim with the operating engine's throttle
held at the rule's value and the flight-path angle solved for, started from the row's last converged trim. A
trim that does not converge counts as usage ∞ (no straight trim: near the stall), so a row may end where
the trim ceases to exist with the controls within their limits (stall-limited: its last trim is then the
non-converged one). A row stops when its speed step is below ``speed_tolerance_kn`` (0.05 kn: VMCA to
0.1 kn) with |u − 1| < 0.02, when its bracket is narrower than two steps (VMCA is then its upper end), or
pinned at an end of the range; one still searching after ``max_iter`` steps stands at the lowest speed known
to be controllable. On the baseline: 9 trim batches, 0.06 s once the aerodynamics is built.

The former search trimmed at a guessed flight-path angle with the throttle free, corrected the usage to the
target throttle with a slope from two probe trims, and retried 0.02 rad lower a trim whose throttle iterate
ended on its stop. Near the stall the non-converged iterates wander and where they end changes with round-off:
the baseline's mirror-image rows (left/right engine out) took different paths, 139.4 against 139.8 kn, and a
usage corrected from throttle 0.83 put VMCA low on an airplane with a ±12° rudder (3° bank: 170.4 against
198.7 kn with the throttle held; the least over the banks 170.3 against 172.6 kn). tests/rules/test_r25_149.py
checks the mirror symmetry, the stability under a 1e-9 change of the mass, and the search against grids.
"""

from __future__ import annotations

import numpy as np
from certkit_rules.part25.support.reference_speeds import reference_stall_speed

from certkit.atmosphere import convert_speed, speed_of_sound
from certkit.models.aero.interface import AeroState
from certkit.models.flight import control_limits
from certkit.units import KN


def vsr_cas(ctx, configuration: str, mass: float, h: float = 0.0) -> float:
    """Reference stall speed (m/s CAS) of ``configuration`` at ``mass`` at altitude ``h``: §25.103's VSR
    (declared, or the 1-g stall speed from the declared CLmax)."""
    eas, _ = reference_stall_speed(ctx, configuration, mass)
    return float(convert_speed(eas, "EAS", "CAS", h))


#: banks searched, as fractions of the largest allowed (5°) toward the operating engine: wings level to 5° in 1° steps
BANK_FRACTIONS = np.linspace(1.0, 0.0, 6)


def _usages(res, limits) -> dict[str, float]:
    """|deflection| / design limit (on the deflected side) of the rudder and the aileron of a trim."""
    use = {}
    for name in ("rudder", "aileron"):
        d = res.controls[name]
        lo, hi = limits[name]
        use[name] = d / hi if d >= 0 else d / lo
    return use


def control_usage(res, limits) -> float:
    """Largest |deflection| / design limit of rudder and aileron (∞ when the trim did not converge)."""
    if not res.converged:
        return np.inf
    return max(_usages(res, limits).values())


def throttle_of(res) -> float:
    return next(v for k, v in res.controls.items() if k.startswith("throttle"))


def vmca_search(ctx, conds, engines, banks, vsr, throttle, low, high, tol, start: float = 1.2, max_iter: int = 16):
    """VMCA (m/s CAS) of each row (``conds[i]`` with ``engines[i]`` inoperative at bank ``banks[i]``) by the
    safeguarded secant in 1/V² of the module docstring, all rows in one trim batch per step; ``vsr`` (m/s CAS)
    per row, ``low``/``high`` the search range and ``start`` the first speed in multiples of VSR, ``tol`` the
    speed step (m/s) at which a row stops. Returns (vmca, pinned_low, pinned_high, history, last trims):
    ``pinned_low``/``pinned_high`` flag rows whose root lies beyond the range (VMCA is then that bound),
    ``history`` per row a list of dicts (speed, usage, gamma, trim); the last trim of a row that ends where the
    straight trim ceases to exist (controls within their limits above) is the non-converged one below."""
    limits = control_limits(ctx.aircraft)
    n = len(conds)
    vsr = np.asarray(vsr, dtype=float)
    v_lo, v_hi = low * vsr, high * vsr
    warm: dict[str, np.ndarray] = {}  # per row, the start of its next trim: its last converged trim (NaN: default)

    def step(speeds):
        cs = [c.with_(speed=float(v), speed_kind="CAS") for c, v in zip(conds, speeds)]
        res = ctx.trim(
            cs,
            kind="oei",
            gamma=warm.get("gamma", np.zeros(n)),
            bank=banks,
            inoperative=list(engines),
            throttle=np.full(n, throttle),
            initial={k: a.copy() for k, a in warm.items()},
        ).results
        for i, r in enumerate(res):
            if r.converged:
                for k, val in r.start().items():
                    warm.setdefault(k, np.full(n, np.nan))[i] = val
        return res, np.array([control_usage(r, limits) for r in res])

    v = np.clip(start * vsr, v_lo, v_hi)
    res, use = step(v)
    hist = [[{"speed": float(v[i]), "usage": float(use[i]), "gamma": res[i].gamma, "trim": res[i]}] for i in range(n)]
    below = np.where(use > 1.0, v, np.nan)  # highest speed known with usage > 1 (or no trim)
    above = np.where(use <= 1.0, v, np.nan)  # lowest speed known with usage ≤ 1
    end_trim = {
        "below": [r if u > 1.0 else None for r, u in zip(res, use)],
        "above": [r if u <= 1.0 else None for r, u in zip(res, use)],
    }
    prev = [None] * n
    cur = [(v[i], use[i]) for i in range(n)]
    done = np.zeros(n, dtype=bool)
    last = list(res)
    for _ in range(max_iter):
        new = v.copy()
        for i in np.flatnonzero(~done):
            v1, u1 = cur[i]
            lo_b = below[i] if np.isfinite(below[i]) else v_lo[i]
            hi_b = above[i] if np.isfinite(above[i]) else v_hi[i]
            cand = np.nan
            if np.isfinite(u1) and prev[i] is None:
                cand = v1 * np.clip(np.sqrt(u1), 0.85, 1.15)  # u ∝ 1/V²: the first step, at most 15 %
            elif np.isfinite(u1) and np.isfinite(prev[i][1]) and abs(u1 - prev[i][1]) > 1e-12:
                s0, s1 = prev[i][0] ** -2, v1**-2
                s_new = s1 + (1.0 - u1) * (s1 - s0) / (u1 - prev[i][1])
                cand = s_new**-0.5 if s_new > 0 else np.nan
            if not (np.isfinite(cand) and lo_b <= cand <= hi_b):
                cand = (0.5 * (lo_b**-2 + hi_b**-2)) ** -0.5  # bisection in 1/V² inside the bracket
            new[i] = cand
        res, use = step(new)
        for i in np.flatnonzero(~done):
            r, uu = res[i], use[i]
            hist[i].append({"speed": float(new[i]), "usage": float(uu), "gamma": r.gamma, "trim": r})
            moved = abs(new[i] - cur[i][0])
            prev[i], cur[i], last[i], v[i] = cur[i], (new[i], uu), r, new[i]
            if not np.isfinite(uu) or uu > 1.0:
                if not new[i] <= below[i]:
                    below[i], end_trim["below"][i] = new[i], r
            elif not new[i] >= above[i]:
                above[i], end_trim["above"][i] = new[i], r
            at_bound = new[i] <= v_lo[i] * (1 + 1e-9) or new[i] >= v_hi[i] * (1 - 1e-9)
            bracketed = np.isfinite(below[i]) and np.isfinite(above[i]) and above[i] - below[i] < 2 * tol
            if (moved < tol and (abs(uu - 1.0) < 0.02 or at_bound)) or bracketed:
                done[i] = True
        if done.all():
            break
    for i in range(n):
        if np.isfinite(above[i]) and np.isfinite(below[i]) and (not done[i] or above[i] - below[i] < 2 * tol):
            # the bracket (or, still searching, the lowest speed known to be controllable)
            v[i], last[i] = above[i], end_trim["above"][i]
            if not end_trim["below"][i].converged:
                last[i] = end_trim["below"][i]  # no trim just below, the controls within limits above: stall-limited
    pinned_low = ~np.isfinite(below) & (v <= v_lo * (1 + 1e-9))
    pinned_high = ~np.isfinite(above) & (v >= v_hi * (1 - 1e-9))
    return v, pinned_low, pinned_high, hist, last


#: a trim whose lift-curve slope at its angle of attack is below this fraction of the linear slope is at the lift
#: maximum: there is no steady flight at a lower speed whatever the controls (the stall limits, not the controls)
STALL_SLOPE_FRACTION = 0.25


def at_lift_maximum(ctx, configuration: str, res, step: float = np.radians(0.25)) -> bool:
    """Whether the trim ``res`` (converged or its last iterate) is at the maximum of the lift curve of
    ``configuration``: dCL/dα at its angle of attack, sideslip, Mach and controls below :data:`STALL_SLOPE_FRACTION`
    of the linear slope CL_α — where a steady trim ceases to exist because the wing cannot give more lift."""
    model = ctx.aero(configuration).model
    mach = float(res.V / speed_of_sound(res.h))
    controls = {k: v for k, v in res.controls.items() if k in model.control_names}
    cl = [
        float(
            np.asarray(
                model.coefficients(AeroState(alpha=res.alpha + d, beta=res.beta, mach=mach, controls=controls)).CL
            )
        )
        for d in (-step, step)
    ]
    return (cl[1] - cl[0]) / (2 * step) < STALL_SLOPE_FRACTION * float(model.derivative("CL_alpha", mach))


def limiting_control(res, limits) -> str:
    """The control at (or nearest) its design limit in the converged trim ``res``: 'rudder' or 'aileron'."""
    use = _usages(res, limits)
    return max(use, key=use.get)


def vmca_from_grid(speeds, usage) -> float | None:
    """Highest speed where the control usage crosses 1 going down in speed (linear interpolation);
    None when the controls stay within their limits at every grid speed."""
    speeds, usage = np.asarray(speeds), np.asarray(usage)
    over = usage > 1.0
    if not over.any():
        return None
    k = int(np.max(np.nonzero(over)[0]))
    if k == len(speeds) - 1:
        return float(speeds[-1])
    u0, u1 = usage[k], usage[k + 1]
    if not np.isfinite(u0):
        return float(speeds[k + 1])
    return float(speeds[k] + (u0 - 1.0) / (u0 - u1) * (speeds[k + 1] - speeds[k]))


def vmc_rows(ctx, conditions, *, bank_deg: float, throttle: float, low: float, high: float, tolerance_kn: float):
    """The search over rows (condition, bank) — :data:`BANK_FRACTIONS` of the largest bank toward the operating
    engine per condition, wings level included (the minimum control speed is the least over the banks the paragraph
    allows: an intermediate bank can balance the rudder's and the aileron's needs); each condition names its
    ``inoperative`` engine. Memoised on the Context (the rules and the evidence share it)."""

    def compute():
        y = {e.name: e.position.y for e in ctx.aircraft.propulsion.engines}
        conds, engines, banks, vsr = [], [], [], []
        for cond in conditions:
            engine = cond.get("inoperative")
            live = [nm for nm in y if nm != engine]
            # bank toward the operating engine: right wing down (+) when the live engine is on the right
            bank = np.radians(bank_deg) * (1.0 if y[live[0]] > 0 else -1.0)
            v = vsr_cas(ctx, cond.configuration, cond.mass, cond.altitude or 0.0)
            for b in BANK_FRACTIONS * bank:
                conds.append(cond)
                engines.append(engine)
                banks.append(b)
                vsr.append(v)
        banks = np.array(banks)
        vmca, lo, hi, hist, last = vmca_search(ctx, conds, engines, banks, vsr, throttle, low, high, tolerance_kn * KN)
        limits = control_limits(ctx.aircraft)
        limited_by = []
        for c, r, pinned in zip(conds, last, lo):
            if pinned:
                limited_by.append("none: controls within limits down to the search's lowest speed")
            elif r is None:
                limited_by.append("none found")
            elif r.converged:
                limited_by.append(limiting_control(r, limits))
            else:  # the row ends where no steady trim exists below: the stall, or a trim that failed
                limited_by.append("stall" if at_lift_maximum(ctx, c.configuration, r) else "trim failure")
        return {
            "vmca": vmca,
            "pinned_low": lo,
            "pinned_high": hi,
            "history": hist,
            "last": last,
            "banks": banks,
            "vsr": vsr,
            "engines": engines,
            "conds": conds,
            "limited_by": limited_by,
        }

    key = (
        "vmc rows",
        tuple((c.mass, c.x_cg, c.configuration, c.altitude, c.get("inoperative")) for c in conditions),
        bank_deg,
        throttle,
        low,
        high,
        tolerance_kn,
    )
    return ctx.memo(key, compute)


def condition_vmc(rows, k: int, low: float) -> tuple[float, int, bool]:
    """The minimum control speed (m/s CAS) of condition ``k`` of :func:`vmc_rows`: the least over its banks; the
    search's lower end (``low`` × VSR) when the controls stay within their limits down to it. Returns (speed, the row
    of the best bank, below the range)."""
    nb = len(BANK_FRACTIONS)
    pair = range(nb * k, nb * k + nb)
    best = min(pair, key=lambda j: rows["vmca"][j])
    if all(rows["pinned_low"][j] for j in pair) or rows["pinned_low"][best]:
        return float(low * rows["vsr"][best]), best, True
    return float(rows["vmca"][best]), best, False
