"""What the compiled (numba) kernels share: their arguments' form, their row copies and borrowed arrays.

numba compiles a kernel once per combination of argument types, and it types a read-only array (a broadcast view,
a table marked read-only) apart from a writeable one of the same dtype and layout: a kernel called once with each
is compiled twice, which costs seconds at the first run after an install. :func:`kernel_array` gives every kernel
argument one type: C-contiguous, writeable, of the stated dtype (a copy only where the array is read-only, not
contiguous or of another dtype; the values are the same).

A row assigned as a whole inside a kernel (``a[i] = b[j]``) makes numba compile its shape check and the formatting
of its error message (a few seconds per argument type at the first run); :func:`copy_row` copies element by
element, the same values, with nothing to check.

numba keys a cached kernel on its own source file only (path, modification time, size): a kernel that calls one
defined in another module — the equations of motion inline the aerodynamic coefficients — keeps its machine code when
only the other module changes, and then reads the new tables with the old layout (silently wrong numbers after an
upgrade). :func:`refresh_stale_kernels`, run when this module is imported (every kernel module imports it before its
kernels are first called), keeps a digest of all of certkit's kernel sources beside their cache and removes certkit's
cached kernels when it changes; numba then compiles them once more.
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
from numba import njit
from numba.core import cgutils
from numba.core.caching import CacheImpl
from numba.extending import intrinsic
from numba.np.arrayobj import make_array

from certkit.lean_imports import numba_without_cffi

#: certkit's modules with kernels cached on disk (``njit(cache=True)``), relative to the package; a test checks the
#: list against the package's sources
KERNEL_MODULES = (
    "atmosphere.py",
    "models/compiled.py",
    "models/dynamics/trim.py",
    "models/dynamics/kernel.py",
    "models/dynamics/pilot_kernel.py",
    "models/aero/tail_ground_effect.py",
    "models/aero/derivative_kernel.py",
    "models/aero/ground_effect.py",
    "models/aero/vlm/biot_savart_kernels.py",
    "models/propulsion/engine.py",
    "models/loads/model.py",
    "models/loads/response.py",
    "models/loads/capability.py",
    "models/loads/gust.py",
)
#: the file, in each kernel cache directory, holding the digest of the sources its kernels were compiled from
DIGEST_FILE = "certkit-kernels.sha256"


def kernel_cache_dirs(package: Path) -> dict[Path, list[str]]:
    """numba's cache directory of each kernel module (as numba locates it: ``NUMBA_CACHE_DIR``, else the module's
    ``__pycache__``, else the user-wide cache) → the module stems cached there."""
    out: dict[Path, list[str]] = {}
    for module in KERNEL_MODULES:
        path = str(package / module)
        locators: list[Any] = list(CacheImpl._locator_classes)  # numba's own order of cache locations
        for locator in locators:
            found = locator.from_function(kernel_array, path)
            if found is not None:
                out.setdefault(Path(found.get_cache_path()), []).append(Path(module).stem)
                break
    return out


def refresh_stale_kernels(package: Path | None = None) -> list[Path]:
    """Remove certkit's cached kernels from every cache directory whose digest file does not hold the digest of the
    current kernel sources (:data:`KERNEL_MODULES`), and write the digest there. Returns the files removed."""
    package = Path(__file__).resolve().parents[1] if package is None else package
    digest = hashlib.sha256(b"".join((package / m).read_bytes() for m in KERNEL_MODULES)).hexdigest()
    removed: list[Path] = []
    for directory, stems in kernel_cache_dirs(package).items():
        stamp = directory / DIGEST_FILE
        try:
            if stamp.read_text() == digest:
                continue
        except OSError:
            pass
        try:
            directory.mkdir(parents=True, exist_ok=True)
            for entry in directory.iterdir():
                if entry.suffix in (".nbi", ".nbc") and entry.name.split(".")[0] in stems:
                    entry.unlink(missing_ok=True)
                    removed.append(entry)
            stamp.write_text(digest)
        except OSError:  # a cache numba cannot write either: it compiles in memory
            continue
    return removed


def kernel_array(values: npt.ArrayLike, dtype: npt.DTypeLike = float) -> np.ndarray:
    """``values`` as a C-contiguous, writeable array of ``dtype``."""
    array = np.ascontiguousarray(values, dtype=dtype)
    return array if array.flags.writeable else array.copy()


@njit(cache=True, inline="always")
def copy_row(destination, source):  # type: ignore[no-untyped-def]
    """``destination[:] = source`` for two 1-D arrays of the same length, element by element."""
    for k in range(source.shape[0]):
        destination[k] = source[k]


@intrinsic
def borrowed(typingctx, array):  # type: ignore[no-untyped-def]
    """``array`` as a view that numba does not reference-count: the same data, shape and strides, no owner.

    numba's own inlining (``inline="always"``) binds each array argument of an inlined function to a new name with an
    atomic reference-count increment, and releases it with an atomic decrement; the equations of motion inlined in the
    RK4 step pass about twenty arrays, and those atomic operations took nearly half of a step (``perf`` found most of
    the step's machine-code samples in them; 1.33 → 0.70 µs per condition and step once its arrays are borrowed).
    A kernel borrows its own array arguments only — the caller holds them for the whole call — and never returns a
    borrowed array, stores it, or borrows an array it allocated (numba frees a local array after its last use)."""
    sig = array(array)

    def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
        struct = make_array(array)  # type: ignore[no-untyped-call]  # numba's internals are not annotated
        source, view = struct(context, builder, value=args[0]), struct(context, builder)
        null = cgutils.get_null_value
        view.meminfo = null(view.meminfo.type)  # type: ignore[no-untyped-call]  # numba's internals are not annotated
        view.parent = null(view.parent.type)  # type: ignore[no-untyped-call]
        for name in ("nitems", "itemsize", "data", "shape", "strides"):
            setattr(view, name, getattr(source, name))
        return view._getvalue()

    return sig, codegen


refresh_stale_kernels()
numba_without_cffi()  # before numba's first typing set-up (the first kernel call of the process)
