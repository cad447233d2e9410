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
_T11 = isa.T0 + isa.LAPSE * isa.H_TROPOPAUSE
_EXP_TROPO = -G0 / (isa.LAPSE * isa.R_AIR)
_P11 = isa.P0 * (_T11 / isa.T0) ** _EXP_TROPO
_K_STRATO = -G0 / (isa.R_AIR * _T11)


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
            self._rgear = tuple(self.r_gear[:, :, k].copy() for k in range(3))
        self.aero_controls = tuple(aero.control_names)
        names = list(self.aero_controls) + [f"throttle:{e.name}" for e in self.engines]
        if ground is not None:
            names.append("brake")
        self.control_names = tuple(names)
        self.throttle_slice = slice(len(self.aero_controls), len(self.aero_controls) + ne)
        self._brake_index = names.index("brake") if ground is not None else None
        self._rref = tuple(self.r_ref[:, k].copy() for k in range(3))
        self._inv_mass = 1.0 / self.mass
        J, K = self.inertia, self.inertia_inv
        self._J = tuple(J[:, i, j].copy() for i, j in ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)))
        self._Jinv = tuple(K[:, i, j].copy() for i, j in ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)))
        if ne:
            self._reng = [tuple(self.r_eng[:, j, k].copy() for k in range(3)) for j in range(ne)]
            self._reng_arr = tuple(self.r_eng[:, :, k].copy() for k in range(3))  # (n, ne) each
            self._deng = tuple(self.d_eng[:, k].copy() for k in range(3))  # (ne,) each
            groups: dict[int, tuple] = {}
            for j, e in enumerate(self.engines):
                groups.setdefault(id(e.thrust), (e.thrust, []))[1].append(j)
            self._thrust_groups = [(fn, np.array(idx)) for fn, idx in groups.values()]
        self._all_operative = self.operative.all(axis=0) if ne else np.zeros(0, dtype=bool)
        ad = getattr(aero, "alpha_dot_derivatives", None)
        self._alpha_dot = ad if callable(ad) else None

    def set_operative(self, operative) -> None:
        """Change which engines run ((n_engines,) or (n, n_engines) booleans), e.g. an engine failure
        during a simulation; a failed engine windmills from the next evaluation on."""
        ne = len(self.engines)
        self.operative = np.broadcast_to(np.asarray(operative, dtype=bool), (self.n, ne)).copy()
        self._all_operative = self.operative.all(axis=0) if ne else np.zeros(0, dtype=bool)

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
        C = tuple(dcm[:, i, j] for i in range(3) for j in range(3))
        res = self._dynamics(h, vel[:, 0], vel[:, 1], vel[:, 2], omega[:, 0], omega[:, 1], omega[:, 2], C,
                             controls, with_outputs)
        pos_dot = np.stack(res[0:3], axis=1)
        vel_dot = np.stack(res[3:6], axis=1)
        omega_dot = np.stack(res[6:9], axis=1)
        return pos_dot, vel_dot, omega_dot, res[9]

    def _dynamics(self, h, u, v, w, p, q, r, C, controls, with_outputs):
        """Component form of the equations (the hot path: (n,) arrays only, no small-matrix
        numpy calls). C = the nine body→NED direction cosines, row by row."""
        n = u.shape[0]
        C11, C12, C13, C21, C22, C23, C31, C32, C33 = C
        V2 = u * u + v * v + w * w
        V = np.sqrt(V2)
        Vs = np.maximum(V, 1e-3)
        uw2 = np.maximum(u * u + w * w, 1e-6)
        alpha = np.arctan2(w, u)
        beta = np.arcsin(np.minimum(np.maximum(v / Vs, -1.0), 1.0))
        # ISA, inlined (troposphere + isothermal layer), altitude clipped to the modelled range
        hc = np.minimum(np.maximum(h, _H_MIN), _H_MAX)
        T_air = np.maximum(isa.T0 + isa.LAPSE * hc, _T11)
        p_air = np.where(hc <= isa.H_TROPOPAUSE, isa.P0 * (T_air / isa.T0) ** _EXP_TROPO,
                         _P11 * np.exp(_K_STRATO * (hc - isa.H_TROPOPAUSE)))
        rho = p_air / (isa.R_AIR * T_air)
        mach = V / np.sqrt(isa.GAMMA * isa.R_AIR * T_air)
        qbar = 0.5 * rho * V2
        b, c, S = self.b, self.c, self.S
        ctrl = {name: controls[:, i] for i, name in enumerate(self.aero_controls)}
        coef = self.aero.coefficients(AeroState(
            alpha=alpha, beta=beta, p_hat=p * (b / 2) / Vs, q_hat=q * (c / 2) / Vs, r_hat=r * (b / 2) / Vs,
            mach=mach, controls=ctrl))
        ca, sa = u / np.sqrt(uw2), w / np.sqrt(uw2)
        qS = qbar * S
        CL, CD = coef.CL, coef.CD
        Fx = qS * (CL * sa - CD * ca)
        Fy = qS * coef.CY
        Fz = -qS * (CD * sa + CL * ca)
        rx, ry, rz = self._rref
        Mx = qS * b * coef.Cl + ry * Fz - rz * Fy
        My = qS * c * coef.Cm + rz * Fx - rx * Fz
        Mz = qS * b * coef.Cn + rx * Fy - ry * Fx

        ne = len(self.engines)
        thrust = None
        if ne:
            thr = controls[:, self.throttle_slice]
            thrust = np.empty((n, ne))
            hc2, mach2 = hc[:, None], mach[:, None]
            for fn, idx in self._thrust_groups:  # one call per distinct thrust function
                thrust[:, idx] = fn(thr[:, idx], hc2, mach2)
            for j, eng in enumerate(self.engines):
                if not self._all_operative[j]:
                    dead = -eng.windmill_drag(qbar, mach) if eng.windmill_drag is not None else 0.0
                    thrust[:, j] = np.where(self.operative[:, j], thrust[:, j], dead)
            dx, dy, dz = self._deng
            ex, ey, ez = self._reng_arr
            fx, fy, fz = thrust * dx, thrust * dy, thrust * dz
            Fx = Fx + fx.sum(1)
            Fy = Fy + fy.sum(1)
            Fz = Fz + fz.sum(1)
            Mx = Mx + (ey * fz - ez * fy).sum(1)
            My = My + (ez * fx - ex * fz).sum(1)
            Mz = Mz + (ex * fy - ey * fx).sum(1)

        gear_load = np.zeros((n, 0))
        if self.ground is not None:
            gx, gy, gz, gl, gm_, gn, gear_load = self._ground_forces(h, u, v, w, p, q, r, C, controls)
            Fx, Fy, Fz = Fx + gx, Fy + gy, Fz + gz
            Mx, My, Mz = Mx + gl, My + gm_, Mz + gn

        im = self._inv_mass
        g = self.g
        udot = Fx * im + g * C31 - (q * w - r * v)
        vdot = Fy * im + g * C32 - (r * u - p * w)
        wdot = Fz * im + g * C33 - (p * v - q * u)
        alpha_dot = (u * wdot - w * udot) / uw2
        if self._alpha_dot is not None:
            CLad, Cmad = self._alpha_dot(mach)
            kf = qS * (c / 2) / Vs * CLad  # lift per unit alpha_dot
            dFx, dFz = kf * sa, -kf * ca
            alpha_dot = alpha_dot / (1.0 - (u * dFz - w * dFx) * im / uw2)
            udot = udot + dFx * im * alpha_dot
            wdot = wdot + dFz * im * alpha_dot
            Fx = Fx + dFx * alpha_dot
            Fz = Fz + dFz * alpha_dot
            Mx = Mx + ry * dFz * alpha_dot
            My = My + (qS * c * (c / 2) / Vs * Cmad + rz * dFx - rx * dFz) * alpha_dot
            Mz = Mz - ry * dFx * alpha_dot

        J11, J12, J13, J22, J23, J33 = self._J
        hx = J11 * p + J12 * q + J13 * r
        hy = J12 * p + J22 * q + J23 * r
        hz = J13 * p + J23 * q + J33 * r
        ax = Mx - (q * hz - r * hy)
        ay = My - (r * hx - p * hz)
        az = Mz - (p * hy - q * hx)
        K11, K12, K13, K22, K23, K33 = self._Jinv
        pdot = K11 * ax + K12 * ay + K13 * az
        qdot = K12 * ax + K22 * ay + K23 * az
        rdot = K13 * ax + K23 * ay + K33 * az
        xNdot = C11 * u + C12 * v + C13 * w
        yEdot = C21 * u + C22 * v + C23 * w
        hdot = -(C31 * u + C32 * v + C33 * w)
        out = None
        if with_outputs:
            Wt = self.mass * g
            out = Outputs(V=V, alpha=alpha, beta=beta, mach=mach, qbar=qbar,
                          n_x=Fx / Wt, n_y=Fy / Wt, n_z=-Fz / Wt, alpha_dot=alpha_dot,
                          thrust=thrust if thrust is not None else np.zeros((n, 0)), gear_load=gear_load,
                          CL=np.broadcast_to(CL, (n,)), CD=np.broadcast_to(CD, (n,)))
        return xNdot, yEdot, hdot, udot, vdot, wdot, pdot, qdot, rdot, out

    def _ground_forces(self, h, u, v, w, p, q, r, C, controls):
        """Gear reactions in component form over (n, n_legs) arrays: returns body force and moment
        components (six (n,) arrays) and the legs' normal loads (n, n_legs)."""
        gm = self.ground
        C11, C12, C13, C21, C22, C23, C31, C32, C33 = (c[:, None] for c in C)
        rx, ry, rz = self._rgear
        height = (h - gm.elevation)[:, None] - (C31 * rx + C32 * ry + C33 * rz)
        n = h.shape[0]
        if not (height < 0.0).any():  # airborne: nothing touches
            z = np.zeros(n)
            return z, z, z, z, z, z, np.zeros((n, rx.shape[1]))
        u, v, w, p, q, r = (a[:, None] for a in (u, v, w, p, q, r))
        vx = u + q * rz - r * ry  # contact-point velocity, body axes
        vy = v + r * rx - p * rz
        vz = w + p * ry - q * rx
        vN = C11 * vx + C12 * vy + C13 * vz
        vE = C21 * vx + C22 * vy + C23 * vz
        vD = C31 * vx + C32 * vy + C33 * vz
        comp = np.maximum(-height, 0.0)
        load = np.where(comp > 0.0, np.maximum(self.k_gear * comp + self.c_gear * vD, 0.0), 0.0)
        # wheel axes on the ground: heading of body x projected on the horizontal plane
        nrm = np.maximum(np.hypot(C11, C21), 1e-9)
        ex, ey = C11 / nrm, C21 / nrm
        v_long = vN * ex + vE * ey
        v_lat = vE * ex - vN * ey
        if self._brake_index is not None:
            brake = np.clip(controls[:, self._brake_index], 0.0, 1.0)[:, None]
            mu_long = self.mu_roll + self.braked * gm.brake_friction * brake
        else:
            mu_long = self.mu_roll
        inv_slip = 1.0 / gm.slip_speed
        f_long = -mu_long * load * np.tanh(v_long * inv_slip)
        f_lat = -self.mu_side * load * np.tanh(v_lat * inv_slip)
        fN = f_long * ex - f_lat * ey
        fE = f_long * ey + f_lat * ex
        fbx = C11 * fN + C21 * fE - C31 * load
        fby = C12 * fN + C22 * fE - C32 * load
        fbz = C13 * fN + C23 * fE - C33 * load
        return (fbx.sum(1), fby.sum(1), fbz.sum(1), (ry * fbz - rz * fby).sum(1), (rz * fbx - rx * fbz).sum(1),
                (rx * fby - ry * fbx).sum(1), load)

    # ------------------------------------------------------------------ state forms
    def derivatives_quat(self, x, controls, with_outputs=False):
        """ẋ for the quaternion state (n, 13)."""
        X = x.T
        q0, q1, q2, q3 = X[9], X[10], X[11], X[12]
        q00, q11, q22, q33 = q0 * q0, q1 * q1, q2 * q2, q3 * q3
        q01, q02, q03, q12, q13, q23 = q0 * q1, q0 * q2, q0 * q3, q1 * q2, q1 * q3, q2 * q3
        C = (q00 + q11 - q22 - q33, 2 * (q12 - q03), 2 * (q13 + q02),
             2 * (q12 + q03), q00 - q11 + q22 - q33, 2 * (q23 - q01),
             2 * (q13 - q02), 2 * (q23 + q01), q00 - q11 - q22 + q33)
        p, q, r = X[6], X[7], X[8]
        res = self._dynamics(X[2], X[3], X[4], X[5], p, q, r, C, controls, with_outputs)
        xd, XD = _translational_part(x, res)
        XD[9] = -0.5 * (p * q1 + q * q2 + r * q3)
        XD[10] = 0.5 * (p * q0 + r * q2 - q * q3)
        XD[11] = 0.5 * (q * q0 - r * q1 + p * q3)
        XD[12] = 0.5 * (r * q0 + q * q1 - p * q2)
        return (xd, res[9]) if with_outputs else xd

    def derivatives_euler(self, x, controls, with_outputs=False):
        """ẋ for the Euler-angle state (n, 12)."""
        X = x.T
        phi, theta, psi = X[9], X[10], X[11]
        sf, cf, st, ct, sp, cp = np.sin(phi), np.cos(phi), np.sin(theta), np.cos(theta), np.sin(psi), np.cos(psi)
        C = (ct * cp, sf * st * cp - cf * sp, cf * st * cp + sf * sp,
             ct * sp, sf * st * sp + cf * cp, cf * st * sp - sf * cp,
             -st, sf * ct, cf * ct)
        p, q, r = X[6], X[7], X[8]
        res = self._dynamics(X[2], X[3], X[4], X[5], p, q, r, C, controls, with_outputs)
        xd, XD = _translational_part(x, res)
        XD[9] = p + (q * sf + r * cf) * st / ct
        XD[10] = q * cf - r * sf
        XD[11] = (q * sf + r * cf) / ct
        return (xd, res[9]) if with_outputs else xd


def _translational_part(x, res):
    xd = np.empty_like(x)
    XD = xd.T
    for k in range(9):
        XD[k] = res[k]
    return xd, XD


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
