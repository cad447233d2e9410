"""Closed-loop pilot models for simulations (vectorised over the batch).

:class:`PitchAttitudeHold`
    Takeoff rotation and attitude hold: below the rotation speed V_R the elevator stays at its
    initial value; from V_R the commanded pitch attitude ramps at ``rotation_rate`` to
    ``theta_target`` and the elevator follows
        δe = δe0 + K_θ (θ − θ_cmd) + K_q q        (positive δe is nose-down, Etkin)
    clipped to the elevator limits.

:class:`TECSApproach`
    A total-energy control system (after Lambregts' TECS) that flies a glide path of angle
    ``glide`` (−3°) at constant airspeed and flares to touchdown:
        throttle = thr0 + K_E (ė_cmd − ė) + K_I ∫(ė_cmd − ė) dt,
            ė = γ + V̇/g  (specific total-energy rate over V)
        θ_cmd = θ0 + K_γ ∫ ... written as a pitch command from the energy *distribution* error
            d = (γ_cmd − γ) − (V̇_cmd − V̇)/g,  θ_cmd ← θ_cmd + K_D d dt,
        plus a proportional part K_P d, and the pitch-attitude law above for the elevator.
    Above the flare height γ_cmd = glide and V_cmd = the initial airspeed (V̇_cmd from the speed
    error). Heights are those of the *wheels* above the runway: h_w is the height of the lowest
    gear contact point at the current attitude (from the model's ground model; without one, or
    with ``gear_height`` given, h_w = h_cg − h_rwy − gear_height). Below the flare height h_f the
    sink-rate command is the exponential flare (Stevens & Lewis, *Aircraft Control and
    Simulation*, 2nd ed., Wiley 2003, §4.7 automatic-landing example: h = h₀ e^(−t/τ) aimed at a
    point h_aim below the runway so that the airplane touches down at a finite sink rate;
    McRuer, Ashkenas & Graham, *Aircraft Dynamics and Automatic Control*, 1973, ch. 10 the same
    exponential flare path)
        ḣ_cmd = −(h_w + h_aim)/τ,   τ = (h_f + h_aim)/|ḣ_approach|,
    continuous with the approach sink rate |ḣ_approach| = V sin|glide| at h_f, and giving a
    commanded touchdown sink rate h_aim/τ = |ḣ_approach| h_aim/(h_f + h_aim); γ_cmd = ḣ_cmd/V.
    In the flare the throttle goes to idle and the pitch loop flies the path alone (the speed
    term leaves the distribution error: with idle thrust the speed is let decay, as a pilot
    does), with the commanded path-angle rate fed forward into the attitude command and the
    tighter gains ``k_p_flare``, ``k_d_flare`` (the flare is a short, precise path task), and a
    path-angle-rate damping term −K_γ̇ γ̇ in the attitude command (without it the PI path loop
    overshoots and the baseline touched down at 3–7 ft/s; with it 1.5–2 ft/s, tests/dynamics/test_flare.py).

:class:`WingsLevel`
    Lateral–directional hold for takeoffs and approaches (an engine failure's asymmetry): aileron
    δa = K_φ φ + K_p p toward wings level and rudder δr = K_r r − K_β β toward zero sideslip
    (positive deflections give negative moments, :mod:`certkit.conventions`), clipped.

:class:`HeadingHold`
    Rudder holding the initial (runway) heading by a PI law with yaw-rate damping, aileron holding wings
    level on the ground and a commanded bank once airborne (an engine failure on the takeoff run).

:class:`EngineFailure`
    Makes the named engines inoperative from the instant the airspeed first reaches ``speed`` (V_EF), per
    condition, and for the rest of the run (§25.111(a)(2)'s failure model): windmilling at once, or with
    ``decay_time`` τ a first-order spool-down, the failed engine's force T = D_wm + (T_run − D_wm) e^(−(t − t_EF)/τ)
    (D_wm the windmilling drag, negative thrust; T_run the thrust it would give running).
"""

from __future__ import annotations

import numpy as np

