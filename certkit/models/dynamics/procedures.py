"""Simulated takeoff and landing procedures over a batch (no regulation content).

:func:`takeoff_run`
    From rest on the runway (gear in static equilibrium at idle thrust, :func:`ground_equilibrium`),
    brakes released at t = 0 with the throttles set to ``throttle`` (no spool-up); the elevator held at
    ``elevator0`` (and any ``settings``, e.g. a stabiliser at its takeoff setting, held throughout) until the
    rotation speed V_R, then the pilot's rotation (:class:`~certkit.models.dynamics.takeoff_pilot.RotationPilot`):
    attitude command rate-limited at ``rotation_rate`` toward ``theta_target`` while on the gear (at most the
    ``tail_strike`` attitude less ``tail_margin``), then toward the attitude that holds ``climb_speed`` once the
    wheels are clear of the runway, elevator by feed-forward (``elevator_ff``) and PI attitude feedback.
    :class:`WingsLevel` holds wings level / zero sideslip; optionally :class:`EngineFailure` fails ``failed_engine``
    at ``failure_speed`` (its thrust decaying with ``failure_decay_time``). Runs until the lowest gear point is
    ``screen_height`` above the runway with no gear load (or ``t_end``). Returns a :class:`TakeoffResult` with V_LOF
    (the lift-off for good: the first record of the airborne stretch that lasts to the end of the run, not a hop on
    the extending struts), the speed, distance and time at the screen height (the first record beyond it; the
    distance also interpolated to where the lowest wheel crosses it, ``x_screen_crossing``), the extreme elevator,
    the largest pitch attitude with a gear leg on the runway, the largest pitch rate before lift-off and the largest
    lateral deviation on the ground.
    ``lateral="heading"`` replaces the wings-level/zero-sideslip hold by :class:`HeadingHold` (rudder
    holds the runway heading and, with ``centreline_gain`` K_y, the centreline on the ground; aileron wings level
    on the ground and ``bank_airborne`` once airborne); ``climb_out`` (s) continues the run past the screen
    height, and the result then carries the climb gradient between records and from the screen height to the
    end of the run. ``lateral="pilot"`` flies the pedals as a pilot does (:class:`DirectionalPilot`: the same law,
    the rudder moved at most at ``rudder_rate`` and held for ``reaction_time`` after the engine failure; with
    ``steering`` the pedals also steer the nose wheel, for a model whose ground model has a steered leg).

:func:`runway_acceleration`
    Quasi-steady acceleration along the runway at a given speed, with a chosen set of engines
    operative (e.g. the speed gained with an engine failed over a recognition interval).

:func:`approach_and_landing`
    From trimmed states on the glide path, :class:`TECSApproach` flies the path, flares
    (exponential flare, throttle to idle at the flare height) and stops at touchdown (first gear
    load). Returns a :class:`LandingResult` with the rate of descent at touchdown and the extreme
    elevator.

Speeds are true airspeeds (m/s); heights in m; angles in rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.dynamics import pilot_kernel
from certkit.models.dynamics.controlled_run import KernelBlock, columns
from certkit.models.dynamics.controllers import EngineFailure, HeadingHold, TECSApproach, WingsLevel
from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.ground import gear_heights, ground_equilibrium, wheel_height
from certkit.models.dynamics.simulate import SimulationResult, simulate
from certkit.models.dynamics.takeoff_pilot import DirectionalPilot, RotationPilot


def _hdot(x13):
    q0, q1, q2, q3 = x13[:, 9:13].T
    return -(
        2 * (q1 * q3 - q0 * q2) * x13[:, 3]
        + 2 * (q2 * q3 + q0 * q1) * x13[:, 4]
        + (q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3) * x13[:, 5]
    )


@dataclass
class TakeoffResult:
    sim: SimulationResult
    x0: np.ndarray  # rest state (n, 12)
    initial_acceleration: np.ndarray  # m/s² along the runway at brake release
    reached: np.ndarray  # bool (n,): screen height reached
    v_lof: np.ndarray  # m/s TAS at the lift-off for good (nan if none; a hop on the extending struts is not one)
    x_lof: np.ndarray  # m from brake release
    v_screen: np.ndarray  # m/s at the screen height (nan if not reached)
    x_screen: np.ndarray
    t_screen: np.ndarray
    elevator_min: np.ndarray  # rad, most nose-up elevator
    elevator_max: np.ndarray
    wheel_height: np.ndarray  # (nt, n) lowest gear point above the runway
    gradient: np.ndarray | None = None  # (nt-1, n) climb gradient between records, airborne (nan on the ground)
    climb_gradient: np.ndarray | None = None  # (n,) mean gradient from the screen height to the end of the run
    screen_index: np.ndarray | None = None  # (n,) record index at the screen height
    pitch_on_ground_max: np.ndarray | None = None  # (n,) rad, largest attitude with a gear leg on the runway
    pitch_rate_max: np.ndarray | None = None  # (n,) rad/s, largest pitch rate from VR to lift-off
    lateral_on_ground_max: np.ndarray | None = None  # (n,) m, largest |y − y0| on the ground
    pitch_to_liftoff_max: np.ndarray | None = None  # (n,) rad, largest attitude up to the first lift-off
    x_screen_crossing: np.ndarray | None = None  # (n,) m, x_screen interpolated to where the wheel crosses the height


@dataclass
class LandingResult:
    sim: SimulationResult
    touched_down: np.ndarray  # bool (n,)
    sink_rate: np.ndarray  # m/s at touchdown (positive down)
    speed: np.ndarray  # m/s TAS at touchdown
    elevator_min: np.ndarray
    elevator_max: np.ndarray
    tau: np.ndarray  # flare time constant (s)
    approach_sink: np.ndarray  # m/s on the glide path


def _elevator_extremes(sim: SimulationResult, j: int):
    e = sim.controls[:, :, j]
    return e.min(axis=0), e.max(axis=0)


class ScreenHeight:
    """The takeoff's stop criterion: ``climb_out`` s after the lowest wheel first rises above ``screen_height`` over
    the runway with no gear load (``t_screen`` (n,): that instant, NaN until then)."""

    __name__ = "screen height"

    def __init__(self, model: AircraftModel, screen_height: float, climb_out: float):
        self.model, self.height, self.climb_out = model, float(screen_height), float(climb_out)
        self.elevation = model.ground.elevation
        self.t_screen = np.full(model.n, np.nan)

    def __call__(self, t, x, out):
        up = (wheel_height(self.model, x, self.elevation) > self.height) & (out.gear_load.sum(axis=1) <= 0.0)
        self.t_screen[np.isnan(self.t_screen) & up] = t
        return t >= self.t_screen + self.climb_out - 1e-9

    def kernel_block(self) -> KernelBlock:
        """This criterion for a compiled run (:mod:`certkit.models.dynamics.controlled_run`)."""

        def restore(s):
            self.t_screen[:] = s[:, 0]

        consts = np.array([self.elevation, self.height, self.climb_out])
        n = self.t_screen.shape[0]
        return KernelBlock(
            "stop", pilot_kernel.SCREEN_HEIGHT, consts, np.zeros((n, 1)), columns(n, self.t_screen), restore, self
        )


class Touchdown:
    """The landing's stop criterion: the first gear load."""

    __name__ = "touchdown"

    def __call__(self, t, x, out):
        return out.gear_load.sum(axis=1) > 0.0

    def kernel_block(self) -> KernelBlock:
        """This criterion for a compiled run (:mod:`certkit.models.dynamics.controlled_run`)."""
        empty = np.zeros((0, 1))
        return KernelBlock("stop", pilot_kernel.TOUCHDOWN, np.zeros(1), empty, empty, lambda s: None, self)


