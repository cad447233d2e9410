"""The checked pitch manoeuvre's input (14 CFR 25.331(c)(2) as certkit reads it, docs/regulation-notes.md): the
elevator δ(t) = δ₁ sin ωt from the trim, held at its peak for Δt when the full sinusoid does not reach the load
factor, found per condition of a batch so that the peak load factor reaches a target — the procedure only; which
target, frequency and deflection the paragraph asks for are the caller's.

For each condition: the sinusoid at the full ``available`` amplitude (no hold) is run first; if it reaches the
search's aim, the target less half the ``tolerance``, the amplitude is searched (``reach``); if not, the hold at full
amplitude is searched up to ``max_hold`` (``held_short`` when even that does not reach the aim: the maximal input).
(A full sinusoid that ends between the aim and the target is within the tolerance: measured against the target
itself it would start a hold search whose bracket does not hold the aim, and end at the longest hold, far beyond the
load factor.) The search (:func:`bisect_batch`, regula falsi) aims there and ends within ``resolution`` of it: the
smallest input that reaches the load factor, so that near the stall line, where the peak is nearly flat in the
amplitude, the input does not jump between neighbouring conditions. The peak is linear in a small amplitude and bends
over near the stall line, where the aim often sits: an amplitude search's first step probes :data:`PROBE` of the
available amplitude and its second goes where that line reaches the aim (the chord from zero to the full amplitude,
flat near the stall, would creep along the bend and leave conditions outside the resolution after its steps). An
amplitude search that did not converge and ends above the target takes the largest amplitude found below it; a hold
takes the bracket end at or above it. Each input found was flown by a step of the search: the recorded run of the
batch is gathered from those steps' runs (:func:`~certkit.models.dynamics.simulate.gather`, bit for bit the run), not
flown again. A condition the batch holds twice (one flight point under two names, bit for bit the same airplane, trim
and settings: an entry speed capped at another) is searched and flown once, its run gathered for both.

Responses: peak n_z − 1 nose up, 1 − lowest n_z nose down, between the samples (the local cubic of
:func:`~certkit.models.dynamics.sampled_peak.peak_between_samples`: the sampled extreme alone is not monotone in the
input as the peak slides across the time grid), over the manoeuvre's window (until t_max = ``periods`` ×
π/(2ω) + Δt, n_z < 0 nose up or n_z > ``n_limit`` nose down end a run).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.sampled_peak import peak_between_samples
from certkit.models.dynamics.simulate import Bound, SimulationResult, gather, simulate
from certkit.models.loads.inputs import SinusoidHold, bisect_batch, linear_probe

#: the amplitude search's first step: this fraction of the available amplitude, where the response is still linear in
#: it (numerical choice: the checked manoeuvre's load factor bends over near the stall line, at 20–35 % of the
#: available elevator in the seed study's conditions)
PROBE = 0.1

#: the search's settings (the keyword arguments of :func:`checked_maneuver_inputs`)
SEARCH = ("n_limit", "max_hold", "dt", "periods", "steps", "tolerance", "resolution", "hold_resolution")

#: a run of the search: its conditions, their inputs (amplitude, hold), its records and the responses
Flown = tuple[np.ndarray, np.ndarray, np.ndarray, SimulationResult, np.ndarray]


@dataclass
class CheckedManeuverInputs:
    """The inputs found and their recorded simulation: amplitude (rad, magnitude) and hold (s) per condition, which
    search each took, the response reached, the records, their window and t_max."""

    amplitude: np.ndarray
    hold: np.ndarray
    reach: np.ndarray  # the full sinusoid reaches the target: the amplitude was searched
    held_short: np.ndarray  # even the longest hold does not reach it: the maximal input
    response: np.ndarray
    sim: SimulationResult
    valid: np.ndarray  # (T, n) within each run's window
    t_max: np.ndarray


def checked_maneuver_inputs(
    model: AircraftModel,
    x0: np.ndarray,
    u0: np.ndarray,
    nose_up: ArrayLike,
    omega: ArrayLike,
    available: ArrayLike,
    target: ArrayLike,
    *,
    n_limit: float,
    max_hold: float,
    dt: float,
    periods: float,
    steps: int,
    tolerance: float,
    resolution: float,
    hold_resolution: float,
) -> CheckedManeuverInputs:
    """The checked manoeuvre's input of every condition of ``model`` (n) from its trim ``x0``/``u0`` (module
    docstring): ``nose_up`` (n,) bool, ``omega`` (n,) rad/s, ``available`` (n,) rad of elevator from the trim to the
    stop the pilot can reach, ``target`` (n,) response to reach."""
    settings = {name: value for name, value in locals().items() if name in SEARCH}  # the keyword arguments
    up_all = np.asarray(nose_up, dtype=bool)
    omega_, available_, target_ = (np.asarray(a, dtype=float) for a in (omega, available, target))
    n = up_all.size
    repeated = _repeats(model, x0, u0, up_all, omega_, available_, target_)
    if repeated is not None:  # a condition repeated in the batch (one flight point twice) is searched once
        first, group = repeated
        per_condition = (x0[first], u0[first], up_all[first], omega_[first], available_[first], target_[first])
        once = checked_maneuver_inputs(model.subset(first), *per_condition, **settings)
        gathered = gather([(once.sim, int(g)) for g in group])
        if gathered is not None:
            return CheckedManeuverInputs(
                once.amplitude[group],
                once.hold[group],
                once.reach[group],
                once.held_short[group],
                once.response[group],
                gathered,
                _within(gathered, once.t_max[group]),
                once.t_max[group],
            )
    sign = np.where(up_all, -1.0, 1.0)
    n_lim, periods = float(n_limit), float(periods)
    Recorded = tuple[np.ndarray, SimulationResult, np.ndarray, np.ndarray]
    flown: list[Flown] = []  # every run of the search

    def t_max_of(rows: np.ndarray, hold_: np.ndarray) -> np.ndarray:
        """The end of the manoeuvre of the conditions ``rows`` held ``hold_``: 3π/(2ω) + Δt."""
        t_max: np.ndarray = 2 * periods * np.pi / (2 * omega_[rows]) + hold_
        return t_max

    def run(amp: np.ndarray, hold: np.ndarray, mask: np.ndarray | None = None) -> Recorded:
        """Simulate the conditions of ``mask`` (all by default): the response for the whole batch (NaN outside the
        mask), the records, their window and t_max."""
        idx = np.flatnonzero(np.ones(n, dtype=bool) if mask is None else mask)
        up = up_all[idx]
        sched = SinusoidHold(sign[idx] * amp[idx], omega_[idx], hold[idx])
        t_max = t_max_of(idx, hold[idx])
        stop = [
            Bound("n_z < 0 (nose up)", "n_z", lower=np.where(up, 0.0, -np.inf)),
            Bound("n_z > limit (nose down)", "n_z", upper=np.where(up, np.inf, n_lim)),
            Bound("t_max", "t", upper=t_max + 1e-9),
        ]
        sub = model if idx.size == n else model.subset(idx)
        sim = simulate(sub, x0[idx], u0[idx], float(t_max.max()) + dt, dt, inputs={"elevator": sched}, stop=stop)
        nz = sim["n_z"]
        valid = _within(sim, t_max)
        resp = np.full(n, np.nan)
        resp[idx] = np.where(up, peak_between_samples(nz, valid) - 1.0, 1.0 + peak_between_samples(-nz, valid))
        flown.append((idx, amp[idx], hold[idx], sim, resp[idx]))
        return resp, sim, valid, t_max

    def response(amp: np.ndarray, hold: np.ndarray, mask: np.ndarray | None = None) -> np.ndarray:
        return run(amp, hold, mask)[0]

    longest = float(max_hold)
    aim = target_ - 0.5 * float(tolerance)  # what the search aims at: within the tolerance below the target counts
    r_full = response(available_, np.zeros(n))
    reach = r_full >= aim
    r_held = np.where(reach, r_full, response(available_, np.full(n, longest), ~reach)) if (~reach).any() else r_full
    held_short = ~reach & (r_held < aim)  # even the longest hold does not reach the load factor: maximal input

    def inputs_of(p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """One parameter per condition: the amplitude fraction (sinusoid reaches the aim) or the
        hold fraction of the longest hold (full deflection)."""
        amp = np.where(reach, p * available_, available_)
        return amp, np.where(reach | held_short, 0.0, p * longest) + held_short * longest

    def searched(p: np.ndarray, mask: np.ndarray) -> np.ndarray:
        amp, hold = inputs_of(p)
        return response(amp, hold, mask)

    search = ~held_short
    lo, f_lo = np.zeros(n), np.where(reach, 0.0, r_full)
    hi, f_hi = np.ones(n), np.where(reach, r_full, r_held)
    first = np.full(n, np.nan)
    probe = reach & (np.abs(r_full - aim) > float(resolution))  # an amplitude search with a step to take
    if steps > 1 and probe.any():  # the probe is the amplitude search's first step (module docstring)
        b_lo, fb_lo, b_hi, fb_hi, first = linear_probe(searched, aim, r_full, probe, PROBE)
        lo, f_lo = np.where(probe, b_lo, lo), np.where(probe, fb_lo, f_lo)
        hi, f_hi = np.where(probe, b_hi, hi), np.where(probe, fb_hi, f_hi)
        steps -= 1
    p, r_p, p_lo, _, p_hi, _ = bisect_batch(
        searched,
        lo,
        hi,
        aim,
        steps=int(steps),
        tol=np.where(reach, float(resolution), 0.0),
        f_lo=f_lo,
        f_hi=f_hi,
        x_tol=np.where(reach, 0.0, float(hold_resolution) / longest),
        first=first,
    )
    # the hold is the minimum time that reaches the load factor: take the bracket end at or above it; an
    # amplitude search that did not converge (a response that jumps across the target near stall) takes the
    # largest amplitude found that does not exceed the load factor, as the paragraph scales the input down
    over = reach & (np.abs(r_p - target_) > float(tolerance)) & (r_p > target_)
    p = np.where(search & ~reach, p_hi, np.where(search, np.where(over, p_lo, p), 1.0))
    amp, hold = inputs_of(p)
    found = _already_flown(flown, amp, hold)
    if found is None:
        resp, sim, valid, t_max = run(amp, hold)  # all conditions, recorded
    else:  # every condition's input was flown by a step of the search: its records, not a run again
        resp, sim = found
        t_max = t_max_of(np.arange(n), hold)
        valid = _within(sim, t_max)
    return CheckedManeuverInputs(amp, hold, reach, held_short, resp, sim, valid, t_max)


def _repeats(model: AircraftModel, *per_condition: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The conditions searched once — the first of each group of equal rows of the model's condition data and the
    ``per_condition`` arrays (bit for bit) — and each condition's group; None when every condition is its own. A
    condition's search and run do not depend on its batch, so a repeat's are its first's."""
    n = model.n
    rows = np.ascontiguousarray(
        np.hstack([model.condition_data()] + [np.asarray(a, dtype=float).reshape(n, -1) for a in per_condition])
    )
    _, first, group = np.unique(
        rows.view(np.dtype((np.void, rows.itemsize * rows.shape[1]))).ravel(), return_index=True, return_inverse=True
    )
    return None if first.size == n else (first, group.ravel())


