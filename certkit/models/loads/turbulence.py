"""Rigid-airplane station loads in continuous vertical and lateral turbulence: frequency responses and the rms load
per unit rms gust velocity, Ā.

The trimmed airplane with the gust pseudo-controls of :mod:`certkit.models.loads.gust` (the gust angle at the wing,
and the same gust at the tail a tail arm / V later) is linearised about its trim — ẋ = A x + B u and the outputs α,
n_z, q̄ alike (central differences, :mod:`certkit.models.dynamics.linearize`). A sinusoidal vertical gust w e^{iωt}
(true airspeed) sets the gust angles w/V at the wing and w e^{−iωτ}/V at the tail (τ = tail arm / V); the states
answer with x = (iω I − A)⁻¹ B_g(ω) w. The strip model's station loads are linear in what they read — each surface's
angle of attack with its own gust angle, the pitch rate, the load factor and the pitch acceleration iω q, and the
dynamic pressure — so the frequency response H(ω) of every station load is the strip model evaluated on the real
and the imaginary parts of those increments. With the spatial frequency Ω = ω/V and von Kármán's normalised
spectrum Φ(Ω) (unit variance),

    Ā = [∫₀^∞ |H(Ω)|² Φ(Ω) dΩ]^½,

the rms load per unit rms gust velocity of a design-envelope analysis (§25.341(b)(1)–(2): P = P_1g ± U_σ Ā).

In lateral turbulence (:func:`lateral_turbulence_response`) the gust is a sideslip v_g/V felt by the fin alone
(:mod:`certkit.models.loads.lateral_gust`), the airplane free in sideslip, roll and yaw.

The gust's lift on each surface lags as Küssner's function gives
(:func:`certkit.models.loads.gust.penetration_transfer`, a Sears-function approximation on the surface's mean
chord). Limits (stated by the rules that use it): the lift of the airplane's own motion is quasi-steady (no Wagner
function); rigid airplane; controls fixed (no pilot or flight control system in the loop), so the phugoid and the
spiral mode, which the pilot flies, are held out (:data:`FREE_STATES`, :data:`LATERAL_FREE_STATES`); the Mach number
is held at the trim's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.dynamics.linearize import linearize, output_sensitivities
from certkit.models.dynamics.simulate import simulate
from certkit.models.loads.gust import GUST_CONTROLS, penetration_transfer
from certkit.models.loads.lateral_gust import CONTROL, FIN
from certkit.models.loads.response import inertia_terms, response_load_parts

#: the airplane's degrees of freedom in turbulence: plunge (w) and pitch (q) at constant speed — the classical rigid
#: airplane of gust-loads analysis (Hoblit, Gust Loads on Aircraft, ch. 3); the phugoid (speed, height, attitude),
#: lightly damped with the controls fixed (ζ ≈ 0.03–0.04 on the baseline) and in service flown by the pilot or the
#: autopilot, would otherwise put half the load factor's variance at its own frequency
FREE_STATES = ("w", "q")
#: … and in lateral turbulence sideslip (v), roll (p) and yaw (r): the Dutch roll and the roll subsidence; the spiral
#: mode (bank and heading), slow and flown by the pilot, left out likewise
LATERAL_FREE_STATES = ("v", "p", "r")
#: von Kármán's constant of the normalised spectrum (Hoblit, *Gust Loads on Aircraft*, 1988, eq. 2.20)
VON_KARMAN_K = 1.339
#: the spectrum's high-frequency slope: Φ ∝ Ω^(−5/3)
HIGH_FREQUENCY_EXPONENT = 5.0 / 3.0
#: spatial frequencies of the integral, as multiples of 1/L: from far below the spectrum's knee to where the
#: airplane's rigid modes are long settled (the rest is added in closed form, :func:`rms_per_unit`); 120 points (18 a
#: decade) give every Ā within 0.5 % of a grid eight times finer (numerical choice, tests/loads/test_turbulence.py;
#: the baseline's normalised margins move by < 0.002 from 240 points)
OMEGA_RANGE = (1e-3, 3e3)
OMEGA_POINTS = 120


def von_karman(omega: np.ndarray, scale: float) -> np.ndarray:
    """Von Kármán's vertical-turbulence spectrum of unit variance, one-sided in the spatial frequency Ω (rad/m), scale
    L (m): Φ(Ω) = (L/π) [1 + (8/3)(1.339 L Ω)²] / [1 + (1.339 L Ω)²]^(11/6) (§25.341(b)(2); Hoblit eq. 2.20)."""
    x = (VON_KARMAN_K * scale * np.asarray(omega, dtype=float)) ** 2
    return scale / np.pi * (1.0 + 8.0 / 3.0 * x) / (1.0 + x) ** (11.0 / 6.0)


def spatial_frequencies(scale: float, points: int = OMEGA_POINTS) -> np.ndarray:
    """The Ω grid (rad/m) of the integral: log-spaced over :data:`OMEGA_RANGE` / L."""
    lo, hi = OMEGA_RANGE
    return np.geomspace(lo / scale, hi / scale, points)


def rms_per_unit(power: np.ndarray, omega: np.ndarray, scale: float) -> np.ndarray:
    """Ā = [∫₀^∞ |H|² Φ dΩ]^½ from |H(Ω)|² (..., nΩ) on the grid ``omega``: the trapezoidal rule in log Ω over the
    grid, below it |H|² taken as its first value, above it as the mean of the last decade times the spectrum's
    Ω^(−5/3) asymptote, integrated in closed form."""
    power = np.asarray(power, dtype=float)
    omega = np.asarray(omega, dtype=float)
    phi = von_karman(omega, scale)
    inside = np.trapezoid(power * phi * omega, np.log(omega), axis=-1)
    below = power[..., 0] * phi[0] * omega[0]  # Φ flat below the knee
    top = omega >= omega[-1] / 10.0
    # ∫_{Ω_max}^∞ (L/π)(8/3)(1.339 L Ω)^(−5/3) dΩ = (L/π)(8/3)(1.339 L)^(−5/3) (3/2) Ω_max^(−2/3)
    tail_phi = scale / np.pi * 8.0 / 3.0 * (VON_KARMAN_K * scale) ** (-HIGH_FREQUENCY_EXPONENT) * 1.5
    above = power[..., top].mean(axis=-1) * tail_phi * omega[-1] ** (1.0 - HIGH_FREQUENCY_EXPONENT)
    return np.sqrt(inside + below + above)


@dataclass
class TurbulenceResponse:
    """Frequency responses per unit gust velocity (m/s TAS) of a batch of n conditions on the grid ``omega``
    (rad/m): the station loads of each surface (nΩ, n, 3, S), the wing's loads per kilogram of each tank's fuel
    (nΩ, n, K, 3, S; None without tanks) and the load factor (nΩ, n)."""

    omega: np.ndarray
    loads: dict[str, np.ndarray]
    fuel_per_kg: dict[str, np.ndarray | None]
    n_z: np.ndarray


def _linear(f, z: np.ndarray) -> np.ndarray:
    """A real linear map ``f`` (without its constant part) applied to a complex argument: f(Re z) + i f(Im z)."""
    return f(z.real) + 1j * f(z.imag)


@dataclass
class SteadyLoads:
    """The trimmed (1 g) state of a gust batch: per surface the aerodynamic and inertial station loads (n, 3, S), the
    wing's loads per kilogram of each tank's fuel (n, K, 3, S; None without tanks), and q̄, Mach (n,)."""

    aero: dict[str, np.ndarray]
    inertia: dict[str, np.ndarray]
    fuel_per_kg: dict[str, np.ndarray | None]
    qbar: np.ndarray
    mach: np.ndarray

    def total(self, surface: str) -> np.ndarray:
        return self.aero[surface] + self.inertia[surface]


def steady_loads(loads, gb, surfaces=("wing", "horizontal_tail")) -> SteadyLoads:
    """The station loads of the trimmed state of the gust batch ``gb`` (the first record of a one-step run)."""
    dt = 0.01
    sim = simulate(gb.model, gb.x0, gb.u0, dt, dt)
    parts = response_load_parts(loads, sim, gb.model, surfaces)
    terms = {k: v[:1] for k, v in inertia_terms(sim, gb.model).items()}
    fuel = {}
    for name in surfaces:
        per_kg = loads[name].fuel_loads(terms)
        fuel[name] = None if per_kg is None else per_kg[0]
    return SteadyLoads(
        {k: a[0] for k, (a, _) in parts.items()},
        {k: i[0] for k, (_, i) in parts.items()},
        fuel,
        np.asarray(sim.history["qbar"][0], dtype=float),
        np.asarray(sim.history["mach"][0], dtype=float),
    )


def _states(lin, C, D, u: np.ndarray, w: np.ndarray, free: tuple[str, ...]):
    """The states (nΩ, n, ns) and outputs (nΩ, n, k) answering the inputs ``u`` (nΩ, n, m) at the circular frequencies
    ``w`` (nΩ, n) with only the ``free`` states moving (the others held at the trim)."""
    idx = [lin.state_names.index(k) for k in free]
    A = lin.A[:, idx][:, :, idx]
    system = 1j * w[..., None, None] * np.eye(len(idx)) - A[None]
    x_free = np.linalg.solve(system, np.einsum("nsm,wnm->wns", lin.B[:, idx], u)[..., None])[..., 0]
    x = np.zeros(x_free.shape[:-1] + (lin.A.shape[-1],), dtype=complex)
    x[..., idx] = x_free
    return x, np.einsum("nks,wns->wnk", C, x) + np.einsum("nkm,wnm->wnk", D, u)


def _surface(s, steady_aero, qbar0, mach0, increments: dict, terms: dict, d_qbar):
    """One surface's station-load response (nΩ, n, 3, S) to the aerodynamic ``increments`` and inertial ``terms``
    (each (nΩ, n), complex), the trimmed aerodynamic loads ``steady_aero`` (n, 3, S) scaled by the change of q̄; and
    its loads per kilogram of each tank's fuel (None without tanks)."""
    zero = s.aero_loads(qbar0, mach0, {})
    keys, names = list(increments), list(terms)
    term_stack = np.stack([terms[k] for k in names])

    def aero(z: np.ndarray) -> np.ndarray:
        return s.aero_loads(qbar0, mach0, dict(zip(keys, z))) - zero

    def inertia(z: np.ndarray) -> np.ndarray:
        return s.inertia_loads(dict(zip(names, z)))

    def per_kg(z: np.ndarray) -> np.ndarray:
        return s.fuel_loads(dict(zip(names, z)))

    loads = (
        _linear(aero, np.stack([increments[k] for k in keys]))
        + (d_qbar / qbar0)[..., None, None] * steady_aero[None]  # linear in q̄ at the trim's Mach number
        + _linear(inertia, term_stack)
    )
    fuel = None if s.fuel_loads({k: np.zeros(1) for k in names}) is None else _linear(per_kg, term_stack)
    return loads, fuel


