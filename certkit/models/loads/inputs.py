"""Pilot-input schedules for the loads manoeuvres, vectorised over a batch of conditions.

:class:`SinusoidHold` is the checked-manoeuvre shape with a hold that may differ per condition (the
dynamics package's :class:`~certkit.models.dynamics.simulate.CheckedManeuver` takes one hold for the
whole batch): δ(t) = δ₁ sin(ω t) up to the peak at t₁ = π/(2ω), held to t₂ = t₁ + Δt, then
δ₁ sin(ω (t − Δt)) back through zero to the opposite peak and to zero at t_max = t₂ + π/ω; zero after.
With Δt = 0 this is the plain sinusoid of duration 3π/(2ω). The numbers the regulation sets (the
frequency floor, the longest hold) belong to the rule, not here.

:func:`bisect_batch` is the batched amplitude search: every condition's amplitude is updated at
once from one batch simulation per step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.dynamics.simulate import Schedule


@dataclass
class SinusoidHold(Schedule):
    time_grid = True
    delta1: float | np.ndarray
    omega: float | np.ndarray
    hold: float | np.ndarray = 0.0
    t0: float = 0.0

    def __call__(self, t):
        w = np.asarray(self.omega, dtype=float)
        d1 = np.asarray(self.delta1, dtype=float)
        dt = np.asarray(self.hold, dtype=float)
        tau = t - self.t0
        t1 = np.pi / (2 * w)
        tau_eff = np.where(tau <= t1, tau, np.where(tau <= t1 + dt, t1, tau - dt))
        on = (tau >= 0) & (tau <= self.t_max - self.t0)
        return np.where(on, d1 * np.sin(w * tau_eff), 0.0)

    @property
    def t_max(self) -> np.ndarray:
        """End of the input: t0 + t₂ + π/ω = t0 + 3π/(2ω) + Δt."""
        w = np.asarray(self.omega, dtype=float)
        return self.t0 + 1.5 * np.pi / w + np.asarray(self.hold, dtype=float)


def bisect_batch(run, lo, hi, target, steps: int = 8, tol=0.0, f_lo=None, f_hi=None, x_tol=0.0, first=None):
    """Batched bracketing search of ``x`` in [lo, hi] (arrays) such that ``run(x, mask) ≈ target``,
    ``run`` increasing in x and evaluated at once for the conditions of ``mask`` (one simulation per
    step, only of the conditions not yet converged; it returns values for the whole batch, anything
    outside the mask). Regula falsi with the Illinois correction: a near-linear response converges in
    two or three steps. A condition has converged when its response is within ``tol`` of the target or
    its bracket is narrower than ``x_tol`` (either may be per condition; ``x_tol`` is for a response
    that flattens, where a small residual leaves x undetermined). ``f_lo``/``f_hi``: run at lo and hi
    when already known (else computed). ``first``: the first step's x per condition where the caller
    has a better guess than the chord (NaN: the chord; kept inside the bracket).
    Returns (x, run(x)) of the last step and the bracket ends (lo, run(lo)) below and (hi, run(hi)) at or
    above the target. Conditions whose bracket does not hold the target are left at hi."""
    lo, hi = np.array(lo, dtype=float), np.array(hi, dtype=float)
    everyone = np.ones(lo.shape, dtype=bool)
    f_lo = (run(lo, everyone) if f_lo is None else np.asarray(f_lo, dtype=float)) - target
    f_hi = (run(hi, everyone) if f_hi is None else np.asarray(f_hi, dtype=float)) - target
    side = np.zeros(lo.shape)
    bracketed = (f_lo <= 0) & (f_hi >= 0)
    x, fx = hi.copy(), f_hi.copy()
    active = bracketed & (np.abs(f_hi) > tol) & (np.abs(hi - lo) > x_tol)
    for k in range(steps):
        if not active.any():
            break
        denom = np.where(np.abs(f_hi - f_lo) > 1e-12, f_hi - f_lo, 1.0)
        step = hi - f_hi * (hi - lo) / denom
        if k == 0 and first is not None:
            step = np.where(np.isfinite(first), first, step)
        x = np.where(active, np.clip(step, np.minimum(lo, hi), np.maximum(lo, hi)), x)
        fx = np.where(active, run(x, active) - target, fx)
        left = active & (np.sign(fx) == np.sign(f_lo))
        right = active & ~left
        lo, f_lo = np.where(left, x, lo), np.where(left, fx, f_lo)
        hi, f_hi = np.where(right, x, hi), np.where(right, fx, f_hi)
        # Illinois: halve the stale end's residual when the same end is kept twice
        f_hi = np.where(left & (side > 0), 0.5 * f_hi, f_hi)
        f_lo = np.where(right & (side < 0), 0.5 * f_lo, f_lo)
        side = np.where(left, 1.0, np.where(right, -1.0, side))
        active = active & (np.abs(fx) > tol) & (np.abs(hi - lo) > x_tol)
    return x, fx + target, lo, f_lo + target, hi, f_hi + target


def linear_probe(run, target, f_full, mask, fraction: float):
    """A first search step for an input x in [0, 1] whose response is linear in a small x, zero at zero, and may bend
    over further on (a load factor near the stall line), where the chord from zero to ``f_full`` = run(1) creeps: run
    the conditions of ``mask`` at ``fraction`` and aim the next step where that line reaches ``target``. Returns the
    bracket (lo, f_lo, hi, f_hi) with the probe in it and the next step's x (NaN where the probe gives no line: the
    chord), for :func:`bisect_batch` (``first``); conditions outside ``mask`` keep [0, 1] and the chord."""
    n = np.shape(f_full)[0]
    r = run(np.full(n, float(fraction)), mask)
    below = mask & (r > 0.0) & (r < target)
    above = mask & (r >= target)
    lo, f_lo = np.where(below, fraction, 0.0), np.where(below, r, 0.0)
    hi, f_hi = np.where(above, fraction, 1.0), np.where(above, r, f_full)
    first = np.where(below, fraction * target / np.where(below, r, 1.0), np.nan)
    return lo, f_lo, hi, f_hi, first
