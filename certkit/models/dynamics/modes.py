"""Identification of the classical rigid-body modes from a linearisation, by eigenvector content.

The eigenproblem is solved on the 8 states u, v, w, p, q, r, φ, θ (position and heading give neutral
roots of no handling interest and are left out) and, with ``density_gradient``, the altitude h as a ninth:
the forces then change with height through ρ(h) (and the engines' thrust through their altitude lapse), and
ḣ = u sin θ − v sin φ cos θ − w cos φ cos θ closes the loop. This is the phugoid with the density gradient: for
constant CL, thrust equal to drag and no pitch dynamics, ΔV̇ = −g Δγ, V Δγ̇ = g (2 ΔV/V + (ρ'/ρ) Δh), Δḣ = V Δγ give

    ω_ph² = 2 g²/V² − g (dρ/dh)/ρ

(Lanchester's 2 g²/V² plus the stiffening of the density gradient: in the troposphere (dρ/dh)/ρ =
−(g + R dT/dh)/(R T), ≈ 15–20 % on the frequency of a jet transport at cruise; Etkin & Reid, *Dynamics of
Flight*, 3rd ed., 1996, §6.5 "Effect of vertical density gradient": the altitude moved into the matrix equation
with Z_z = −m g κ, κ = −(dρ/dh)/ρ, and the Lanchester estimate modified the same way). The altitude adds a slow
real root (the height mode), reported under ``other_<k>``.
Each eigenvector is made dimensionless — velocities divided by the trim airspeed (u/V, β ≈ v/V, α ≈ w/V),
rates divided by |λ| so that a rate counts like the angle it integrates to, the height multiplied by |λ|/V
(the flight-path angle whose integral it is) — and then:

* longitudinal vs lateral: the share of the vector's norm in (u, w, q, θ) vs (v, p, r, φ);
* longitudinal oscillations: phugoid = the pair with the largest speed share |u/V| / (|u/V|+|α|),
  short period = the pair with the largest angle-of-attack share (two real roots with dominant α
  are reported as an aperiodic short period);
* lateral: Dutch roll = the oscillatory pair; among the real roots, roll subsidence = the one with
  the largest roll-rate share |p| / (|p| + |r|), spiral = the one with the largest yaw-rate share.

No assignment relies on the ordering or size of the eigenvalues.
For each mode: eigenvalue λ = σ + iω_d, natural frequency ω_n = |λ|, damping ratio ζ = −σ/|λ|,
period 2π/ω_d (oscillatory), time to half amplitude ln 2/(−σ) (σ < 0) or to double ln 2/σ (σ > 0).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from certkit.models.dynamics.linearize import Linearization
from certkit.units import G0

_SUB = ("u", "v", "w", "p", "q", "r", "phi", "theta", "h")
_LON = np.array([True, False, True, False, True, False, False, True, True])


@dataclass
class Mode:
    name: str
    eigenvalue: complex
    natural_frequency: float  # rad/s
    damping_ratio: float
    period: float | None  # s, oscillatory modes
    time_to_half: float | None  # s, convergent
    time_to_double: float | None  # s, divergent
    eigenvector: np.ndarray  # dimensionless, over u/V, β, α, p, q, r, φ, θ (rates over |λ|) [, h |λ|/V]

    @property
    def stable(self) -> bool:
        return self.eigenvalue.real < 0


def _mode(name, lam, vec) -> Mode:
    wn = abs(lam)
    zeta = -lam.real / wn if wn > 0 else 1.0
    period = 2 * np.pi / abs(lam.imag) if abs(lam.imag) > 1e-12 else None
    half = np.log(2) / -lam.real if lam.real < 0 else None
    double = np.log(2) / lam.real if lam.real > 0 else None
    return Mode(name, complex(lam), float(wn), float(zeta), period, half, double, vec)


@lru_cache(maxsize=16)
def _submatrix(state_names: tuple[str, ...], n: int) -> tuple[np.ndarray, np.ndarray]:
    """The index of the first ``n`` states of ``_SUB`` among ``state_names``, rows and columns (``np.ix_``)."""
    idx = [state_names.index(s) for s in _SUB[:n]]
    return np.ix_(idx, idx)


def identify_modes(lin: Linearization, i: int, density_gradient: bool = False) -> dict[str, Mode]:
    """Modes of condition ``i``: keys ``short_period``, ``phugoid``, ``dutch_roll``, ``roll``,
    ``spiral`` (a mode that does not appear in its classical form is left out; extra roots go
    under ``other_<k>``). ``density_gradient`` adds the altitude state (module docstring); without it the
    longitudinal equations are the textbook four (Etkin & Reid eq. 4.9,18)."""
    return identify_rows(lin, [i], density_gradient)[0]


def identify_rows(lin: Linearization, rows=None, density_gradient: bool = False) -> list[dict[str, Mode]]:
    """:func:`identify_modes` of each condition of ``rows`` (all by default), their eigenproblems solved in one
    batched call (LAPACK's solver matrix by matrix: the same values as one at a time)."""
    n = len(_SUB) if density_gradient else len(_SUB) - 1
    rows = list(range(lin.A.shape[0])) if rows is None else [int(i) for i in rows]
    if not rows:
        return []
    ix = _submatrix(tuple(lin.state_names), n)
    lam_all, vecs_all = np.linalg.eig(lin.A[rows][:, ix[0], ix[1]])
    return [
        _identified(lam_all[j], vecs_all[j], float(np.linalg.norm(lin.x0[i, 3:6])), n, density_gradient)
        for j, i in enumerate(rows)
    ]


def _identified(lam: np.ndarray, vecs: np.ndarray, V: float, n: int, density_gradient: bool) -> dict[str, Mode]:
    """The modes of one condition from its eigenvalues ``lam`` and eigenvectors ``vecs`` (columns) at speed ``V``."""
    scaled = vecs.copy()
    scaled[:3] /= V
    size = [abs(x) for x in lam]  # |λ| by the scalar's abs (the array's SIMD loop may differ in the last bit)
    scaled[3:6] /= np.array([max(x, 1e-6) for x in size])
    if density_gradient:
        scaled[8] *= np.array([x / V for x in size])
    scaled /= np.linalg.norm(scaled, axis=0, keepdims=True)
    mag = np.abs(scaled)
    lon_share = np.sum(mag[_LON[:n]] ** 2, axis=0).tolist()
    # the eigenvalues' parts and the vectors' magnitudes as Python floats for the choices below (the same values)
    real, imag = lam.real.tolist(), lam.imag.tolist()
    m_u, m_v, m_w, m_p, _, m_r = mag[:6].tolist()
    # one representative per conjugate pair (imag ≥ 0)
    keep = [k for k in range(lam.size) if imag[k] >= -1e-12]
    lon = [k for k in keep if lon_share[k] >= 0.5]
    lat = [k for k in keep if lon_share[k] < 0.5]
    modes: dict[str, Mode] = {}

    def take(name, pool, k):
        modes[name] = _mode(name, lam[k], scaled[:, k])
        pool.remove(k)

    def split(ks):
        return [k for k in ks if abs(imag[k]) > 1e-9], [k for k in ks if abs(imag[k]) <= 1e-9]

    osc, real_roots = split(lon)
    speed_share = lambda k: m_u[k] / (m_u[k] + m_w[k] + 1e-30)  # noqa: E731
    if osc:
        ph = max(osc, key=speed_share)
        if speed_share(ph) > 0.5 or len(osc) > 1:
            take("phugoid", osc, ph)
        if osc:
            take("short_period", osc, min(osc, key=speed_share))
    a_dom = [k for k in real_roots if speed_share(k) < 0.5]
    if a_dom and "short_period" not in modes:
        take("short_period", real_roots, min(a_dom, key=lambda k: real[k]))
    rest = osc + real_roots

    osc, real_roots = split(lat)
    if osc:
        take("dutch_roll", osc, max(osc, key=lambda k: m_v[k]))
    # p and r carry the same 1/|λ| factor, so this ratio is that of the raw rates
    roll_share = lambda k: m_p[k] / (m_p[k] + m_r[k] + 1e-30)  # noqa: E731
    if real_roots:
        take("roll", real_roots, max(real_roots, key=roll_share))
    if real_roots:
        take("spiral", real_roots, min(real_roots, key=roll_share))
    for j, k in enumerate(rest + osc + real_roots):
        modes[f"other_{j}"] = _mode(f"other_{j}", lam[k], scaled[:, k])
    return modes


def identify_all(lin: Linearization) -> list[dict[str, Mode]]:
    return identify_rows(lin)


__all__ = ["Mode", "identify_modes", "identify_rows", "identify_all"]


def load_factor_per_alpha(lin: Linearization) -> np.ndarray:
    """n/α (g per rad) of each condition of ``lin``: the normal load factor per unit angle of attack at constant
    speed and pitch rate, −Z_w V / g with Z_w = ∂ẇ/∂w of the linearised body-axis equations and V the trim's
    airspeed (Etkin & Reid §4.9: Z_w ≈ −(C_Lα + C_D) q̄S/(mV), so n/α ≈ q̄ S C_Lα / (m g)). Used with the short period's
    frequency for the control anticipation parameter ω²/(n/α)."""
    iu, iv, iw = (lin.state_names.index(s) for s in ("u", "v", "w"))
    speed = np.sqrt(lin.x0[:, iu] ** 2 + lin.x0[:, iv] ** 2 + lin.x0[:, iw] ** 2)
    return -lin.A[:, iw, iw] * speed / G0
