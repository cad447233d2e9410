"""Imports that third-party packages make at start-up and certkit never uses, kept out of every certkit process.

- ``numpy.f2py`` (numpy's Fortran wrapper generator): scipy ≥ 1.15 copies numpy's namespace into its array-API layer
  with ``from numpy import *``, and numpy's ``__all__`` names ``f2py``, whose import compiles some hundred regular
  expressions — about 0.1 s of every process that imports ``scipy.linalg``. :func:`lazy_f2py` registers the module
  with the standard library's :class:`importlib.util.LazyLoader`: ``numpy.f2py`` exists (``from numpy import *``
  binds it) and is executed only when one of its attributes is read.
- dask, imported by pint when it is installed (pint's support for quantities wrapping dask arrays, which certkit's
  boundary conversion of plain numbers never builds): 50–90 ms with its dependencies. :func:`pint_without_dask`
  hides dask from pint's import only; ``import dask`` afterwards (a study on a Dask cluster) works as usual.
- cffi (and its C parser), imported by numba when it first sets up its typing (the first kernel call of a process)
  for its support of cffi functions inside kernels, which certkit's kernels do not call: 30 ms of each worker
  process. :func:`numba_without_cffi` imports numba's cffi module with cffi hidden, so numba records that support
  as absent; cffi itself imports as usual afterwards.

Both are measured in ``benchmarks/bench_check.py`` (the coordinator's start-up before the worker processes fork).
"""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Iterator
from contextlib import AbstractContextManager, contextmanager

import numpy


def lazy_f2py() -> None:
    """Register ``numpy.f2py`` for lazy execution unless it is already imported (or not installed)."""
    if "numpy.f2py" in sys.modules:
        return
    spec = importlib.util.find_spec("numpy.f2py")
    if spec is None or spec.loader is None:
        return
    loader = importlib.util.LazyLoader(spec.loader)
    spec.loader = loader
    module = importlib.util.module_from_spec(spec)
    sys.modules["numpy.f2py"] = module
    # the package attribute too: numpy resolves ``numpy.f2py`` through its own __getattr__, which imports it ``as``
    # the attribute, so without one it would recurse
    numpy.f2py = module  # type: ignore[attr-defined]
    loader.exec_module(module)


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


def pint_without_dask() -> AbstractContextManager[None]:
    """The block that imports pint, with dask hidden (pint's test for it is ``find_spec("dask")``)."""
    return hidden("dask")


def numba_without_cffi() -> None:
    """numba's cffi support module imported with cffi hidden, unless numba already imported it."""
    if "numba.core.typing.cffi_utils" in sys.modules:
        return
    with hidden("cffi"):
        from numba.core.typing import (  # deferred: numba only in the processes that run kernels
            cffi_utils,  # noqa: F401  # imported for its effect: numba's cffi support recorded absent
        )
