"""Compiled closed-loop runs: the takeoff, engine-cut, landing and yaw pilots stepped in machine code.

:func:`integrate_controlled` is the loop of :func:`certkit.models.dynamics.simulate.simulate` for a run whose
controllers are, in this order, a pitch law (:class:`~certkit.models.dynamics.takeoff_pilot.RotationPilot`,
:class:`~certkit.models.dynamics.controllers.PitchAttitudeHold` or the approach's
:class:`~certkit.models.dynamics.controllers.TECSApproach`, which flies the throttles too), a lateral law
(:class:`~certkit.models.dynamics.controllers.WingsLevel`, :class:`~certkit.models.dynamics.controllers.HeadingHold`,
:class:`~certkit.models.dynamics.takeoff_pilot.DirectionalPilot` or the yaw manoeuvre's
:class:`~certkit.models.loads.yaw.RollHold`) and an :class:`~certkit.models.dynamics.controllers.EngineFailure`, each
optional, with at most one stop criterion (the takeoff's screen height,
:class:`~certkit.models.dynamics.procedures.ScreenHeight`; the engine cut's end,
:class:`~certkit.models.dynamics.ground_control.EngineCutEnd`; the yaw manoeuvre's settled sideslip,
:class:`~certkit.models.loads.yaw.SideslipSettled`; the landing's
:class:`~certkit.models.dynamics.procedures.Touchdown`) and any scheduled inputs. Each step is the Python loop's: the
state evaluated with the step's scheduled controls (:func:`~certkit.models.dynamics.kernel.air_data`,
:func:`~certkit.models.dynamics.kernel.engine_forces`, :func:`~certkit.models.dynamics.kernel.derivatives`), the laws
in order on those outputs, the state evaluated again with their controls, the stop criterion on these outputs, the
record, then :func:`~certkit.models.dynamics.kernel.rk4_step`. The laws are the Python classes' arithmetic, operation
for operation, on each row (their docstrings hold the equations); every row is stepped by the laws, stopped or not,
as the Python loop does, so their states end alike. The transcendental functions are libm's here and numpy's SIMD
ones in Python: the two may differ in the last bit (tested to agree within round-off).

Each law is a block: its kind (0: none), integer arguments (control columns), constants (C,), per-row parameters
(n, P) and per-row state (n, S) updated in place; the layouts are :mod:`certkit.models.dynamics.controlled_run`'s.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from certkit.models.dynamics.kernel import air_data, derivatives, engine_forces, record, rk4_step

#: pitch laws
ROTATION, ATTITUDE_HOLD, TECS = 1, 2, 3
#: lateral laws
WINGS_LEVEL, HEADING_HOLD, DIRECTIONAL, ROLL_HOLD = 1, 2, 3, 4
#: stop criteria
SCREEN_HEIGHT, ENGINE_CUT, SIDESLIP_SETTLED, TOUCHDOWN = 1, 2, 3, 4
#: the engine failure (the one kind of its block)
ENGINE_FAILURE = 1

_V, _BETA = 0, 2  # columns of kernel.OUTPUTS


@njit(cache=True)
def _max(a, b):
    """numpy's maximum of two floats (NaN propagated)."""
    return a if (a != a or a >= b) else b


@njit(cache=True)
def _min(a, b):
    """numpy's minimum of two floats (NaN propagated)."""
    return a if (a != a or a <= b) else b


@njit(cache=True)
def _clip(x, lo, hi):
    """numpy's clip of a float."""
    y = x if (x != x or x > lo) else lo
    return y if (y != y or y < hi) else hi


@njit(cache=True)
def _sign(x):
    if x > 0.0:
        return 1.0
    if x < 0.0:
        return -1.0
    return x  # 0 or NaN


@njit(cache=True)
def _on_stop(raw, err, lo, hi):
    """:func:`certkit.models.dynamics.controllers.on_stop` of one row."""
    return (raw >= hi and err > 0.0) or (raw <= lo and err < 0.0)


@njit(cache=True)
def _gear_sum(gear):
    s = 0.0
    for j in range(gear.shape[0]):
        s += gear[j]
    return s