from certkit.models.dynamics import pilot_kernel
from certkit.models.dynamics.controlled_run import KernelBlock, columns
from certkit.models.dynamics.eom import AircraftModel, quat_to_euler
from certkit.models.dynamics.ground import wheel_height
from certkit.models.dynamics.simulate import Controller


def _pitch_law(u, j, de0, theta, theta_cmd, q, k_theta, k_q, limits):
    u[:, j] = np.clip(de0 + k_theta * (theta - theta_cmd) + k_q * q, limits[0], limits[1])
    return u


class PitchAttitudeHold(Controller):
    def __init__(
        self,
        model: AircraftModel,
        u0: np.ndarray,
        rotation_speed,
        theta_target,
        rotation_rate: float = np.radians(3.0),
        k_theta: float = 2.0,
        k_q: float = 1.0,
        elevator: str = "elevator",
        limits=(-np.radians(30), np.radians(20)),
    ):
        self.j = model.control_index(elevator)
        self.de0 = np.asarray(u0, dtype=float)[:, self.j].copy()
        self.vr = np.broadcast_to(np.asarray(rotation_speed, dtype=float), (model.n,))
        self.target = np.broadcast_to(np.asarray(theta_target, dtype=float), (model.n,))
        self.rate, self.kt, self.kq, self.limits = rotation_rate, k_theta, k_q, limits
        self.theta_cmd = None
        self.rotating = np.zeros(model.n, dtype=bool)

    def update(self, t, x, out, u, dt):
        theta = quat_to_euler(x[:, 9:13])[:, 1]
        if self.theta_cmd is None:
            self.theta_cmd = theta.copy()
        self.rotating |= out.V >= self.vr
        step = np.where(self.rotating, self.rate * dt, 0.0)
        self.theta_cmd = np.where(self.rotating, np.minimum(self.theta_cmd + step, self.target), theta)
        held = _pitch_law(u.copy(), self.j, self.de0, theta, self.theta_cmd, x[:, 7], self.kt, self.kq, self.limits)
        u[:, self.j] = np.where(self.rotating, held[:, self.j], self.de0)
        return u

    def kernel_block(self) -> KernelBlock | None:
        """This law for a compiled run (:mod:`certkit.models.dynamics.controlled_run`), before its first step."""
        if self.theta_cmd is not None:
            return None
        n = self.rotating.shape[0]

        def restore(s):
            self.rotating, self.theta_cmd = s[:, 0] != 0.0, s[:, 1].copy()

        consts = np.array([self.j, self.rate, self.kt, self.kq, self.limits[0], self.limits[1]], dtype=float)
        params = columns(n, self.de0, self.vr, self.target)
        return KernelBlock(
            "pitch", pilot_kernel.ATTITUDE_HOLD, consts, params, columns(n, self.rotating, 0.0), restore, self
        )


