"""Minimum control speeds in the air (§25.149(b)-(c) VMCA, §25.149(f) VMCL): the search shared by the rules that need
them (§§25.107, 25.125, 25.149), memoised on the Context.

Search (:func:`vmca_search`): every (inoperative engine, bank) row of the rule is solved in the same trim
batch at each step (a trim batch costs about the same for 4 rows as for 1). The control usage
u = max(|δr|/δr_lim, |δa|/δa_lim) of a straight OEI trim is nearly linear in 1/V² (the asymmetric thrust
moment over the dynamic pressure), so VMCA — the root of u − 1 — is found from 1.2 VSR by a first step
V·√u (at most ±15 %), then a secant in s = 1/V², kept inside the bracket of speeds known above and below
(bisection in 1/V² when the secant leaves it). Each iterate is one trim at a fixed flight-path angle: two
probe trims at γ = −0.04 and −0.02 at the start speed give dthrottle/dγ and du/dthrottle, the usage of each
iterate is brought to the full-throttle value by that first-order correction, and the next flight-path
angle is the corrected one, extrapolated linearly in speed; an iterate that needs more than full thrust at
its guessed angle is retried 0.02 rad lower (it says nothing about the controls). A row stops when its
speed step is below ``speed_tolerance_kn`` (0.05 kn: VMCA to 0.1 kn) with |u − 1| < 0.02, or pinned at
an end of the range. On the baseline: 7 trim batches, 0.3 s, against 12 batches of 33 speeds (3.3 s) for
the former grid; the grid's VMCA is 0.36 kn higher because its throttle matching ends at 0.978, not 0.99
(tests/rules/test_r25_149.py compares both, and a fine grid with the throttle on target within 0.1 kn).
"""

from __future__ import annotations

import numpy as np

from certkit.atmosphere import convert_speed
from certkit.models.flight import control_limits
from certkit.reference_speeds import reference_stall_speed
from certkit.units import KN


def vsr_cas(ctx, configuration: str, mass: float, h: float = 0.0) -> float:
    """Reference stall speed (m/s CAS) of ``configuration`` at ``mass`` at altitude ``h``: §25.103's VSR
    (declared, or the 1-g stall speed from the declared CLmax)."""
    eas, _ = reference_stall_speed(ctx, configuration, mass)
    return float(convert_speed(eas, "EAS", "CAS", h))


#: banks searched, as fractions of the largest allowed (5°) toward the operating engine: wings level to 5° in 1° steps
BANK_FRACTIONS = np.linspace(1.0, 0.0, 6)


def control_usage(res, limits) -> float:
    """Largest |deflection| / design limit of rudder and aileron (∞ when the trim did not converge)."""
    if not res.converged:
        return np.inf
    use = []
    for name in ("rudder", "aileron"):
        d = res.controls[name]
        lo, hi = limits[name]
        use.append(d / hi if d >= 0 else d / lo)
    return max(use)


def throttle_of(res) -> float:
    return next(v for k, v in res.controls.items() if k.startswith("throttle"))


