"""Velocity induced by horseshoe vortices (Biot–Savart law) over all point–vortex pairs.

A horseshoe is a bound segment A→B plus two semi-infinite legs along +X from A and B (Katz &
Plotkin, *Low-Speed Aerodynamics*, 2nd ed., §10.4.5; the AVL horseshoe with legs parallel to the X
axis). Compressibility enters by the Prandtl–Glauert stretch x → x/β of all coordinates and u → u/β
(Drela, AVL). Each segment carries a finite core r_c, Leishman's r⁴ variant of the Scully
(Burnham–Hallock) model used by AVL 3.4+: the velocity of a line vortex at distance r becomes
∝ r/√(r⁴ + r_c⁴), which keeps every entry finite for coincident or collinear points.

The pairs are evaluated one at a time in a loop compiled with numba (cached on disk after the first
use): no N×M temporaries.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

_FOUR_PI_INV = 1.0 / (4.0 * np.pi)


@njit(cache=True, error_model="numpy", inline="always")
def _pair(px, py, pz, ax, ay, az, bx, by, bz, rc4):
    """Unscaled (×4π) velocity of a unit horseshoe at one point: the bound segment's part (u, v, w)
    and the full velocity's v and w (the legs along +x add nothing to u).

    ``p`` the point and ``a``, ``b`` the segment ends, x already stretched; ``rc4`` the fourth power
    of the core radius."""
    ax -= px
    ay -= py
    az -= pz
    bx -= px
    by -= py
    bz -= pz
    ryz_a = ay * ay + az * az
    ryz_b = by * by + bz * bz
    asq = ax * ax + ryz_a
    bsq = bx * bx + ryz_b
    # bound segment A→B (Leishman core)
    cx = ay * bz - az * by
    cy = az * bx - ax * bz
    cz = ax * by - ay * bx
    adb = ax * bx + ay * by + az * bz
    alsq = asq + bsq - 2.0 * adb
    alsq = alsq * alsq * rc4
    den = cx * cx + cy * cy + cz * cz
    den = math.sqrt(den * den + alsq)
    ta = math.sqrt(math.sqrt(asq * asq + rc4))
    tb = math.sqrt(math.sqrt(bsq * bsq + rc4))
    t = ((bsq - adb) / tb - (adb - asq) / ta) / den
    cx *= t
    cy *= t
    cz *= t
    # semi-infinite legs along +x: from infinity into A, from B out to infinity
    fa = (ax / max(math.sqrt(asq), 1e-300) - 1.0) / math.sqrt(ryz_a * ryz_a + rc4)
    fb = (bx / max(math.sqrt(bsq), 1e-300) - 1.0) / math.sqrt(ryz_b * ryz_b + rc4)  # = −(factor of the leg leaving B)
    vy = cy + az * fa - bz * fb
    vz = cz - ay * fa + by * fb
    return cx, cy, cz, vy, vz


@njit(cache=True, error_model="numpy")
def _normalwash(px, py, pz, ax, ay, az, bx, by, bz, rc4, nx, ny, nz, own_vortex, out):
    """out[i, j] = (velocity of horseshoe j at point i) · normal i (normals scaled by the caller).

    Coordinates come as separate contiguous arrays (points ``p*`` (M,), segment ends ``a*``, ``b*``
    (N,)) so that the inner loop runs on SIMD registers; ``rc4`` is (M, N) or (1, N)."""
    m, n = out.shape
    full_rc4 = rc4.shape[0] > 1
    for i in range(m):
        r = rc4[i] if full_rc4 else rc4[0]
        x, y, z, n0, n1, n2 = px[i], py[i], pz[i], nx[i], ny[i], nz[i]
        row = out[i]
        for j in range(n):
            cx, cy, cz, vy, vz = _pair(x, y, z, ax[j], ay[j], az[j], bx[j], by[j], bz[j], r[j])
            row[j] = cx * n0 + vy * n1 + vz * n2
        j = own_vortex[i]
        if j >= 0:  # drop the vortex's own bound segment
            cx, cy, cz, vy, vz = _pair(x, y, z, ax[j], ay[j], az[j], bx[j], by[j], bz[j], r[j])
            row[j] -= n0 * cx + n1 * cy + n2 * cz


@njit(cache=True, error_model="numpy")
def _velocity(px, py, pz, ax, ay, az, bx, by, bz, rc4, inv_beta, own_vortex, out):
    """out[:, i, j] = velocity (×4π) of horseshoe j at point i, u scaled by 1/β (arguments as
    :func:`_normalwash`)."""
    m, n = out.shape[1], out.shape[2]
    full_rc4 = rc4.shape[0] > 1
    for i in range(m):
        r = rc4[i] if full_rc4 else rc4[0]
        x, y, z = px[i], py[i], pz[i]
        u_row, v_row, w_row = out[0, i], out[1, i], out[2, i]
        for j in range(n):
            cx, cy, cz, vy, vz = _pair(x, y, z, ax[j], ay[j], az[j], bx[j], by[j], bz[j], r[j])
            u_row[j] = cx * inv_beta
            v_row[j] = vy
            w_row[j] = vz
        j = own_vortex[i]
        if j >= 0:  # drop the vortex's own bound segment
            cx, cy, cz, vy, vz = _pair(x, y, z, ax[j], ay[j], az[j], bx[j], by[j], bz[j], r[j])
            u_row[j] -= cx * inv_beta
            v_row[j] -= cy
            w_row[j] -= cz


def horseshoe_velocity(
    points: np.ndarray,
    rv1: np.ndarray,
    rv2: np.ndarray,
    core4: np.ndarray,
    beta: float = 1.0,
    *,
    normals: np.ndarray | None = None,
    own_vortex: np.ndarray | None = None,
    out_rhs: np.ndarray | None = None,
) -> np.ndarray:
    """Velocity at ``points`` (M, 3) induced by unit-strength horseshoes (N) with bound legs
    ``rv1``→``rv2`` (N, 3).

    ``core4`` holds the fourth powers of the core radii, (M, N) or (1, N) for every point alike.
    Returns (3, M, N) velocities, or the (M, N) normal-wash matrix if ``normals`` (M, 3) is given.
    ``own_vortex`` (M,) names, for each point, the vortex whose bound segment is dropped there (the
    point is that segment's midpoint, where it induces nothing). If ``out_rhs`` (N, K) is given, the
    (3, M, K) product of the velocity matrix with it is returned."""
    m, n = points.shape[0], rv1.shape[0]
    inv_beta = 1.0 / beta
    stretch = np.array([inv_beta, 1.0, 1.0])
    columns = lambda v: tuple(np.ascontiguousarray(c) for c in v.T)  # noqa: E731
    coords = columns(points * stretch) + columns(rv1 * stretch) + columns(rv2 * stretch)
    rc4 = np.ascontiguousarray(np.atleast_2d(np.asarray(core4, dtype=float)))
    if rc4.shape[1] != n or rc4.shape[0] not in (1, m):
        raise ValueError(f"core4 has shape {rc4.shape}; expected ({m}, {n}) or (1, {n})")
    own = np.full(m, -1, dtype=np.int64) if own_vortex is None else np.ascontiguousarray(own_vortex, dtype=np.int64)
    if normals is not None:  # fold 1/4π and the u-scaling 1/β into the normals
        result = np.empty((m, n))
        _normalwash(*coords, rc4, *columns(normals * (_FOUR_PI_INV * stretch)), own, result)
        return result
    result = np.empty((3, m, n))
    _velocity(*coords, rc4, inv_beta, own, result)
    if out_rhs is not None:
        return result @ (out_rhs * _FOUR_PI_INV)
    result *= _FOUR_PI_INV
    return result