class TECSApproach(Controller):
    def __init__(
        self,
        model: AircraftModel,
        x0: np.ndarray,
        u0: np.ndarray,
        glide: float = np.radians(-3.0),
        flare_height: float = 15.0,
        aim_below: float = 1.0,
        runway_elevation: float | None = None,
        k_e: float = 2.0,
        k_i: float = 0.3,
        k_d: float = 0.5,
        k_theta: float = 2.0,
        k_q: float = 1.0,
        k_v: float = 0.1,
        k_p: float = 1.5,
        elevator: str = "elevator",
        limits=(-np.radians(30), np.radians(20)),
        gear_height=None,
        k_p_flare: float = 4.0,
        k_d_flare: float = 1.0,
        k_gdot_flare: float = 2.0,
    ):
        self.model = model
        self.k_p_flare, self.k_d_flare, self.k_gdot_flare = k_p_flare, k_d_flare, k_gdot_flare
        self.prev_gamma = None
        self.j = model.control_index(elevator)
        self.thr = np.arange(model.throttle_slice.start, model.throttle_slice.stop)
        u0 = np.asarray(u0, dtype=float)
        self.de0 = u0[:, self.j].copy()
        self.thr0 = u0[:, self.thr].mean(axis=1)
        x0 = np.asarray(x0, dtype=float)
        self.V_cmd = np.linalg.norm(x0[:, 3:6], axis=1)
        if runway_elevation is None:
            runway_elevation = model.ground.elevation if model.ground is not None else 0.0
        # wheel heights from the gear geometry at the current attitude, or a fixed CG-to-wheel height
        self.gear_geometry = gear_height is None and model.ground is not None
        self.h_gear = np.broadcast_to(np.asarray(gear_height or 0.0, dtype=float), (model.n,))
        self.glide, self.hf, self.aim, self.h_rwy = glide, flare_height, aim_below, runway_elevation
        self.k_e, self.k_i, self.k_d, self.kt, self.kq, self.k_v, self.k_p = k_e, k_i, k_d, k_theta, k_q, k_v, k_p
        self.limits = limits
        self.sink = self.V_cmd * np.sin(-glide)
        self.tau = (flare_height + aim_below) / np.maximum(self.sink, 0.1)
        self.integral = np.zeros(model.n)
        self.theta_cmd = None
        self.prev_V = None
        self.flaring = np.zeros(model.n, dtype=bool)

    def wheel_height(self, x) -> np.ndarray:
        """Height of the lowest gear contact point (or of the CG less ``gear_height``) above the runway."""
        if not self.gear_geometry:
            return x[:, 2] - self.h_rwy - self.h_gear
        return wheel_height(self.model, x, self.h_rwy)

    def update(self, t, x, out, u, dt):
        theta = quat_to_euler(x[:, 9:13])[:, 1]
        V = out.V
        # flight-path angle from the earth-frame climb rate
        q0, q1, q2, q3 = (x[:, 9 + k] for k in range(4))
        c31, c32, c33 = 2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
        hdot = -(c31 * x[:, 3] + c32 * x[:, 4] + c33 * x[:, 5])
        Vs = np.maximum(V, 1.0)
        gamma = np.arcsin(np.clip(hdot / Vs, -1, 1))
        h_w = self.wheel_height(x)
        self.flaring |= h_w <= self.hf
        flare_hdot = -(np.maximum(h_w, 0.0) + self.aim) / self.tau
        gamma_cmd = np.where(self.flaring, np.arcsin(np.clip(flare_hdot / Vs, -1, 1)), self.glide)
        if self.prev_V is None:
            self.prev_V = V.copy()
            self.theta_cmd = theta.copy()
        vdot = (V - self.prev_V) / max(dt, 1e-9)
        self.prev_V = V.copy()
        g = self.model.g
        vdot_cmd = self.k_v * (self.V_cmd - V)
        path_err = gamma_cmd - gamma
        speed_err = (vdot_cmd - vdot) / g
        e_err = path_err + speed_err
        d_err = np.where(self.flaring, path_err, path_err - speed_err)
        self.integral += np.where(self.flaring, 0.0, e_err) * dt
        thr = np.clip(self.thr0 + self.k_e * e_err + self.k_i * self.integral, 0.0, 1.0)
        thr = np.where(self.flaring, 0.0, thr)
        u[:, self.thr] = thr[:, None]
        # flare: feed the commanded path-angle rate forward (γ̇_cmd = ḧ_cmd/V = −ḣ/(τ V))
        ff = np.where(self.flaring, -hdot / self.tau / Vs, 0.0)
        k_d = np.where(self.flaring, self.k_d_flare, self.k_d)
        k_p = np.where(self.flaring, self.k_p_flare, self.k_p)
        self.theta_cmd = self.theta_cmd + (k_d * d_err + ff) * dt
        cmd = self.theta_cmd + k_p * d_err
        # flare: damp the path loop with the path-angle rate (γ̇ from successive samples)
        if self.prev_gamma is not None:
            gdot = (gamma - self.prev_gamma) / max(dt, 1e-9)
            cmd = cmd - np.where(self.flaring, self.k_gdot_flare * gdot, 0.0)
        self.prev_gamma = gamma.copy()
        return _pitch_law(u, self.j, self.de0, theta, cmd, x[:, 7], self.kt, self.kq, self.limits)

    def kernel_block(self) -> KernelBlock | None:
        """This law for a compiled run (:mod:`certkit.models.dynamics.controlled_run`), before its first step."""
        if self.prev_V is not None or self.prev_gamma is not None or self.theta_cmd is not None:
            return None
        if self.gear_geometry and self.model.ground is None:
            return None
        n = self.flaring.shape[0]

        def restore(s):
            self.flaring, self.integral = s[:, 0] != 0.0, s[:, 1].copy()
            self.theta_cmd, self.prev_V, self.prev_gamma = s[:, 2].copy(), s[:, 3].copy(), s[:, 4].copy()

        consts = np.array(
            [
                self.j,
                self.thr[0] if self.thr.size else 0,
                self.thr[-1] + 1 if self.thr.size else 0,
                self.glide,
                self.hf,
                self.aim,
                self.h_rwy,
                self.k_e,
                self.k_i,
                self.k_d,
                self.kt,
                self.kq,
                self.k_v,
                self.k_p,
                self.limits[0],
                self.limits[1],
                self.k_p_flare,
                self.k_d_flare,
                self.k_gdot_flare,
                float(self.gear_geometry),
                self.model.g,
            ],
            dtype=float,
        )
        params = columns(n, self.de0, self.thr0, self.V_cmd, self.h_gear, self.tau)
        state = columns(n, self.flaring, self.integral, 0.0, 0.0, 0.0)
        return KernelBlock("pitch", pilot_kernel.TECS, consts, params, state, restore, self)


