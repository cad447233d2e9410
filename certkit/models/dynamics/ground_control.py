"""The minimum control speed on the ground by simulation: engine cuts on the takeoff run, rudder only (no regulation
numbers here: the deviation bound, the reaction time and the pedal rate are the caller's).

:func:`engine_cut_runs`
    Each row of the batch rolls along the centreline with every engine at ``throttle`` (from about
    ``lead_time`` before the failure, at the quasi-steady runway acceleration of the failure speed, at the attitude
    and gear compression of rest), any ``settings`` (e.g. a stabiliser at its takeoff setting) held and the elevator
    holding the attitude of rest (the nose wheel on the runway, no rotation); ``engine`` fails when the airspeed
    reaches the row's ``failure_speed`` (its thrust decaying with ``decay_time``,
    :class:`~certkit.models.dynamics.controllers.EngineFailure`);
    the pilot (:class:`~certkit.models.dynamics.takeoff_pilot.DirectionalPilot`, no nose-wheel steering) holds the
    rudder for ``reaction_time`` after the failure, then flies the heading and centreline with the rudder moved at most
    at ``rudder_rate``; the ailerons hold the wings level. The model's nose wheel should caster (a ground model built
    with ``nose_wheel="castering"``): the rudder alone keeps the direction. The run of a row ends when the heading,
    after its swing toward the failed engine, is back parallel to the centreline (the recovery), or ``after`` s after
    the failure, or when the gear leaves the runway first (a light airplane lifts off at the attitude of rest, an
    unrotated lift-off, before its heading has recovered: the takeoff run is over). Returned per row: the largest
    lateral deviation from the centreline between the failure and the recovery or that lift-off (m; infinite when
    the heading did not recover within the run on the runway), whether the run ended in the lift-off, the heading
    swing and the peak rudder.

:func:`ground_minimum_control_speed`
    For each condition of the batch, the failure speed at which the largest lateral deviation of
    :func:`engine_cut_runs` equals ``deviation_limit``: the runs over ``grid`` failure speeds from 0.85 to 1.15 times
    the static rudder-moment balance speed (:func:`rudder_balance_speed`: one batch of model evaluations; a run costs
    its steps, so one pass of runs where VMCG lies is cheaper than a coarse pass over the whole range and a refining
    one), more toward the range's ends only where the crossing lies outside, the speed interpolated linearly in the
    bracket (the deviation falls as the failure speed rises: the rudder's power grows with q̄ while the
    thrust asymmetry does not). A condition whose deviation stays within the bound at the lowest speed of the grid is
    reported at that speed with ``below`` set (VMCG no higher); one beyond the bound at the highest with ``above`` set.
    A run that lifts off before its heading recovers (``airborne``) counts with its deviation on the runway: the
    minimum control speed on the ground is about the takeoff run ("the calibrated airspeed during the takeoff run"),
    and a simulator's VMCG test asks for the recovery "with the main gear on the ground" (14 CFR Part 60, Appendix A,
    test 1.b.2): beyond the bound there, it failed on the runway; within it with the swing arrested on the runway
    (the heading already turning back at the lift-off: ``arrested``), the rudder held the path for the whole takeoff
    run after the cut (what follows is the air minimum control speed's case); within it with the heading still
    swinging away, it decides nothing and is left out (a condition without a deciding run has no speed, NaN).
    ``lifted`` says which of the runs kept lifted off.

Speeds are true airspeeds (m/s), lengths m, angles rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.dynamics import pilot_kernel
from certkit.models.dynamics.controlled_run import KernelBlock, columns
from certkit.models.dynamics.controllers import EngineFailure, PitchAttitudeHold
from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.ground import ground_equilibrium
from certkit.models.dynamics.procedures import runway_acceleration
from certkit.models.dynamics.simulate import SimulationResult, simulate
from certkit.models.dynamics.takeoff_pilot import DirectionalPilot

#: heading swing (rad) below which a row has not yet swung (its recovery is not looked for before)
_SWING = np.radians(0.02)


@dataclass
class EngineCutRuns:
    failure_speed: np.ndarray  # (n,) m/s TAS
    deviation: np.ndarray  # (n,) m, largest |y| from the failure to the recovery (inf: not recovered)
    recovered: np.ndarray  # (n,) bool
    heading_swing: np.ndarray  # (n,) rad, largest |ψ| after the failure
    rudder_peak: np.ndarray  # (n,) rad, largest |δr|
    recovery_time: np.ndarray  # (n,) s after the failure (nan: not recovered)
    airborne: np.ndarray  # (n,) bool: the gear left the runway before the recovery (the deviation up to then)
    arrested: np.ndarray  # (n,) bool: airborne with the swing arrested (the heading turning back) at the lift-off
    sim: SimulationResult


@dataclass
class GroundControlSpeed:
    speed: np.ndarray  # (n,) m/s TAS, the failure speed at which the deviation equals the bound
    below: np.ndarray  # (n,) bool: within the bound at the lowest speed searched
    above: np.ndarray  # (n,) bool: beyond the bound at the highest speed searched
    speeds: list  # per condition, the failure speeds run (sorted)
    deviations: list  # per condition, their deviations (m)
    lifted: list  # per condition, whether each of those runs lifted off before its heading recovered
    undecided: list  # per condition, the failure speeds (sorted) of the runs left out: lifted off still swinging
    runs: list  # the EngineCutRuns of each pass
    balance_speed: np.ndarray  # (n,) m/s TAS, the static rudder-moment balance the search started from (NaN: none)


class EngineCutEnd:
    """The end of an engine-cut run (:func:`engine_cut_runs`): the heading back parallel to the centreline after its
    swing (``recovered``), ``after`` s past the failure, the gear off the runway once the pilot reacts (``airborne``;
    ``arrested``: the yaw rate then back toward the runway) or ``departure`` m off the centreline (from ``y0``)."""

    __name__ = "recovered"

    def __init__(self, failure: EngineFailure, y0: np.ndarray, reaction_time: float, after: float, departure: float):
        n = y0.shape[0]
        self.failure, self.y0 = failure, y0
        self.reaction_time, self.after, self.departure = float(reaction_time), float(after), float(departure)
        self.swing_sign = np.zeros(n)
        self.recovered = np.zeros(n, dtype=bool)
        self.airborne = np.zeros(n, dtype=bool)
        self.arrested = np.zeros(n, dtype=bool)

    def __call__(self, t, x, out):
        q0, q1, q2, q3 = x[:, 9], x[:, 10], x[:, 11], x[:, 12]
        psi = np.arctan2(2.0 * (q0 * q3 + q1 * q2), 1.0 - 2.0 * (q2 * q2 + q3 * q3))
        t_fail, swing_sign = self.failure.fail_time, self.swing_sign
        failed = np.isfinite(t_fail)
        started = failed & (swing_sign == 0.0) & (np.abs(psi) > _SWING)
        swing_sign[started] = np.sign(psi[started])
        back = failed & (swing_sign != 0.0) & (psi * swing_sign <= 0.0)
        self.recovered[back] = True
        with np.errstate(invalid="ignore"):
            late = failed & (t >= t_fail + self.after)
            reacted = failed & (t >= t_fail + self.reaction_time)
        up = reacted & ~back & (out.gear_load.sum(axis=1) <= 0.0)
        self.airborne[up] = True
        # the yaw rate back toward the runway
        self.arrested[up] = (swing_sign[up] != 0.0) & (x[up, 8] * swing_sign[up] < 0.0)
        return back | late | up | (np.abs(x[:, 1] - self.y0) > self.departure)

    def kernel_block(self) -> KernelBlock:
        """This criterion for a compiled run (:mod:`certkit.models.dynamics.controlled_run`)."""

        def restore(s):
            self.swing_sign[:] = s[:, 0]
            self.recovered[:], self.airborne[:], self.arrested[:] = s[:, 1] != 0.0, s[:, 2] != 0.0, s[:, 3] != 0.0

        n = self.y0.shape[0]
        consts = np.array([_SWING, self.reaction_time, self.after, self.departure])
        state = columns(n, self.swing_sign, self.recovered, self.airborne, self.arrested)
        block = KernelBlock("stop", pilot_kernel.ENGINE_CUT, consts, columns(n, self.y0), state, restore, self)
        block.waits_for = self.failure
        return block


def engine_cut_runs(
    model: AircraftModel,
    failure_speed,
    engine: str,
    reaction_time: float,
    rudder_rate: float,
    decay_time: float | None = None,
    throttle: float = 1.0,
    settings=None,
    lateral_limits=None,
    lead_time: float = 3.0,
    after: float = 15.0,
    dt: float = 0.1,
    centreline_gain: float = 0.004,
    departure: float = 60.0,
    elevator_limits=(-np.radians(30), np.radians(20)),
) -> EngineCutRuns:
    """The engine-cut runs of the batch (module docstring); ``departure`` (m) off the centreline ends a row early."""
    n = model.n
    vf = np.broadcast_to(np.asarray(failure_speed, dtype=float), (n,)).copy()
    u = np.zeros((n, len(model.control_names)))
    for name, value in (settings or {}).items():
        u[:, model.control_index(name)] = value
    x0 = ground_equilibrium(model, u)  # attitude and gear compression of rest, engines idle
    u[:, model.throttle_slice] = throttle
    v0 = np.maximum(vf - runway_acceleration(model, vf, throttle) * lead_time, 1.0)
    x0[:, 3], x0[:, 5] = v0 * np.cos(x0[:, 10]), v0 * np.sin(x0[:, 10])
    # the column holds the attitude of rest: the nose wheel stays on the runway (no rotation)
    pitch = PitchAttitudeHold(model, u, 0.0, x0[:, 10], limits=elevator_limits)
    failure = EngineFailure(model, engine, vf, decay_time=decay_time)
    pilot = DirectionalPilot(
        model, u, failure, reaction_time, rudder_rate, None, limits=lateral_limits, k_y=centreline_gain
    )
    y0 = x0[:, 1].copy()
    end = EngineCutEnd(failure, y0, reaction_time, after, departure)
    t_end = lead_time * 3.0 + after + 10.0
    sim = simulate(model, x0, u, t_end, dt, controllers=[pitch, pilot, failure], stop=[end])
    recovered, airborne, arrested = end.recovered, end.airborne, end.arrested
    k_fail = np.argmax(sim["V"] >= vf[None, :], axis=0)
    nt = sim.t.size
    k = np.arange(nt)[:, None]
    window = (k >= k_fail[None, :]) & (sim.t[:, None] <= sim.stop_time[None, :] + 1e-9)
    y = np.abs(sim["y_E"] - y0[None, :])
    dev = np.where(window, y, 0.0).max(axis=0)
    dev = np.where(recovered | airborne, dev, np.inf)
    swing = np.where(window, np.abs(sim["psi"]), 0.0).max(axis=0)
    rudder = np.abs(sim.controls[:, :, model.control_index("rudder")]).max(axis=0)
    t_rec = np.where(recovered, sim.stop_time - sim.t[np.minimum(k_fail, nt - 1)], np.nan)
    return EngineCutRuns(vf, dev, recovered, swing, rudder, t_rec, airborne, arrested, sim)


def rudder_balance_speed(
    model: AircraftModel,
    engine: str,
    rudder_limits,
    low: float,
    high: float,
    settings=None,
    throttle: float = 1.0,
    points: int = 25,
) -> np.ndarray:
    """The speed (m/s TAS, one per condition; NaN where none between ``low`` and ``high``) at which the rudder on its
    stop balances the yawing moment of ``engine`` failed (windmilling) and the others at ``throttle``: straight,
    wings level, no sideslip, no rates, clear of the runway — the static rudder-moment balance, where the search of
    :func:`ground_minimum_control_speed` looks first."""
    n, m = model.n, points
    rows = np.repeat(np.arange(n), m)
    sub = model.subset(rows)
    names = [e.name for e in sub.engines]
    op = np.ones((sub.n, len(names)), dtype=bool)
    op[:, names.index(engine)] = False
    sub.set_operative(op)
    v = np.tile(np.linspace(low, high, m), n)
    x = np.zeros((sub.n, 12))
    x[:, 2] = sub.ground.elevation + 30.0 + np.abs(sub.r_gear[:, :, 2]).max(axis=1) if sub.ground is not None else 30.0
    x[:, 3] = v
    u = np.zeros((sub.n, len(sub.control_names)))
    for name, value in (settings or {}).items():
        u[:, sub.control_index(name)] = np.broadcast_to(np.asarray(value, dtype=float), (n,))[rows]
    u[:, sub.throttle_slice] = throttle
    jr = sub.control_index("rudder")
    yaw = {}
    for stop in rudder_limits:
        u[:, jr] = stop
        yaw[stop] = sub.derivatives_euler(x, u)[:, 8].reshape(n, m)
    u[:, jr] = 0.0
    free = sub.derivatives_euler(x, u)[:, 8].reshape(n, m)
    out = np.full(n, np.nan)
    for c in range(n):
        sign = np.sign(free[c, -1])
        for stop in rudder_limits:
            r = -yaw[stop][c] * sign  # the stop that opposes the failure's yaw turns positive past the balance
            k = np.flatnonzero((r[:-1] < 0.0) & (r[1:] >= 0.0))
            if k.size:
                k0 = k[0]
                vv = v.reshape(n, m)[c]
                out[c] = vv[k0] + (vv[k0 + 1] - vv[k0]) * (-r[k0]) / (r[k0 + 1] - r[k0])
    return out


def ground_minimum_control_speed(
    model: AircraftModel,
    engine: str,
    low: float,
    high: float,
    deviation_limit: float,
    reaction_time: float,
    rudder_rate: float,
    grid: int = 9,
    extend: int = 4,
    window=(0.85, 1.15),
    settings=None,
    **runs,
) -> GroundControlSpeed:
    """The failure speed of each condition at which the deviation equals ``deviation_limit`` (module docstring),
    searched from ``low`` to ``high`` (m/s TAS): ``grid`` failure speeds across ``window`` × the static rudder-moment
    balance speed (:func:`rudder_balance_speed`, the rudder at its stop in ``runs["lateral_limits"]``; the whole range
    where it has none), then, for a condition whose crossing lies outside them, ``extend`` more toward ``low`` or
    ``high``; ``settings`` (control → value, one or (n,) per condition) held; ``runs`` go to :func:`engine_cut_runs`."""
    n = model.n
    speeds = [[] for _ in range(n)]
    devs = [[] for _ in range(n)]
    lifted = [[] for _ in range(n)]
    undecided = [[] for _ in range(n)]
    passes = []
    limits = (runs.get("lateral_limits") or {}).get("rudder", (-np.radians(25), np.radians(25)))
    guess = rudder_balance_speed(model, engine, limits, low, high, settings)
    lo = np.where(np.isfinite(guess), np.maximum(low, window[0] * guess), low)
    hi = np.where(np.isfinite(guess), np.minimum(high, window[1] * guess), high)
    plan = {c: np.linspace(lo[c], hi[c], grid) for c in range(n)}
    for _ in range(3):
        if not plan:
            break
        cond = np.array(sorted(plan))
        rows = np.concatenate([np.full(plan[c].size, c) for c in cond])
        vf = np.concatenate([plan[c] for c in cond])
        held = {k: np.broadcast_to(np.asarray(v, dtype=float), (n,))[rows] for k, v in (settings or {}).items()}
        res = engine_cut_runs(model.subset(rows), vf, engine, reaction_time, rudder_rate, settings=held, **runs)
        passes.append(res)
        for i, (v, d) in enumerate(zip(vf, res.deviation)):
            if res.airborne[i] and d <= deviation_limit and not res.arrested[i]:
                undecided[rows[i]].append(float(v))  # off the runway within the bound, the swing not arrested
                continue
            speeds[rows[i]].append(float(v))
            devs[rows[i]].append(float(d))
            lifted[rows[i]].append(bool(res.airborne[i]))
        plan = {}
        for c in cond:
            order = np.argsort(speeds[c])
            v, d = np.asarray(speeds[c])[order], np.asarray(devs[c])[order]
            speeds[c], devs[c], lifted[c] = list(v), list(d), [lifted[c][k] for k in order]
            if v.size == 0:  # every run lifted off undecided: look lower
                if lo[c] > low * (1 + 1e-9):
                    plan[c] = np.linspace(low, lo[c], extend + 1)[:-1]
                    lo[c] = low
                continue
            beyond = np.flatnonzero(d > deviation_limit)
            if beyond.size == 0 and v[0] > low * (1 + 1e-9):  # within the bound throughout: look lower
                plan[c] = np.linspace(low, v[0], extend + 1)[:-1]
            elif beyond.size and beyond[-1] == v.size - 1 and v[-1] < high * (1 - 1e-9):  # beyond throughout: higher
                plan[c] = np.linspace(v[-1], high, extend + 1)[1:]
        # a run already made (decided or undecided) is not made again: above undecided runs the same speeds come back
        for c, p in list(plan.items()):
            made = {*speeds[c], *undecided[c]}
            plan[c] = p[[float(s) not in made for s in p]]
        plan = {c: p for c, p in plan.items() if p.size}
    speed = np.empty(n)
    below, above = np.zeros(n, dtype=bool), np.zeros(n, dtype=bool)
    for c in range(n):
        v, d = np.asarray(speeds[c]), np.asarray(devs[c])
        beyond = np.flatnonzero(d > deviation_limit)
        if v.size == 0:
            speed[c] = np.nan
        elif beyond.size == 0:
            speed[c], below[c] = v[0], True
        elif beyond[-1] == v.size - 1:
            speed[c], above[c] = v[-1], True
        else:
            k = beyond[-1]
            d0 = min(d[k], 10.0 * deviation_limit)  # an unrecovered run counts as far beyond the bound
            speed[c] = v[k] + (v[k + 1] - v[k]) * (d0 - deviation_limit) / (d0 - d[k + 1])
    return GroundControlSpeed(speed, below, above, speeds, devs, lifted, [sorted(u) for u in undecided], passes, guess)


__all__ = [
    "EngineCutEnd",
    "engine_cut_runs",
    "ground_minimum_control_speed",
    "rudder_balance_speed",
    "EngineCutRuns",
    "GroundControlSpeed",
]