def _within(sim: SimulationResult, t_max: np.ndarray) -> np.ndarray:
    """(T, n): the records of ``sim`` within each condition's run (up to its stop and its ``t_max``)."""
    inside: np.ndarray = sim.t[:, None] <= np.minimum(sim.stop_time, t_max)[None, :] + 1e-9
    return inside


def _already_flown(flown: list[Flown], amp: np.ndarray, hold: np.ndarray) -> tuple[np.ndarray, SimulationResult] | None:
    """The responses and records of the inputs ``amp``/``hold`` (n,) gathered from the search's runs ``flown`` (the
    latest run of each condition with exactly those inputs, :func:`~certkit.models.dynamics.simulate.gather`), or
    None when a condition's input was not flown or its run cannot be gathered."""
    picks: list[tuple[SimulationResult, int] | None] = [None] * amp.shape[0]
    resp = np.full(amp.shape[0], np.nan)
    for idx, a, h, sim, r in flown:
        same = (a == amp[idx]) & (h == hold[idx])
        for k in np.flatnonzero(same):
            picks[idx[k]] = (sim, int(k))
            resp[idx[k]] = r[k]
    if any(p is None for p in picks):
        return None
    gathered = gather([p for p in picks if p is not None])
    return None if gathered is None else (resp, gathered)
