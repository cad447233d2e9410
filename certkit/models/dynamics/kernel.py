"""Compiled equations of motion: the arithmetic behind :class:`certkit.models.dynamics.eom.AircraftModel`.

The physics, frames and conventions are documented in :mod:`certkit.models.dynamics.eom`; this module
is their only implementation, written one condition at a time and compiled with numba (cached on disk
after the first use), so a batch costs a loop in machine code instead of ~150 numpy calls per
evaluation. :func:`rk4_step` advances a whole batch by one fixed step without returning to Python
between the four stages.

Arguments are packed by :class:`~certkit.models.dynamics.eom.AircraftModel` (``_kernel_args``):

    props (n, 16)   1/m, J11 J12 J13 J22 J23 J33, (J⁻¹) K11 K12 K13 K22 K23 K33, r_ref (body, 3)
    consts (4,)     b, c, S, g
    aero            T, machs, clmax, stall, alpha_drag, after_stall (see
                    :mod:`certkit.models.aero.derivative_kernel`), ``use_table`` (False: the
                    coefficients are given per condition in ``coef`` (n, 8), computed in Python by a
                    model that is not a derivative table)
    r_eng (n, ne, 3), d_eng (ne, 3); thrust (n, ne) N along each thrust line, from Python (engines are
                    Python models) or, for the parametric turbofan, from :func:`engine_forces`; held over an RK4 step
                    like the controls
    ground          has_ground, r_gear (n, nl, 3), legs (nl, 6) = stiffness, damping, rolling and side
                    friction, braked, steered (the wheel turned by the steering control, positive toward body +y:
                    nose right); gparams = runway elevation, brake friction, slip speed, then the
                    ground effect's wing (:meth:`~certkit.models.dynamics.eom.AircraftModel._ground_effect_params`:
                    [3] span, 0 for none; [4] aspect ratio; [5] tan Λ½; [6:9] wing point from the aero reference,
                    body axes), the tail's ([9:12] its point likewise; [12] ε₀, [13] dε/dα of the free-air downwash;
                    [14] C_Lα,t, 0 for none; [15] C_mα,t; [16:20] the R table's √(h/b) start and step, Δz start and
                    step; [20:22] its shape), the φ(h/b) table ([22:22 + N_TABLE]) and the R table (row-major);
                    brake_index, steer_index (control columns; −1: none)

Outputs per condition, columns of :data:`OUTPUTS`; gear normal loads (n, nl).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from certkit import atmosphere as isa
from certkit.atmosphere import isa_scalar
from certkit.models.aero.derivative_kernel import _row, coefficients_one, mach_weights
from certkit.models.aero.ground_effect import H_OVER_B_MAX, N_TABLE, induced_drag_factor_at, lift_ratio
from certkit.models.aero.tail_ground_effect import downwash_ratio_one
from certkit.models.compiled import borrowed, copy_row
from certkit.models.propulsion.engine import turbofan_row_thrust, windmill_drag_one

OUTPUTS = ("V", "alpha", "beta", "mach", "qbar", "n_x", "n_y", "n_z", "alpha_dot", "CL", "CD")
AIR = ("h_clipped", "V", "alpha", "beta", "mach", "qbar")

_R, _GAMMA = isa.R_AIR, isa.GAMMA
#: where the φ table and the tail's R table start in gparams
_PHI = 22
_RATIO = _PHI + N_TABLE
_H_MIN, _H_MAX = -600.0, isa.H_MAX


@njit(cache=True, error_model="numpy", fastmath=True, inline="always")
def _air(h, u, v, w):
    """ISA (troposphere + isothermal layer, altitude clipped to the modelled range) and air data:
    (h clipped, V, α, β, Mach, q̄)."""
    hc = min(max(h, _H_MIN), _H_MAX)
    T_air, p_air = isa_scalar(hc)
    rho = p_air / (_R * T_air)
    V2 = u * u + v * v + w * w
    V = math.sqrt(V2)
    Vs = max(V, 1e-3)
    alpha = math.atan2(w, u)
    beta = math.asin(min(max(v / Vs, -1.0), 1.0))
    return hc, V, alpha, beta, V / math.sqrt(_GAMMA * _R * T_air), 0.5 * rho * V2


@njit(cache=True, error_model="numpy", fastmath=True)
def air_data(X):
    """Air data (columns of :data:`AIR`) of each state row (h, u, v, w at columns 2–5)."""
    n = X.shape[0]
    out = np.empty((n, 6))
    for i in range(n):
        r = _air(X[i, 2], X[i, 3], X[i, 4], X[i, 5])
        for k in range(6):
            out[i, k] = r[k]
    return out


@njit(cache=True, error_model="numpy", fastmath=True, inline="always")
def _dcm(x, quat):
    """Body→NED direction cosines (row by row) from the quaternion or the Euler angles."""
    if quat:
        q0, q1, q2, q3 = x[9], x[10], x[11], x[12]
        q00, q11, q22, q33 = q0 * q0, q1 * q1, q2 * q2, q3 * q3
        q01, q02, q03, q12, q13, q23 = q0 * q1, q0 * q2, q0 * q3, q1 * q2, q1 * q3, q2 * q3
        return (
            q00 + q11 - q22 - q33,
            2 * (q12 - q03),
            2 * (q13 + q02),
            2 * (q12 + q03),
            q00 - q11 + q22 - q33,
            2 * (q23 - q01),
            2 * (q13 - q02),
            2 * (q23 + q01),
            q00 - q11 - q22 + q33,
        )
    sf, cf = math.sin(x[9]), math.cos(x[9])
    st, ct = math.sin(x[10]), math.cos(x[10])
    sp, cp = math.sin(x[11]), math.cos(x[11])
    return (
        ct * cp,
        sf * st * cp - cf * sp,
        cf * st * cp + sf * sp,
        ct * sp,
        sf * st * sp + cf * cp,
        cf * st * sp - sf * cp,
        -st,
        sf * ct,
        cf * ct,
    )


@njit(cache=True, error_model="numpy", fastmath=True, inline="always")
def _add_force(Fx, Fy, Fz, Mx, My, Mz, fx, fy, fz, rx, ry, rz):
    """Totals plus the force (fx, fy, fz) applied at body point (rx, ry, rz)."""
    return (Fx + fx, Fy + fy, Fz + fz, Mx + ry * fz - rz * fy, My + rz * fx - rx * fz, Mz + rx * fy - ry * fx)


@njit(cache=True, error_model="numpy", fastmath=True, inline="always")
def _ground_effect(C31, C32, C33, height, props_i, gparams, T, machs, mach, alpha, coef):
    """Ground effect (:mod:`certkit.models.aero.ground_effect`) on the table's CL and CD: the wing point's
    height over the span gives φ; CL × λ = a(A/φ)/a(A), induced drag k (CL − CL_minD)² × φ at the new CL. With the
    tail's data, the downwash at the tail (:mod:`certkit.models.aero.tail_ground_effect`): ε = R λ ε_free, so the
    tail's angle of attack rises by ε_free (1 − R λ), through its lift and moment slopes, and the downwash-lag
    derivatives scale by R λ."""
    wx, wy, wz = props_i[13] + gparams[6], props_i[14] + gparams[7], props_i[15] + gparams[8]
    hb = (height - (C31 * wx + C32 * wy + C33 * wz)) / gparams[3]
    if hb >= H_OVER_B_MAX:
        return
    phi = induced_drag_factor_at(gparams[_PHI:_RATIO], hb)
    i0, i1, w = mach_weights(machs, mach)
    k, cl_min = _row(T, 5, i0, i1, w), _row(T, 6, i0, i1, w)
    cl = coef[0]
    lam = lift_ratio(phi, gparams[4], gparams[5], mach)
    cl_ge = cl * lam
    coef[0] = cl_ge
    coef[1] += k * (phi * (cl_ge - cl_min) ** 2 - (cl - cl_min) ** 2)
    if gparams[14] != 0.0:
        tx, ty, tz = props_i[13] + gparams[9], props_i[14] + gparams[10], props_i[15] + gparams[11]
        dz = C31 * (wx - tx) + C32 * (wy - ty) + C33 * (wz - tz)  # the tail's height over the wing point
        nr, nz = int(gparams[20]), int(gparams[21])
        keep = lam * downwash_ratio_one(
            hb,
            dz,
            gparams[_RATIO : _RATIO + nr * nz].reshape((nr, nz)),
            gparams[16],
            gparams[17],
            gparams[18],
            gparams[19],
        )
        d_alpha = (gparams[12] + gparams[13] * alpha) * (1.0 - keep)
        coef[0] += gparams[14] * d_alpha
        coef[4] += gparams[15] * d_alpha
        coef[6] *= keep
        coef[7] *= keep


# inlined (numba IR) where it is called: a call passing ~15 arrays costs as much as the arithmetic (a study's
# simulations run ~0.8 → 0.4 µs per evaluation); the RK4 step calls it from one site to keep the compile short
@njit(cache=True, error_model="numpy", fastmath=True, inline="always")
def derivative_one(
    i,
    x,
    quat,
    ctrl,
    thrust_i,
    coef_i,
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
    xd,
    out,
    gear,
):
    """State derivative of condition ``i`` (state ``x``, 13 quaternion or 12 Euler components) into
    ``xd``; outputs into ``out`` (:data:`OUTPUTS`) and gear loads into ``gear``."""
    h, u, v, w, p, q, r = x[2], x[3], x[4], x[5], x[6], x[7], x[8]
    C11, C12, C13, C21, C22, C23, C31, C32, C33 = _dcm(x, quat)
    hc, V, alpha, beta, mach, qbar = _air(h, u, v, w)
    Vs = max(V, 1e-3)
    uw2 = max(u * u + w * w, 1e-6)
    b, c, S, g = consts[0], consts[1], consts[2], consts[3]
    coef = coef_i
    if use_table:  # coef_i is scratch space, else it holds the coefficients computed in Python
        coefficients_one(
            T,
            machs,
            clmax,
            stall,
            alpha_drag,
            after_stall,
            alpha,
            beta,
            p * (b / 2) / Vs,
            q * (c / 2) / Vs,
            r * (b / 2) / Vs,
            mach,
            ctrl[:n_aero],
            coef,
        )
        if has_ground and gparams[3] > 0.0:
            _ground_effect(C31, C32, C33, h - gparams[0], props[i], gparams, T, machs, mach, alpha, coef)
    CL, CD = coef[0], coef[1]
    suw = math.sqrt(uw2)
    ca, sa = u / suw, w / suw
    qS = qbar * S
    Fx = qS * (CL * sa - CD * ca)
    Fy = qS * coef[2]
    Fz = -qS * (CD * sa + CL * ca)
    rx, ry, rz = props[i, 13], props[i, 14], props[i, 15]
    Mx = qS * b * coef[3] + ry * Fz - rz * Fy
    My = qS * c * coef[4] + rz * Fx - rx * Fz
    Mz = qS * b * coef[5] + rx * Fy - ry * Fx
    for j in range(thrust_i.shape[0]):
        t = thrust_i[j]
        fx, fy, fz = t * d_eng[j, 0], t * d_eng[j, 1], t * d_eng[j, 2]
        Fx, Fy, Fz, Mx, My, Mz = _add_force(
            Fx, Fy, Fz, Mx, My, Mz, fx, fy, fz, r_eng[i, j, 0], r_eng[i, j, 1], r_eng[i, j, 2]
        )
    if has_ground:
        # spring–damper legs; friction along and across the wheel heading (body x projected on
        # the horizontal plane), smooth saturation tanh(v / slip speed)
        nrm = max(math.hypot(C11, C21), 1e-9)
        hx, hy = C11 / nrm, C21 / nrm
        brake = 0.0
        if brake_index >= 0:
            brake = min(max(ctrl[brake_index], 0.0), 1.0)
        inv_slip = 1.0 / gparams[2]
        for k in range(legs.shape[0]):
            gx, gy, gz = r_gear[i, k, 0], r_gear[i, k, 1], r_gear[i, k, 2]
            height = (h - gparams[0]) - (C31 * gx + C32 * gy + C33 * gz)
            if height >= 0.0:
                gear[k] = 0.0
                continue
            vx = u + q * gz - r * gy
            vy = v + r * gx - p * gz
            vz = w + p * gy - q * gx
            vN = C11 * vx + C12 * vy + C13 * vz
            vE = C21 * vx + C22 * vy + C23 * vz
            vD = C31 * vx + C32 * vy + C33 * vz
            load = max(legs[k, 0] * (-height) + legs[k, 1] * vD, 0.0)
            gear[k] = load
            wx, wy = hx, hy  # the wheel's heading: the body's, or turned by the steering angle on a steered leg
            if steer_index >= 0 and legs[k, 5] != 0.0:
                cs, sn = math.cos(ctrl[steer_index]), math.sin(ctrl[steer_index])
                sx, sy = C11 * cs + C12 * sn, C21 * cs + C22 * sn
                ns = max(math.hypot(sx, sy), 1e-9)
                wx, wy = sx / ns, sy / ns
            mu_long = legs[k, 2] + legs[k, 4] * gparams[1] * brake
            f_long = -mu_long * load * math.tanh((vN * wx + vE * wy) * inv_slip)
            f_lat = -legs[k, 3] * load * math.tanh((vE * wx - vN * wy) * inv_slip)
            fN = f_long * wx - f_lat * wy
            fE = f_long * wy + f_lat * wx
            fbx = C11 * fN + C21 * fE - C31 * load
            fby = C12 * fN + C22 * fE - C32 * load
            fbz = C13 * fN + C23 * fE - C33 * load
            Fx, Fy, Fz, Mx, My, Mz = _add_force(Fx, Fy, Fz, Mx, My, Mz, fbx, fby, fbz, gx, gy, gz)
    im = props[i, 0]
    udot = Fx * im + g * C31 - (q * w - r * v)
    vdot = Fy * im + g * C32 - (r * u - p * w)
    wdot = Fz * im + g * C33 - (p * v - q * u)
    alpha_dot = (u * wdot - w * udot) / uw2
    CLad, Cmad = coef[6], coef[7]
    if CLad != 0.0 or Cmad != 0.0:
        # the α̇ forces are linear in α̇: solve the implicit equation exactly
        kf = qS * (c / 2) / Vs * CLad
        dFx, dFz = kf * sa, -kf * ca
        alpha_dot = alpha_dot / (1.0 - (u * dFz - w * dFx) * im / uw2)
        udot += dFx * im * alpha_dot
        wdot += dFz * im * alpha_dot
        Fx += dFx * alpha_dot
        Fz += dFz * alpha_dot
        Mx += ry * dFz * alpha_dot
        My += (qS * c * (c / 2) / Vs * Cmad + rz * dFx - rx * dFz) * alpha_dot
        Mz -= ry * dFx * alpha_dot
    J11, J12, J13, J22, J23, J33 = props[i, 1], props[i, 2], props[i, 3], props[i, 4], props[i, 5], props[i, 6]
    hx_ = J11 * p + J12 * q + J13 * r
    hy_ = J12 * p + J22 * q + J23 * r
    hz_ = J13 * p + J23 * q + J33 * r
    ax = Mx - (q * hz_ - r * hy_)
    ay = My - (r * hx_ - p * hz_)
    az = Mz - (p * hy_ - q * hx_)
    K11, K12, K13, K22, K23, K33 = props[i, 7], props[i, 8], props[i, 9], props[i, 10], props[i, 11], props[i, 12]
    xd[0] = C11 * u + C12 * v + C13 * w
    xd[1] = C21 * u + C22 * v + C23 * w
    xd[2] = -(C31 * u + C32 * v + C33 * w)
    xd[3] = udot
    xd[4] = vdot
    xd[5] = wdot
    xd[6] = K11 * ax + K12 * ay + K13 * az
    xd[7] = K12 * ax + K22 * ay + K23 * az
    xd[8] = K13 * ax + K23 * ay + K33 * az
    if quat:
        q0, q1, q2, q3 = x[9], x[10], x[11], x[12]
        xd[9] = -0.5 * (p * q1 + q * q2 + r * q3)
        xd[10] = 0.5 * (p * q0 + r * q2 - q * q3)
        xd[11] = 0.5 * (q * q0 - r * q1 + p * q3)
        xd[12] = 0.5 * (r * q0 + q * q1 - p * q2)
    else:
        sf, cf = math.sin(x[9]), math.cos(x[9])
        st, ct = math.sin(x[10]), math.cos(x[10])
        xd[9] = p + (q * sf + r * cf) * st / ct
        xd[10] = q * cf - r * sf
        xd[11] = (q * sf + r * cf) / ct
    Wt = g / im
    out[0] = V
    out[1] = alpha
    out[2] = beta
    out[3] = mach
    out[4] = qbar
    out[5] = Fx / Wt
    out[6] = Fy / Wt
    out[7] = -Fz / Wt
    out[8] = alpha_dot
    out[9] = CL
    out[10] = CD


@njit(cache=True, inline="always")
def _borrowed_model(props, consts, T, machs, clmax, stall, after_stall, r_eng, d_eng, r_gear, legs, gparams):  # type: ignore[no-untyped-def]
    """The model's arrays :func:`~certkit.models.compiled.borrowed`: :func:`derivatives` and :func:`rk4_step` borrow
    every array they are given, so that the equations of motion inlined in them alias the arrays without atomic
    reference counts."""
    return (
        borrowed(props),
        borrowed(consts),
        borrowed(T),
        borrowed(machs),
        borrowed(clmax),
        borrowed(stall),
        borrowed(after_stall),
        borrowed(r_eng),
        borrowed(d_eng),
        borrowed(r_gear),
        borrowed(legs),
        borrowed(gparams),
    )


@njit(cache=True, error_model="numpy", fastmath=True)
def derivatives(
    X,
    rows,
    quat,
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
):
    """:func:`derivative_one` over the batch: row i of ``X`` is a state of condition ``rows[i]``.
    Returns ẋ (rows, states), outputs (rows, 11), gear loads (rows, nl)."""
    n, ns = X.shape
    xd = np.empty((n, ns))
    out = np.empty((n, len(OUTPUTS)))
    gear = np.zeros((n, legs.shape[0]))
    derivatives_into(
        X,
        rows,
        quat,
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
        xd,
        out,
        gear,
        np.ones(n, dtype=np.bool_),
    )
    return xd, out, gear


@njit(cache=True, error_model="numpy", fastmath=True)
def derivatives_into(
    X,
    rows,
    quat,
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
    xd,
    out,
    gear,
    active,
):
    """:func:`derivatives` into the caller's arrays ``xd``, ``out`` and ``gear`` (the gear loads zero where a leg does
    not touch) for the rows ``active`` (n,) marks, the others' left as they are: every array borrowed
    (:func:`~certkit.models.compiled.borrowed`), none counted per row."""
    X, rows, U, thrust, coef = borrowed(X), borrowed(rows), borrowed(U), borrowed(thrust), borrowed(coef)
    xd, out, gear, active = borrowed(xd), borrowed(out), borrowed(gear), borrowed(active)
    props, consts, T, machs, clmax, stall, after_stall, r_eng, d_eng, r_gear, legs, gparams = _borrowed_model(
        props, consts, T, machs, clmax, stall, after_stall, r_eng, d_eng, r_gear, legs, gparams
    )
    n = X.shape[0]
    for i in range(n):
        if not active[i]:
            continue
        derivative_one(
            rows[i],
            X[i],
            quat,
            U[i],
            thrust[i],
            coef[i],
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
            xd[i],
            out[i],
            gear[i],
        )


@njit(cache=True, inline="always")
def failed_engine_force(running, dead, fraction):
    """Force of a failed engine: its windmilling force ``dead`` (minus the drag) plus ``fraction`` of the difference
    to its ``running`` thrust (a spool-down; 0: windmilling at once)."""
    return dead + fraction * (running - dead)


@njit(cache=True, fastmath=False)
def failed_engine_forces(thrust, dead, operative, fraction):
    """:func:`failed_engine_force` in place of the running thrust (n, ne) of the engines not ``operative``."""
    for i in range(thrust.shape[0]):
        for j in range(thrust.shape[1]):
            if not operative[i, j]:
                thrust[i, j] = failed_engine_force(thrust[i, j], dead[i, j], fraction[i, j])


# fastmath off, explicitly (a callee inherits its caller's unless set): the thrust bit for bit as the engine models
# give it in Python (AircraftModel.thrust_forces)
@njit(cache=True, fastmath=False)
def engine_forces(air, U, rows, turbofan, throttle_start, operative, fraction, windmill):
    """Force of each engine along its thrust line (n, ne), N, from the air data (:data:`AIR` columns) and the controls
    of each row, row i of condition ``rows[i]``: the parametric turbofan ``turbofan``
    (:meth:`~certkit.models.propulsion.engine.ParametricTurbofan.kernel_parameters`) at the clipped altitude and Mach;
    a failed engine (``operative`` False) by :func:`failed_engine_force` (``fraction`` (n, ne)) with its windmilling
    drag (``windmill`` row: :meth:`~certkit.models.propulsion.engine.WindmillDrag.kernel_parameters`, NaN: none)."""
    n, ne = air.shape[0], operative.shape[1]
    thrust = np.empty((n, ne))
    for i in range(n):
        hc, mach, qbar, c = air[i, 0], air[i, 4], air[i, 5], rows[i]
        turbofan_row_thrust(
            hc, mach, U[i, throttle_start : throttle_start + ne], turbofan[0], turbofan[1], turbofan[2], thrust[i]
        )
        for j in range(ne):
            if not operative[c, j]:
                dead = 0.0 if math.isnan(windmill[j, 0]) else -windmill_drag_one(qbar, mach, windmill[j])
                thrust[i, j] = failed_engine_force(thrust[i, j], dead, fraction[c, j])
    return thrust


@njit(cache=True, error_model="numpy", fastmath=True)
def rk4_step(
    X,
    XD1,
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
):
    """Advance the active conditions of the quaternion-state batch ``X`` (n, 13) in place by one
    classical RK4 step of ``dts[i]`` each, controls and thrust held; ``XD1`` the derivative at the
    step's start. The quaternion is renormalised after the step."""
    ns = X.shape[1]
    k = np.empty((3, ns))  # k2, k3, k4 (one call site of the inlined derivative: a third of the compiled code)
    xs = np.empty(ns)
    out = np.empty(len(OUTPUTS))
    gear = np.zeros(legs.shape[0])
    rk4_step_into(
        X,
        XD1,
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
        k,
        xs,
        out,
        gear,
    )


