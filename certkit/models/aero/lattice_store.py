"""A folder of vortex-lattice solutions (:func:`~certkit.models.aero.airplane.lattice_derivatives`'s result) kept
between runs: a check of an aircraft file whose geometry did not change loads its lattice (its derivatives at every
Mach breakpoint and the unit solutions the strip loads spread) instead of solving it again.

An entry is found by a digest of everything the solution is computed from: the aircraft file's sections that
:func:`lattice_derivatives` reads (:data:`LATTICE_INPUTS`, tested to be all it reads), the Mach numbers, the
source text of certkit's modules with the numpy, numba and Python versions, and the process's BLAS thread settings (a
threaded BLAS solves the lattice to other last bits) — a change of any of them is another entry, never an old
solution. An entry that cannot be read is solved again. The newest :data:`KEEP` entries are kept.
"""

from __future__ import annotations

import hashlib
import json
import platform
from functools import lru_cache
from importlib.metadata import version
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from certkit.models.aero.airplane import LatticeDerivatives, lattice_derivatives
from certkit.user_cache import PickleFolder, sources_digest, thread_settings

#: the aircraft file's sections the lattice is computed from (geometry and lattice resolution, the reference lengths
#: and point, the design speeds that set the Mach breakpoints)
LATTICE_INPUTS = ("aerodynamics", "geometry", "reference", "speeds")

#: entries kept in the folder (about 7 MB each for the baseline), the most recently used
KEEP = 8

#: the layout of an entry; another layout is another entry
FORMAT = 1


@lru_cache(maxsize=1)
def source_digest() -> str:
    """A digest of the text of every module of the certkit package (the lattice's code and the aircraft model's
    derived quantities it reads), of the numpy, numba and Python versions, the machine's architecture and
    :data:`FORMAT`. (A cache folder shared by machines of one architecture but different processors could give
    them a solution that differs from their own in the last bits: numba compiles for the processor it runs on.)"""
    package = Path(__file__).resolve().parents[2]
    versions = f"{FORMAT} {np.__version__} {version('numba')} {platform.python_version()} {platform.machine()}"
    return sources_digest(package, sorted(package.rglob("*.py")), versions.encode() + b"\n")


def entry_key(aircraft: Any, machs: Sequence[float] | None = None) -> str:
    """The digest naming ``aircraft``'s lattice solution at ``machs`` (None: its Mach breakpoints)."""
    inputs = {name: _plain(getattr(aircraft, name)) for name in LATTICE_INPUTS}
    inputs["machs"] = None if machs is None else [float(m) for m in machs]
    inputs["threads"] = thread_settings()  # the lattice's LU in a threaded BLAS: other last bits
    text = json.dumps(inputs, sort_keys=True, default=repr)
    return hashlib.sha256((source_digest() + "\n" + text).encode()).hexdigest()


def _plain(section: Any) -> Any:
    return section.model_dump(mode="json") if hasattr(section, "model_dump") else section


class LatticeStore:
    """The folder ``folder`` of lattice solutions; :meth:`derivatives` is :func:`lattice_derivatives` through it."""

    def __init__(self, folder: Path | str):
        self.folder = Path(folder)
        self._entries = PickleFolder(self.folder, KEEP)

    def derivatives(self, aircraft: Any, machs: Sequence[float] | None = None) -> LatticeDerivatives:
        """:func:`lattice_derivatives` of ``aircraft`` at ``machs``: the stored solution of the same inputs, or
        solved and stored."""
        key = entry_key(aircraft, machs)
        stored = self._entries.load(key)
        if stored is not None:
            return stored  # type: ignore[no-any-return]
        solved = lattice_derivatives(aircraft, machs)
        self._entries.save(key, solved)
        return solved
