"""certkit's folder in the user's cache: ``$XDG_CACHE_HOME/certkit`` or ``~/.cache/certkit``.

It holds what can be rebuilt at any time (the rule index, pint's parsed unit definitions, lattice solutions, the
declared airplanes' sizing baselines); losing it only costs time.
"""

from __future__ import annotations

import hashlib
import os
import pickle
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import Any

#: the thread settings a BLAS reads: a threaded BLAS sums in another order (other last bits), so a numerical result kept
#: in the cache is keyed on them too
THREAD_SETTINGS = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def thread_settings() -> dict[str, str | None]:
    """The process's :data:`THREAD_SETTINGS` (None where unset)."""
    return {name: os.environ.get(name) for name in THREAD_SETTINGS}


def sources_digest(root: Path, files: Iterable[Path], header: bytes = b"") -> str:
    """The SHA-256 of ``header`` and of each of ``files`` (their paths relative to ``root`` and their bytes): what a
    cached result computed by that code is keyed on."""
    h = hashlib.sha256(header)
    for path in files:
        h.update(str(path.relative_to(root)).encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()


def cache_folder() -> Path:
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "certkit"


class PickleFolder:
    """Values pickled under keys (file names) in ``folder``, the newest ``keep`` kept: a miss for anything that cannot
    be read, nothing for a folder that cannot be written (such a store only saves time)."""

    def __init__(self, folder: Path | str, keep: int):
        self.folder = Path(folder)
        self.keep = keep

    def load(self, key: str) -> Any | None:
        """The value stored under ``key``, or None (none yet, an unreadable folder, a damaged or foreign entry)."""
        path = self.folder / f"{key}.pickle"
        try:
            with open(path, "rb") as f:
                value = pickle.load(f)
            os.utime(path)  # most recently used: kept longest
        except Exception:  # noqa: BLE001 - any unreadable entry is only a miss
            return None
        return value

    def save(self, key: str, value: Any) -> None:
        """Write ``value`` under ``key`` whole or not at all (another process may be writing the same entry), then
        keep the newest entries."""
        tmp = None
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(dir=self.folder, suffix=".tmp")
            with os.fdopen(fd, "wb") as f:
                pickle.dump(value, f, protocol=pickle.HIGHEST_PROTOCOL)
            os.replace(tmp, self.folder / f"{key}.pickle")
            tmp = None
            entries = sorted(self.folder.glob("*.pickle"), key=lambda p: p.stat().st_mtime_ns, reverse=True)
            for old in entries[self.keep :]:
                old.unlink(missing_ok=True)
        except OSError:
            return
        finally:
            if tmp is not None:
                Path(tmp).unlink(missing_ok=True)