@njit(cache=True, error_model="numpy", fastmath=True)
def rk4_step_into(
    X,
    XD1,
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
    k,
    xs,
    out,
    gear,
):
    """:func:`rk4_step` with the caller's scratch: ``k`` (3, states) for k2–k4, ``xs`` (states,) the stage's state,
    ``out`` (outputs,) and ``gear`` (legs,) zeros (a leg not touching stays zero). Every array borrowed, so the
    equations of motion inlined here count none per row and stage."""
    X, XD1, active, dts = borrowed(X), borrowed(XD1), borrowed(active), borrowed(dts)
    U, thrust, coef = borrowed(U), borrowed(thrust), borrowed(coef)
    k, xs, out, gear = borrowed(k), borrowed(xs), borrowed(out), borrowed(gear)
    props, consts, T, machs, clmax, stall, after_stall, r_eng, d_eng, r_gear, legs, gparams = _borrowed_model(
        props, consts, T, machs, clmax, stall, after_stall, r_eng, d_eng, r_gear, legs, gparams
    )
    n, ns = X.shape
    for i in range(n):
        if not active[i]:
            continue
        dt = dts[i]
        x, k1 = X[i], XD1[i]
        for stage in range(3):
            prev = k1 if stage == 0 else k[stage - 1]
            h = dt if stage == 2 else 0.5 * dt
            for s in range(ns):
                xs[s] = x[s] + h * prev[s]
            derivative_one(
                i,
                xs,
                True,
                U[i],
                thrust[i],
                coef[i],
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
                k[stage],
                out,
                gear,
            )
        for s in range(ns):
            x[s] = x[s] + dt / 6.0 * (k1[s] + 2.0 * k[0, s] + 2.0 * k[1, s] + k[2, s])
        nq = math.sqrt(x[9] * x[9] + x[10] * x[10] + x[11] * x[11] + x[12] * x[12])
        for s in range(9, 13):
            x[s] /= nq


