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
_BLOCK_PAIRS = 1 << 14  # target×source pairs per block: temporaries of 128 kB stay in cache


def _leg_factor(dx, dist_sq, ryz_sq, rc4):
    """(dx/|d| − 1)/√(ryz⁴ + r_c⁴) of a semi-infinite leg along +x, computed in place in ``dx``."""
    np.sqrt(dist_sq, out=dist_sq)
    np.maximum(dist_sq, 1e-300, out=dist_sq)
    dx /= dist_sq
    dx -= 1.0
    ryz_sq *= ryz_sq
    ryz_sq += rc4
    np.sqrt(ryz_sq, out=ryz_sq)
    dx /= ryz_sq
    return dx


def _block(px, py, pz, ax, ay, az, bx, by, bz, rc4, bound=True):
    """Unscaled (×4π) velocity components of unit horseshoes at a block of points.

    ``px`` … are (m, 1) point coordinates, ``ax`` … (1, n) segment ends already stretched, ``rc4``
    the (m, n) or (1, n) fourth power of the core radius. ``bound=False``: bound segment only (for
    removing a vortex's own bound leg at its midpoint)."""
    ax = ax - px
    ay = ay - py
    az = az - pz
    bx = bx - px
    by = by - py
    bz = bz - pz
    ryz_a = ay * ay
    ryz_a += az * az
    ryz_b = by * by
    ryz_b += bz * bz
    asq = ax * ax
    asq += ryz_a
    bsq = bx * bx
    bsq += ryz_b
    # bound segment A→B (Leishman core)
    cx = ay * bz
    cx -= az * by
    cy = az * bx
    cy -= ax * bz
    cz = ax * by
    cz -= ay * bx
    adb = ax * bx
    adb += ay * by
    adb += az * bz
    alsq = asq + bsq
    alsq -= 2.0 * adb
    alsq *= alsq
    alsq *= rc4
    den = cx * cx
    den += cy * cy
    den += cz * cz
    den *= den
    den += alsq
    np.sqrt(den, out=den)
    ta = asq * asq
    ta += rc4
    np.sqrt(ta, out=ta)
    np.sqrt(ta, out=ta)
    tb = bsq * bsq
    tb += rc4
    np.sqrt(tb, out=tb)
    np.sqrt(tb, out=tb)
    t = bsq - adb
    t /= tb
    adb -= asq
    adb /= ta
    t -= adb
    t /= den
    cx *= t
    cy *= t
    cz *= t
    if not bound:
        return cx, cy, cz
    # semi-infinite legs along +x: from infinity into A, from B out to infinity
    ax = _leg_factor(ax, asq, ryz_a, rc4)
    bx = _leg_factor(bx, bsq, ryz_b, rc4)  # = −(factor of the leg leaving B)
    az *= ax
    cy += az
    bz *= bx
    cy -= bz
    ay *= ax
    cz -= ay
    by *= bx
    cz += by
    return cx, cy, cz


def horseshoe_velocity(
    points: np.ndarray,
    rv1: np.ndarray,
    rv2: np.ndarray,
    core4,
    beta: float = 1.0,
    *,
    normals: np.ndarray | None = None,
    own_vortex: np.ndarray | None = None,
    out_rhs: np.ndarray | None = None,
) -> np.ndarray:
    """Velocity at ``points`` (M, 3) induced by unit-strength horseshoes (N) with bound legs
    ``rv1``→``rv2`` (N, 3).

    ``core4(rows)`` returns the fourth powers of the core radii (len(rows), N) (or broadcastable)
    for the given target rows. Returns (3, M, N) velocities, or the (M, N) normal-wash matrix if
    ``normals`` (M, 3) is given. ``own_vortex`` (M,) names, for each point, the vortex whose bound
    segment is dropped there (the point is that segment's midpoint, where it induces nothing). If ``out_rhs`` (N, K) is given, the
    (3, M, K) product of the velocity matrix with it is returned."""
    m, n = points.shape[0], rv1.shape[0]
    inv_beta = 1.0 / beta
    ax, ay, az = (rv1[:, 0] * inv_beta)[None], rv1[:, 1][None], rv1[:, 2][None]
    bx, by, bz = (rv2[:, 0] * inv_beta)[None], rv2[:, 1][None], rv2[:, 2][None]
    p = points.copy()
    p[:, 0] *= inv_beta
    if normals is not None:  # fold 1/4π and the u-scaling 1/β into the normals
        normals = normals * (_FOUR_PI_INV * np.array([inv_beta, 1.0, 1.0]))
    rows = max(1, _BLOCK_PAIRS // max(n, 1))
    result = np.empty((m, n)) if normals is not None else np.empty((3, m, n))
    for start in range(0, m, rows):
        sl = slice(start, min(m, start + rows))
        u, v, w = _block(p[sl, 0:1], p[sl, 1:2], p[sl, 2:3], ax, ay, az, bx, by, bz, core4(sl))
        if normals is not None:
            nb = normals[sl]
            u *= nb[:, 0:1]
            v *= nb[:, 1:2]
            w *= nb[:, 2:3]
            u += v
            u += w
            result[sl] = u
        else:
            u *= inv_beta
            result[0, sl], result[1, sl], result[2, sl] = u, v, w
    if own_vortex is not None:
        k = np.arange(m)
        j = np.asarray(own_vortex)
        rc4 = np.broadcast_to(core4(slice(0, m)), (m, n))[k, j]
        own = _block(p[k, 0], p[k, 1], p[k, 2], ax[0, j], ay[0, j], az[0, j], bx[0, j], by[0, j], bz[0, j], rc4, bound=False)
        if normals is not None:
            result[k, j] -= normals[k, 0] * own[0] + normals[k, 1] * own[1] + normals[k, 2] * own[2]
        else:
            result[0, k, j] -= own[0] * inv_beta
            result[1, k, j] -= own[1]
            result[2, k, j] -= own[2]
    if normals is not None:
        return result
    if out_rhs is not None:
        return result @ (out_rhs * _FOUR_PI_INV)
    result *= _FOUR_PI_INV
    return result
