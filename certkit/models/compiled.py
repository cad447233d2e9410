"""What the compiled (numba) kernels share: their arguments' form and their row copies.

numba compiles a kernel once per combination of argument types, and it types a read-only array (a broadcast view,
a table marked read-only) apart from a writeable one of the same dtype and layout: a kernel called once with each
is compiled twice, which costs seconds at the first run after an install. :func:`kernel_array` gives every kernel
argument one type: C-contiguous, writeable, of the stated dtype (a copy only where the array is read-only, not
contiguous or of another dtype; the values are the same).

A row assigned as a whole inside a kernel (``a[i] = b[j]``) makes numba compile its shape check and the formatting
of its error message (a few seconds per argument type at the first run); :func:`copy_row` copies element by
element, the same values, with nothing to check.
"""

from __future__ import annotations

import os

import numpy as np
import numpy.typing as npt
from numba import njit


def kernel_array(values: npt.ArrayLike, dtype: npt.DTypeLike = float) -> np.ndarray:
    """``values`` as a C-contiguous, writeable array of ``dtype``."""
    array = np.ascontiguousarray(values, dtype=dtype)
    return array if array.flags.writeable else array.copy()


@njit(cache=True, inline="always")
def copy_row(destination, source):  # type: ignore[no-untyped-def]
    """``destination[:] = source`` for two 1-D arrays of the same length, element by element."""
    for k in range(source.shape[0]):
        destination[k] = source[k]


def kernels_cached() -> bool:
    """Does numba's cache hold the compiled equations of motion (False at the first run after an install, when the
    kernels are compiled: the command says so before it goes quiet for a while)?"""
    from certkit.models.dynamics import kernel

    try:
        index = kernel.derivatives._cache._cache_file._index_path  # numba's cache layout, not a public API
    except AttributeError:
        return True  # another numba: say nothing rather than guess
    return os.path.exists(index)