class WingsLevel(Controller):
    def __init__(
        self,
        model: AircraftModel,
        u0: np.ndarray,
        k_phi: float = 2.0,
        k_p: float = 1.0,
        k_beta: float = 3.0,
        k_r: float = 2.0,
        aileron: str = "aileron",
        rudder: str = "rudder",
        limits: dict | None = None,
    ):
        self.ja, self.jr = model.control_index(aileron), model.control_index(rudder)
        u0 = np.asarray(u0, dtype=float)
        self.da0, self.dr0 = u0[:, self.ja].copy(), u0[:, self.jr].copy()
        self.k_phi, self.k_p, self.k_beta, self.k_r = k_phi, k_p, k_beta, k_r
        lim = limits or {}
        self.lim_a = lim.get(aileron, (-np.radians(25), np.radians(25)))
        self.lim_r = lim.get(rudder, (-np.radians(25), np.radians(25)))

    def update(self, t, x, out, u, dt):
        phi = quat_to_euler(x[:, 9:13])[:, 0]
        u[:, self.ja] = np.clip(self.da0 + self.k_phi * phi + self.k_p * x[:, 6], *self.lim_a)
        u[:, self.jr] = np.clip(self.dr0 + self.k_r * x[:, 8] - self.k_beta * out.beta, *self.lim_r)
        return u

    def kernel_block(self) -> KernelBlock:
        """This law for a compiled run (:mod:`certkit.models.dynamics.controlled_run`)."""
        n = self.da0.shape[0]
        consts = np.array([self.k_phi, self.k_p, self.k_beta, self.k_r, *self.lim_a, *self.lim_r], dtype=float)
        return KernelBlock(
            "lateral",
            pilot_kernel.WINGS_LEVEL,
            consts,
            columns(n, self.da0, self.dr0),
            np.zeros((n, 1)),
            lambda s: None,
            self,
            (self.ja, self.jr, -1),
        )


