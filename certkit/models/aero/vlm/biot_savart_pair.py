"""One point–horseshoe pair of the Biot–Savart sums (:mod:`certkit.models.aero.vlm.biot_savart`), written once for
both implementations: compiled per pair by numba (:mod:`~certkit.models.aero.vlm.biot_savart_kernels`) and applied
to numpy blocks (:mod:`~certkit.models.aero.vlm.biot_savart_numpy`), so the two do the same IEEE operations in the
same order (np.sqrt and np.maximum act on scalars under numba as on arrays under numpy).
"""

from __future__ import annotations

import numpy as np


def pair(px, py, pz, ax, ay, az, bx, by, bz, rc4):
    """Unscaled (×4π) velocity of a unit horseshoe at one point: the bound segment's part (u, v, w)
    and the full velocity's v and w (the legs along +x add nothing to u).

    ``p`` the point and ``a``, ``b`` the segment ends, x already stretched; ``rc4`` the fourth power
    of the core radius (scalars, or arrays broadcasting together)."""
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
    # bound segment A→B (Leishman core)
    cx = ay * bz - az * by
    cy = az * bx - ax * bz
    cz = ax * by - ay * bx
    adb = ax * bx + ay * by + az * bz
    alsq = asq + bsq - 2.0 * adb
    alsq = alsq * alsq * rc4
    den = cx * cx + cy * cy + cz * cz
    den = np.sqrt(den * den + alsq)
    ta = np.sqrt(np.sqrt(asq * asq + rc4))
    tb = np.sqrt(np.sqrt(bsq * bsq + rc4))
    t = ((bsq - adb) / tb - (adb - asq) / ta) / den
    cx = cx * t
    cy = cy * t
    cz = cz * t
    # semi-infinite legs along +x: from infinity into A, from B out to infinity
    fa = (ax / np.maximum(np.sqrt(asq), 1e-300) - 1.0) / np.sqrt(ryz_a * ryz_a + rc4)
    fb = (bx / np.maximum(np.sqrt(bsq), 1e-300) - 1.0) / np.sqrt(
        ryz_b * ryz_b + rc4
    )  # = −(factor of the leg leaving B)
    vy = cy + az * fa - bz * fb
    vz = cz - ay * fa + by * fb
    return cx, cy, cz, vy, vz
