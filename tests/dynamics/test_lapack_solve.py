"""The compiled Newton iteration of the trims solves its steps with :func:`certkit.models.compiled.lapack_solve`
(LAPACK's dgesv, called as numba's ``np.linalg.solve`` calls it). Reference: ``numpy.linalg.solve`` (numpy's own
LAPACK build) on the same systems — random and badly scaled, of the trims' sizes — bit for bit (tolerance zero); a
singular matrix must be reported by LAPACK's info, not solved."""

import numpy as np
from numba import njit

from certkit.models.compiled import LAPACK_INT, lapack_solve


@njit(cache=False)
def _solve_each(J, r):
    n, k = r.shape
    out, info = np.empty_like(r), np.empty(n, dtype=np.int64)
    lu, pivots = np.empty((k, k)), np.empty(k, dtype=LAPACK_INT)
    for a in range(n):
        info[a] = lapack_solve(J[a], r[a], lu, out[a], pivots)
    return out, info


def test_lapack_solve_is_numpys_solve_bit_for_bit():
    rng = np.random.default_rng(11)
    for k in (2, 4, 6):
        for scale in (1e-6, 1.0, 1e4):  # columns scaled over six decades: pivoting matters
            J = rng.standard_normal((3000, k, k)) * scale * 10.0 ** rng.uniform(-3, 3, (3000, 1, k))
            r = rng.standard_normal((3000, k))
            x, info = _solve_each(J, r)
            assert (info == 0).all()
            ref = np.linalg.solve(J, r[:, :, None])[:, :, 0]
            np.testing.assert_array_equal(x.view(np.int64), ref.view(np.int64))  # the same bits, signed zeros too


def test_a_singular_matrix_is_reported_not_solved():
    J = np.array([[[1.0, 2.0, 0.0], [2.0, 4.0, 0.0], [0.0, 0.0, 1.0]], np.eye(3)])  # rows 1 and 2 dependent
    _, info = _solve_each(J, np.ones((2, 3)))
    assert info[0] > 0 and info[1] == 0
