"""Velocity induced by horseshoe vortices (Biot–Savart law) over all point–vortex pairs.

A horseshoe is a bound segment A→B plus two semi-infinite legs along +X from A and B (Katz &
Plotkin, *Low-Speed Aerodynamics*, 2nd ed., §10.4.5; the AVL horseshoe with legs parallel to the X
axis). Compressibility enters by the Prandtl–Glauert stretch x → x/β of all coordinates and u → u/β
(Drela, AVL). Each segment carries a finite core r_c, Leishman's r⁴ variant of the Scully
(Burnham–Hallock) model used by AVL 3.4+: the velocity of a line vortex at distance r becomes
∝ r/√(r⁴ + r_c⁴), which keeps every entry finite for coincident or collinear points.

Two implementations of the same arithmetic give the same bits: loops compiled with numba
(:mod:`~certkit.models.aero.vlm.biot_savart_kernels`), used once numba is loaded or for large lattices, and numpy
blocks (:mod:`~certkit.models.aero.vlm.biot_savart_numpy`), which spare a short process (``certkit derivatives
FILE.avl``) numba's import and kernel loading.
"""

from __future__ import annotations

import sys

import numpy as np

from . import biot_savart_numpy

_FOUR_PI_INV = 1.0 / (4.0 * np.pi)
#: point–vortex pairs above which the compiled loops are worth loading numba for (numpy: ~25 ns a pair; numba's
#: import and cached kernels ~0.3 s)
COMPILED_ABOVE_PAIRS = 5_000_000


def _kernels(pairs: int):
    """The compiled kernels when numba is already loaded or the sum is large, else the numpy blocks."""
    if "numba" in sys.modules or pairs > COMPILED_ABOVE_PAIRS:
        from . import biot_savart_kernels as k  # deferred: numba only when already loaded or the lattice is large

        return k._normalwash, k._velocity
    return biot_savart_numpy.normalwash, biot_savart_numpy.velocity


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
    normalwash, velocity = _kernels(m * n)
    if normals is not None:  # fold 1/4π and the u-scaling 1/β into the normals
        result = np.empty((m, n))
        normalwash(*coords, rc4, *columns(normals * (_FOUR_PI_INV * stretch)), own, result)
        return result
    result = np.empty((3, m, n))
    velocity(*coords, rc4, inv_beta, own, result)
    if out_rhs is not None:
        return result @ (out_rhs * _FOUR_PI_INV)
    result *= _FOUR_PI_INV
    return result
