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
      a failed engine produces its windmilling drag instead (if the engine gives one), or while it spools down
      the drag plus the fraction ``failed_thrust_fraction`` of the difference to its running thrust.
    * gravity, g along earth-down.
    * ground reactions (optional :class:`GroundModel`): spring–damper gear legs with rolling and
      side friction, for takeoff and landing.

Equations: m(v̇_b + ω × v_b) = F,   J ω̇ + ω × J ω = M  with the full inertia tensor
    J = [[Ixx, −Ixy, −Ixz], [−Ixy, Iyy, −Iyz], [−Ixz, −Iyz, Izz]] (products Ixz = ∫ x z dm),
    about the CG in body axes.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from certkit.models.aero.ground_effect import H_OVER_B_MAX, induced_drag_factor_table
from certkit.models.aero.interface import AeroModel, AeroState
from certkit.models.aero.tail_ground_effect import downwash_table
from certkit.models.compiled import kernel_array
from certkit.models.dynamics import kernel
from certkit.models.propulsion.engine import WindmillDrag
from certkit.units import G0

QUAT_STATE = ("x_N", "y_E", "h", "u", "v", "w", "p", "q", "r", "q0", "q1", "q2", "q3")
EULER_STATE = ("x_N", "y_E", "h", "u", "v", "w", "p", "q", "r", "phi", "theta", "psi")

#: the control turning the steered gear legs (rad, positive: nose right)
STEERING = "nose_wheel_steering"


def airplane_to_body(points, cg) -> np.ndarray:
    """Airplane-frame points (X aft, Y right, Z up), shape (..., 3), to body axes about ``cg``."""
    return (np.asarray(points, dtype=float) - np.asarray(cg, dtype=float)) * _AIRPLANE_TO_BODY


#: the signs turning airplane-frame offsets into body axes (X forward, Y right, Z down): a product by ±1 is exact
_AIRPLANE_TO_BODY = np.array([-1.0, 1.0, -1.0])


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


def _shared_thrust(engines) -> Callable | None:
    """The thrust function of every engine when they are all one model with equal parameters (bound methods of
    equal objects), so that one call serves them all; None otherwise."""
    fns = [e.thrust for e in engines]
    if len(fns) < 2 or not all(hasattr(f, "__self__") and f.__func__ is fns[0].__func__ for f in fns):
        return None
    first = fns[0].__self__
    try:
        same = all(
            f.__self__ is first or (type(f.__self__) is type(first) and bool(f.__self__ == first)) for f in fns[1:]
        )
    except (ValueError, TypeError):  # objects whose equality is not a single truth value (array fields)
        return None
    return fns[0] if same else None


def _windmill_parameters(engines) -> np.ndarray | None:
    """(n_engines, 3) windmilling-drag parameters of compiled code (NaN rows: no drag), None when an engine's drag
    is not a :class:`~certkit.models.propulsion.engine.WindmillDrag`."""
    out = np.full((len(engines), 3), np.nan)
    for j, e in enumerate(engines):
        if isinstance(e.windmill_drag, WindmillDrag):
            out[j] = e.windmill_drag.kernel_parameters()
        elif e.windmill_drag is not None:
            return None
    return out


@dataclass
class GearLeg:
    """A gear contact point (airplane frame, wheel bottom at full extension), spring stiffness
    (N/m), damping (N s/m), rolling and side-friction coefficients; ``braked`` legs add the
    brake control's friction; a ``steered`` leg's wheel turns by the ``nose_wheel_steering`` control (rad, positive
    toward the right: the nose goes right). A castering wheel (steering disengaged) is a leg without side friction."""

    name: str
    position: Sequence[float]
    stiffness: float
    damping: float
    rolling_friction: float = 0.02
    side_friction: float = 0.6
    braked: bool = False
    steered: bool = False


