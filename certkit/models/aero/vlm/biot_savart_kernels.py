"""The Biot–Savart loops of :mod:`certkit.models.aero.vlm.biot_savart` compiled with numba (cached on disk after the
first use): the pairs one at a time, no N×M temporaries. :mod:`certkit.models.aero.vlm.biot_savart_numpy` does the
same arithmetic, operation for operation, on numpy blocks.
"""

from __future__ import annotations

from numba import njit

from .biot_savart_pair import pair

#: one point–horseshoe pair (:func:`certkit.models.aero.vlm.biot_savart_pair.pair`), compiled and inlined
_pair = njit(cache=True, error_model="numpy", inline="always")(pair)


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