def takeoff_run(
    model: AircraftModel,
    rotation_speed,
    theta_target,
    climb_speed=None,
    throttle: float = 1.0,
    elevator0=0.0,
    settings=None,
    elevator_ff=None,
    tail_strike=None,
    tail_margin: float = np.radians(2.0),
    rotation_rate: float = np.radians(2.5),
    screen_height: float = 35 * 0.3048,
    elevator_limits=(-np.radians(30), np.radians(25)),
    lateral_limits=None,
    failed_engine: str | None = None,
    failure_speed=None,
    failure_decay_time: float | None = None,
    t_end: float = 120.0,
    dt: float = 0.05,
    lateral: str = "wings level",
    bank_airborne=0.0,
    climb_out: float = 0.0,
    centreline_gain: float = 0.004,
    reaction_time: float = 0.0,
    rudder_rate: float | None = None,
    steering: float | None = None,
) -> TakeoffResult:
    n = model.n
    u = np.zeros((n, len(model.control_names)))
    for name, value in (settings or {}).items():
        u[:, model.control_index(name)] = value
    u[:, model.throttle_slice] = throttle
    je = model.control_index("elevator")
    u[:, je] = elevator0
    idle = u.copy()
    idle[:, model.throttle_slice] = 0.0
    x0 = ground_equilibrium(model, idle)  # at rest on the brakes, engines idle; then takeoff thrust and release
    xd = model.derivatives_euler(x0, u)
    th = x0[:, 10]
    a0 = np.cos(th) * xd[:, 3] + np.sin(th) * xd[:, 5]
    ctrls = [
        RotationPilot(
            model,
            u,
            rotation_speed,
            theta_target,
            np.nan if climb_speed is None else climb_speed,
            rotation_rate=rotation_rate,
            elevator_ff=elevator_ff,
            tail_strike=tail_strike,
            tail_margin=tail_margin,
            limits=elevator_limits,
        ),
        WingsLevel(model, u, limits=lateral_limits)
        if lateral == "wings level"
        else HeadingHold(model, u, bank=bank_airborne, limits=lateral_limits, k_y=centreline_gain),
    ]
    failure = None
    if failed_engine is not None:
        failure = EngineFailure(model, failed_engine, failure_speed, decay_time=failure_decay_time)
    if lateral == "pilot":
        ctrls[1] = DirectionalPilot(
            model,
            u,
            failure,
            reaction_time,
            rudder_rate or np.inf,
            steering,
            bank=bank_airborne,
            limits=lateral_limits,
            k_y=centreline_gain,
        )
    if failure is not None:
        ctrls.append(failure)
    screen = ScreenHeight(model, screen_height, climb_out)
    sim = simulate(model, x0, u, t_end, dt, controllers=ctrls, stop=[screen])
    t_scr = screen.t_screen
    nt = sim.t.size
    x12 = np.zeros((nt * n, 12))
    x12[:, 2], x12[:, 9], x12[:, 10] = sim["h"].ravel(), sim["phi"].ravel(), sim["theta"].ravel()
    idx = np.tile(np.arange(n), nt)
    heights = gear_heights(model.subset(idx), x12).reshape(nt, n, -1)
    wheel = heights.min(axis=2)
    reached = np.isfinite(t_scr)
    airborne = wheel > 0.0
    k_end = np.minimum(np.searchsorted(sim.t, sim.stop_time - 1e-9), nt - 1)
    # the lift-off for good: the first record of the airborne stretch that lasts to the end of the run (a hop on the
    # extending struts, the wheels back on the runway a moment later, is not the lift-off)
    k_lof = np.full(n, nt, dtype=int)
    for i in range(n):
        if airborne[k_end[i], i]:
            ground = np.flatnonzero(~airborne[: k_end[i] + 1, i])
            k_lof[i] = ground[-1] + 1 if ground.size else 0
    lifted = k_lof < nt
    cols = np.arange(n)
    k_at = np.minimum(k_lof, nt - 1)
    v_lof = np.where(lifted, sim["V"][k_at, cols], np.nan)
    x_lof = np.where(lifted, sim["x_N"][k_at, cols], np.nan)
    k_scr = np.minimum(np.searchsorted(sim.t, np.where(reached, t_scr, sim.t[-1]) - 1e-9), nt - 1)
    v_scr = np.where(reached, sim["V"][k_scr, cols], np.nan)
    x_scr = np.where(reached, sim["x_N"][k_scr, cols] - x0[:, 0], np.nan)
    t_scr = np.where(reached, t_scr, np.nan)
    # the record at the screen height is the first beyond it: between it and the one before, the lowest wheel's height
    # is interpolated linearly for the distance at which it crosses the screen height (within a step's travel)
    k_before = np.maximum(k_scr - 1, 0)
    h_before, h_at = wheel[k_before, cols], wheel[k_scr, cols]
    with np.errstate(invalid="ignore", divide="ignore"):
        frac = np.where(h_at > h_before, np.clip((screen_height - h_before) / (h_at - h_before), 0.0, 1.0), 1.0)
    x_before = sim["x_N"][k_before, cols]
    x_cross = np.where(reached, x_before + frac * (sim["x_N"][k_scr, cols] - x_before) - x0[:, 0], np.nan)
    # climb gradient (height gained per horizontal distance) between successive records, airborne only
    s_path = np.concatenate(
        [np.zeros((1, n)), np.cumsum(np.hypot(np.diff(sim["x_N"], axis=0), np.diff(sim["y_E"], axis=0)), axis=0)]
    )
    with np.errstate(invalid="ignore", divide="ignore"):
        grad = np.diff(sim["h"], axis=0) / np.diff(s_path, axis=0)
    grad = np.where(airborne[1:] & airborne[:-1], grad, np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        climb = np.where(
            reached & (k_end > k_scr),
            (sim["h"][k_end, cols] - sim["h"][k_scr, cols]) / (s_path[k_end, cols] - s_path[k_scr, cols]),
            np.nan,
        )
    emin, emax = _elevator_extremes(sim, je)
    on_ground = ~airborne & (np.arange(nt)[:, None] <= k_end[None, :])
    vr = np.broadcast_to(np.asarray(rotation_speed, dtype=float), (n,))
    to_lof = np.arange(nt)[:, None] < k_lof[None, :]  # the records before the lift-off
    before_lof = (sim["V"] >= vr[None, :]) & to_lof
    with np.errstate(invalid="ignore"):
        pitch_ground = np.where(on_ground, sim["theta"], -np.inf).max(axis=0)
        rate_max = np.where(before_lof, sim["q"], -np.inf).max(axis=0)
        pitch_to_lof = np.where(to_lof, sim["theta"], -np.inf).max(axis=0)
    lateral_ground = np.where(on_ground, np.abs(sim["y_E"] - sim["y_E"][0]), 0.0).max(axis=0)
    return TakeoffResult(
        sim,
        x0,
        a0,
        reached,
        v_lof,
        x_lof - x0[:, 0],
        v_scr,
        x_scr,
        t_scr,
        emin,
        emax,
        wheel,
        grad,
        climb,
        k_scr,
        pitch_ground,
        np.where(np.isfinite(rate_max), rate_max, np.nan),
        lateral_ground,
        pitch_to_lof,
        x_cross,
    )


def runway_acceleration(model: AircraftModel, speed, throttle: float = 1.0, operative=None) -> np.ndarray:
    """Acceleration (m/s², along the runway) of the batch rolling at ``speed`` (m/s TAS, along the runway) in the
    attitude and gear compression of rest (:func:`ground_equilibrium` at idle), throttles at ``throttle``, with
    the engines ``operative`` ((n, n_engines) booleans; the model's own when None; restored after). The gear
    carries the weight of rest: the lift at ``speed`` would unload it and lower the rolling friction (μ_roll L),
    which this quasi-steady value leaves out."""
    u = np.zeros((model.n, len(model.control_names)))
    x = ground_equilibrium(model, u)
    u[:, model.throttle_slice] = throttle
    th = x[:, 10]
    v = np.broadcast_to(np.asarray(speed, dtype=float), (model.n,))
    x[:, 3], x[:, 5] = v * np.cos(th), v * np.sin(th)
    saved = model.operative.copy()
    try:
        if operative is not None:
            model.set_operative(operative)
        xd = model.derivatives_euler(x, u)
    finally:
        model.set_operative(saved)
    return np.cos(th) * xd[:, 3] + np.sin(th) * xd[:, 5]


def engine_failure_speed(
    model: AircraftModel, v1: float, engine: str, recognition_time: float, decay_time: float | None = None
) -> tuple[np.ndarray, str]:
    """VEF (m/s TAS, one per condition) such that V1 is reached ``recognition_time`` after the failure of ``engine``
    (§25.107(a)(2)), at the runway accelerations of :func:`runway_acceleration` at V1 (``v1``, m/s TAS): engine out,
    or, with the failed engine's thrust decaying as e^(−t/τ) (``decay_time`` τ), from the all-engines value to it;
    and how it was obtained."""
    names = [e.name for e in model.engines]
    op = np.ones((model.n, len(names)), dtype=bool)
    op[:, names.index(engine)] = False
    a = runway_acceleration(model, v1, operative=op)
    if not decay_time:
        return v1 - a * recognition_time, f"V1 less {recognition_time:g} s of the engine-out acceleration at V1"
    a_all = runway_acceleration(model, v1)
    gain = a * recognition_time + (a_all - a) * decay_time * (1.0 - np.exp(-recognition_time / decay_time))
    return v1 - gain, (
        f"V1 less the speed gained over {recognition_time:g} s after the failure at V1's "
        f"accelerations (engine-out, plus the decaying thrust of the failed engine, τ = {decay_time:g} s)"
    )


def approach_and_landing(
    model: AircraftModel,
    x0: np.ndarray,
    u0: np.ndarray,
    glide: float = np.radians(-3.0),
    flare_height: float = 15.0,
    aim_below: float = 1.0,
    elevator_limits=(-np.radians(30), np.radians(25)),
    lateral_limits=None,
    t_end: float = 90.0,
    dt: float = 0.05,
) -> LandingResult:
    u = np.zeros((model.n, len(model.control_names)))
    u0 = np.asarray(u0, dtype=float)
    u[:, : u0.shape[1]] = u0
    tecs = TECSApproach(
        model, x0, u, glide=glide, flare_height=flare_height, aim_below=aim_below, limits=elevator_limits
    )
    sim = simulate(
        model,
        x0,
        u,
        t_end,
        dt,
        controllers=[tecs, WingsLevel(model, u, limits=lateral_limits)],
        stop=[Touchdown()],
    )
    touched = np.array([r == "touchdown" for r in sim.stop_reason])
    sink = np.where(touched, -_hdot(sim.final_state), np.nan)
    speed = np.where(touched, np.linalg.norm(sim.final_state[:, 3:6], axis=1), np.nan)
    emin, emax = _elevator_extremes(sim, model.control_index("elevator"))
    return LandingResult(sim, touched, sink, speed, emin, emax, tecs.tau, tecs.sink)


__all__ = [
    "ScreenHeight",
    "Touchdown",
    "takeoff_run",
    "runway_acceleration",
    "approach_and_landing",
    "TakeoffResult",
    "LandingResult",
]