class EngineFailure(Controller):
    def __init__(self, model: AircraftModel, engines, speed, decay_time: float | None = None):
        self.model = model
        self.decay_time = decay_time
        names = [e.name for e in model.engines]
        idx = [names.index(e) if isinstance(e, str) else int(e) for e in np.atleast_1d(engines)]
        self.mask = np.zeros(len(names), dtype=bool)
        self.mask[idx] = True
        self.speed = np.broadcast_to(np.asarray(speed, dtype=float), (model.n,))
        self.failed = np.zeros(model.n, dtype=bool)
        self.fail_time = np.full(model.n, np.nan)

    def update(self, t, x, out, u, dt):
        now = ~self.failed & (out.V >= self.speed)
        if now.any():
            self.failed |= now
            self.fail_time[now] = t
            op = self.model.operative.copy()
            op[self.failed[:, None] & self.mask[None, :]] = False
            self.model.set_operative(op)
        if self.decay_time is not None and self.failed.any():
            frac = np.exp(-(t - np.where(self.failed, self.fail_time, t)) / self.decay_time)
            self.model.failed_thrust_fraction = np.where(self.failed[:, None] & self.mask[None, :], frac[:, None], 0.0)
        return u

    def kernel_block(self) -> KernelBlock:
        """This failure for a compiled run (:mod:`certkit.models.dynamics.controlled_run`)."""
        n = self.failed.shape[0]

        def restore(s):
            self.failed, self.fail_time = s[:, 0] != 0.0, s[:, 1].copy()

        decay = np.nan if self.decay_time is None else float(self.decay_time)
        state = columns(n, self.failed, self.fail_time)
        return KernelBlock(
            "failure",
            pilot_kernel.ENGINE_FAILURE,
            np.array([decay]),
            columns(n, self.speed),
            state,
            restore,
            self,
            mask=self.mask,
        )


#: the share of the weight on the wheels below which the lateral laws fly the airplane as airborne (the bank toward
#: the operating engine growing as the load goes to zero)
LIGHT_GEAR = 0.1


