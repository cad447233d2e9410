"""Rigid-body six-degree-of-freedom equations of motion, vectorised over a batch of conditions.

Frames and states (conventions of :mod:`certkit.conventions`)
    Earth frame: flat, non-rotating, north-east-down; altitude h is positive up.
    Body axes: origin at the condition's CG, x forward, y right, z down.

    Simulation state, shape (n, 13)  — :data:`QUAT_STATE`
        x_N, y_E, h, u, v, w, p, q, r, q0, q1, q2, q3
    Trim / linearisation state, shape (n, 12)  — :data:`EULER_STATE`
        x_N, y_E, h, u, v, w, p, q, r, phi, theta, psi

    The simulation integrates the attitude quaternion (q0 scalar part): it has no singularity at
    θ = ±90°, costs no trigonometry per step and stays well conditioned through rolling
    manoeuvres; its unit norm is restored after each step. Trims and linearisations use Euler
    angles, which is what they report and what the textbooks' A matrices are written in
    (the kinematic singularity at θ = ±90° is far from any trimmed transport condition).
    :func:`quat_to_euler` and :func:`euler_to_quat` convert.

Forces and moments
    * aerodynamic: the :class:`~certkit.models.aero.interface.AeroModel` coefficients at
      α = atan2(w, u), β = asin(v/V), body rates normalised p b/2V, q c/2V, r b/2V; forces
      CX, CZ from CL, CD by rotation through α (:meth:`Coefficients.body_forces`), moments about
      the aero reference point transferred to each condition's CG (M_cg = M_ref + r_ref × F).
      If the model offers ``alpha_dot_derivatives(mach)`` (CL_α̇, Cm_α̇ per unit α̇ c/2V), the
      implicit α̇ term is solved exactly: with a₀ the accelerations without it, the α̇ forces
      are linear in α̇, so α̇ = α̇₀ / (1 − (u k_z − w k_x)/(u² + w²)), k the α̇-force per unit α̇
      over m.
    * thrust: per engine, ``thrust(throttle, h, mach)`` in newtons along the engine's thrust line
      at its position, so an engine out (``operative`` False) gives the asymmetric yawing moment;
      a failed engine produces its windmilling drag instead (if the engine gives one).
    * gravity, g along earth-down.
    * ground reactions (optional :class:`GroundModel`): spring–damper gear legs with rolling and
      side friction, for takeoff and landing.

Equations: m(v̇_b + ω × v_b) = F,   J ω̇ + ω × J ω = M  with the full inertia tensor
    J = [[Ixx, −Ixy, −Ixz], [−Ixy, Iyy, −Iyz], [−Ixz, −Iyz, Izz]] (products Ixz = ∫ x z dm),
    about the CG in body axes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from certkit import atmosphere as isa
from certkit.models.aero.interface import AeroModel, AeroState
from certkit.units import G0

QUAT_STATE = ("x_N", "y_E", "h", "u", "v", "w", "p", "q", "r", "q0", "q1", "q2", "q3")
EULER_STATE = ("x_N", "y_E", "h", "u", "v", "w", "p", "q", "r", "phi", "theta", "psi")

_H_MIN, _H_MAX = -600.0, isa.H_MAX


def airplane_to_body(points, cg) -> np.ndarray:
    """Airplane-frame points (X aft, Y right, Z up), shape (..., 3), to body axes about ``cg``."""
    points = np.asarray(points, dtype=float)
    cg = np.asarray(cg, dtype=float)
    d = points - cg
    return np.stack([-d[..., 0], d[..., 1], -d[..., 2]], axis=-1)


@dataclass
class Engine:
    """One engine. ``thrust(throttle, h, mach) -> N`` (arrays of the batch's shape); ``position``
    in the airplane frame (X aft, Y right, Z up, m); ``direction`` the thrust line as a unit
    vector in body axes; ``windmill_drag(qbar, mach) -> N`` when failed (None: zero)."""

    name: str
    thrust: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]
    position: Sequence[float] = (0.0, 0.0, 0.0)
    direction: Sequence[float] = (1.0, 0.0, 0.0)
    windmill_drag: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None


@dataclass
class GearLeg:
    """A gear contact point (airplane frame, wheel bottom at full extension), spring stiffness
    (N/m), damping (N s/m), rolling and side-friction coefficients; ``braked`` legs add the
    brake control's friction."""

    name: str
    position: Sequence[float]
    stiffness: float
    damping: float
    rolling_friction: float = 0.02
    side_friction: float = 0.6
    braked: bool = False


@dataclass
class GroundModel:
    """Flat runway at ``elevation`` (m). ``brake_friction`` is the friction coefficient of the
    braked legs at full brake (control ``brake`` in [0, 1]). Friction forces use a smooth
    saturation tanh(v/``slip_speed``) so that the aircraft can stand still without chattering."""

    legs: Sequence[GearLeg]
    elevation: float = 0.0
    brake_friction: float = 0.4
    slip_speed: float = 0.3


def euler_to_quat(phi, theta, psi) -> np.ndarray:
    cphi, sphi = np.cos(phi / 2), np.sin(phi / 2)
    cth, sth = np.cos(theta / 2), np.sin(theta / 2)
    cpsi, spsi = np.cos(psi / 2), np.sin(psi / 2)
    return np.stack([
        cphi * cth * cpsi + sphi * sth * spsi,
        sphi * cth * cpsi - cphi * sth * spsi,
        cphi * sth * cpsi + sphi * cth * spsi,
        cphi * cth * spsi - sphi * sth * cpsi,
    ], axis=-1)


def quat_to_euler(quat) -> np.ndarray:
    q0, q1, q2, q3 = (quat[..., i] for i in range(4))
    phi = np.arctan2(2 * (q0 * q1 + q2 * q3), 1 - 2 * (q1 * q1 + q2 * q2))
    theta = np.arcsin(np.clip(2 * (q0 * q2 - q3 * q1), -1.0, 1.0))
    psi = np.arctan2(2 * (q0 * q3 + q1 * q2), 1 - 2 * (q2 * q2 + q3 * q3))
    return np.stack([phi, theta, psi], axis=-1)


def quat_to_dcm(quat) -> np.ndarray:
    """Body-to-earth (NED) direction cosine matrix, shape (..., 3, 3)."""
    q0, q1, q2, q3 = (quat[..., i] for i in range(4))
    return np.stack([
        np.stack([1 - 2 * (q2 * q2 + q3 * q3), 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)], -1),
        np.stack([2 * (q1 * q2 + q0 * q3), 1 - 2 * (q1 * q1 + q3 * q3), 2 * (q2 * q3 - q0 * q1)], -1),
        np.stack([2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), 1 - 2 * (q1 * q1 + q2 * q2)], -1),
    ], -2)