def vmca_search(ctx, conds, engines, banks, vsr, throttle, low, high, tol, start: float = 1.2, max_iter: int = 10):
    """VMCA (m/s CAS) of each row (``conds[i]`` with ``engines[i]`` inoperative at bank ``banks[i]``) by the
    safeguarded secant in 1/V² of the module docstring, all rows in one trim batch per step; ``vsr`` (m/s CAS)
    per row, ``low``/``high`` the search range and ``start`` the first speed in multiples of VSR, ``tol`` the
    speed step (m/s) at which a row stops. Returns (vmca, pinned_low, pinned_high, history, last trims):
    ``pinned_low``/``pinned_high`` flag rows whose root lies beyond the range (VMCA is then that bound),
    ``history`` per row a list of dicts (speed, usage at the target throttle, gamma, trim)."""
    limits = control_limits(ctx.aircraft)
    n = len(conds)
    vsr = np.asarray(vsr, dtype=float)
    v_lo, v_hi = low * vsr, high * vsr

    def trims(speeds, gammas):
        cs = [c.with_(speed=float(v), speed_kind="CAS") for c, v in zip(conds, speeds)]
        return ctx.trim(cs, kind="oei", gamma=gammas, bank=banks, inoperative=list(engines)).results

    # two probe trims at the start speed: usage and throttle slopes per row
    g0, g1 = -0.04, -0.02
    v = np.clip(start * vsr, v_lo, v_hi)
    probe = [trims(v, np.full(n, g)) for g in (g0, g1)]
    t = np.array([[throttle_of(r) for r in p] for p in probe])
    u = np.array([[control_usage(r, limits) for r in p] for p in probe])
    ok = np.isfinite(u).all(axis=0) & (np.abs(t[1] - t[0]) > 1e-9)
    with np.errstate(invalid="ignore", divide="ignore"):
        dthr_dg = np.where(ok, (t[1] - t[0]) / (g1 - g0), np.nan)
        du_dthr = np.where(ok, (u[1] - u[0]) / (t[1] - t[0]), 0.0)
        gam = np.where(ok, np.clip(g1 + (throttle - t[1]) / dthr_dg, -0.3, 0.3), g1)
    use = np.where(ok, u[1] + du_dthr * (throttle - t[1]), np.inf)
    hist = [[{"speed": float(v[i]), "usage": float(use[i]), "gamma": float(gam[i]), "trim": probe[1][i]}] for i in range(n)]
    below = np.where(use > 1.0, v, np.nan)    # highest speed known with usage > 1 (or no trim)
    above = np.where(use <= 1.0, v, np.nan)   # lowest speed known with usage ≤ 1
    prev = [None] * n
    cur = [(v[i], use[i], gam[i]) for i in range(n)]
    done = np.zeros(n, dtype=bool)
    last = list(probe[1])
    for _ in range(max_iter):
        new, g_new = v.copy(), gam.copy()
        for i in np.flatnonzero(~done):
            v1, u1, gg1 = cur[i]
            lo_b = below[i] if np.isfinite(below[i]) else v_lo[i]
            hi_b = above[i] if np.isfinite(above[i]) else v_hi[i]
            cand = np.nan
            if np.isfinite(u1) and prev[i] is None:
                cand = v1 * np.clip(np.sqrt(u1), 0.85, 1.15)   # u ∝ 1/V²: the first step, at most 15 %
            elif np.isfinite(u1) and np.isfinite(prev[i][1]) and abs(u1 - prev[i][1]) > 1e-12:
                s0, s1 = prev[i][0] ** -2, v1 ** -2
                s_new = s1 + (1.0 - u1) * (s1 - s0) / (u1 - prev[i][1])
                cand = s_new ** -0.5 if s_new > 0 else np.nan
            if not (np.isfinite(cand) and lo_b <= cand <= hi_b):
                cand = (0.5 * (lo_b ** -2 + hi_b ** -2)) ** -0.5   # bisection in 1/V² inside the bracket
            new[i] = cand
            g_new[i] = gg1
            if prev[i] is not None and abs(v1 - prev[i][0]) > 1e-9:  # γ linear in V through the last two
                g_new[i] = gg1 + (cand - v1) * (gg1 - prev[i][2]) / (v1 - prev[i][0])
            g_new[i] = float(np.clip(g_new[i], -0.3, 0.3))
        res = trims(new, g_new)
        for i in np.flatnonzero(~done):
            r = res[i]
            thr = throttle_of(r)
            # the trim keeps its throttle iterate just below 1: at the stop it is thrust-limited
            if not r.converged and (thr >= 1.0 - 1e-4 or any(e.control == "throttle" for e in r.limits_exceeded)):
                # thrust-limited at the guessed flight-path angle (not a control verdict): retry lower
                hist[i].append({"speed": float(new[i]), "usage": np.nan, "gamma": float(g_new[i]), "trim": r})
                gam[i] = cur[i][2] - 0.02 if abs(new[i] - cur[i][0]) < 1e-9 else g_new[i] - 0.02
                cur[i] = (cur[i][0], cur[i][1], gam[i])
                prev[i] = None if prev[i] is None else (prev[i][0], prev[i][1], prev[i][2] - 0.02)
                v[i] = cur[i][0]
                continue
            uu = control_usage(r, limits) + du_dthr[i] * (throttle - thr)
            gg = float(np.clip(g_new[i] + (throttle - thr) / dthr_dg[i], -0.3, 0.3)) if ok[i] and r.converged else g_new[i]
            hist[i].append({"speed": float(new[i]), "usage": float(uu), "gamma": gg, "trim": r})
            step = abs(new[i] - cur[i][0])
            prev[i], cur[i], last[i] = cur[i], (new[i], uu, gg), r
            v[i], gam[i] = new[i], gg
            if not np.isfinite(uu) or uu > 1.0:
                below[i] = np.nanmax([below[i], new[i]])
            else:
                above[i] = np.nanmin([above[i], new[i]])
            at_bound = new[i] <= v_lo[i] * (1 + 1e-9) or new[i] >= v_hi[i] * (1 - 1e-9)
            bracketed = np.isfinite(below[i]) and np.isfinite(above[i]) and above[i] - below[i] < 2 * tol
            if step < tol and (abs(uu - 1.0) < 0.02 or at_bound or bracketed):
                done[i] = True
        if done.all():
            break
    pinned_low = ~np.isfinite(below) & (v <= v_lo * (1 + 1e-9))
    pinned_high = ~np.isfinite(above) & (v >= v_hi * (1 - 1e-9))
    return v, pinned_low, pinned_high, hist, last


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
        return {"vmca": vmca, "pinned_low": lo, "pinned_high": hi, "history": hist, "last": last, "banks": banks,
                "vsr": vsr, "engines": engines, "conds": conds}

    key = ("vmc rows", tuple((c.mass, c.x_cg, c.configuration, c.altitude, c.get("inoperative")) for c in conditions),
           bank_deg, throttle, low, high, tolerance_kn)
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