@njit(cache=True)
def _wheel_height(x, r_gear, elevation):
    """:func:`certkit.models.dynamics.ground.wheel_height` of one quaternion state (its legs ``r_gear`` (nl, 3))."""
    q0, q1, q2, q3 = x[9], x[10], x[11], x[12]
    lowest = -np.inf
    for leg in range(r_gear.shape[0]):
        down = (
            2 * (q1 * q3 - q0 * q2) * r_gear[leg, 0]
            + 2 * (q2 * q3 + q0 * q1) * r_gear[leg, 1]
            + (q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3) * r_gear[leg, 2]
        )
        if down != down or down > lowest:
            lowest = down
            if down != down:
                break
    return x[2] - elevation - lowest


@njit(cache=True)
def _theta(x):
    return math.asin(_clip(2.0 * (x[9] * x[11] - x[12] * x[10]), -1.0, 1.0))


@njit(cache=True)
def _phi(x):
    q0, q1, q2, q3 = x[9], x[10], x[11], x[12]
    return math.atan2(2.0 * (q0 * q1 + q2 * q3), 1.0 - 2.0 * (q1 * q1 + q2 * q2))


@njit(cache=True)
def _psi(x):
    q0, q1, q2, q3 = x[9], x[10], x[11], x[12]
    return math.atan2(2.0 * (q0 * q3 + q1 * q2), 1.0 - 2.0 * (q2 * q2 + q3 * q3))


@njit(cache=True)
def _rotation(first, any_rotating, t, dt, x, out, u, j, c, p, s, r_gear):
    """:class:`~certkit.models.dynamics.takeoff_pilot.RotationPilot` on one row. Constants ``c``: rate, lead,
    lead_time, k_θ, k_I, k_q, k_V, k_VI, trend_time, g, clear_height, elevator limits (2), runway elevation;
    parameters ``p``: δe0, VR, V_climb, climb free (1/0), θ_ground, δe_ff; state ``s``: rotating, airborne, θ_cmd,
    θ̇_cmd, θ_climb, integral, speed integral, V_prev, V̇, V_prev set (1/0)."""
    rate, lead, lead_time, kt, ki, kq, kv, kvi, trend, g, clear, lo, hi, elevation = (
        c[0],
        c[1],
        c[2],
        c[3],
        c[4],
        c[5],
        c[6],
        c[7],
        c[8],
        c[9],
        c[10],
        c[11],
        c[12],
        c[13],
    )
    theta = _theta(x)
    V = out[_V]
    if s[9] != 0.0:
        s[8] += ((V - s[7]) / dt - s[8]) * min(dt / trend, 1.0)
    s[7] = V
    s[9] = 1.0
    if V >= p[1]:
        s[0] = 1.0
    rotating = s[0] != 0.0
    if first or not any_rotating or not rotating:  # before VR (for a row not rotating both of the Python branches)
        s[2] = theta
        u[j] = p[5] if rotating else p[0]
        return
    wheels = _wheel_height(x, r_gear, elevation)
    climb_free = p[3] != 0.0
    if s[1] == 0.0 and wheels >= clear:
        s[4] = theta if climb_free else theta + s[8] / g
        s[1] = 1.0
    if s[1] != 0.0:
        dv = 0.0 if climb_free else V - p[2]
        s[6] += dv * dt
        target = s[4] + kv * dv + kvi * s[6]
    else:
        target = p[4]
    previous = s[2]
    dr = rate * dt / lead_time
    rem = target - previous
    wanted = _sign(rem) * _min(_min(abs(rem) / dt, rate), math.sqrt(2.0 * rate / lead_time * abs(rem)))
    rate_cmd = _clip(wanted, s[3] - dr, s[3] + dr)
    cmd = _min(previous + rate_cmd * dt, theta + lead)
    s[2] = cmd
    s[3] = rate_cmd
    err = theta - cmd
    raw = p[5] + kt * err + ki * s[5] + kq * (x[7] - rate_cmd)
    if not _on_stop(raw, err, lo, hi):
        s[5] += err * dt
    else:
        s[5] += 0.0
    u[j] = _clip(raw, lo, hi)