@njit(cache=True)
def record(out_rec, x_rec, u_rec, irec, out, X, U, active, all_active):
    """Record ``irec`` of a run: each condition's outputs, state and controls, a stopped one (not ``active``, unless
    ``all_active`` still) keeping its last record."""
    for i in range(X.shape[0]):
        if irec == 0 or active[i] or all_active:
            copy_row(out_rec[irec, i], out[i])
            copy_row(x_rec[irec, i], X[i])
            copy_row(u_rec[irec, i], U[i])
        else:  # a stopped condition keeps its last record
            copy_row(out_rec[irec, i], out_rec[irec - 1, i])
            copy_row(x_rec[irec, i], x_rec[irec - 1, i])
            copy_row(u_rec[irec, i], u_rec[irec - 1, i])


@njit(cache=True, error_model="numpy", fastmath=True)
def integrate_open_loop(
    X,
    U_all,
    dts,
    record_every,
    turbofan,
    throttle_start,
    n_engines,
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
    stop_cols,
    stop_lo,
    stop_hi,
    out_rec,
    x_rec,
    u_rec,
    stop_step,
    stop_which,
    rows,
    thrust,
    active,
    xd,
    out,
    gear,
    k_stages,
    x_stage,
    out_stage,
    gear_stage,
):
    """The whole fixed-step run of :func:`certkit.models.dynamics.simulate.simulate` when nothing in it needs Python:
    the controls of every step given (``U_all`` (nsteps + 1, n, m)), no controllers, every engine running as the
    parametric turbofan ``turbofan`` = (static thrust, throttle ratio, idle fraction) — the thrust of each step from
    the air data as :meth:`certkit.models.propulsion.engine.ParametricTurbofan.thrust_rows` gives it, then
    :func:`derivatives` and :func:`rk4_step` as the Python loop calls them — and stop criteria that are bounds
    (:class:`certkit.models.dynamics.simulate.Bound`): criterion c stops a condition when its output column
    ``stop_cols[c]`` (−1: the time) lies strictly below ``stop_lo[c, i]`` or above ``stop_hi[c, i]``, the first
    criterion in order naming the stop (``stop_which``, ``stop_step``: −1 when none); a stopped condition keeps its
    state and its last record (nothing of it is computed any more), and the run ends when every
    condition has stopped. ``X`` advances in place; the
    outputs, states and controls of every ``record_every``-th step go to ``out_rec``, ``x_rec`` and ``u_rec``.
    The caller gives the scratch arrays: ``rows`` = 0 … n − 1, ``thrust`` (n, engines), ``active`` (n,) all True,
    ``xd``, ``out``, ``gear`` (n, states / outputs / legs) and the RK4 step's ``k_stages`` (3, states), ``x_stage``,
    ``out_stage`` and ``gear_stage`` (the gear buffers zero); every array is borrowed, so that the views of a step
    (the step's controls, a row's throttles and thrust, the records' rows) count nothing.
    Returns the number recorded."""
    X, U_all, dts, turbofan, coef = borrowed(X), borrowed(U_all), borrowed(dts), borrowed(turbofan), borrowed(coef)
    stop_cols, stop_lo, stop_hi = borrowed(stop_cols), borrowed(stop_lo), borrowed(stop_hi)
    out_rec, x_rec, u_rec = borrowed(out_rec), borrowed(x_rec), borrowed(u_rec)
    stop_step, stop_which, rows, thrust, active = (
        borrowed(stop_step),
        borrowed(stop_which),
        borrowed(rows),
        borrowed(thrust),
        borrowed(active),
    )
    xd, out, gear = borrowed(xd), borrowed(out), borrowed(gear)
    k_stages, x_stage, out_stage, gear_stage = (
        borrowed(k_stages),
        borrowed(x_stage),
        borrowed(out_stage),
        borrowed(gear_stage),
    )
    props, consts, T, machs, clmax, stall, after_stall, r_eng, d_eng, r_gear, legs, gparams = _borrowed_model(
        props, consts, T, machs, clmax, stall, after_stall, r_eng, d_eng, r_gear, legs, gparams
    )
    n = X.shape[0]
    quaternion_state = X.shape[1] == 13  # a bool, not the literal True: the kernel compiled once for both callers
    n_active = n
    irec = 0
    nsteps = U_all.shape[0] - 1
    for k in range(nsteps + 1):
        U = U_all[k]
        for i in range(n):
            if not active[i]:  # a stopped condition keeps its state and last record: nothing of it is computed
                continue
            air = _air(X[i, 2], X[i, 3], X[i, 4], X[i, 5])
            turbofan_row_thrust(
                air[0],
                air[4],
                U[i, throttle_start : throttle_start + n_engines],
                turbofan[0],
                turbofan[1],
                turbofan[2],
                thrust[i],
            )
        derivatives_into(
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
            xd,
            out,
            gear,
            active,
        )
        for c in range(stop_cols.shape[0]):
            for i in range(n):
                if active[i]:
                    v = k * dts[i] if stop_cols[c] < 0 else out[i, stop_cols[c]]
                    if v < stop_lo[c, i] or v > stop_hi[c, i]:
                        active[i] = False
                        n_active -= 1
                        stop_step[i] = k
                        stop_which[i] = c
        if k % record_every == 0:
            record(out_rec, x_rec, u_rec, irec, out, X, U, active, n_active == n)
            irec += 1
        if k == nsteps or n_active == 0:
            break
        rk4_step_into(
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
            k_stages,
            x_stage,
            out_stage,
            gear_stage,
        )
    return irec