class HeadingHold(Controller):
    """Lateral–directional hold of the initial heading (the runway's), for an engine failure on the takeoff
    run and climb-out: rudder on the heading error (proportional + integral, so that the steady asymmetric
    yawing moment needs no standing heading error) with yaw-rate damping,
        δr = δr0 + K_ψ e + K_I ∫e dt + K_r r,   e = (ψ − ψ0) + c,   c = K_y (y − y0) limited to ± ``max_correction``,
    the integral frozen while the rudder is on its limit in the error's direction (anti-windup); with K_y > 0 the
    ground run also tracks the centreline (a lateral outer loop: track command ψ0 − c, back to the centreline
    with a time constant of about 1/(V K_y), a crab of at most 3°) and, on the ground, e steers the track ψ + β
    rather than the nose (a pilot follows the runway: on lightly loaded wheels — a long rotated run — the rudder's
    side force lets the airplane sideslip, and holding the nose alone would let it slide off the centreline),
    c held at its last ground value once airborne
    (no step in the rudder at lift-off); no nose-wheel steering (the §25.149(e) VMCG
    demonstration uses the rudder alone). Aileron toward the commanded bank, wings level on the ground and
    ``bank`` (rad, per condition) once the gear carries no load (e.g. a few degrees toward the operating engine),
    coming in as the wheels unload (in proportion as their load falls below :data:`LIGHT_GEAR` of the weight: on
    lightly loaded wheels the tyres no longer hold the rudder's side force, the bank's weight component does):
        δa = δa0 + K_φ (φ − φ_cmd) + K_p p,
    both clipped to ``limits`` (positive deflections give negative moments, :mod:`certkit.conventions`)."""

    def __init__(
        self,
        model: AircraftModel,
        u0: np.ndarray,
        k_psi: float = 3.0,
        k_i: float = 1.0,
        k_r: float = 3.0,
        k_phi: float = 2.0,
        k_p: float = 1.0,
        bank=0.0,
        aileron: str = "aileron",
        rudder: str = "rudder",
        limits: dict | None = None,
        k_y: float = 0.0,
        max_correction: float = np.radians(3.0),
    ):
        self.ja, self.jr = model.control_index(aileron), model.control_index(rudder)
        u0 = np.asarray(u0, dtype=float)
        self.da0, self.dr0 = u0[:, self.ja].copy(), u0[:, self.jr].copy()
        self.k_psi, self.k_i, self.k_r, self.k_phi, self.k_p, self.k_y = k_psi, k_i, k_r, k_phi, k_p, k_y
        self.bank = np.broadcast_to(np.asarray(bank, dtype=float), (model.n,))
        self.weight = np.broadcast_to(np.asarray(model.mass, dtype=float) * model.g, (model.n,))
        lim = limits or {}
        self.lim_a = lim.get(aileron, (-np.radians(25), np.radians(25)))
        self.lim_r = lim.get(rudder, (-np.radians(25), np.radians(25)))
        self.max_correction = max_correction
        self.psi0 = self.y0 = None
        self.integral, self.correction = np.zeros(model.n), np.zeros(model.n)

    def update(self, t, x, out, u, dt):
        q0, q1, q2, q3 = x[:, 9], x[:, 10], x[:, 11], x[:, 12]
        phi = np.arctan2(2.0 * (q0 * q1 + q2 * q3), 1.0 - 2.0 * (q1 * q1 + q2 * q2))
        psi = np.arctan2(2.0 * (q0 * q3 + q1 * q2), 1.0 - 2.0 * (q2 * q2 + q3 * q3))
        if self.psi0 is None:
            self.psi0, self.y0 = psi.copy(), x[:, 1].copy()
        airborne = out.gear_load.sum(axis=1) <= 0.0
        err = (psi - self.psi0 + np.pi) % (2.0 * np.pi) - np.pi
        if self.k_y:  # the centreline's heading correction, limited, held at its last value on the ground once airborne
            ground = np.clip(self.k_y * (x[:, 1] - self.y0), -self.max_correction, self.max_correction)
            self.correction = np.where(airborne, self.correction, ground)
            # on the ground the track, not the nose, is steered back: the sideslip the tyres let through counts
            err = err + self.correction + np.where(airborne, 0.0, out.beta)
        raw = self.dr0 + self.k_psi * err + self.k_i * self.integral + self.k_r * x[:, 8]
        lo, hi = self.lim_r
        self.integral += np.where(on_stop(raw, err, lo, hi), 0.0, err) * dt
        u[:, self.jr] = np.clip(raw, lo, hi)
        # the bank toward the operating engine comes in as the wheels unload (none with a tenth of the weight on them)
        unloading = np.clip(1.0 - out.gear_load.sum(axis=1) / (LIGHT_GEAR * self.weight), 0.0, 1.0)
        phi_cmd = unloading * self.bank
        u[:, self.ja] = np.clip(self.da0 + self.k_phi * (phi - phi_cmd) + self.k_p * x[:, 6], *self.lim_a)
        return u

    def kernel_block(self) -> KernelBlock | None:
        """This law for a compiled run (:mod:`certkit.models.dynamics.controlled_run`), before its first step."""
        if self.psi0 is not None:
            return None
        n = self.da0.shape[0]

        def restore(s):
            self.psi0, self.y0 = s[:, 0].copy(), s[:, 1].copy()
            self.integral, self.correction = s[:, 2].copy(), s[:, 3].copy()

        consts = np.array(
            [
                self.k_psi,
                self.k_i,
                self.k_r,
                self.k_phi,
                self.k_p,
                self.k_y,
                self.max_correction,
                *self.lim_a,
                *self.lim_r,
                LIGHT_GEAR,
                0.0,
                0.0,
                0.0,
                0.0,
            ],
            dtype=float,
        )
        params = columns(n, self.da0, self.dr0, self.bank, self.weight)
        state = columns(n, 0.0, 0.0, self.integral, self.correction, 0.0)
        kind = pilot_kernel.HEADING_HOLD
        return KernelBlock("lateral", kind, consts, params, state, restore, self, (self.ja, self.jr, -1))


def on_stop(raw, err, lo, hi) -> np.ndarray:
    """True where the command ``raw`` is on a stop in the direction the error ``err`` (command − state, with a
    positive gain) drives it: an integral is frozen there (anti-windup)."""
    return ((raw >= hi) & (err > 0)) | ((raw <= lo) & (err < 0))


__all__ = ["PitchAttitudeHold", "TECSApproach", "WingsLevel", "EngineFailure", "HeadingHold", "on_stop"]