def euler_to_dcm(phi, theta, psi) -> np.ndarray:
    cf, sf, ct, st, cp, sp = np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta), np.cos(psi), np.sin(psi)
    return np.stack([
        np.stack([ct * cp, sf * st * cp - cf * sp, cf * st * cp + sf * sp], -1),
        np.stack([ct * sp, sf * st * sp + cf * cp, cf * st * sp - sf * cp], -1),
        np.stack([-st, sf * ct, cf * ct], -1),
    ], -2)


def inertia_tensor(Ixx, Iyy, Izz, Ixz=0.0, Ixy=0.0, Iyz=0.0) -> np.ndarray:
    """Inertia tensor (…, 3, 3) from moments and products (products ∫xz dm etc., body axes)."""
    Ixx, Iyy, Izz, Ixz, Ixy, Iyz = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (Ixx, Iyy, Izz, Ixz, Ixy, Iyz)))
    return np.stack([
        np.stack([Ixx, -Ixy, -Ixz], -1),
        np.stack([-Ixy, Iyy, -Iyz], -1),
        np.stack([-Ixz, -Iyz, Izz], -1),
    ], -2)


@dataclass
class Outputs:
    """Quantities computed alongside the derivatives, arrays of shape (n,)."""

    V: np.ndarray
    alpha: np.ndarray
    beta: np.ndarray
    mach: np.ndarray
    qbar: np.ndarray
    n_x: np.ndarray
    n_y: np.ndarray
    n_z: np.ndarray
    alpha_dot: np.ndarray
    thrust: np.ndarray  # (n, n_engines), N, along each thrust line (negative: windmilling drag)
    gear_load: np.ndarray  # (n, n_legs), normal reaction N
    CL: np.ndarray
    CD: np.ndarray


