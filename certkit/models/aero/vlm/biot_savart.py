"""Velocity induced by horseshoe vortices (Biot–Savart law), vectorised over all point–vortex pairs.

A horseshoe is a bound segment A→B plus two semi-infinite legs along +X from A and B (Katz &
Plotkin, *Low-Speed Aerodynamics*, 2nd ed., §10.4.5; the AVL horseshoe with legs parallel to the X
axis). Compressibility enters by the Prandtl–Glauert stretch x → x/β of all coordinates and u → u/β
(Drela, AVL). Each segment carries a finite core r_c, Leishman's r⁴ variant of the Scully
(Burnham–Hallock) model used by AVL 3.4+: the velocity of a line vortex at distance r becomes
∝ r/√(r⁴ + r_c⁴), which keeps every entry finite for coincident or collinear points.

The pairs are evaluated in blocks of target points so that the temporaries stay in cache.
"""

from __future__ import annotations

import numpy as np

_FOUR_PI_INV = 1.0 / (4.0 * np.pi)
_BLOCK_PAIRS = 1 << 15  # target×source pairs per block: temporaries of 256 kB each


def _block(px, py, pz, ax, ay, az, bx, by, bz, rc4, bound_mask):
    """Unscaled (×4π) velocity components of unit horseshoes at a block of points.

    ``px`` … are (m, 1) point coordinates, ``ax`` … (1, n) segment ends already stretched, ``rc4``
    the (m, n) or (1, n) fourth power of the core radius, ``bound_mask`` None or a (m, n) 0/1 factor on the
    bound segment."""
    ax = ax - px
    ay = ay - py
    az = az - pz
    bx = bx - px
    by = by - py
    bz = bz - pz
    ryz_a = ay * ay + az * az
    ryz_b = by * by + bz * bz
    asq = ax * ax + ryz_a
    bsq = bx * bx + ryz_b
    amag = np.sqrt(asq)
    bmag = np.sqrt(bsq)
    # bound segment A→B
    cx = ay * bz - az * by
    cy = az * bx - ax * bz
    cz = ax * by - ay * bx
    adb = ax * bx + ay * by + az * bz
    alsq = asq + bsq - 2.0 * adb
    cc = cx * cx + cy * cy + cz * cz
    t = ((bsq - adb) / np.sqrt(np.sqrt(bsq * bsq + rc4)) + (asq - adb) / np.sqrt(np.sqrt(asq * asq + rc4))) / np.sqrt(cc * cc + alsq * alsq * rc4)
    if bound_mask is not None:
        t *= bound_mask
    u = cx * t
    v = cy * t
    w = cz * t
    # semi-infinite legs along +x: from infinity into A, from B out to infinity
    ta = (ax / np.maximum(amag, 1e-300) - 1.0) / np.sqrt(ryz_a * ryz_a + rc4)
    tb = (1.0 - bx / np.maximum(bmag, 1e-300)) / np.sqrt(ryz_b * ryz_b + rc4)
    v += az * ta + bz * tb
    w -= ay * ta + by * tb
    return u, v, w


def horseshoe_velocity(
    points: np.ndarray,
    rv1: np.ndarray,
    rv2: np.ndarray,
    core4,
    beta: float = 1.0,
    *,
    normals: np.ndarray | None = None,
    skip_own_bound: bool = False,
    out_rhs: np.ndarray | None = None,
) -> np.ndarray:
    """Velocity at ``points`` (M, 3) induced by unit-strength horseshoes (N) with bound legs
    ``rv1``→``rv2`` (N, 3).

    ``core4(rows)`` returns the fourth powers of the core radii (len(rows), N) (or broadcastable) for the given
    target rows. Returns (3, M, N) velocities, or the (M, N) normal-wash matrix if ``normals``
    (M, 3) is given. ``skip_own_bound`` drops the bound segment of vortex i at point i (its own
    midpoint, where that segment induces nothing). If ``out_rhs`` (N, K) is given, the (3, M, K)
    product of the velocity matrix with it is returned instead, without storing the matrix."""
    m, n = points.shape[0], rv1.shape[0]
    inv_beta = 1.0 / beta
    ax, ay, az = (rv1[:, 0] * inv_beta)[None], rv1[:, 1][None], rv1[:, 2][None]
    bx, by, bz = (rv2[:, 0] * inv_beta)[None], rv2[:, 1][None], rv2[:, 2][None]
    p = points.copy()
    p[:, 0] *= inv_beta
    rows = max(1, _BLOCK_PAIRS // max(n, 1))
    if out_rhs is not None:
        result = np.empty((3, m, out_rhs.shape[1]))
    elif normals is not None:
        result = np.empty((m, n))
    else:
        result = np.empty((3, m, n))
    for start in range(0, m, rows):
        stop = min(m, start + rows)
        sl = slice(start, stop)
        mask = None
        if skip_own_bound:
            mask = np.ones((stop - start, n))
            idx = np.arange(start, stop)
            own = idx < n
            mask[idx[own] - start, idx[own]] = 0.0
        u, v, w = _block(p[sl, 0:1], p[sl, 1:2], p[sl, 2:3], ax, ay, az, bx, by, bz, core4(sl), mask)
        u *= inv_beta
        if out_rhs is not None:
            result[0, sl] = u @ out_rhs
            result[1, sl] = v @ out_rhs
            result[2, sl] = w @ out_rhs
        elif normals is not None:
            nb = normals[sl]
            result[sl] = nb[:, 0:1] * u + nb[:, 1:2] * v + nb[:, 2:3] * w
        else:
            result[0, sl], result[1, sl], result[2, sl] = u, v, w
    result *= _FOUR_PI_INV
    return result
