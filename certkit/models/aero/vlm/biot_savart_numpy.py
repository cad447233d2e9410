"""The Biot–Savart sums of :mod:`certkit.models.aero.vlm.biot_savart` in plain numpy, for processes that have not
loaded numba (importing it and its cached kernels costs more than a small lattice: ``certkit derivatives FILE.avl``).

Each function is :mod:`certkit.models.aero.vlm.biot_savart_kernels`'s loop over blocks of points, with the same pair
arithmetic (:mod:`~certkit.models.aero.vlm.biot_savart_pair`) and the same sums, so the two give the same bits
(tests/aero/test_vlm_startup_paths.py).
"""

from __future__ import annotations

import numpy as np

from .biot_savart_pair import pair as _pair

#: pairs per block: 400 kB per temporary, the working set stays in cache (50,000 pairs: 60 ms for 400 × 800, 250,000:
#: 90 ms)
_BLOCK_PAIRS = 50_000


def _blocks(m: int, n: int):
    step = max(1, _BLOCK_PAIRS // max(n, 1))
    for lo in range(0, m, step):
        yield slice(lo, min(m, lo + step))


def _own(px, py, pz, ax, ay, az, bx, by, bz, rc4, own_vortex):
    """The pair of each point with its own vortex (points without one: index −1, left out)."""
    i = np.flatnonzero(own_vortex >= 0)
    j = own_vortex[i]
    r = rc4[i, j] if rc4.shape[0] > 1 else rc4[0, j]
    with np.errstate(all="ignore"):
        return i, j, _pair(px[i], py[i], pz[i], ax[j], ay[j], az[j], bx[j], by[j], bz[j], r)


def normalwash(px, py, pz, ax, ay, az, bx, by, bz, rc4, nx, ny, nz, own_vortex, out):
    """As :func:`certkit.models.aero.vlm.biot_savart_kernels._normalwash`."""
    m, n = out.shape
    for b in _blocks(m, n):
        r = rc4[b] if rc4.shape[0] > 1 else rc4[0][None, :]
        with np.errstate(all="ignore"):
            cx, cy, cz, vy, vz = _pair(px[b, None], py[b, None], pz[b, None], ax, ay, az, bx, by, bz, r)
        out[b] = cx * nx[b, None] + vy * ny[b, None] + vz * nz[b, None]
    i, j, (cx, cy, cz, _, _) = _own(px, py, pz, ax, ay, az, bx, by, bz, rc4, own_vortex)
    out[i, j] -= nx[i] * cx + ny[i] * cy + nz[i] * cz


def velocity(px, py, pz, ax, ay, az, bx, by, bz, rc4, inv_beta, own_vortex, out):
    """As :func:`certkit.models.aero.vlm.biot_savart_kernels._velocity`."""
    m, n = out.shape[1], out.shape[2]
    for b in _blocks(m, n):
        r = rc4[b] if rc4.shape[0] > 1 else rc4[0][None, :]
        with np.errstate(all="ignore"):
            cx, cy, cz, vy, vz = _pair(px[b, None], py[b, None], pz[b, None], ax, ay, az, bx, by, bz, r)
        out[0, b] = cx * inv_beta
        out[1, b] = vy
        out[2, b] = vz
    i, j, (cx, cy, cz, _, _) = _own(px, py, pz, ax, ay, az, bx, by, bz, rc4, own_vortex)
    out[0, i, j] -= cx * inv_beta
    out[1, i, j] -= cy
    out[2, i, j] -= cz