@njit(cache=True)
def _attitude_hold(first, dt, x, out, u, j, c, p, s):
    """:class:`~certkit.models.dynamics.controllers.PitchAttitudeHold` on one row. Constants: rate, k_θ, k_q,
    elevator limits (2); parameters: δe0, V_R, θ_target; state: rotating, θ_cmd."""
    theta = _theta(x)
    if first:
        s[1] = theta
    if out[_V] >= p[1]:
        s[0] = 1.0
    rotating = s[0] != 0.0
    step = c[0] * dt if rotating else 0.0
    s[1] = _min(s[1] + step, p[2]) if rotating else theta
    held = _clip(p[0] + c[1] * (theta - s[1]) + c[2] * x[7], c[3], c[4])
    u[j] = held if rotating else p[0]


@njit(cache=True)
def _wings_level(x, out, u, ja, jr, c, p):
    """:class:`~certkit.models.dynamics.controllers.WingsLevel` on one row. Constants: K_φ, K_p, K_β, K_r, aileron
    limits (2), rudder limits (2); parameters: δa0, δr0."""
    phi = _phi(x)
    u[ja] = _clip(p[0] + c[0] * phi + c[1] * x[6], c[4], c[5])
    u[jr] = _clip(p[1] + c[3] * x[8] - c[2] * out[_BETA], c[6], c[7])


@njit(cache=True)
def _heading_hold(first, x, out, gear_sum, u, dt, ja, jr, c, p, s):
    """:class:`~certkit.models.dynamics.controllers.HeadingHold` on one row. Constants: K_ψ, K_I, K_r, K_φ, K_p, K_y,
    largest correction, aileron limits (2), rudder limits (2), light-gear fraction; parameters: δa0, δr0, bank,
    weight; state: ψ0, y0, integral, correction."""
    phi = _phi(x)
    psi = _psi(x)
    if first:
        s[0], s[1] = psi, x[1]
    airborne = gear_sum <= 0.0
    err = (psi - s[0] + np.pi) % (2.0 * np.pi) - np.pi
    if c[5] != 0.0:
        ground = _clip(c[5] * (x[1] - s[1]), -c[6], c[6])
        if not airborne:
            s[3] = ground
        err = err + s[3] + (0.0 if airborne else out[_BETA])
    raw = p[1] + c[0] * err + c[1] * s[2] + c[2] * x[8]
    lo, hi = c[9], c[10]
    s[2] += (0.0 if _on_stop(raw, err, lo, hi) else err) * dt
    u[jr] = _clip(raw, lo, hi)
    unloading = _clip(1.0 - gear_sum / (c[11] * p[3]), 0.0, 1.0)
    phi_cmd = unloading * p[2]
    u[ja] = _clip(p[0] + c[3] * (phi - phi_cmd) + c[4] * x[6], c[7], c[8])


@njit(cache=True)
def _pedals(t, dt, gear_sum, u, jr, js, c, s, fail_time):
    """:class:`~certkit.models.dynamics.takeoff_pilot.DirectionalPilot`'s pedal after the heading law. Constants
    (after the law's): rudder rate, reaction time, steering gain, whether it waits for the run's failure (1/0);
    state: pedal (after the law's); ``fail_time`` the failure's (NaN: none yet, or no failure to wait for)."""
    rate, reaction, steer = c[12], c[13], c[14]
    step = _clip(u[jr] - s[4], -rate * dt, rate * dt)
    if t < fail_time + reaction - 1e-9:  # NaN (no failure yet): False
        step = 0.0
    s[4] = s[4] + step
    u[jr] = s[4]
    if js >= 0:
        u[js] = -steer * s[4] if gear_sum > 0.0 else 0.0


@njit(cache=True)
def _fail(t, i, V, p, s, mask, operative):
    """:class:`~certkit.models.dynamics.controllers.EngineFailure`'s failure of one row. Parameters: V_EF; state:
    failed, failure time."""
    if s[0] == 0.0 and V >= p[0]:
        s[0] = 1.0
        s[1] = t
        for e in range(mask.shape[0]):
            if mask[e]:
                operative[i, e] = False


