"""Imports that third-party packages make at start-up and certkit never uses, kept out of every certkit process.

- ``numpy.f2py`` (numpy's Fortran wrapper generator): scipy ≥ 1.15 copies numpy's namespace into its array-API layer
  with ``from numpy import *``, and numpy's ``__all__`` names ``f2py``, whose import compiles some hundred regular
  expressions — about 0.1 s of every process that imports ``scipy.linalg``. :func:`lazy_f2py` has the import system
  load it with the standard library's :class:`importlib.util.LazyLoader` (a finder first on ``sys.meta_path``, for
  that one module): ``numpy.f2py`` exists (``from numpy import *`` binds it) and is executed only when one of its
  attributes is read; numpy itself is not imported for it.
- dask, imported by pint when it is installed (pint's support for quantities wrapping dask arrays, which certkit's
  boundary conversion of plain numbers never builds): 50–90 ms with its dependencies. ``certkit.units`` imports
  pint within :func:`hidden` (``"dask"``), pint's test being ``find_spec("dask")``; ``import dask`` afterwards (a
  study on a Dask cluster) works as usual.
- cffi (and its C parser), imported by numba when it first sets up its typing (the first kernel call of a process)
  for its support of cffi functions inside kernels, which certkit's kernels do not call: 30 ms of each worker
  process. :func:`numba_without_cffi` imports numba's cffi module with cffi hidden, so numba records that support
  as absent; cffi itself imports as usual afterwards.

Measured with ``python -X importtime`` and ``benchmarks/bench_check.py`` (the coordinator's start-up before the worker
processes fork); tests/hardening/test_lean_imports.py checks each module stays out and still works when used.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import importlib.util
import sys
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from types import ModuleType

#: the modules :class:`LazyFinder` loads lazily
LAZY = ("numpy.f2py",)


class LazyFinder(importlib.abc.MetaPathFinder):
    """Finds the modules of :data:`LAZY` with the other finders and gives them a :class:`importlib.util.LazyLoader`."""

    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname not in LAZY:
            return None
        for finder in sys.meta_path:
            if finder is self or not hasattr(finder, "find_spec"):
                continue
            spec = finder.find_spec(fullname, path, target)
            if spec is not None:
                if spec.loader is not None and hasattr(spec.loader, "exec_module"):
                    spec.loader = importlib.util.LazyLoader(spec.loader)
                return spec
        return None


def lazy_f2py() -> None:
    """Put :class:`LazyFinder` first on ``sys.meta_path`` (once)."""
    if not any(isinstance(f, LazyFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, LazyFinder())


@contextmanager
def hidden(name: str) -> Iterator[None]:
    """Within the block, module ``name`` cannot be imported (``importlib.util.find_spec`` answers None, ``import``
    raises ImportError), unless it is already imported; afterwards it imports as usual."""
    hide = name not in sys.modules
    if hide:
        sys.modules[name] = None  # type: ignore[assignment]  # the import system's "not importable" marker
    try:
        yield
    finally:
        if hide and sys.modules.get(name, 0) is None:
            del sys.modules[name]


def numba_without_cffi() -> None:
    """numba's cffi support module imported with cffi hidden, unless numba already imported it."""
    if "numba.core.typing.cffi_utils" in sys.modules:
        return
    with hidden("cffi"):
        from numba.core.typing import (  # deferred: numba only in the processes that run kernels
            cffi_utils,  # noqa: F401  # imported for its effect: numba's cffi support recorded absent
        )
