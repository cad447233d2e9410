"""Arrays borrowed by the kernels (:func:`certkit.models.compiled.borrowed`): a view without numba's reference count
reads and writes the caller's data with its shape and strides, and the equations of motion that borrow every array
they are given leave the caller's arrays' reference counts as they found them (nothing kept, nothing released)."""

from __future__ import annotations

import sys

import numpy as np
from numba import njit

from certkit.models.compiled import borrowed
from certkit.models.dynamics import kernel
from certkit.models.dynamics.eom import AircraftModel, euler_state_to_quat_state

from . import b747_etkin as ref


@njit(cache=False)
def _row_sums_twice(a, out):
    """Row sums of ``a`` through row views of the borrowed array, written into the borrowed ``out``, and a second
    borrow of a borrowed array."""
    b, o = borrowed(a), borrowed(out)
    c = borrowed(b)
    for i in range(b.shape[0]):
        row = b[i]
        s = 0.0
        for k in range(row.shape[0]):
            s += row[k] + c[i, k]
        o[i] = s


def test_a_borrowed_array_is_the_callers_data():
    """A strided view (every other column of a Fortran-ordered array) borrowed: the sums are numpy's; the output
    written through the borrowed array lands in the caller's."""
    base = np.asfortranarray(np.arange(60.0).reshape(6, 10) ** 1.5)
    a = base[:, ::2]
    out = np.zeros(6)
    _row_sums_twice(a, out)
    np.testing.assert_array_equal(out, 2.0 * a.sum(axis=1))


def test_the_equations_of_motion_leave_their_arguments_reference_counts_alone():
    """:func:`kernel.derivatives` and :func:`kernel.rk4_step`, called 200 times with the same arrays: every argument's
    reference count as before, the results those of a copy of the inputs (the kernels read the caller's data), and
    the state advanced in place."""
    base, h = ref.build(n=3)
    model = AircraftModel(base.aero, mass=base.mass, cg=base.cg, inertia=base.inertia, n=3)
    x = np.zeros((3, 12))
    x[:, 2] = h
    x[:, 3:6] = [[230.0, 1.0, 8.0], [228.0, -2.0, 12.0], [240.0, 0.0, 9.0]]
    x[:, 6:9] = 0.01
    X = np.ascontiguousarray(euler_state_to_quat_state(x))
    U = np.zeros((3, len(model.control_names)))
    thrust = np.zeros((3, 0))
    coef = np.empty((3, 8))
    args = model._kernel_args
    arrays = [X, U, thrust, coef, *(a for a in args if isinstance(a, np.ndarray))]
    before = [sys.getrefcount(a) for a in arrays]
    rows = np.arange(3)
    first = kernel.derivatives(X, rows, True, U, thrust, coef, *args)
    for _ in range(200):
        again = kernel.derivatives(X, rows, True, U, thrust, coef, *args)
    for a, b in zip(first, again):
        np.testing.assert_array_equal(a, b)
    copied = kernel.derivatives(X.copy(), rows.copy(), True, U.copy(), thrust.copy(), coef.copy(), *args)
    np.testing.assert_array_equal(copied[0], first[0])
    X0 = X.copy()
    active, dts = np.ones(3, dtype=np.bool_), np.full(3, 0.01)
    for _ in range(200):
        kernel.rk4_step(X, first[0], active, dts, U, thrust, coef, *args)
    assert not np.array_equal(X[:, :3], X0[:, :3])  # it moved
    assert [sys.getrefcount(a) for a in arrays] == before