@dataclass
class GroundModel:
    """Flat runway at ``elevation`` (m). ``brake_friction`` is the friction coefficient of the
    braked legs at full brake (control ``brake`` in [0, 1]). Friction forces use a smooth
    saturation tanh(v/``slip_speed``) so that the aircraft can stand still without chattering."""

    legs: Sequence[GearLeg]
    elevation: float = 0.0
    brake_friction: float = 0.4
    slip_speed: float = 0.3
    #: the wing whose ground effect the aerodynamic table gets near the runway (None: no ground effect)
    wing: "GroundEffectWing | None" = None


@dataclass
class GroundEffectWing:
    """The wing as ground effect (:mod:`certkit.models.aero.ground_effect`) sees it: ``point`` where its
    height above the runway is taken (airplane frame, m: the MAC quarter chord), span (m), aspect ratio and
    half-chord sweep (rad); ``lines``: the wing's and the horizontal tail's quarter-chord lines
    (:func:`certkit.models.aero.tail_ground_effect.lifting_line`) for the downwash at the tail, which is reduced near
    the runway when the aerodynamic model also gives its free-air downwash (``tail_downwash``). Applied to
    derivative-table models only."""

    point: Sequence[float]
    span: float
    aspect_ratio: float
    sweep_half_chord: float
    lines: tuple | None = None


def euler_to_quat(phi, theta, psi) -> np.ndarray:
    cphi, sphi = np.cos(phi / 2), np.sin(phi / 2)
    cth, sth = np.cos(theta / 2), np.sin(theta / 2)
    cpsi, spsi = np.cos(psi / 2), np.sin(psi / 2)
    return np.stack(
        [
            cphi * cth * cpsi + sphi * sth * spsi,
            sphi * cth * cpsi - cphi * sth * spsi,
            cphi * sth * cpsi + sphi * cth * spsi,
            cphi * cth * spsi - sphi * sth * cpsi,
        ],
        axis=-1,
    )


def quat_to_euler(quat) -> np.ndarray:
    q0, q1, q2, q3 = (quat[..., i] for i in range(4))
    phi = np.arctan2(2 * (q0 * q1 + q2 * q3), 1 - 2 * (q1 * q1 + q2 * q2))
    theta = np.arcsin(np.clip(2 * (q0 * q2 - q3 * q1), -1.0, 1.0))
    psi = np.arctan2(2 * (q0 * q3 + q1 * q2), 1 - 2 * (q2 * q2 + q3 * q3))
    return np.stack([phi, theta, psi], axis=-1)


def quat_to_dcm(quat) -> np.ndarray:
    """Body-to-earth (NED) direction cosine matrix, shape (..., 3, 3)."""
    q0, q1, q2, q3 = (quat[..., i] for i in range(4))
    return np.stack(
        [
            np.stack([1 - 2 * (q2 * q2 + q3 * q3), 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)], -1),
            np.stack([2 * (q1 * q2 + q0 * q3), 1 - 2 * (q1 * q1 + q3 * q3), 2 * (q2 * q3 - q0 * q1)], -1),
            np.stack([2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), 1 - 2 * (q1 * q1 + q2 * q2)], -1),
        ],
        -2,
    )


def euler_to_dcm(phi, theta, psi) -> np.ndarray:
    cf, sf, ct, st, cp, sp = np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta), np.cos(psi), np.sin(psi)
    return np.stack(
        [
            np.stack([ct * cp, sf * st * cp - cf * sp, cf * st * cp + sf * sp], -1),
            np.stack([ct * sp, sf * st * sp + cf * cp, cf * st * sp - sf * cp], -1),
            np.stack([-st, sf * ct, cf * ct], -1),
        ],
        -2,
    )