class AircraftModel:
    """Everything the equations of motion need for a batch of n conditions.

    Parameters
    ----------
    aero : AeroModel (moments about ``aero.reference`` x_ref, z_ref, airplane frame)
    mass : kg, float or (n,)
    cg : airplane-frame CG (X aft of nose, Y, Z up), (3,) or (n, 3)
    inertia : body-axis inertia tensor about the CG, (3, 3) or (n, 3, 3) — see :func:`inertia_tensor`
    engines : sequence of :class:`Engine`
    operative : (n_engines,) or (n, n_engines) booleans; a False engine windmills
    ground : optional :class:`GroundModel`
    g : gravity (m/s²)

    Controls are one array of shape (n, n_controls) in the order :attr:`control_names`: the aero
    model's controls, one throttle per engine (``throttle:<name>``), then ``brake`` when there is a
    ground model.
    """

    def __init__(self, aero: AeroModel, mass, cg, inertia, engines: Sequence[Engine] = (), operative=None,
                 ground: GroundModel | None = None, g: float = G0, n: int | None = None) -> None:
        self.aero = aero
        mass = np.asarray(mass, dtype=float)
        cg = np.asarray(cg, dtype=float)
        inertia = np.asarray(inertia, dtype=float)
        if n is None:
            n = max(mass.size if mass.ndim else 1, cg.shape[0] if cg.ndim == 2 else 1,
                    inertia.shape[0] if inertia.ndim == 3 else 1)
        self.n = n
        self.mass = np.broadcast_to(mass, (n,)).copy()
        self.cg = np.broadcast_to(cg, (n, 3)).copy()
        self.inertia = np.broadcast_to(inertia, (n, 3, 3)).copy()
        self.inertia_inv = np.linalg.inv(self.inertia)
        self.engines = tuple(engines)
        ne = len(self.engines)
        op = np.ones((n, ne), dtype=bool) if operative is None else np.broadcast_to(np.asarray(operative, dtype=bool), (n, ne)).copy()
        self.operative = op
        self.ground = ground
        self.g = float(g)
        ref = aero.reference
        self.b, self.c, self.S = ref.span, ref.chord, ref.area
        self.r_ref = airplane_to_body(np.array([ref.x_ref, 0.0, ref.z_ref]), self.cg)  # (n,3)
        if ne:
            pos = np.array([e.position for e in self.engines], dtype=float)  # (ne,3)
            self.r_eng = airplane_to_body(pos[None, :, :], self.cg[:, None, :])  # (n,ne,3)
            d = np.array([e.direction for e in self.engines], dtype=float)
            self.d_eng = d / np.linalg.norm(d, axis=1, keepdims=True)  # (ne,3)
        if ground is not None:
            pos = np.array([leg.position for leg in ground.legs], dtype=float)
            self.r_gear = airplane_to_body(pos[None, :, :], self.cg[:, None, :])  # (n,nl,3)
            self.k_gear = np.array([leg.stiffness for leg in ground.legs])
            self.c_gear = np.array([leg.damping for leg in ground.legs])
            self.mu_roll = np.array([leg.rolling_friction for leg in ground.legs])
            self.mu_side = np.array([leg.side_friction for leg in ground.legs])
            self.braked = np.array([leg.braked for leg in ground.legs], dtype=float)
        self.aero_controls = tuple(aero.control_names)
        names = list(self.aero_controls) + [f"throttle:{e.name}" for e in self.engines]
        if ground is not None:
            names.append("brake")
        self.control_names = tuple(names)
        self.throttle_slice = slice(len(self.aero_controls), len(self.aero_controls) + ne)
        ad = getattr(aero, "alpha_dot_derivatives", None)
        self._alpha_dot = ad if callable(ad) else None

    def control_index(self, name: str) -> int:
        return self.control_names.index(name)

    def subset(self, idx) -> "AircraftModel":
        """The model restricted to conditions ``idx`` (index array or boolean mask)."""
        idx = np.arange(self.n)[idx]
        return AircraftModel(self.aero, self.mass[idx], self.cg[idx], self.inertia[idx], self.engines,
                             self.operative[idx], self.ground, self.g, n=idx.size)

    # ------------------------------------------------------------------ core
    def body_dynamics(self, h, vel, omega, dcm, controls, with_outputs=False):
        """Accelerations for positions/velocities of the batch.

        h (n,), vel (n,3) body velocity, omega (n,3) body rates, dcm (n,3,3) body→NED,
        controls (n, n_controls). Returns (pos_dot (n,3) as ẋ_N, ẏ_E, ḣ; vel_dot; omega_dot) and
        an :class:`Outputs` when asked.
        """
        n = vel.shape[0]
        u, v, w = vel[:, 0], vel[:, 1], vel[:, 2]
        p, q, r = omega[:, 0], omega[:, 1], omega[:, 2]
        V = np.sqrt(u * u + v * v + w * w)
        Vs = np.maximum(V, 1e-3)
        alpha = np.arctan2(w, u)
        beta = np.arcsin(np.clip(v / Vs, -1.0, 1.0))
        hc = np.clip(h, _H_MIN, _H_MAX)
        T_air = np.where(hc <= isa.H_TROPOPAUSE, isa.T0 + isa.LAPSE * hc, isa.T0 + isa.LAPSE * isa.H_TROPOPAUSE)
        rho = isa.density(hc)
        a_snd = np.sqrt(isa.GAMMA * isa.R_AIR * T_air)
        mach = V / a_snd
        qbar = 0.5 * rho * V * V
        b, c, S = self.b, self.c, self.S
        ctrl = {name: controls[:, i] for i, name in enumerate(self.aero_controls)}
        coef = self.aero.coefficients(AeroState(
            alpha=alpha, beta=beta, p_hat=p * b / (2 * Vs), q_hat=q * c / (2 * Vs), r_hat=r * b / (2 * Vs),
            mach=mach, controls=ctrl))
        ca, sa = np.cos(alpha), np.sin(alpha)
        qS = qbar * S
        F = np.empty((n, 3))
        F[:, 0] = qS * (-coef.CD * ca + coef.CL * sa)
        F[:, 1] = qS * np.broadcast_to(coef.CY, (n,))
        F[:, 2] = qS * (-coef.CD * sa - coef.CL * ca)
        M = np.empty((n, 3))
        M[:, 0] = qS * b * coef.Cl
        M[:, 1] = qS * c * coef.Cm
        M[:, 2] = qS * b * coef.Cn
        M += np.cross(self.r_ref, F)

        ne = len(self.engines)
        thrust = np.zeros((n, ne))
        if ne:
            thr = controls[:, self.throttle_slice]
            for j, eng in enumerate(self.engines):
                t = np.asarray(eng.thrust(thr[:, j], hc, mach), dtype=float)
                if eng.windmill_drag is not None:
                    dwm = np.asarray(eng.windmill_drag(qbar, mach), dtype=float)
                else:
                    dwm = 0.0
                thrust[:, j] = np.where(self.operative[:, j], t, -dwm)
            Fe = thrust[:, :, None] * self.d_eng[None, :, :]
            F += Fe.sum(axis=1)
            M += np.cross(self.r_eng, Fe).sum(axis=1)

        gear_load = np.zeros((n, 0))
        if self.ground is not None:
            Fg, Mg, gear_load = self._ground_forces(h, vel, omega, dcm, controls)
            F += Fg
            M += Mg

        m = self.mass
        g_body = self.g * dcm[:, 2, :]  # third row of body→NED = earth-down in body axes
        wxv = np.cross(omega, vel)
        vel_dot = F / m[:, None] + g_body - wxv

        alpha_dot = (u * vel_dot[:, 2] - w * vel_dot[:, 0]) / np.maximum(u * u + w * w, 1e-6)
        if self._alpha_dot is not None:
            CLad, Cmad = self._alpha_dot(mach)
            kf = qS * c / (2 * Vs) * CLad  # lift per unit alpha_dot
            dF = np.stack([kf * sa, np.zeros(n), -kf * ca], axis=1)  # force per unit alpha_dot
            kx, kz = dF[:, 0] / m, dF[:, 2] / m
            denom = 1.0 - (u * kz - w * kx) / np.maximum(u * u + w * w, 1e-6)
            alpha_dot = alpha_dot / denom
            vel_dot = vel_dot + dF / m[:, None] * alpha_dot[:, None]
            dM = np.zeros((n, 3))
            dM[:, 1] = qS * c * c / (2 * Vs) * Cmad
            dM += np.cross(self.r_ref, dF)
            F = F + dF * alpha_dot[:, None]
            M = M + dM * alpha_dot[:, None]

        J = self.inertia
        Jw = np.einsum("nij,nj->ni", J, omega)
        omega_dot = np.einsum("nij,nj->ni", self.inertia_inv, M - np.cross(omega, Jw))
        v_ned = np.einsum("nij,nj->ni", dcm, vel)
        pos_dot = np.stack([v_ned[:, 0], v_ned[:, 1], -v_ned[:, 2]], axis=1)
        if not with_outputs:
            return pos_dot, vel_dot, omega_dot, None
        W = m * self.g
        out = Outputs(V=V, alpha=alpha, beta=beta, mach=mach, qbar=qbar,
                      n_x=F[:, 0] / W, n_y=F[:, 1] / W, n_z=-F[:, 2] / W, alpha_dot=alpha_dot,
                      thrust=thrust, gear_load=gear_load,
                      CL=np.broadcast_to(coef.CL, (n,)), CD=np.broadcast_to(coef.CD, (n,)))
        return pos_dot, vel_dot, omega_dot, out

    def _ground_forces(self, h, vel, omega, dcm, controls):
        gm = self.ground
        r = self.r_gear  # (n,nl,3)
        r_ned = np.einsum("nij,nlj->nli", dcm, r)
        height = h[:, None] - gm.elevation - r_ned[:, :, 2]  # point height above runway
        v_pt = vel[:, None, :] + np.cross(omega[:, None, :], r)  # body
        v_ned = np.einsum("nij,nlj->nli", dcm, v_pt)
        comp = np.maximum(-height, 0.0)
        load = np.where(comp > 0.0, np.maximum(self.k_gear * comp + self.c_gear * v_ned[:, :, 2], 0.0), 0.0)
        # wheel axes on the ground: heading of body x projected on the horizontal plane
        hx = dcm[:, 0, 0]
        hy = dcm[:, 1, 0]
        nrm = np.maximum(np.hypot(hx, hy), 1e-9)
        ex = np.stack([hx / nrm, hy / nrm], axis=1)  # (n,2)
        ey = np.stack([-ex[:, 1], ex[:, 0]], axis=1)
        v_long = v_ned[:, :, 0] * ex[:, None, 0] + v_ned[:, :, 1] * ex[:, None, 1]
        v_lat = v_ned[:, :, 0] * ey[:, None, 0] + v_ned[:, :, 1] * ey[:, None, 1]
        if "brake" in self.control_names:
            brake = np.clip(controls[:, self.control_names.index("brake")], 0.0, 1.0)
        else:
            brake = np.zeros(h.shape)
        mu_long = self.mu_roll[None, :] + self.braked[None, :] * gm.brake_friction * brake[:, None]
        f_long = -mu_long * load * np.tanh(v_long / gm.slip_speed)
        f_lat = -self.mu_side[None, :] * load * np.tanh(v_lat / gm.slip_speed)
        f_ned = np.empty(r.shape)
        f_ned[:, :, 0] = f_long * ex[:, None, 0] + f_lat * ey[:, None, 0]
        f_ned[:, :, 1] = f_long * ex[:, None, 1] + f_lat * ey[:, None, 1]
        f_ned[:, :, 2] = -load
        f_body = np.einsum("nji,nlj->nli", dcm, f_ned)
        return f_body.sum(axis=1), np.cross(r, f_body).sum(axis=1), load

    # ------------------------------------------------------------------ state forms
    def derivatives_quat(self, x, controls, with_outputs=False):
        """ẋ for the quaternion state (n, 13)."""
        quat = x[:, 9:13]
        dcm = quat_to_dcm(quat)
        pos_dot, vel_dot, omega_dot, out = self.body_dynamics(x[:, 2], x[:, 3:6], x[:, 6:9], dcm, controls, with_outputs)
        p, q, r = x[:, 6], x[:, 7], x[:, 8]
        q0, q1, q2, q3 = quat[:, 0], quat[:, 1], quat[:, 2], quat[:, 3]
        qdot = 0.5 * np.stack([
            -p * q1 - q * q2 - r * q3,
            p * q0 + r * q2 - q * q3,
            q * q0 - r * q1 + p * q3,
            r * q0 + q * q1 - p * q2,
        ], axis=1)
        xd = np.concatenate([pos_dot, vel_dot, omega_dot, qdot], axis=1)
        return (xd, out) if with_outputs else xd

    def derivatives_euler(self, x, controls, with_outputs=False):
        """ẋ for the Euler-angle state (n, 12)."""
        phi, theta, psi = x[:, 9], x[:, 10], x[:, 11]
        dcm = euler_to_dcm(phi, theta, psi)
        pos_dot, vel_dot, omega_dot, out = self.body_dynamics(x[:, 2], x[:, 3:6], x[:, 6:9], dcm, controls, with_outputs)
        p, q, r = x[:, 6], x[:, 7], x[:, 8]
        sf, cf, ct, tt = np.sin(phi), np.cos(phi), np.cos(theta), np.tan(theta)
        eul_dot = np.stack([
            p + (q * sf + r * cf) * tt,
            q * cf - r * sf,
            (q * sf + r * cf) / ct,
        ], axis=1)
        xd = np.concatenate([pos_dot, vel_dot, omega_dot, eul_dot], axis=1)
        return (xd, out) if with_outputs else xd


def euler_state_to_quat_state(x12) -> np.ndarray:
    return np.concatenate([x12[:, :9], euler_to_quat(x12[:, 9], x12[:, 10], x12[:, 11])], axis=1)


def quat_state_to_euler_state(x13) -> np.ndarray:
    return np.concatenate([x13[:, :9], quat_to_euler(x13[:, 9:13])], axis=1)


def energy(model: AircraftModel, x13) -> np.ndarray:
    """Total mechanical energy (J) per condition: translational + rotational kinetic + potential."""
    vel, omega = x13[:, 3:6], x13[:, 6:9]
    kin = 0.5 * model.mass * np.sum(vel * vel, axis=1)
    rot = 0.5 * np.einsum("ni,nij,nj->n", omega, model.inertia, omega)
    return kin + rot + model.mass * model.g * x13[:, 2]


__all__ = [
    "QUAT_STATE", "EULER_STATE", "Engine", "GearLeg", "GroundModel", "AircraftModel", "Outputs",
    "inertia_tensor", "airplane_to_body", "euler_to_quat", "quat_to_euler", "quat_to_dcm", "euler_to_dcm",
    "euler_state_to_quat_state", "quat_state_to_euler_state", "energy",
]
