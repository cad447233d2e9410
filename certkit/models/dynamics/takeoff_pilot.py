"""The takeoff rotation a pilot flies (vectorised over the batch).

:class:`RotationPilot`
    The pitch technique of the transport-airplane takeoff (Boeing, *The importance of proper rotation technique*,
    Flight Operations Review, 14 March 1986: rotation initiated at VR, a smooth continuous manoeuvre to the target
    pitch attitude at typically 2–3°/s, not more than 3°/s; the lift-off attitude about 2–4° below the tail-strike
    attitude, the least tail clearance just after the lift-off; Boeing 777 FCTM §3: lift-off attitude 8.5°, tail
    strike at 12.1° for the 777-200 with the struts extended):
      * below VR the elevator stays at its take-off setting ``u0`` (the stabiliser, if any, at its setting);
      * from VR the pilot flies a commanded rate θ̇_c: the rotation rate r, changed by at most r per ``lead_time``
        (0.5 s) and slowed in time to stop on the target, so a rotation starts, stops or reverses smoothly; the
        commanded attitude θ_c integrates it but never runs more than r × ``lead_time`` ahead of the attitude. The
        rate asked for is not cut when the airplane lags (with an engine out it pitches up less readily): the rate
        feedback pulls harder, as a pilot pulls until he sees the rate;
      * the target: ``theta_ground`` on the runway — at most the tail-strike attitude less ``tail_margin`` —, held
        until the airplane flies off: the lowest wheel ``clear_height`` (0.3 m) above the runway. A wheel that
        leaves it for a moment as the struts extend does not count: rotating on then sets the wheels back down
        nearer the tail-strike attitude. Then the climb attitude, θ_air = θ_climb + K_V (V − V_climb) +
        K_VI ∫(V − V_climb) dt, with θ_climb = θ_off + V̇_off/g the attitude the acceleration there could hold in a
        climb (its potential flight path; V̇ the speed trend, a ``trend_time`` first-order lag of the acceleration),
        corrected for the speed error (the flight director's speed-on-pitch law: V2 with an engine out, a few knots
        more with all engines): the rotation goes on toward it rather than pausing below the climb speed;
      * the elevator: feed-forward plus proportional–integral attitude feedback and rate feedback on the commanded
        rate,
            δe = δe_ff + K_θ (θ − θ_c) + K_I ∫(θ − θ_c) dt + K_q (q − θ̇_c)   (positive δe nose-down, Etkin)
        with δe_ff the elevator of the airborne climb (e.g. the V2 trim's), the integral frozen while the elevator
        is on its stop in the error's direction (anti-windup), clipped to the elevator ``limits``.
    How fast the airplane follows is the airplane's (its elevator power against the weight on the main gear).
    Gains K_θ 6 (rad/rad), K_I 1 /s, K_q 6 s, K_V 1°/(m/s), K_VI 0.1°/m are a choice, made on the baseline: the pitch
    rate before lift-off within the 3°/s ceiling at every CG (2.7–3.0°/s) and the held attitude reached one lead time
    after the ideal rotation (with K_θ 3, K_I 0.5 and a command slowed to the lagging airplane's rate, the
    engine-out airplane rotated at 1.1–1.8°/s for two seconds and then sat 0.6° short of the target for 4 s).

:class:`DirectionalPilot`
    The pedals of the takeoff run: the heading-and-centreline law of
    :class:`~certkit.models.dynamics.controllers.HeadingHold` (``k_y`` > 0 tracks the centreline) says where the
    rudder should be; the pilot's rudder follows it at most at ``rudder_rate`` (a pedal pushed by a foot, not a
    step), and after an engine failure (``failure``, an :class:`~certkit.models.dynamics.controllers.EngineFailure`)
    stays where it was for ``reaction_time`` — the pilot does not anticipate the failure — before it moves. With
    ``steering`` (rad at full pedal) the pedals also turn the steered nose wheel in proportion,
        δ_nw = −steering · δr / max|rudder travel|   (right pedal: rudder δr < 0, nose wheel right > 0),
    while a gear leg carries load (the model's ``nose_wheel_steering`` control; none airborne).
    The law's gains are firmer than the heading hold's (K_ψ 15 rad/rad, K_I 2 /s, K_r 10 s against 3, 1, 3): a yaw
    rate of 1°/s asks for 10° of rudder and a heading error of 1° for 15°, so that once the pilot reacts the pedal
    moves at his rate rather than at the pace of a small heading error (with the heading hold's gains the baseline's
    rudder reached its stop only ~7 s after a failure at 147 kn, and the run left the 30-ft band of the centreline).
"""

from __future__ import annotations

import numpy as np