def turbulence_response(loads, gb, steady: SteadyLoads, omega: np.ndarray) -> TurbulenceResponse:
    """The frequency responses (:class:`TurbulenceResponse`) of the gust batch ``gb``
    (:func:`certkit.models.loads.gust_response.gust_batch`) to a unit vertical gust on the spatial frequencies
    ``omega`` (rad/m), about its trimmed state ``steady`` (:func:`steady_loads`), for the surfaces ``steady``
    holds; the airplane free to plunge and pitch (:data:`FREE_STATES`)."""
    omega = np.asarray(omega, dtype=float)
    model = gb.model
    lin = linearize(model, gb.x0, gb.u0)
    C, D = output_sensitivities(model, gb.x0, gb.u0, ("alpha", "n_z", "qbar"))
    names = list(lin.control_names)
    gw, gt = (names.index(c) for c in GUST_CONTROLS)
    v = gb.v_tas  # (n,)
    w = omega[:, None] * v[None, :]  # (nΩ, n) rad/s
    u = np.zeros(w.shape + (len(names),), dtype=complex)  # gust angles per unit gust velocity
    c_wing, c_tail = gb.chords  # Küssner's penetration lag of each surface (certkit.models.loads.gust)
    u[..., gw] = penetration_transfer(omega, c_wing)[:, None] / v
    u[..., gt] = penetration_transfer(omega, c_tail)[:, None] * np.exp(-1j * w * (gb.tail_arm / v)[None, :]) / v
    x, y = _states(lin, C, D, u, w, FREE_STATES)
    d_alpha, d_nz, d_qbar = y[..., 0], y[..., 1], y[..., 2]
    q = x[..., lin.state_names.index("q")]
    q_dot = 1j * w * q
    qbar0 = np.broadcast_to(steady.qbar[None, :], w.shape)
    mach0 = np.broadcast_to(steady.mach[None, :], w.shape)
    gust_alpha = {"wing": u[..., gw], "horizontal_tail": u[..., gt]}
    terms = {"n_z": d_nz, "qdot_xcg": q_dot * model.cg[:, 0][None, :], "qdot": q_dot}
    out: dict[str, np.ndarray] = {}
    fuel: dict[str, np.ndarray | None] = {}
    for name in steady.aero:
        increments = {"alpha": d_alpha + gust_alpha.get(name, 0.0), "q_hat": q * model.c / (2.0 * v[None, :])}
        out[name], fuel[name] = _surface(loads[name], steady.aero[name], qbar0, mach0, increments, terms, d_qbar)
    return TurbulenceResponse(omega, out, fuel, d_nz)