def inertia_tensor(Ixx, Iyy, Izz, Ixz=0.0, Ixy=0.0, Iyz=0.0) -> np.ndarray:
    """Inertia tensor (…, 3, 3) from moments and products (products ∫xz dm etc., body axes)."""
    Ixx, Iyy, Izz, Ixz, Ixy, Iyz = np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (Ixx, Iyy, Izz, Ixz, Ixy, Iyz))
    )
    return np.stack(
        [
            np.stack([Ixx, -Ixy, -Ixz], -1),
            np.stack([-Ixy, Iyy, -Iyz], -1),
            np.stack([-Ixz, -Iyz, Izz], -1),
        ],
        -2,
    )


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
    ground model and ``nose_wheel_steering`` when a leg is steered.
    """

    def __init__(
        self,
        aero: AeroModel,
        mass,
        cg,
        inertia,
        engines: Sequence[Engine] = (),
        operative=None,
        ground: GroundModel | None = None,
        g: float = G0,
        n: int | None = None,
    ) -> None:
        self.aero = aero
        mass = np.asarray(mass, dtype=float)
        cg = np.asarray(cg, dtype=float)
        inertia = np.asarray(inertia, dtype=float)
        if n is None:
            n = max(
                mass.size if mass.ndim else 1,
                cg.shape[0] if cg.ndim == 2 else 1,
                inertia.shape[0] if inertia.ndim == 3 else 1,
            )
        self.n = n
        self.mass = np.broadcast_to(mass, (n,)).copy()
        self.cg = np.broadcast_to(cg, (n, 3)).copy()
        self.inertia = np.broadcast_to(inertia, (n, 3, 3)).copy()
        self.inertia_inv = np.linalg.inv(self.inertia)
        self.engines = tuple(engines)
        ne = len(self.engines)
        op = (
            np.ones((n, ne), dtype=bool)
            if operative is None
            else np.broadcast_to(np.asarray(operative, dtype=bool), (n, ne)).copy()
        )
        self.operative = op
        #: share of its running thrust a failed engine still gives (n, n_engines): 0 windmills at once; a spool-down
        #: (:class:`~certkit.models.dynamics.controllers.EngineFailure`) lets it decay from 1
        self.failed_thrust_fraction = np.zeros((n, ne))
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
        self.aero_controls = tuple(aero.control_names)
        names = list(self.aero_controls) + [f"throttle:{e.name}" for e in self.engines]
        if ground is not None:
            names.append("brake")
            if any(leg.steered for leg in ground.legs):
                names.append(STEERING)
        self.control_names = tuple(names)
        self.throttle_slice = slice(len(self.aero_controls), len(self.aero_controls) + ne)
        self._brake_index = names.index("brake") if ground is not None else None
        self._steer_index = names.index(STEERING) if STEERING in names else -1
        self._all_operative = self.operative.all(axis=0) if ne else np.zeros(0, dtype=bool)
        self._shared_thrust = _shared_thrust(self.engines)
        engine_model = getattr(self._shared_thrust, "__self__", None)
        self._thrust_rows = getattr(engine_model, "thrust_rows", None)
        #: the engines' parameters for a compiled run (:meth:`open_loop_run`), when their model provides them
        self._turbofan = engine_model.kernel_parameters() if hasattr(engine_model, "kernel_parameters") else None
        self._windmill = _windmill_parameters(self.engines)
        ad = getattr(aero, "alpha_dot_derivatives", None)
        self._alpha_dot = ad if callable(ad) else None
        self._pack()

    def set_operative(self, operative) -> None:
        """Change which engines run ((n_engines,) or (n, n_engines) booleans), e.g. an engine failure
        during a simulation; a failed engine windmills from the next evaluation on."""
        ne = len(self.engines)
        self.operative = np.broadcast_to(np.asarray(operative, dtype=bool), (self.n, ne)).copy()
        self._all_operative = self.operative.all(axis=0) if ne else np.zeros(0, dtype=bool)

    def condition_data(self) -> np.ndarray:
        """Each condition's own data, (n, k): mass, CG, inertia, the engines running and a failed engine's thrust
        fraction; the rest of the model (aerodynamics, engines, gear) every condition shares. Two conditions with
        equal rows are one airplane."""
        n = self.n
        return np.hstack(
            [
                self.mass[:, None],
                self.cg,
                self.inertia.reshape(n, 9),
                self.operative.reshape(n, -1).astype(float),
                self.failed_thrust_fraction.reshape(n, -1),
            ]
        )

    def control_index(self, name: str) -> int:
        return self.control_names.index(name)

    def subset(self, idx) -> "AircraftModel":
        """The model restricted to conditions ``idx`` (index array or boolean mask), as a new model of those rows
        would be (no failed engine's thrust carried over): the per-row arrays are this model's rows (each row's
        inverse inertia and arms are computed row by row, so the same values), the rest is shared."""
        idx = np.arange(self.n)[idx]
        new = copy.copy(self)
        new.n = idx.size
        new.mass, new.cg, new.inertia, new.inertia_inv = (
            self.mass[idx],
            self.cg[idx],
            self.inertia[idx],
            self.inertia_inv[idx],
        )
        new.operative = self.operative[idx]
        ne = len(self.engines)
        new.failed_thrust_fraction = np.zeros((idx.size, ne))
        new.r_ref = self.r_ref[idx]
        if ne:
            new.r_eng = self.r_eng[idx]
        if self.ground is not None:
            new.r_gear = self.r_gear[idx]
        new._all_operative = new.operative.all(axis=0) if ne else np.zeros(0, dtype=bool)
        new._pack()
        return new

    # ------------------------------------------------------------------ core
    def _pack(self) -> None:
        """The compiled kernel's arguments (layout in :mod:`certkit.models.dynamics.kernel`)."""
        n, ne = self.n, len(self.engines)
        props = np.empty((n, 16))
        props[:, 0] = 1.0 / self.mass
        J, K = self.inertia, self.inertia_inv
        for k, (a, b_) in enumerate(((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))):
            props[:, 1 + k] = J[:, a, b_]
            props[:, 7 + k] = K[:, a, b_]
        props[:, 13:16] = self.r_ref
        table = getattr(self.aero, "kernel_data", None)
        self._use_table = table is not None
        if table is None:
            table = (np.zeros((1, 1)), np.zeros(1), np.zeros(1), np.zeros(5), False, np.zeros(0, dtype=np.bool_))
        r_eng = np.ascontiguousarray(self.r_eng) if ne else np.zeros((n, 0, 3))
        d_eng = np.ascontiguousarray(self.d_eng) if ne else np.zeros((0, 3))
        gm = self.ground
        if gm is not None:
            r_gear = np.ascontiguousarray(self.r_gear)
            legs = np.array(
                [
                    [
                        leg.stiffness,
                        leg.damping,
                        leg.rolling_friction,
                        leg.side_friction,
                        float(leg.braked),
                        float(leg.steered),
                    ]
                    for leg in gm.legs
                ],
                dtype=float,
            ).reshape(-1, 6)
            gparams = np.concatenate(
                [[gm.elevation, gm.brake_friction, gm.slip_speed], self._ground_effect_params(gm.wing)]
            )
        else:
            r_gear, legs, gparams = np.zeros((n, 0, 3)), np.zeros((0, 6)), np.zeros(9)
        self._kernel_args = (
            props,
            np.array([self.b, self.c, self.S, self.g]),
            *table,
            len(self.aero_controls),
            self._use_table,
            r_eng,
            d_eng,
            gm is not None,
            r_gear,
            legs,
            gparams,
            -1 if self._brake_index is None else self._brake_index,
            self._steer_index,
        )

    def _ground_effect_params(self, wing: "GroundEffectWing | None") -> np.ndarray:
        """gparams[3:] of the kernel (layout in :mod:`certkit.models.dynamics.kernel`): span (0: none), aspect ratio,
        tan Λ½, wing point minus the aero reference in body axes (3); the tail's point likewise (3), its free-air
        downwash ε₀ and dε/dα, lift and moment slopes (0: no ground effect at the tail), the R table's axes and shape
        (6); the φ(h/b) table; the R table."""
        if wing is None:
            return np.zeros(6)
        ref = self.aero.reference
        origin = np.array([ref.x_ref, 0.0, ref.z_ref])
        d = np.asarray(wing.point, dtype=float) - origin
        tail = np.zeros(13)
        table = np.zeros(0)
        free_air = getattr(self.aero, "tail_downwash", None)
        if wing.lines is not None and free_air is not None:
            line, tail_line = wing.lines
            r = downwash_table(line, tail_line, wing.span, H_OVER_B_MAX)
            dt = np.array([tail_line.reference[0], 0.0, tail_line.reference[1]]) - origin
            tail[:] = (
                -dt[0],
                dt[1],
                -dt[2],
                free_air.epsilon0,
                free_air.gradient,
                free_air.lift_slope,
                free_air.moment_slope,
                r.root_start,
                r.root_step,
                r.dz_start,
                r.dz_step,
                *r.ratio.shape,
            )
            table = r.ratio.ravel()
        return np.concatenate(
            [
                [wing.span, wing.aspect_ratio, np.tan(wing.sweep_half_chord), -d[0], d[1], -d[2]],
                tail,
                induced_drag_factor_table(),
                table,
            ]
        )

    def thrust_forces(self, air: np.ndarray, controls: np.ndarray, rows=None) -> np.ndarray:
        """Force of each engine along its thrust line (n, n_engines), N, from the air data
        (:data:`kernel.AIR` columns) and the throttles of conditions ``rows`` (default: all); a
        failed engine gives minus its windmilling drag."""
        n, ne = air.shape[0], len(self.engines)
        thrust = np.zeros((n, ne))
        if not ne:
            return thrust
        thr = controls[:, self.throttle_slice]
        hc, mach, qbar = air[:, 0], air[:, 4], air[:, 5]
        if self._thrust_rows is not None:  # identical engines whose model takes them all at once
            thrust = self._thrust_rows(thr, hc, mach)
        elif self._shared_thrust is not None:  # identical engines: one call for all, row by row as the throttles
            thrust[:] = self._shared_thrust(thr.reshape(-1), np.repeat(hc, ne), np.repeat(mach, ne)).reshape(n, ne)
        if self._shared_thrust is None:  # else one call per engine, on arrays of one shape (no broadcasting)
            for j, eng in enumerate(self.engines):
                thrust[:, j] = eng.thrust(thr[:, j], hc, mach)
        if not self._all_operative.all():
            dead = np.zeros((n, ne))
            for j, eng in enumerate(self.engines):
                if not self._all_operative[j] and eng.windmill_drag is not None:
                    dead[:, j] = -eng.windmill_drag(qbar, mach)
            op = self.operative if rows is None else self.operative[rows]
            frac = self.failed_thrust_fraction if rows is None else self.failed_thrust_fraction[rows]
            kernel.failed_engine_forces(thrust, dead, op, np.ascontiguousarray(frac, dtype=float))
        return thrust

    def _coefficients(self, X, air, controls) -> np.ndarray:
        """(n, 8) coefficient rows for a model the kernel cannot evaluate itself (not a derivative
        table): CL, CD, CY, Cl, Cm, Cn, CL_α̇, Cm_α̇ from the model's own ``coefficients``."""
        n = X.shape[0]
        if self._use_table:
            return np.empty((n, 8))  # scratch space for the kernel
        Vs = np.maximum(air[:, 1], 1e-3)
        b, c = self.b, self.c
        coef = self.aero.coefficients(
            AeroState(
                alpha=air[:, 2],
                beta=air[:, 3],
                p_hat=X[:, 6] * (b / 2) / Vs,
                q_hat=X[:, 7] * (c / 2) / Vs,
                r_hat=X[:, 8] * (b / 2) / Vs,
                mach=air[:, 4],
                controls={name: controls[:, i] for i, name in enumerate(self.aero_controls)},
            )
        )
        out = np.zeros((n, 8))
        for k, name in enumerate(("CL", "CD", "CY", "Cl", "Cm", "Cn")):
            out[:, k] = np.broadcast_to(getattr(coef, name), (n,))
        if self._alpha_dot is not None:
            ad = self._alpha_dot(air[:, 4])
            out[:, 6], out[:, 7] = np.broadcast_to(ad[0], (n,)), np.broadcast_to(ad[1], (n,))
        return out

    def evaluate(self, x, controls, thrust=None, rows=None):
        """State derivative of the batch (quaternion (n, 13) or Euler (n, 12) states), the outputs
        and the thrust used. ``thrust`` (n, n_engines) holds the engines' forces (e.g. over an
        integration step); by default they are computed at the state. ``rows`` (int array) says
        which condition each row of ``x`` belongs to (default: row i is condition i), so a subset
        of the batch, or several states per condition, are evaluated in one call."""
        X = kernel_array(x)
        U = kernel_array(controls)
        idx = np.arange(X.shape[0]) if rows is None else kernel_array(rows, np.int64)
        air = None
        if thrust is None or not self._use_table:
            air = kernel.air_data(X)
        if thrust is None and self.thrust_compiled:
            thrust = kernel.engine_forces(air, U, idx, *self._engine_args())
        elif thrust is None:
            thrust = self.thrust_forces(air, U, rows)
        thrust = kernel_array(thrust)
        xd, out, gear = kernel.derivatives(
            X, idx, X.shape[1] == 13, U, thrust, self._coefficients(X, air, U), *self._kernel_args
        )
        return xd, out, gear, thrust

    def _engine_args(self) -> tuple:
        """:func:`kernel.engine_forces`' arguments after the rows: the engine model, the throttles' first column, which
        engines run, the failed engines' thrust fractions and windmilling drag."""
        return (
            self._turbofan,
            self.throttle_slice.start,
            self.operative,
            np.ascontiguousarray(self.failed_thrust_fraction, dtype=float),
            self._windmill,
        )

    def compiled_thrust_args(self) -> tuple:
        """The arguments :meth:`evaluate` gives :func:`kernel.engine_forces` and :func:`kernel.derivatives` after the
        rows' state and controls, for a model whose :attr:`thrust_compiled`: the engines' (:meth:`_engine_args`), then
        the model's arrays."""
        return (*self._engine_args(), *self._kernel_args)

    @property
    def thrust_compiled(self) -> bool:
        """Does :meth:`evaluate` compute the thrust in compiled code (:func:`kernel.engine_forces`, the arithmetic of
        :meth:`thrust_forces` bit for bit): derivative-table aerodynamics, one parametric engine model for every
        engine, failed engines windmilling by :class:`~certkit.models.propulsion.engine.WindmillDrag` (or without
        drag)."""
        return bool(self._use_table and self._turbofan is not None and self._windmill is not None)

    @property
    def runs_open_loop_compiled(self) -> bool:
        """Can :meth:`open_loop_run` integrate this model: derivative-table aerodynamics, one parametric engine
        model for every engine, all of them running."""
        return bool(self._use_table and self._turbofan is not None and self._all_operative.all())

    def open_loop_run(self, x13, U_all, dts, record_every: int, out_rec, x_rec, u_rec, stops=None) -> tuple:
        """A whole fixed-step run in compiled code (:func:`kernel.integrate_open_loop`), for a model that
        :attr:`runs_open_loop_compiled`; ``stops`` = (output columns (c,), lower (c, n), upper (c, n)) bounds or None.
        Returns the number of records and, per condition, the step it stopped at and the criterion (−1: none)."""
        n = x13.shape[0]
        cols, lo, hi = stops if stops is not None else (np.zeros(0, dtype=np.int64), np.zeros((0, n)), np.zeros((0, n)))
        stop_step = np.full(n, -1, dtype=np.int64)
        stop_which = np.full(n, -1, dtype=np.int64)
        ns, legs = x13.shape[1], 0 if self.ground is None else len(self.ground.legs)
        outputs = len(kernel.OUTPUTS)
        irec = kernel.integrate_open_loop(
            kernel_array(x13),
            kernel_array(U_all),
            kernel_array(dts),
            record_every,
            self._turbofan,
            self.throttle_slice.start,
            len(self.engines),
            np.empty((n, 8)),
            *self._kernel_args,
            cols,
            lo,
            hi,
            out_rec,
            x_rec,
            u_rec,
            stop_step,
            stop_which,
            np.arange(n),  # the kernel's scratch: rows, thrust, active, each step's start, its RK4 stages
            np.empty((n, len(self.engines))),
            np.ones(n, dtype=np.bool_),
            np.empty((n, ns)),
            np.empty((n, outputs)),
            np.zeros((n, legs)),
            np.empty((3, ns)),
            np.empty(ns),
            np.empty(outputs),
            np.zeros(legs),
        )
        return int(irec), stop_step, stop_which

    def make_outputs(self, out, gear, thrust) -> Outputs:
        cols = {name: out[:, k] for k, name in enumerate(kernel.OUTPUTS)}
        return Outputs(thrust=thrust, gear_load=gear, **cols)

    def rk4_step(self, x, xd1, controls, thrust, dt, active) -> np.ndarray:
        """One RK4 step of the quaternion-state batch (controls and thrust held over the step) of ``dt``, one
        for all or one per condition (n,); the conditions not ``active`` keep their state. Returns the new state."""
        X = np.array(x, dtype=float, order="C")
        U = kernel_array(controls)
        thrust = kernel_array(thrust)
        act = kernel_array(active, np.bool_)
        if self._use_table:
            dts = np.full(X.shape[0], dt) if np.ndim(dt) == 0 else kernel_array(dt)
            kernel.rk4_step(X, kernel_array(xd1), act, dts, U, thrust, np.empty((X.shape[0], 8)), *self._kernel_args)
            return X
        dt = np.asarray(dt, dtype=float)[..., None] if np.ndim(dt) else dt
        k2 = self.evaluate(X + 0.5 * dt * xd1, U, thrust)[0]
        k3 = self.evaluate(X + 0.5 * dt * k2, U, thrust)[0]
        k4 = self.evaluate(X + dt * k3, U, thrust)[0]
        x_new = X + dt / 6.0 * (xd1 + 2 * k2 + 2 * k3 + k4)
        x_new[:, 9:13] /= np.linalg.norm(x_new[:, 9:13], axis=1, keepdims=True)
        return np.where(act[:, None], x_new, X)

    # ------------------------------------------------------------------ state forms
    def derivatives_quat(self, x, controls, with_outputs=False):
        """ẋ for the quaternion state (n, 13)."""
        xd, out, gear, thrust = self.evaluate(x, controls)
        return (xd, self.make_outputs(out, gear, thrust)) if with_outputs else xd

    def derivatives_euler(self, x, controls, with_outputs=False, rows=None):
        """ẋ for the Euler-angle state (n, 12) (rows of conditions ``rows``, see :meth:`evaluate`)."""
        xd, out, gear, thrust = self.evaluate(x, controls, rows=rows)
        return (xd, self.make_outputs(out, gear, thrust)) if with_outputs else xd


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
    "QUAT_STATE",
    "EULER_STATE",
    "Engine",
    "GearLeg",
    "GroundModel",
    "AircraftModel",
    "Outputs",
    "inertia_tensor",
    "airplane_to_body",
    "euler_to_quat",
    "quat_to_euler",
    "quat_to_dcm",
    "euler_to_dcm",
    "euler_state_to_quat_state",
    "quat_state_to_euler_state",
    "energy",
]
