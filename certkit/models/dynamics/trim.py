"""Vectorised trims of a batch of conditions (Newton with a finite-difference Jacobian).

Trim kinds (``kind`` argument of :func:`trim`), with the six unknowns solved for and what is given:

    straight  steady straight flight at flight-path angle γ (0: level; climb/descent otherwise),
              wings level.          Unknowns α, β, pitch, roll, yaw controls, throttle.
    turn      steady coordinated turn (β = 0) at bank φ and flight-path angle γ.
              Unknowns α, turn rate ψ̇, pitch, roll, yaw controls, throttle.
    oei       one engine inoperative (``operative`` mask of the model), straight flight at a
              given bank φ (|φ| ≤ 5°, §25.149) and γ; the sideslip results.
              Unknowns α, β, pitch, roll, yaw controls, throttle of the operative engines.
    sideslip  steady-heading sideslip at a given β; the bank results.
              Unknowns α, φ, pitch, roll, yaw controls, throttle.

Equations: the six body-axis accelerations u̇, v̇, ẇ (m/s²) and ṗ, q̇, ṙ (rad/s²) vanish.
The attitude θ follows from the flight-path constraint (Stevens & Lewis, *Aircraft Control and
Simulation*, §3.6): with a = cos α cos β, b = sin φ sin β + cos φ sin α cos β,
    sin γ = a sin θ − b cos θ  ⇒  θ = atan[(a b + sin γ √(a² − sin²γ + b²)) / (a² − sin²γ)],
and the body rates from the turn rate: p = −ψ̇ sin θ, q = ψ̇ sin φ cos θ, r = ψ̇ cos φ cos θ.

Without engines, or with the throttle fixed (``throttle=``, e.g. a power-off glide), the throttle
unknown is replaced by γ.

A control that would have to go past its limit is not an error: the trim is solved without
limits and each :class:`TrimResult` lists the :class:`LimitExceedance` found ("needs −34.2°
elevator, limit −30°") with a hint. Conditions that do not converge are reported as such with
their residual; nothing raises for a single bad condition.

A movable horizontal stabiliser (:class:`StabilizerTrim`, from ``geometry.horizontal_tail.stabilizer``) takes the
elevator's place as the pitch unknown, the elevator held at its trim setting. Where the stabiliser would pass its
trim limit it is left at that stop and the condition is trimmed again with the elevator (the airplane is held, not
trimmed: ``stabilizer_at_stop`` and ``stabilizer_required`` say so, and the elevator's own limits are checked as
usual). A stabiliser given as a setting (``stabilizer_setting``) is held there and the elevator trims: the state
after a change made without re-trimming, or the start of a manoeuvre.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np
from numba import njit

from certkit.models.compiled import copy_row
from certkit.models.dynamics import kernel
from certkit.models.dynamics.eom import AircraftModel

KINDS = ("straight", "turn", "oei", "sideslip")

DEFAULT_ROLES = {"pitch": "elevator", "roll": "aileron", "yaw": "rudder"}

_HINTS = {
    "pitch": (
        "pitch control authority is insufficient here: check the CG against its limits, the speed, and the "
        "stabilizer/trim setting"
    ),
    "roll": "roll control authority is insufficient: raise the speed or reduce the rolling asymmetry",
    "yaw": (
        "directional control is insufficient (below VMC for this thrust?): raise the speed, bank toward the live "
        "engine, or reduce the asymmetric thrust"
    ),
    "throttle_high": "not enough thrust for this flight-path gradient at this weight and altitude",
    "throttle_low": (
        "less than idle thrust needed: the descent is too steep for a clean configuration (use drag devices)"
    ),
}


#: range of the throttle iterate (the engine models' throttle range, kept 1e-5 inside at full thrust)
_THROTTLE_BOX = (0.0, 1.0 - 1e-5)


@dataclass
class LimitExceedance:
    control: str
    required: float  # rad, or throttle fraction
    limit: float
    excess: float  # required − limit, same unit
    message: str
    hint: str


@dataclass
class TrimResult:
    index: int
    kind: str
    converged: bool
    residual_norm: float
    iterations: int
    V: float
    h: float
    alpha: float
    beta: float
    theta: float
    phi: float
    gamma: float
    turn_rate: float
    controls: dict[str, float]
    thrust: dict[str, float]
    limits_exceeded: list[LimitExceedance] = field(default_factory=list)
    #: movable stabiliser (None without one): the incidence set (rad, leading edge up positive), the incidence the
    #: trim would need with the elevator at its trim setting (beyond the stop when the stop is reached), the stop
    #: reached ("nose-up"/"nose-down", the elevator then carrying the rest) and whether it was held as given
    stabilizer: float | None = None
    stabilizer_required: float | None = None
    stabilizer_at_stop: str = ""
    stabilizer_frozen: bool = False

    @property
    def ok(self) -> bool:
        return self.converged and not self.limits_exceeded

    def start(self) -> dict[str, float]:
        """This trim as the warm start (``initial``) of a nearby one: α, β, the controls and the throttle."""
        thr = [v for k, v in self.controls.items() if k.startswith("throttle")]
        return {
            "alpha": self.alpha,
            "beta": self.beta,
            **{k: v for k, v in self.controls.items() if not k.startswith("throttle")},
            **({"throttle": thr[0]} if thr else {}),
        }

    def summary(self) -> str:
        d = np.degrees
        s = (
            f"[{self.index}] {self.kind} {'converged' if self.converged else 'NOT converged'} "
            f"(|r|={self.residual_norm:.1e}, {self.iterations} it): V={self.V:.1f} m/s h={self.h:.0f} m "
            f"α={d(self.alpha):.2f}° β={d(self.beta):.2f}° θ={d(self.theta):.2f}° φ={d(self.phi):.2f}° "
            + " ".join(f"{k}={d(v) if not k.startswith('throttle') else v:.3g}" for k, v in self.controls.items())
        )
        if self.stabilizer is not None:
            s += f" stabiliser {d(self.stabilizer):.2f}°" + (" (held)" if self.stabilizer_frozen else "")
            if self.stabilizer_at_stop:
                s += f" at its {self.stabilizer_at_stop} stop (needs {d(self.stabilizer_required):.2f}°)"
        for lim in self.limits_exceeded:
            s += f"\n    {lim.message} — {lim.hint}"
        return s


@dataclass
class TrimBatch:
    """Trim of n conditions: Euler state x (n, 12), controls u (n, n_controls), per-condition results."""

    model: AircraftModel
    x: np.ndarray
    u: np.ndarray
    results: list[TrimResult]

    @property
    def converged(self) -> np.ndarray:
        return np.array([r.converged for r in self.results])

    def __getitem__(self, i) -> TrimResult:
        return self.results[i]

    def __len__(self) -> int:
        return len(self.results)


def theta_from_gamma(alpha, beta, phi, gamma):
    """Pitch attitude giving flight-path angle γ (Stevens & Lewis rate-of-climb constraint)."""
    a = np.cos(alpha) * np.cos(beta)
    b = np.sin(phi) * np.sin(beta) + np.cos(phi) * np.sin(alpha) * np.cos(beta)
    sg = np.sin(gamma)
    return np.arctan2(a * b + sg * np.sqrt(np.maximum(a * a - sg * sg + b * b, 0.0)), a * a - sg * sg)


def assemble_state(V, h, alpha, beta, phi, gamma, turn_rate, psi=0.0):
    """Euler state (n, 12) of a steady condition: body velocities from V, α, β; the pitch attitude from γ
    (:func:`theta_from_gamma`); body rates of a steady turn at ``turn_rate`` (ψ̇) with bank φ."""
    args = [np.asarray(a, dtype=float) for a in (V, h, alpha, beta, phi, gamma, turn_rate, psi)]
    n = max(a.size for a in args)
    cols = [a if a.ndim == 1 and a.size == n else np.broadcast_to(a, (n,)) for a in args]
    x = np.empty((n, 12))
    _assemble(*(np.ascontiguousarray(c) for c in cols), x)
    return x


@njit(cache=True, fastmath=False)
def _assemble(V, h, alpha, beta, phi, gamma, turn_rate, psi, x):
    for i in range(x.shape[0]):
        _state_row(V[i], h[i], alpha[i], beta[i], phi[i], gamma[i], turn_rate[i], psi[i], x[i])


@njit(cache=True, fastmath=False, inline="always")
def _state_row(V, h, alpha, beta, phi, gamma, turn_rate, psi, x):
    """One row of :func:`assemble_state`."""
    ca, sa, cb, sb = math.cos(alpha), math.sin(alpha), math.cos(beta), math.sin(beta)
    cp, sp, sg = math.cos(phi), math.sin(phi), math.sin(gamma)
    a = ca * cb
    b = sp * sb + cp * sa * cb
    theta = math.atan2(a * b + sg * math.sqrt(max(a * a - sg * sg + b * b, 0.0)), a * a - sg * sg)
    st, ct = math.sin(theta), math.cos(theta)
    x[0] = 0.0
    x[1] = 0.0
    x[2] = h
    x[3] = V * ca * cb
    x[4] = V * sb
    x[5] = V * sa * cb
    x[6] = -turn_rate * st
    x[7] = turn_rate * sp * ct
    x[8] = turn_rate * cp * ct
    x[9] = phi
    x[10] = theta
    x[11] = psi


@njit(cache=True, fastmath=False)
def _iterates(z, rows, V, h, given, sources, u0, control_cols, throttle_col, throttles):
    """Euler states (m, 12) and controls (m, n_controls) of the Newton iterates ``z`` (m, k) of conditions ``rows``.
    α is z[:, 0]; β, φ, ψ̇, γ (``sources``) come from the column of z given there, or from ``given`` (n, 4) where it
    is −1; the controls are ``u0`` with the columns ``control_cols`` (control, column of z) replaced, and the
    throttles (``throttles`` = first, count) set to ``throttle_col`` of z (−1: none)."""
    m = z.shape[0]
    X = np.empty((m, 12))
    U = np.empty((m, u0.shape[1]))
    vals = np.empty(4)
    for i in range(m):
        c = rows[i]
        for k in range(4):
            vals[k] = given[c, k] if sources[k] < 0 else z[i, sources[k]]
        _state_row(V[c], h[c], z[i, 0], vals[0], vals[1], vals[3], vals[2], 0.0, X[i])
        copy_row(U[i], u0[c])
        for k in range(control_cols.shape[0]):
            U[i, control_cols[k, 0]] = z[i, control_cols[k, 1]]
        if throttle_col >= 0:
            U[i, throttles[0] : throttles[0] + throttles[1]] = z[i, throttle_col]
    return X, U


# The Newton iteration's bookkeeping, compiled (fastmath off: the arithmetic of the numpy expressions it replaces, bit
# for bit); the residuals (the model's evaluation) and the linear solves stay with their numpy callers.


@njit(cache=True, fastmath=False)
def _norms(r, scale):
    """max_e |r[i, e] scale[e]| per row (NaN if any is NaN)."""
    out = np.empty(r.shape[0])
    for i in range(r.shape[0]):
        m = abs(r[i, 0] * scale[0])
        for e in range(1, r.shape[1]):
            v = abs(r[i, e] * scale[e])
            if v != v or v > m:
                m = v
            if m != m:
                break
        out[i] = m
    return out


@njit(cache=True, fastmath=False)
def _active(rnorm, stalls, tol, iters):
    """The conditions still iterating (residual above ``tol``, fewer than 3 stalls); counts their iteration."""
    idx = np.flatnonzero((rnorm > tol) & (stalls < 3))
    for i in idx:
        iters[i] += 1
    return idx


@njit(cache=True, fastmath=False)
def _perturbed(z, idx, hstep):
    """The forward-difference points of the conditions ``idx``: row j·na + i is z[idx[i]] with unknown j moved by
    hstep[j]; and the condition of each row."""
    na, k = idx.size, z.shape[1]
    zp = np.empty((k * na, k))
    rows = np.empty(k * na, dtype=np.int64)
    for j in range(k):
        for i in range(na):
            copy_row(zp[j * na + i], z[idx[i]])
            zp[j * na + i, j] += hstep[j]
            rows[j * na + i] = idx[i]
    return zp, rows


@njit(cache=True, fastmath=False)
def _jacobian(rp, r, idx, hstep):
    """Forward-difference Jacobians (na, equations, unknowns) from the residuals ``rp`` of :func:`_perturbed`'s
    points, and the residuals of the conditions ``idx``."""
    na, k = idx.size, hstep.size
    J = np.empty((na, r.shape[1], k))
    ra = np.empty((na, r.shape[1]))
    for i in range(na):
        copy_row(ra[i], r[idx[i]])
        for j in range(k):
            for e in range(r.shape[1]):
                J[i, e, j] = (rp[j * na + i, e] - ra[i, e]) / hstep[j]
    return J, ra


@njit(cache=True, fastmath=False)
def _limited_step(s, smax):
    """The Newton step −s (non-finite components 0), scaled down where a component exceeds its ``smax``."""
    dz = np.empty_like(s)
    for i in range(s.shape[0]):
        ratio = 1.0
        for j in range(s.shape[1]):
            d = -s[i, j]
            dz[i, j] = d if math.isfinite(d) else 0.0
            ratio = max(ratio, abs(dz[i, j]) / smax[j])
        for j in range(s.shape[1]):
            dz[i, j] = dz[i, j] / ratio
    return dz


@njit(cache=True, fastmath=False)
def _trial(z, idx, dz, lam, j_thr, box):
    """The iterates z[idx] + λ dz, the throttle column ``j_thr`` (−1: none) kept in ``box`` as ``np.clip`` keeps it
    (NaN stays NaN, −0 becomes 0)."""
    zt = np.empty_like(dz)
    for i in range(idx.size):
        for j in range(dz.shape[1]):
            zt[i, j] = z[idx[i], j] + lam[i] * dz[i, j]
        t = zt[i, j_thr] if j_thr >= 0 else 0.0
        if j_thr >= 0 and not math.isnan(t):
            t = t if t > box[0] else box[0]
            zt[i, j_thr] = t if t < box[1] else box[1]
    return zt


@njit(cache=True, fastmath=False)
def _backtrack(r_try, scale, rn_a, lam, bad):
    """Residual norms of the trial iterates; ``bad`` where they do not fall below ``rn_a`` (λ halved there when any is
    bad). Returns the norms and whether any is bad."""
    rn = _norms(r_try, scale)
    any_bad = False
    for i in range(rn.size):
        bad[i] = not (rn[i] < rn_a[i])
        any_bad |= bad[i]
    if any_bad:
        for i in range(rn.size):
            if bad[i]:
                lam[i] *= 0.5
    return rn, any_bad


@njit(cache=True, fastmath=False)
def _accept(idx, z_try, r_try, rn_try, bad, z, r, rnorm, stalls, iters, checkpoint, window, factor):
    """Take the last trial iterates of the conditions ``idx``; a bad step counts a stall; every ``window``
    iterations after the first ``window``, a condition whose residual fell less than ``factor``-fold since the
    last check stops (3 stalls)."""
    for a in range(idx.size):
        i = idx[a]
        stalls[i] = stalls[i] + 1 if bad[a] else 0
        copy_row(z[i], z_try[a])
        copy_row(r[i], r_try[a])
        rnorm[i] = rn_try[a] if math.isfinite(rn_try[a]) else np.inf
        if iters[i] % window == 0 and iters[i] > window:
            if not (rnorm[i] * factor < checkpoint[i]):
                stalls[i] = 3
            checkpoint[i] = rnorm[i]


@njit(cache=True, fastmath=False)
def _residual_rows(
    z,
    rows,
    V,
    h,
    given,
    sources,
    u0,
    control_cols,
    throttle_col,
    throttles,
    eq_cols,
    turbofan,
    throttle_start,
    operative,
    fraction,
    windmill,
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
    """The trim equations ``eq_cols`` of the iterates ``z`` of conditions ``rows`` (:func:`_iterates`) for a model whose
    thrust is compiled (:attr:`~certkit.models.dynamics.eom.AircraftModel.thrust_compiled`): the air data, the
    engines' forces and the equations of motion of :meth:`~certkit.models.dynamics.eom.AircraftModel.evaluate`, the
    same kernels in one call."""
    X, U = _iterates(z, rows, V, h, given, sources, u0, control_cols, throttle_col, throttles)
    air = kernel.air_data(X)
    thrust = kernel.engine_forces(air, U, rows, turbofan, throttle_start, operative, fraction, windmill)
    quat = X.shape[1] == 13  # a bool, not a literal: the equations of motion compiled once for every caller
    xd = kernel.derivatives(
        X,
        rows,
        quat,
        U,
        thrust,
        np.empty((X.shape[0], 8)),
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
    )[0]
    r = np.empty((X.shape[0], eq_cols.shape[0]))
    for i in range(X.shape[0]):
        for e in range(eq_cols.shape[0]):
            r[i, e] = xd[i, eq_cols[e]]
    return r


#: the state parameters given per condition or solved for, in :func:`_iterates`' order
_GIVEN = ("beta", "phi", "turn_rate", "gamma")

#: Newton's progress test (numerical choice; see :func:`_solve`)
SLOW_WINDOW, SLOW_FACTOR = 8, 2.0


def newton_steps(J: np.ndarray, r: np.ndarray) -> np.ndarray:
    """The Newton steps J⁻¹ r of each condition, (n, k) from Jacobians (n, k, k) and residuals (n, k); a singular
    Jacobian's by its pseudo-inverse. Each condition's step is the one it would have in a batch of its own (a singular
    matrix does not change the others': a condition's trim does not depend on the batch it is solved in)."""
    try:
        return np.linalg.solve(J, r[:, :, None])[:, :, 0]
    except np.linalg.LinAlgError:
        if J.shape[0] == 1:
            return np.einsum("nij,nj->ni", np.linalg.pinv(J), r)
        return np.concatenate([newton_steps(J[i : i + 1], r[i : i + 1]) for i in range(J.shape[0])])


def _solve(
    model: AircraftModel,
    V,
    h,
    kind: str = "straight",
    gamma=0.0,
    bank=0.0,
    beta=0.0,
    controls: Mapping[str, float | np.ndarray] | None = None,
    limits: Mapping[str, tuple[float, float]] | None = None,
    roles: Mapping[str, str] | None = None,
    initial_alpha=0.05,
    tol: float = 1e-9,
    max_iter: int = 40,
    throttle=None,
    initial: Mapping[str, float | np.ndarray] | None = None,
) -> TrimBatch:
    """The trim of :func:`trim` with the given pitch, roll and yaw controls (no stabiliser logic)."""
    if kind not in KINDS:
        raise ValueError(f"unknown trim kind {kind!r}; one of {KINDS}")
    n = model.n
    roles = {**DEFAULT_ROLES, **(roles or {})}
    bc = lambda a: np.broadcast_to(np.asarray(a, dtype=float), (n,)).astype(float)  # noqa: E731
    V, h, gamma, bank, beta_in = bc(V), bc(h), bc(gamma), bc(bank), bc(beta)
    names = model.control_names
    u0 = np.zeros((n, len(names)))
    for k, v in (controls or {}).items():
        u0[:, names.index(k)] = bc(v)
    has_engines = len(model.engines) > 0
    thr_idx = np.arange(model.throttle_slice.start, model.throttle_slice.stop)
    if throttle is not None:
        u0[:, thr_idx] = bc(throttle)[:, None]
    solve_throttle = has_engines and throttle is None

    # unknowns: ordered list of names; equations: indices into (u̇ v̇ ẇ ṗ q̇ ṙ)
    unknowns = ["alpha"]
    unknowns.append({"straight": "beta", "oei": "beta", "turn": "turn_rate", "sideslip": "phi"}[kind])
    equations = [0, 1, 2, 3, 4, 5]
    unsolved = []  # moment equations without a control: not solved for, but checked at the end
    for role, eq in (("pitch", 4), ("roll", 3), ("yaw", 5)):
        if roles.get(role) in model.aero_controls:
            unknowns.append(role)
        else:
            equations.remove(eq)
            unsolved.append(eq)
    unknowns.append("throttle" if solve_throttle else "gamma")
    while len(unknowns) > len(equations):  # symmetric models lacking lateral controls
        drop = "beta" if "beta" in unknowns else ("phi" if "phi" in unknowns else "turn_rate")
        unknowns.remove(drop)
    if len(unknowns) != len(equations):
        raise ValueError(f"trim {kind}: {len(unknowns)} unknowns {unknowns} for {len(equations)} equations")

    # initial values
    z = np.zeros((n, len(unknowns)))
    for j, name in enumerate(unknowns):
        if name == "alpha":
            z[:, j] = initial_alpha
        elif name == "turn_rate":
            z[:, j] = model.g * np.tan(bank) / np.maximum(V, 1.0)
        elif name == "throttle":
            z[:, j] = 0.5
        elif name == "gamma":
            z[:, j] = gamma
        elif name == "beta":
            z[:, j] = beta_in if kind == "sideslip" else 0.0

    for key, val in (
        initial or {}
    ).items():  # warm start: an unknown by its name or its control's, NaN keeps the default
        col = [j for j, name in enumerate(unknowns) if key == name or key == roles.get(name)]
        if col:
            v = bc(val)
            z[:, col[0]] = np.where(np.isfinite(v), v, z[:, col[0]])

    j_thr = unknowns.index("throttle") if "throttle" in unknowns else None
    given = np.stack(
        [
            beta_in if kind == "sideslip" else np.zeros(n),
            bank if kind in ("turn", "oei") else np.zeros(n),
            np.zeros(n),
            gamma,
        ],
        axis=1,
    )  # β, φ, ψ̇, γ where they are not unknowns
    sources = np.array([unknowns.index(name) if name in unknowns else -1 for name in _GIVEN])
    control_cols = np.array(
        [
            (names.index(roles[name]), j)
            for j, name in enumerate(unknowns)
            if name not in _GIVEN and name not in ("alpha", "throttle")
        ],
        dtype=np.int64,
    ).reshape(-1, 2)
    throttles = np.array([model.throttle_slice.start, thr_idx.size])
    layout = (V, h, given, sources, u0, control_cols, -1 if j_thr is None else j_thr, throttles)

    eq_cols = 3 + np.array(equations)

    if model.thrust_compiled:  # the iterates, air data, thrust and equations of motion in one compiled call
        fixed = (*layout, eq_cols, *model.compiled_thrust_args())

        def residual(z, idx):
            """Residual equations of the iterates ``z`` (rows of conditions ``idx``)."""
            return _residual_rows(z, idx, *fixed)

    else:

        def residual(z, idx):
            """Residual equations of the iterates ``z`` (rows of conditions ``idx``)."""
            x, u = _iterates(z, idx, *layout)
            return model.derivatives_euler(x, u, rows=idx)[:, eq_cols]

    steps = {
        "alpha": 1e-6,
        "beta": 1e-6,
        "phi": 1e-6,
        "turn_rate": 1e-7,
        "gamma": 1e-6,
        "pitch": 1e-6,
        "roll": 1e-6,
        "yaw": 1e-6,
        "throttle": 1e-6,
    }
    max_step = {
        "alpha": 0.1,
        "beta": 0.1,
        "phi": 0.2,
        "turn_rate": 0.05,
        "gamma": 0.05,
        "pitch": 0.2,
        "roll": 0.2,
        "yaw": 0.2,
        "throttle": 0.5,
    }
    hstep = np.array([steps[u] for u in unknowns])
    smax = np.array([max_step[u] for u in unknowns])
    # the engine models saturate outside throttle [0, 1]: an iterate beyond has a flat Jacobian column and
    # Newton stalls there, so the throttle iterate is kept inside (just below 1, where the forward difference
    # still sees the engine); a condition needing more than full thrust ends non-converged at the bound
    box = np.array(_THROTTLE_BOX)
    iters = np.zeros(n, dtype=np.int64)
    stalls = np.zeros(n, dtype=np.int64)
    everyone = np.arange(n)
    r = residual(z, everyone)
    scale = np.where(np.array(equations) < 3, 1.0 / model.g, 1.0)
    rnorm = _norms(r, scale)
    checkpoint = rnorm.copy()
    for _ in range(max_iter):
        # a condition leaves the iteration when converged, or after three Newton steps that could not
        # reduce its residual even when cut 64-fold (a limit or a non-trimmable condition)
        idx = _active(rnorm, stalls, tol, iters)
        if idx.size == 0:
            break
        # forward-difference Jacobian: the k perturbed iterates of every active condition in one call
        Jm, ra = _jacobian(residual(*_perturbed(z, idx, hstep)), r, idx, hstep)
        sol = newton_steps(Jm, ra)
        dz = _limited_step(sol, smax)
        # backtracking: accept the step if it reduces the residual, else halve (per condition)
        lam = np.ones(idx.size)
        bad = np.empty(idx.size, dtype=np.bool_)
        rn_a = rnorm[idx]
        for _bt in range(6):
            z_try = _trial(z, idx, dz, lam, -1 if j_thr is None else j_thr, box)
            r_try = residual(z_try, idx)
            rn_try, any_bad = _backtrack(r_try, scale, rn_a, lam, bad)
            if not any_bad:
                break
        # after 2 SLOW_WINDOW iterations, a condition whose residual fell less than SLOW_FACTOR-fold over its last
        # SLOW_WINDOW iterations is not converging (a limit, a non-trimmable condition): it leaves like a stalled one
        _accept(idx, z_try, r_try, rn_try, bad, z, r, rnorm, stalls, iters, checkpoint, SLOW_WINDOW, SLOW_FACTOR)

    x, u = _iterates(z, everyone, *layout)
    vals = {name: (z[:, j] if j >= 0 else given[:, k]) for k, (name, j) in enumerate(zip(_GIVEN, sources))}
    vals["alpha"] = z[:, 0]
    if unsolved:  # a model without (say) a pitch control trims only where that moment is zero by itself
        left = model.derivatives_euler(x, u)[:, 3:9][:, unsolved]
        rnorm = np.maximum(rnorm, np.max(np.abs(left), axis=1))
    lim = {
        roles["pitch"]: (-np.radians(30), np.radians(30)),
        roles["roll"]: (-np.radians(30), np.radians(30)),
        roles["yaw"]: (-np.radians(30), np.radians(30)),
        "throttle": (0.0, 1.0),
    }
    lim.update(limits or {})
    _, out = model.derivatives_euler(x, u, with_outputs=True)
    # rows as lists of Python floats (the values of float(a[i, j]), without a conversion per element)
    ul, zl, thrust, x9, x10 = u.tolist(), z.tolist(), out.thrust.tolist(), x[:, 9].tolist(), x[:, 10].tolist()
    vl = {key: np.asarray(v, dtype=float).tolist() for key, v in vals.items()}
    engine_names = [e.name for e in model.engines]
    checked = [(role, roles[role]) for role in ("pitch", "roll", "yaw") if role in unknowns and roles[role] in lim]
    results = []
    for i in range(n):
        ctrl = dict(zip(names, ul[i]))
        found = []
        for role, cname in checked:
            found += _check(cname, ctrl[cname], lim[cname], _HINTS[role], angle=True)
        if j_thr is not None:
            tval = zl[i][j_thr]
            lo, hi = lim["throttle"]
            found += _check(
                "throttle", tval, (lo, hi), _HINTS["throttle_high" if tval > hi else "throttle_low"], angle=False
            )
            # a non-converged iterate on a throttle stop says so even when a control is also past its limit (level
            # flight out of thrust leaves the controls' iterate unreliable): callers retry at the stop
            on_stop = tval >= _THROTTLE_BOX[1] or tval <= _THROTTLE_BOX[0]
            if rnorm[i] > tol and on_stop and not any(e.control == "throttle" for e in found):
                high = tval >= _THROTTLE_BOX[1]
                found.append(
                    LimitExceedance(
                        control="throttle",
                        required=tval,
                        limit=hi if high else lo,
                        excess=0.0,
                        message=f"needs {'more than full' if high else 'less than idle'} throttle",
                        hint=_HINTS["throttle_high" if high else "throttle_low"],
                    )
                )
        results.append(
            TrimResult(
                index=i,
                kind=kind,
                converged=bool(rnorm[i] <= tol),
                residual_norm=float(rnorm[i]),
                iterations=int(iters[i]),
                V=float(V[i]),
                h=float(h[i]),
                alpha=vl["alpha"][i],
                beta=vl["beta"][i],
                theta=x10[i],
                phi=x9[i],
                gamma=vl["gamma"][i],
                turn_rate=vl["turn_rate"][i],
                controls=ctrl,
                thrust=dict(zip(engine_names, thrust[i])),
                limits_exceeded=found,
            )
        )
    return TrimBatch(model=model, x=x, u=u, results=results)


@dataclass(frozen=True)
class StabilizerTrim:
    """A movable horizontal stabiliser as a trim device: the model control ``control`` is its deflection from the
    datum incidence ``datum`` (rad), solved within ``limits`` (deflections, rad) with the ``elevator`` held at
    ``elevator_trim``."""

    limits: tuple[float, float]
    datum: float = 0.0
    elevator_trim: float = 0.0
    control: str = "stabilizer"
    elevator: str = "elevator"


def trim(
    model: AircraftModel,
    V,
    h,
    kind: str = "straight",
    gamma=0.0,
    bank=0.0,
    beta=0.0,
    controls: Mapping[str, float | np.ndarray] | None = None,
    limits: Mapping[str, tuple[float, float]] | None = None,
    roles: Mapping[str, str] | None = None,
    initial_alpha=0.05,
    tol: float = 1e-9,
    max_iter: int = 40,
    throttle=None,
    stabilizer: StabilizerTrim | None = None,
    stabilizer_setting=None,
    initial: Mapping[str, float | np.ndarray] | None = None,
) -> TrimBatch:
    """Trim every condition of ``model`` (n conditions) at true airspeed ``V`` (m/s) and altitude
    ``h`` (m); scalars or (n,) arrays.

    ``gamma`` flight-path angle (rad), ``bank`` φ for turn/oei, ``beta`` for sideslip.
    ``controls`` fixes the controls that are not trim unknowns (flap, stabilizer …; radians).
    ``limits`` maps control names (and ``throttle``) to (min, max); the defaults are ±30° for the
    role controls and (0, 1) for the throttle. ``roles`` maps pitch/roll/yaw to control names.

    ``stabilizer`` (a model with a movable stabiliser): the stabiliser is the pitch unknown with the elevator at its
    trim setting; a condition whose stabiliser would pass a limit is trimmed again with the stabiliser at that stop
    and the elevator as the pitch unknown (the elevator carries the rest; its own limits are checked as usual), and
    its result says so (``stabilizer_at_stop``, ``stabilizer_required``). ``stabilizer_setting`` (deflections, one
    per condition or a scalar) holds the stabiliser where it was trimmed — a manoeuvre or a change "without
    re-trimming" — and the elevator is solved for. Without ``stabilizer`` this is the plain trim.

    ``initial`` warm-starts the Newton iteration: values (scalars or one per condition, NaN for the default) keyed by
    unknown (``alpha``, ``beta``, ``phi``, ``turn_rate``, ``throttle``, ``gamma``) or by control name (``rudder``, …);
    keys that are not unknowns of this trim are ignored. The default start is β = 0, α = ``initial_alpha``, the
    role controls 0 and the throttle 0.5 — far from a trim near the stall or the control limits, where Newton from
    there may fail or land on another solution; a nearby converged trim is the better start.
    """
    plain = dict(
        kind=kind,
        gamma=gamma,
        bank=bank,
        beta=beta,
        limits=limits,
        initial_alpha=initial_alpha,
        tol=tol,
        max_iter=max_iter,
        throttle=throttle,
        initial=initial,
    )
    if stabilizer is None:
        return _solve(model, V, h, controls=controls, roles=roles, **plain)
    n = model.n
    bc = lambda a: np.broadcast_to(np.asarray(a, dtype=float), (n,)).astype(float)  # noqa: E731
    st = stabilizer
    fixed = dict(controls or {})
    lim = {**(limits or {}), st.control: st.limits}
    plain["limits"] = lim
    if stabilizer_setting is not None:
        fixed[st.control] = bc(stabilizer_setting)
        batch = _solve(model, V, h, controls=fixed, roles=roles, **plain)
        _mark_stabilizer(batch, st, frozen=True)
        return batch
    fixed.setdefault(st.elevator, st.elevator_trim)
    batch = _solve(model, V, h, controls=fixed, roles={**(roles or {}), "pitch": st.control}, **plain)
    need = batch.u[:, model.control_names.index(st.control)].copy()
    lo, hi = st.limits
    over = np.flatnonzero((need < lo) | (need > hi))
    if over.size:
        sub = dict(plain)
        for key in ("gamma", "bank", "beta", "throttle"):
            if plain[key] is not None:
                sub[key] = bc(plain[key])[over]
        if initial is not None:
            sub["initial"] = {k: bc(v)[over] for k, v in initial.items()}
        again = dict(controls or {})
        for k, v in again.items():
            again[k] = bc(v)[over]
        again[st.control] = np.clip(need[over], lo, hi)
        part = _solve(model.subset(over), bc(V)[over], bc(h)[over], controls=again, roles=roles, **sub)
        batch.x[over], batch.u[over] = part.x, part.u
        for j, i in enumerate(over):
            r = part.results[j]
            r.index = int(i)
            batch.results[i] = r
    _mark_stabilizer(batch, st, frozen=False, required=need)
    return batch


def held_stabilizer(results) -> np.ndarray | None:
    """The movable stabiliser's deflection (rad, per :class:`TrimResult`), to hold in a manoeuvre or a change that
    follows those trims without re-trimming (``stabilizer_setting``); None on an airplane without one."""
    if not results or results[0].stabilizer is None:
        return None
    return np.array([r.controls["stabilizer"] for r in results])


def _mark_stabilizer(batch: TrimBatch, st: StabilizerTrim, frozen: bool, required=None) -> None:
    """The stabiliser fields of each result (absolute incidence = datum + deflection)."""
    j = batch.model.control_names.index(st.control)
    lo, hi = st.limits
    for i, r in enumerate(batch.results):
        r.stabilizer = st.datum + float(batch.u[i, j])
        r.stabilizer_frozen = frozen
        need = float(batch.u[i, j] if required is None else required[i])
        r.stabilizer_required = st.datum + need
        if not frozen:  # the stabiliser's own limit is reported by its stop, not as an exceedance
            r.stabilizer_at_stop = "nose-up" if need < lo else ("nose-down" if need > hi else "")
            r.limits_exceeded = [e for e in r.limits_exceeded if e.control != st.control]


def _check(name, value, bounds, hint, angle):
    lo, hi = bounds
    if lo <= value <= hi:
        return []
    lim = hi if value > hi else lo
    f = (lambda a: f"{np.degrees(a):.1f}°") if angle else (lambda a: f"{a:.2f}")
    return [
        LimitExceedance(
            control=name,
            required=float(value),
            limit=float(lim),
            excess=float(value - lim),
            message=f"needs {f(value)} {name}, limit {f(lim)}",
            hint=hint,
        )
    ]


__all__ = [
    "trim",
    "StabilizerTrim",
    "held_stabilizer",
    "TrimBatch",
    "TrimResult",
    "LimitExceedance",
    "theta_from_gamma",
    "assemble_state",
    "KINDS",
]