@njit(cache=True)
def _screen(t, x, gear_sum, r_gear, c, s):
    """:class:`~certkit.models.dynamics.procedures.ScreenHeight` of one row. Constants: runway elevation, screen
    height, climb-out time; state: time at the screen height (NaN: not yet)."""
    up = _wheel_height(x, r_gear, c[0]) > c[1] and gear_sum <= 0.0
    if s[0] != s[0] and up:
        s[0] = t
    return t >= s[0] + c[2] - 1e-9


@njit(cache=True)
def _engine_cut_end(t, x, gear_sum, c, p, s, fail_time):
    """:class:`~certkit.models.dynamics.ground_control.EngineCutEnd` of one row. Constants: swing threshold, reaction
    time, time after the failure, departure; parameters: y0; state: swing sign, recovered, airborne, arrested."""
    swing, reaction, after, departure = c[0], c[1], c[2], c[3]
    psi = _psi(x)
    failed = math.isfinite(fail_time)
    if failed and s[0] == 0.0 and abs(psi) > swing:
        s[0] = _sign(psi)
    back = failed and s[0] != 0.0 and psi * s[0] <= 0.0
    if back:
        s[1] = 1.0
    late = failed and t >= fail_time + after
    reacted = failed and t >= fail_time + reaction
    up = reacted and not back and gear_sum <= 0.0
    if up:
        s[2] = 1.0
        s[3] = 1.0 if (s[0] != 0.0 and x[8] * s[0] < 0.0) else 0.0
    return back or late or up or abs(x[1] - p[0]) > departure


@njit(cache=True)
def _tecs(first, dt, x, out, u, j, c, p, s, r_gear):
    """:class:`~certkit.models.dynamics.controllers.TECSApproach` on one row. Constants: throttle columns (start,
    stop), glide, flare height, aim below, runway elevation, K_E, K_I, K_D, K_θ, K_q, K_V, K_P, elevator limits (2),
    K_P and K_D of the flare, K_γ̇ of the flare, wheel heights from the gear (1/0), g; parameters: δe0, throttle0,
    V_cmd, CG-to-wheel height, τ; state: flaring, integral, θ_cmd, V_prev, γ_prev."""
    q0, q1, q2, q3 = x[9], x[10], x[11], x[12]
    theta = _theta(x)
    V = out[_V]
    c31, c32, c33 = 2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
    hdot = -(c31 * x[3] + c32 * x[4] + c33 * x[5])
    Vs = _max(V, 1.0)
    gamma = math.asin(_clip(hdot / Vs, -1.0, 1.0))
    h_w = _wheel_height(x, r_gear, c[5]) if c[18] != 0.0 else x[2] - c[5] - p[3]
    if h_w <= c[3]:
        s[0] = 1.0
    flaring = s[0] != 0.0
    tau = p[4]
    flare_hdot = -(_max(h_w, 0.0) + c[4]) / tau
    gamma_cmd = math.asin(_clip(flare_hdot / Vs, -1.0, 1.0)) if flaring else c[2]
    if first:
        s[3] = V
        s[2] = theta
    vdot = (V - s[3]) / max(dt, 1e-9)
    s[3] = V
    vdot_cmd = c[11] * (p[2] - V)
    path_err = gamma_cmd - gamma
    speed_err = (vdot_cmd - vdot) / c[19]
    e_err = path_err + speed_err
    d_err = path_err if flaring else path_err - speed_err
    s[1] += (0.0 if flaring else e_err) * dt
    thr = 0.0 if flaring else _clip(p[1] + c[6] * e_err + c[7] * s[1], 0.0, 1.0)
    for col in range(int(c[0]), int(c[1])):
        u[col] = thr
    ff = -hdot / tau / Vs if flaring else 0.0
    k_d = c[16] if flaring else c[8]
    k_p = c[15] if flaring else c[12]
    s[2] = s[2] + (k_d * d_err + ff) * dt
    cmd = s[2] + k_p * d_err
    if not first:
        gdot = (gamma - s[4]) / max(dt, 1e-9)
        cmd = cmd - (c[17] * gdot if flaring else 0.0)
    s[4] = gamma
    u[j] = _clip(p[0] + c[9] * (theta - cmd) + c[10] * x[7], c[13], c[14])


