"""A folder of the declared airplanes' sizing baselines kept between processes: the elevator actuators the unmodified
aircraft file is sized to and its near-critical loads conditions (:class:`~certkit.design.sizing_loop
.BaselineActuators`, without its context), which every design of a study starts from. A process evaluating designs
computes them once, from a full pass of the horizontal-tail loads rules over the declared airplane (about a second);
with the store, the first design of each study worker and each ``certkit evaluate`` loads them instead.

An entry is found by a digest of everything the value is computed from: the declared aircraft (its whole parsed model),
the source text of certkit's modules with the numpy, numba and Python versions and the machine's architecture
(:func:`certkit.models.aero.lattice_store.source_digest`), the source text of every package the sizing rules come from
(the bundled ``rules`` or a plugin's), the rules' ids, and the process's BLAS/OpenMP thread settings (a threaded BLAS
sums in another order: other last bits). A change of any of them is another entry, never an old value; an entry that
cannot be read is computed again. The newest :data:`KEEP` entries are kept.
"""

from __future__ import annotations

import hashlib
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from certkit.models.aero.lattice_store import source_digest
from certkit.user_cache import PickleFolder, cache_folder, sources_digest, thread_settings

#: entries kept in the folder (a few kB each), the most recently used
KEEP = 16

#: the layout of an entry; another layout is another entry
FORMAT = 1


def _package_digest(module: str) -> str:
    """The digest of the text of every module of ``module``'s top-level package (a single module: its own text)."""
    top = sys.modules.get(module.split(".")[0])
    where = getattr(top, "__file__", None)
    if where is None:
        return "unknown"
    path = Path(where).resolve()
    return sources_digest(path.parent, sorted(path.parent.rglob("*.py")) if path.name == "__init__.py" else [path])


def entry_key(aircraft: Any, rules: Sequence[type]) -> str:
    """The digest naming the baseline of the declared ``aircraft`` sized by ``rules`` (the sizing rule classes)."""
    model = aircraft.model_dump(mode="json") if hasattr(aircraft, "model_dump") else repr(aircraft)
    packages = sorted({r.__module__.split(".")[0] for r in rules})
    inputs = {
        "format": FORMAT,
        "aircraft": model,
        "rules": sorted(str(getattr(r, "id", r.__qualname__)) for r in rules),
        "packages": {p: _package_digest(p) for p in packages},
        "threads": thread_settings(),
    }
    text = json.dumps(inputs, sort_keys=True, default=repr)
    return hashlib.sha256((source_digest() + "\n" + text).encode()).hexdigest()


def store() -> PickleFolder:
    """The folder of baselines in the user's cache."""
    return PickleFolder(cache_folder() / "baselines", KEEP)