from certkit.models.dynamics import pilot_kernel
from certkit.models.dynamics.controlled_run import KernelBlock, columns
from certkit.models.dynamics.controllers import HeadingHold, on_stop
from certkit.models.dynamics.eom import STEERING, AircraftModel
from certkit.models.dynamics.ground import wheel_height
from certkit.models.dynamics.simulate import Controller


class RotationPilot(Controller):
    def __init__(
        self,
        model: AircraftModel,
        u0: np.ndarray,
        rotation_speed,
        theta_ground,
        climb_speed,
        rotation_rate: float = np.radians(2.5),
        elevator_ff=None,
        tail_strike=None,
        tail_margin: float = np.radians(2.0),
        clear_height: float = 0.3,
        k_theta: float = 6.0,
        k_i: float = 1.0,
        k_q: float = 6.0,
        k_v: float = np.radians(1.0),
        k_vi: float = np.radians(0.1),
        lead_time: float = 0.5,
        trend_time: float = 1.0,
        elevator: str = "elevator",
        limits=(-np.radians(30), np.radians(20)),
    ):
        n = model.n
        self.model = model
        self.j = model.control_index(elevator)
        self.de0 = np.asarray(u0, dtype=float)[:, self.j].copy()
        b = lambda v: np.broadcast_to(np.asarray(v, dtype=float), (n,)).copy()  # noqa: E731
        self.vr, self.v_climb = b(rotation_speed), b(climb_speed)
        self.climb_free = np.isnan(self.v_climb)
        ground = b(theta_ground)
        if tail_strike is not None:
            ground = np.minimum(ground, b(tail_strike) - tail_margin)
        self.theta_ground = ground
        self.clear_height = clear_height
        self.de_ff = self.de0.copy() if elevator_ff is None else b(elevator_ff)
        self.rate, self.limits, self.lead, self.lead_time = rotation_rate, limits, rotation_rate * lead_time, lead_time
        self.kt, self.ki, self.kq, self.kv, self.kvi = k_theta, k_i, k_q, k_v, k_vi
        self.trend_time, self.g = trend_time, model.g
        self.rotating = np.zeros(n, dtype=bool)
        self.airborne = np.zeros(n, dtype=bool)
        self.theta_cmd = None
        self.rate_cmd = np.zeros(n)
        self.theta_climb = np.full(n, np.nan)
        self.integral = np.zeros(n)
        self.speed_integral = np.zeros(n)
        self.v_prev = None
        self.v_dot = np.zeros(n)

    def update(self, t, x, out, u, dt):
        q0, q1, q2, q3 = x[:, 9], x[:, 10], x[:, 11], x[:, 12]
        theta = np.arcsin(np.clip(2.0 * (q0 * q2 - q3 * q1), -1.0, 1.0))
        V = out.V
        if self.v_prev is not None:  # the speed trend the pilot reads (first-order lag of the acceleration)
            self.v_dot += ((V - self.v_prev) / dt - self.v_dot) * min(dt / self.trend_time, 1.0)
        self.v_prev = V.copy()
        rotating = self.rotating
        rotating |= V >= self.vr
        if (
            self.theta_cmd is None or not rotating.any()
        ):  # the ground roll before VR: elevator at its takeoff setting, command on the attitude
            self.theta_cmd = theta
            u[:, self.j] = np.where(rotating, self.de_ff, self.de0)
            return u
        wheels = wheel_height(self.model, x)
        lifted = rotating & ~self.airborne & (wheels >= self.clear_height)
        if lifted.any():  # the climb attitude the acceleration at lift-off can hold (its potential flight path)
            climb = np.where(self.climb_free, theta, theta + self.v_dot / self.g)
            self.theta_climb = np.where(lifted, climb, self.theta_climb)
            self.airborne |= lifted
        airborne = self.airborne
        if airborne.any():
            dv = np.where(self.climb_free, 0.0, V - self.v_climb)  # no climb speed: hold the lift-off attitude
            self.speed_integral += np.where(airborne, dv, 0.0) * dt
            climb = self.theta_climb + self.kv * dv + self.kvi * self.speed_integral
            target = np.where(airborne, climb, self.theta_ground)
        else:
            target = self.theta_ground
        previous = self.theta_cmd
        dr = self.rate * dt / self.lead_time  # the commanded rate's largest change over the step
        rem = target - previous  # approach the target at a rate that can still stop on it
        wanted = np.sign(rem) * np.minimum(
            np.minimum(np.abs(rem) / dt, self.rate), np.sqrt(2.0 * self.rate / self.lead_time * np.abs(rem))
        )
        # the rate the pilot flies (it leads the attitude by at most r × lead_time: a lagging airplane is pulled
        # harder by the rate term, not given a slower command)
        rate_cmd = np.where(rotating, np.clip(wanted, self.rate_cmd - dr, self.rate_cmd + dr), 0.0)
        cmd = np.where(rotating, np.minimum(previous + rate_cmd * dt, theta + self.lead), theta)
        self.theta_cmd = cmd
        self.rate_cmd = rate_cmd
        err = theta - cmd
        lo, hi = self.limits
        raw = self.de_ff + self.kt * err + self.ki * self.integral + self.kq * (x[:, 7] - rate_cmd)
        self.integral += np.where(rotating & ~on_stop(raw, err, lo, hi), err * dt, 0.0)
        u[:, self.j] = np.where(rotating, np.clip(raw, lo, hi), self.de0)
        return u

    def kernel_block(self) -> KernelBlock | None:
        """This pilot for a compiled run (:mod:`certkit.models.dynamics.controlled_run`), before its first step."""
        if self.theta_cmd is not None or self.v_prev is not None or self.model.ground is None:
            return None
        n = self.model.n

        def restore(s):
            self.rotating, self.airborne = s[:, 0] != 0.0, s[:, 1] != 0.0
            self.theta_cmd, self.rate_cmd, self.theta_climb = s[:, 2].copy(), s[:, 3].copy(), s[:, 4].copy()
            self.integral, self.speed_integral = s[:, 5].copy(), s[:, 6].copy()
            self.v_prev, self.v_dot = s[:, 7].copy(), s[:, 8].copy()

        consts = np.array(
            [
                self.j,
                self.rate,
                self.lead,
                self.lead_time,
                self.kt,
                self.ki,
                self.kq,
                self.kv,
                self.kvi,
                self.trend_time,
                self.g,
                self.clear_height,
                self.limits[0],
                self.limits[1],
                self.model.ground.elevation,
            ],
            dtype=float,
        )
        params = columns(n, self.de0, self.vr, self.v_climb, self.climb_free, self.theta_ground, self.de_ff)
        state = columns(
            n,
            self.rotating,
            self.airborne,
            0.0,
            self.rate_cmd,
            self.theta_climb,
            self.integral,
            self.speed_integral,
            0.0,
            self.v_dot,
            0.0,
        )
        return KernelBlock("pitch", pilot_kernel.ROTATION, consts, params, state, restore, self)


