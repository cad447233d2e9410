"""Hand span loads of a straight-tapered wing, independent of certkit's lattice and strips (test helper).

Schrenk's approximation (O. Schrenk, "A simple approximation method for obtaining the spanwise lift distribution",
NACA TM 948, 1940): the lift per unit span of a wing without twist is the mean of its chord distribution and the
elliptic distribution of the same area, l(y) ∝ ½ [c(y) + (4 S / (π b)) √(1 − (2y/b)²)]. Beam statics of the half
wing as a cantilever at a station (Megson, *Aircraft Structures for Engineering Students*, 4th ed., §16.1): the
bending moment is Σ (force × arm) of everything outboard. A dihedral Γ tilts the normal force (vertical lift
/ cos Γ) and lengthens the arm along the span (Δy / cos Γ): the air load's bending is L Δy / cos² Γ, the weight's
(normal component m g n cos Γ) m g n Δy.
"""

from __future__ import annotations

import numpy as np

G0 = 9.80665


def planform(area: float, aspect_ratio: float, taper: float):
    """(semispan, root chord, chord function c(y)) of the straight-tapered wing."""
    b = np.sqrt(aspect_ratio * area)
    cr = 2 * area / (b * (1 + taper))
    return b / 2, cr, lambda y: cr * (1 - (1 - taper) * np.asarray(y) / (b / 2))


def schrenk(area: float, aspect_ratio: float, taper: float, n: int = 4001):
    """(y, l(y)) on the half span, l normalised so that ∫ l dy = 1 over the half span."""
    s, _, c = planform(area, aspect_ratio, taper)
    y = np.linspace(0.0, s, n)
    ell = 0.5 * (c(y) + 4 * area / (np.pi * 2 * s) * np.sqrt(np.clip(1 - (y / s) ** 2, 0.0, None)))
    return y, ell / np.trapezoid(ell, y)


def outboard_moment(y, w, station: float) -> float:
    """∫ w(y) (y − station) dy outboard of ``station`` (first moment of a distribution about it)."""
    keep = y >= station
    return float(np.trapezoid(w[keep] * (y[keep] - station), y[keep]))


def bending_at(
    station: float,
    half_wing_air_load: float,
    n: float,
    wing: dict,
    wing_mass_half: float,
    point_masses=(),
    dihedral: float = 0.0,
) -> float:
    """Limit bending (N·m) at |y| ``station`` of one half wing at load factor n: the air load spread by Schrenk, the
    wing's own mass spread in proportion to the chord, point masses (kg, |y|) — engines, fuel tanks' centroids."""
    y, ell = schrenk(**wing)
    _, _, c = planform(**wing)
    chord = c(y)
    air = half_wing_air_load * outboard_moment(y, ell, station) / np.cos(dihedral) ** 2
    structure = wing_mass_half * G0 * n * outboard_moment(y, chord / np.trapezoid(chord, y), station)
    points = sum(m * G0 * n * max(yp - station, 0.0) for m, yp in point_masses)
    return air - structure - points


def lift_centroid(y, load) -> float:
    """Spanwise centroid ∫ l y dy / ∫ l dy of a span load."""
    return float(np.trapezoid(load * y, y) / np.trapezoid(load, y))


def _segment_w(p, a, b):
    """z-velocity at points p (..., 3) induced by a unit-circulation straight vortex from a to b (Biot–Savart, the
    segment formula of Bertin & Cummings, *Aerodynamics for Engineers*, 5th ed., eq. 7.38)."""
    r0, r1, r2 = b - a, p - a, p - b
    cross = np.cross(r1, r2)
    c2 = np.sum(cross**2, axis=-1)
    n1, n2 = np.linalg.norm(r1, axis=-1), np.linalg.norm(r2, axis=-1)
    k = np.sum(r0 * (r1 / n1[..., None] - r2 / n2[..., None]), axis=-1) / np.where(c2 > 1e-12, c2, np.inf)
    return cross[..., 2] * k / (4 * np.pi)


def weissinger(
    area: float, aspect_ratio: float, taper: float, sweep_quarter_chord: float, mach: float = 0.0, panels: int = 80
):
    """Additional span load (per unit angle of attack, shape only) of a swept tapered wing by Weissinger's
    three-quarter-chord method: one horseshoe vortex per spanwise panel bound on the quarter-chord line, trailing
    legs streamwise, flow tangency at the panel's three-quarter-chord point (Bertin & Cummings §7.5; Katz & Plotkin,
    *Low-Speed Aerodynamics*, 2nd ed., §12.2). Compressibility by the Prandtl–Glauert–Göthert rule: the
    incompressible solution of the wing stretched streamwise by 1/√(1 − M²) (Katz & Plotkin §12.5 / Anderson,
    *Modern Compressible Flow*, §9.4), whose span-load shape is the compressible wing's. Returns (y of the right half's
    panel centres, circulation)."""
    s, _, c = planform(area, aspect_ratio, taper)
    beta = np.sqrt(1.0 - mach**2)
    edges = np.linspace(-s, s, 2 * panels + 1)
    ya, yb = edges[:-1], edges[1:]
    xq = lambda y: np.abs(y) * np.tan(sweep_quarter_chord) / beta  # noqa: E731 - quarter-chord line, stretched
    ym = 0.5 * (ya + yb)
    cp = np.stack([xq(ym) + 0.5 * c(np.abs(ym)) / beta, ym, np.zeros_like(ym)], axis=1)
    far = 1e4 * s
    A = np.stack([xq(ya), ya, 0 * ya], axis=1)
    B = np.stack([xq(yb), yb, 0 * yb], axis=1)
    Af, Bf = A + [far, 0, 0], B + [far, 0, 0]
    P = cp[:, None, :]
    w = _segment_w(P, Af[None], A[None]) + _segment_w(P, A[None], B[None]) + _segment_w(P, B[None], Bf[None])
    gamma = np.linalg.solve(w, -np.ones(len(ym)))  # w Γ = −V∞ α per unit V∞ α
    right = ym > 0
    return ym[right], gamma[right]