@njit(cache=True)
def _roll_hold(dt, x, u, ja, c, p, s):
    """:class:`~certkit.models.loads.yaw.RollHold` on one row. Constants: K_φ, K_p, K_I, aileron limits (2);
    parameters: δa0; state: integral."""
    phi = _phi(x)
    s[0] += phi * dt
    u[ja] = _clip(p[0] + c[0] * phi + c[2] * s[0] + c[1] * x[6], c[3], c[4])


@njit(cache=True)
def _sideslip_settled(t, beta, c, s):
    """:class:`~certkit.models.loads.yaw.SideslipSettled` of one row. Constants: window length (samples), tolerance,
    earliest time; state: the window's samples, the peak |β|, the samples taken."""
    m = int(c[0])
    calls = int(s[m + 1])
    s[calls % m] = beta
    calls += 1
    s[m + 1] = calls
    s[m] = _max(s[m], abs(beta))
    if calls < m or t < c[2]:
        return False
    band = np.nan
    for k in range(m):
        d = abs(s[k] - beta)
        if d == d and (band != band or d > band):
            band = d
    return band <= c[1] * abs(beta) and abs(beta) < s[m]


@njit(cache=True, error_model="numpy")
def integrate_controlled(
    X,
    U_all,
    dt,
    nsteps,
    record_every,
    turbofan,
    throttle_start,
    operative,
    fraction,
    windmill,
    pitch,
    pitch_c,
    pitch_p,
    pitch_s,
    lateral,
    lateral_j,
    lateral_c,
    lateral_p,
    lateral_s,
    failing,
    fail_mask,
    fail_c,
    fail_p,
    fail_s,
    stop,
    stop_c,
    stop_p,
    stop_s,
    out_rec,
    x_rec,
    u_rec,
    stop_step,
    coef,
    props,
    consts,
    T,
    machs,
    clmax,
    stall,
    alpha_drag,
    after_stall,
    n_aero,
    use_table,
    r_eng,
    d_eng,
    has_ground,
    r_gear,
    legs,
    gparams,
    brake_index,
    steer_index,
):
    """The controlled run (module docstring) of the quaternion-state batch ``X`` (advanced in place) from the controls
    ``U_all`` of every step before the laws (nsteps + 1, n, m: the trim plus the schedules; (1, n, m): the trim
    throughout), ``nsteps`` steps of ``dt``; ``operative`` and ``fraction`` (n, ne) the engines'
    state, updated in place; the law blocks (``pitch``: kind, elevator column (``pitch_c``'s layout in the laws),
    ``lateral_j`` = aileron, rudder, steering columns); ``fail_c`` = [spool-down time τ (NaN: windmilling at once)];
    records of every ``record_every``-th step into ``out_rec``, ``x_rec``, ``u_rec``, a stopped row keeping its
    last; ``stop_step`` (n,) the step a row stopped at (−1: none). Returns the number of records."""
    n = X.shape[0]
    rows = np.arange(n)
    active = np.ones(n, dtype=np.bool_)
    n_active = n
    irec = 0
    ja, jr, js = lateral_j[0], lateral_j[1], lateral_j[2]
    jp = int(pitch_c[0])
    decay = fail_c[0]
    quaternion_state = X.shape[1] == 13  # a bool, not the literal True: derivatives compiled once for every caller
    pilot_failure = failing and lateral == DIRECTIONAL and lateral_c[15] != 0.0
    for k in range(nsteps + 1):
        t = k * dt
        U = U_all[k if U_all.shape[0] > 1 else 0].copy()
        for stage in range(2):  # the state with the trim controls, then with the laws' (one call site each)
            air = air_data(X)
            thrust = engine_forces(air, U, rows, turbofan, throttle_start, operative, fraction, windmill)
            xd, out, gear = derivatives(
                X,
                rows,
                quaternion_state,
                U,
                thrust,
                coef,
                props,
                consts,
                T,
                machs,
                clmax,
                stall,
                alpha_drag,
                after_stall,
                n_aero,
                use_table,
                r_eng,
                d_eng,
                has_ground,
                r_gear,
                legs,
                gparams,
                brake_index,
                steer_index,
            )
            if stage == 1:
                break
            any_rotating = False
            if pitch == ROTATION:  # the rotation's branch is the batch's: every row before VR until one rotates
                for i in range(n):
                    if pitch_s[i, 0] != 0.0 or out[i, _V] >= pitch_p[i, 1]:
                        any_rotating = True
            for i in range(n):
                x, o, u = X[i], out[i], U[i]
                gsum = _gear_sum(gear[i])
                if pitch == ROTATION:
                    _rotation(k == 0, any_rotating, t, dt, x, o, u, jp, pitch_c[1:], pitch_p[i], pitch_s[i], r_gear[i])
                elif pitch == ATTITUDE_HOLD:
                    _attitude_hold(k == 0, dt, x, o, u, jp, pitch_c[1:], pitch_p[i], pitch_s[i])
                elif pitch == TECS:
                    _tecs(k == 0, dt, x, o, u, jp, pitch_c[1:], pitch_p[i], pitch_s[i], r_gear[i])
                if lateral == WINGS_LEVEL:
                    _wings_level(x, o, u, ja, jr, lateral_c, lateral_p[i])
                elif lateral == ROLL_HOLD:
                    _roll_hold(dt, x, u, ja, lateral_c, lateral_p[i], lateral_s[i])
                elif lateral == HEADING_HOLD or lateral == DIRECTIONAL:
                    _heading_hold(k == 0, x, o, gsum, u, dt, ja, jr, lateral_c, lateral_p[i], lateral_s[i])
                    if lateral == DIRECTIONAL:
                        _pedals(
                            t, dt, gsum, u, jr, js, lateral_c, lateral_s[i], fail_s[i, 1] if pilot_failure else np.nan
                        )
                if failing:
                    _fail(t, i, o[_V], fail_p[i], fail_s[i], fail_mask, operative)
            if failing and decay == decay:
                any_failed = False
                for i in range(n):
                    any_failed = any_failed or fail_s[i, 0] != 0.0
                if any_failed:
                    for i in range(n):
                        for e in range(fail_mask.shape[0]):
                            if fail_s[i, 0] != 0.0 and fail_mask[e]:
                                fraction[i, e] = math.exp(-(t - fail_s[i, 1]) / decay)
                            else:
                                fraction[i, e] = 0.0
        if stop != 0:
            for i in range(n):
                gsum = _gear_sum(gear[i])
                if stop == SCREEN_HEIGHT:
                    hit = _screen(t, X[i], gsum, r_gear[i], stop_c, stop_s[i])
                elif stop == SIDESLIP_SETTLED:
                    hit = _sideslip_settled(t, out[i, _BETA], stop_c, stop_s[i])
                elif stop == TOUCHDOWN:
                    hit = gsum > 0.0
                else:
                    hit = _engine_cut_end(
                        t, X[i], gsum, stop_c, stop_p[i], stop_s[i], fail_s[i, 1] if failing else np.nan
                    )
                if active[i] and hit:
                    active[i] = False
                    n_active -= 1
                    stop_step[i] = k
        if k % record_every == 0:
            record(out_rec, x_rec, u_rec, irec, out, X, U, active, n_active == n)
            irec += 1
        if k == nsteps or n_active == 0:
            break
        dts = np.full(n, dt)
        rk4_step(
            X,
            xd,
            active,
            dts,
            U,
            thrust,
            coef,
            props,
            consts,
            T,
            machs,
            clmax,
            stall,
            alpha_drag,
            after_stall,
            n_aero,
            use_table,
            r_eng,
            d_eng,
            has_ground,
            r_gear,
            legs,
            gparams,
            brake_index,
            steer_index,
        )
    return irec