def lateral_turbulence_response(loads, lb, steady: SteadyLoads, omega: np.ndarray) -> TurbulenceResponse:
    """The fin's station-load response to a unit lateral gust (TAS, m/s: a sideslip v_g/V felt by the fin,
    :mod:`certkit.models.loads.lateral_gust`) of the batch ``lb``, on the spatial frequencies ``omega`` (rad/m), about
    its trimmed state ``steady``; the airplane free in sideslip, roll and yaw (:data:`LATERAL_FREE_STATES`).
    ``n_z`` holds the lateral load factor n_y."""
    omega = np.asarray(omega, dtype=float)
    model = lb.model
    lin = linearize(model, lb.x0, lb.u0)
    C, D = output_sensitivities(model, lb.x0, lb.u0, ("beta", "n_y", "qbar"))
    names = list(lin.control_names)
    v = lb.v_tas
    w = omega[:, None] * v[None, :]
    u = np.zeros(w.shape + (len(names),), dtype=complex)
    u[..., names.index(CONTROL)] = penetration_transfer(omega, loads[FIN].mean_chord)[:, None] / v
    x, y = _states(lin, C, D, u, w, LATERAL_FREE_STATES)
    d_beta, d_ny, d_qbar = y[..., 0], y[..., 1], y[..., 2]
    p, r = x[..., lin.state_names.index("p")], x[..., lin.state_names.index("r")]
    p_dot, r_dot = 1j * w * p, 1j * w * r
    increments = {
        "beta": d_beta + u[..., names.index(CONTROL)],
        "p_hat": p * model.b / (2.0 * v[None, :]),
        "r_hat": r * model.b / (2.0 * v[None, :]),
    }
    terms = {
        "n_y": d_ny,
        "rdot_xcg": r_dot * model.cg[:, 0][None, :],
        "rdot": r_dot,
        "pdot_zcg": p_dot * model.cg[:, 2][None, :],
        "pdot": p_dot,
    }
    qbar0 = np.broadcast_to(steady.qbar[None, :], w.shape)
    mach0 = np.broadcast_to(steady.mach[None, :], w.shape)
    fin, per_kg = _surface(loads[FIN], steady.aero[FIN], qbar0, mach0, increments, terms, d_qbar)
    return TurbulenceResponse(omega, {FIN: fin}, {FIN: per_kg}, d_ny)


__all__ = [
    "FREE_STATES",
    "LATERAL_FREE_STATES",
    "lateral_turbulence_response",
    "SteadyLoads",
    "TurbulenceResponse",
    "rms_per_unit",
    "spatial_frequencies",
    "steady_loads",
    "turbulence_response",
    "von_karman",
]
