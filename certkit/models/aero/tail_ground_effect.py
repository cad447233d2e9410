"""Ground effect on the downwash at the horizontal tail: the image of the wing's vortex system.

Method. The runway is a plane of symmetry, so the wing's bound and trailing vortices have a mirror image below it,
of opposite circulation, whose upwash at the tail cancels part of the wing's downwash there (Katzoff & Sweberg,
*Ground effect on downwash angles and wake location*, NACA Report 738, 1942). Near the runway the image also changes
the wing's span load, so the load is solved with the image present: Weissinger's lifting-surface approximation
(one horseshoe per spanwise strip, bound leg on the quarter-chord line, flow tangency at the three-quarter chord;
Weissinger, NACA TM 1120, 1947), :data:`N_WING` cosine-spaced strips on the declared quarter-chord line (sweep,
dihedral, taper), trailing legs running aft parallel to the runway (a flat wake: the tail of a transport is less
than a span behind the wing). The downwash is the Biot–Savart sum of the segments (Katz & Plotkin, *Low-Speed
Aerodynamics*, 2nd ed., §10.4.5, with a vortex core of :data:`CORE_FRACTION` × span so that the tail may cross the
wake), taken on the tail's quarter-chord line and averaged with the weight √(1 − η²) (lifting-line theory: a
surface's lift responds to a spanwise-varying angle through the first term of its Glauert series, exactly so for an
elliptic planform).

What the equations of motion need is the downwash at the tail **per unit wing lift**, relative to its free-air value:

    R(h_w, Δz) = [ε/C_L,w](ground) / [ε/C_L,w](free air)            (:func:`downwash_ratio`)

with h_w the height of the wing's reference point (its MAC quarter chord) above the runway and Δz = h_t − h_w the
tail's reference point above it (the attitude moves the tail up and down through the wake). The flight model's
own lift ratio λ in ground effect (:mod:`certkit.models.aero.ground_effect`) carries the lift, so the downwash in
ground effect is ε = R λ ε_free, ε_free from the vortex lattice (:mod:`certkit.models.aero.tail_downwash`). R is
tabulated once per geometry (:func:`downwash_table`) on √(h_w/b) and Δz, and interpolated in the compiled
equations of motion below the height where the wing's ground effect ends; far from the runway R → 1 (as 1/h²).

Checks (tests/aero/test_tail_ground_effect.py): one horseshoe against its closed form; the far wake of an elliptic
load against the Trefftz-plane (Munk flat-plate) closed form, with and without the image; no flow through the
runway; the 1/h² far-field decay; AVL 3.52 (optvl) with its ground plane on the baseline's wing and tail.

Not modelled: the wake's upward displacement near the ground and its descent and roll-up between the wing and the
tail (Katzoff & Sweberg treat both), the flaps' own span load (the table is for the clean wing's load, the flap
increment's downwash is scaled by the same R), the change of the tail's own lift slope near the runway,
compressibility (the table is incompressible: near the runway M ≤ 0.3), and the attitude's effect on the geometry
beyond the tail's height over the wing.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numba import njit

from certkit.models.aero import planform

#: strips of the wing's load, tail stations
N_WING, N_TAIL = 40, 12
#: vortex core radius over the wing span (about a wing strip's width at the root)
CORE_FRACTION = 0.01
#: the table: √(h_w/b) from its lowest row to √(h/b max) in N_HEIGHT points (0.004 from a table 1.5 times as fine in
#: both and with 16 tail stations, on the baseline); Δz in steps of DZ_STEP (m) over the tail heights
#: of the attitudes ATTITUDE_RANGE (beyond them it is held at its ends)
N_HEIGHT, DZ_STEP = 24, 0.75
ATTITUDE_RANGE = (np.radians(-10.0), np.radians(25.0))


@dataclass(frozen=True)
class LiftingLine:
    """A surface's quarter-chord line: root point (x, z) on the plane of symmetry, tip point (x, y, z), root and tip
    chords, and its reference point (MAC quarter chord, x and z) for heights; airplane frame (X aft, Y right, Z up,
    m)."""

    root: tuple[float, float]
    tip: tuple[float, float, float]
    chords: tuple[float, float]
    reference: tuple[float, float]

    def points(self, eta) -> np.ndarray:
        """Points (n, 3) of the quarter-chord line at η = 2y/b ∈ [−1, 1]."""
        (x0, z0), (xt, yt, zt) = self.root, self.tip
        a = np.abs(eta)
        return np.stack([x0 + a * (xt - x0), eta * yt, z0 + a * (zt - z0)], axis=-1)

    def chord(self, eta) -> np.ndarray:
        return self.chords[0] + np.abs(eta) * (self.chords[1] - self.chords[0])


def lifting_line(surface) -> LiftingLine:
    """The quarter-chord line of an aircraft-file lifting surface (trapezoidal half, root at y = 0) and its MAC
    quarter-chord point (DATCOM §1.2.2 station, dihedral included)."""
    semi = float(planform.span(surface.area, surface.aspect_ratio)) / 2.0
    cr = float(planform.root_chord(surface.area, surface.aspect_ratio, surface.taper))
    le = surface.root_leading_edge
    x0 = le.x + 0.25 * cr
    t_sweep, t_dih = float(np.tan(surface.sweep_quarter_chord)), float(np.tan(surface.dihedral))
    y_mac = float(planform.mac_spanwise_position(surface.area, surface.aspect_ratio, surface.taper))
    return LiftingLine(
        (x0, le.z),
        (x0 + semi * t_sweep, semi, le.z + semi * t_dih),
        (cr, cr * surface.taper),
        (x0 + y_mac * t_sweep, le.z + y_mac * t_dih),
    )


def induced_upwash(points, a, b, core) -> np.ndarray:
    """Upward velocity (..., n), times 4π, induced at ``points`` (..., 3) by each of n horseshoe vortices of unit
    circulation: bound leg ``a`` → ``b`` (n, 3), legs from +X infinity into ``a`` and from ``b`` out to +X infinity;
    Biot–Savart (Katz & Plotkin §10.4.5) with a core of radius ``core`` (|r₁ × r₂|² + core² |r₀|²)."""
    p = np.asarray(points, dtype=float)
    flat = np.ascontiguousarray(p.reshape(-1, 3))
    out = _upwash(flat, np.ascontiguousarray(a, dtype=float), np.ascontiguousarray(b, dtype=float), float(core))
    return out.reshape(p.shape[:-1] + (len(a),))


@njit(cache=True, error_model="numpy", fastmath=True)
def _upwash(p, a, b, core):
    """:func:`induced_upwash` on flat arrays: p (m, 3), a and b (n, 3)."""
    m, n = p.shape[0], a.shape[0]
    out = np.empty((m, n))
    c2 = core * core
    for i in range(m):
        for k in range(n):
            r1x, r1y, r1z = p[i, 0] - a[k, 0], p[i, 1] - a[k, 1], p[i, 2] - a[k, 2]
            r2x, r2y, r2z = p[i, 0] - b[k, 0], p[i, 1] - b[k, 1], p[i, 2] - b[k, 2]
            r0x, r0y, r0z = b[k, 0] - a[k, 0], b[k, 1] - a[k, 1], b[k, 2] - a[k, 2]
            cx = r1y * r2z - r1z * r2y
            cy = r1z * r2x - r1x * r2z
            cz = r1x * r2y - r1y * r2x
            n1 = np.sqrt(r1x * r1x + r1y * r1y + r1z * r1z)
            n2 = np.sqrt(r2x * r2x + r2y * r2y + r2z * r2z)
            dot = r0x * (r1x / n1 - r2x / n2) + r0y * (r1y / n1 - r2y / n2) + r0z * (r1z / n1 - r2z / n2)
            bound = cz * dot / (cx * cx + cy * cy + cz * cz + c2 * (r0x * r0x + r0y * r0y + r0z * r0z))
            # semi-infinite legs along +X: (e × r)_z (1 + e·r/|r|)/|e × r|², into a (reversed) and out of b
            leg_a = r1y * (1.0 + r1x / n1) / (r1y * r1y + r1z * r1z + c2)
            leg_b = r2y * (1.0 + r2x / n2) / (r2y * r2y + r2z * r2z + c2)
            out[i, k] = bound - leg_a + leg_b
    return out


def vertical_velocity(points, a, b, gamma, core) -> np.ndarray:
    """Upward velocity at ``points`` (..., 3), times 4π, of horseshoes (:func:`induced_upwash`) of circulation
    ``gamma`` (n,)."""
    return induced_upwash(points, a, b, core) @ np.asarray(gamma, dtype=float)


def mirror(a, b, gamma, z_plane: float):
    """The image of horseshoes (``a``, ``b``, ``gamma``) in the plane Z = ``z_plane``: mirrored, opposite
    circulation (no flow through the plane)."""
    flip = np.array([1.0, 1.0, -1.0])
    shift = np.array([0.0, 0.0, 2.0 * z_plane])
    return a * flip + shift, b * flip + shift, -np.asarray(gamma)


def wing_horseshoes(wing: LiftingLine, n: int = N_WING):
    """Bound legs (a, b) of ``n`` cosine-spaced strips, their three-quarter-chord control points and widths (m)."""
    eta = np.cos(np.linspace(np.pi, 0.0, n + 1))
    pts = wing.points(eta)
    mid = 0.5 * (eta[1:] + eta[:-1])
    control = wing.points(mid) + np.stack([0.5 * wing.chord(mid), 0 * mid, 0 * mid], axis=-1)
    return pts[:-1], pts[1:], control, np.diff(pts[:, 1])


def span_load(wing: LiftingLine, span: float, ground: float | None = None, n: int = N_WING) -> np.ndarray:
    """Weissinger strip circulations (n,) per unit 4π V α (flow tangency at the control points), with the image in the
    runway plane Z = ``ground`` when given."""
    a, b, control, _ = wing_horseshoes(wing, n)
    aic = induced_upwash(control, a, b, CORE_FRACTION * span)  # (control point, horseshoe)
    if ground is not None:
        ia, ib, _ = mirror(a, b, 1.0, ground)
        aic -= induced_upwash(control, ia, ib, CORE_FRACTION * span)
    return np.linalg.solve(aic, -np.ones(n))


def tail_stations(tail: LiftingLine, n: int = N_TAIL):
    """Tail points (n, 3) at cosine-spaced midpoints and their weights √(1 − η²) dη (sum 1)."""
    th = np.pi * (np.arange(n) + 0.5) / n
    w = np.sin(th) ** 2  # √(1 − η²) dη with η = −cos θ
    return tail.points(-np.cos(th)), w / w.sum()


def mean_downwash(points, weights, a, b, core) -> np.ndarray:
    """Weighted mean downwash (..., n), times 4π, over the tail ``points`` (..., m, 3) of each unit horseshoe."""
    return -np.einsum("...mn,m->...n", induced_upwash(points, a, b, core), weights)


@dataclass(frozen=True)
class DownwashTable:
    """R on √(h_w/b) = ``root_start`` + k ``root_step`` (rows) × Δz = ``dz_start`` + j ``dz_step`` (columns); module
    docstring. The lowest row has the wing's lowest quarter-chord point a quarter of its root chord above the runway
    (the strip model's images would come closer than the chord); below it the table holds."""

    root_start: float
    root_step: float
    dz_start: float
    dz_step: float
    ratio: np.ndarray


@lru_cache(maxsize=16)
def _table(wing: LiftingLine, tail: LiftingLine, span: float, h_over_b_max: float) -> DownwashTable:
    dx = tail.reference[0] - wing.reference[0]
    dz0 = tail.reference[1] - wing.reference[1]
    ends = [dz0 * np.cos(t) - dx * np.sin(t) for t in ATTITUDE_RANGE]  # the airframe pitched about the wing point
    dz = np.arange(min(ends) - 1.0, max(ends) + 1.0 + DZ_STEP, DZ_STEP)
    lowest = wing.reference[1] - min(wing.root[1], wing.tip[2]) + 0.25 * wing.chords[0]
    roots = np.linspace(np.sqrt(lowest / span), np.sqrt(h_over_b_max), N_HEIGHT)
    a, b, _, width = wing_horseshoes(wing)
    pts, w = tail_stations(tail)
    core = CORE_FRACTION * span
    tails = pts[None, :, :] + (dz - dz0)[:, None, None] * np.array([0.0, 0.0, 1.0])  # (Δz, station, 3)
    free_load = span_load(wing, span)
    real = mean_downwash(tails, w, a, b, core)  # (Δz, horseshoe), the wing's own part at every height
    free = real @ free_load / (free_load * width).sum()
    ratio = np.empty((N_HEIGHT, dz.size))
    for k, root in enumerate(roots):
        ground = wing.reference[1] - root**2 * span
        load = span_load(wing, span, ground)
        ia, ib, ig = mirror(a, b, load, ground)
        ground_dw = real @ load + mean_downwash(tails, w, ia, ib, core) @ ig
        ratio[k] = ground_dw / (load * width).sum() / free
        ratio[k, root**2 * span + dz <= 0.0] = 0.0  # a tail on (or below) the runway: no flow through it
    return DownwashTable(float(roots[0]), float(roots[1] - roots[0]), float(dz[0]), DZ_STEP, ratio)


def downwash_table(wing: LiftingLine, tail: LiftingLine, span: float, h_over_b_max: float) -> DownwashTable:
    """R of the wing and tail (:func:`lifting_line`) for wing heights up to ``h_over_b_max`` spans (cached)."""
    return _table(wing, tail, float(span), float(h_over_b_max))


@njit(cache=True, error_model="numpy", fastmath=True, inline="always")
def downwash_ratio_one(h_over_b, dz, ratio, root_start, root_step, dz_start, dz_step):
    """R (module docstring) at the wing's height over the span and the tail's height over the wing (m), bilinear in
    √(h_w/b) and Δz, held at the table's ends."""
    nr, nz = ratio.shape
    u = min(max((np.sqrt(max(h_over_b, 0.0)) - root_start) / root_step, 0.0), nr - 1.000001)
    v = min(max((dz - dz_start) / dz_step, 0.0), nz - 1.000001)
    i, j = int(u), int(v)
    f, g = u - i, v - j
    return (ratio[i, j] * (1.0 - g) + ratio[i, j + 1] * g) * (1.0 - f) + (
        ratio[i + 1, j] * (1.0 - g) + ratio[i + 1, j + 1] * g
    ) * f


def downwash_ratio(table: DownwashTable, h_over_b, dz) -> np.ndarray:
    """:func:`downwash_ratio_one` over arrays (broadcast)."""
    hb, d = np.broadcast_arrays(np.asarray(h_over_b, dtype=float), np.asarray(dz, dtype=float))
    out = np.empty(hb.shape)
    for k in np.ndindex(hb.shape):
        out[k] = downwash_ratio_one(
            hb[k], d[k], table.ratio, table.root_start, table.root_step, table.dz_start, table.dz_step
        )
    return out


__all__ = [
    "LiftingLine",
    "lifting_line",
    "induced_upwash",
    "vertical_velocity",
    "mirror",
    "wing_horseshoes",
    "span_load",
    "tail_stations",
    "mean_downwash",
    "DownwashTable",
    "downwash_table",
    "downwash_ratio",
    "downwash_ratio_one",
]