class DirectionalPilot(HeadingHold):
    def __init__(
        self,
        model: AircraftModel,
        u0: np.ndarray,
        failure=None,
        reaction_time: float = 1.0,
        rudder_rate: float = np.radians(30.0),
        steering: float | None = None,
        k_psi: float = 15.0,
        k_i: float = 2.0,
        k_r: float = 10.0,
        **law,
    ):
        super().__init__(model, u0, k_psi=k_psi, k_i=k_i, k_r=k_r, **law)
        self.failure, self.reaction, self.rate = failure, float(reaction_time), float(rudder_rate)
        self.pedal = self.dr0.copy()
        self.js = None
        if steering:
            self.js = model.control_index(STEERING)
            self.steer_gain = float(steering) / max(abs(self.lim_r[0]), abs(self.lim_r[1]))

    def update(self, t, x, out, u, dt):
        u = super().update(t, x, out, u, dt)
        step = np.clip(u[:, self.jr] - self.pedal, -self.rate * dt, self.rate * dt)
        if self.failure is not None:  # held from the failure until the pilot reacts
            with np.errstate(invalid="ignore"):
                step = np.where(t < self.failure.fail_time + self.reaction - 1e-9, 0.0, step)
        self.pedal = self.pedal + step
        u[:, self.jr] = self.pedal
        if self.js is not None:
            loaded = out.gear_load.sum(axis=1) > 0.0
            u[:, self.js] = np.where(loaded, -self.steer_gain * self.pedal, 0.0)
        return u

    def kernel_block(self) -> KernelBlock | None:
        """This pilot for a compiled run (:mod:`certkit.models.dynamics.controlled_run`), before its first step."""
        block = super().kernel_block()
        if block is None:
            return None
        law_restore = block.restore

        def restore(s):
            law_restore(s)
            self.pedal = s[:, 4].copy()

        block.kind, block.restore = pilot_kernel.DIRECTIONAL, restore
        block.consts[12:] = [self.rate, self.reaction, self.steer_gain if self.js is not None else 0.0, 0.0]
        if self.failure is not None:
            block.consts[15], block.waits_for = 1.0, self.failure
        block.state[:, 4] = self.pedal
        block.columns = (self.ja, self.jr, -1 if self.js is None else self.js)
        return block


__all__ = ["RotationPilot", "DirectionalPilot"]
