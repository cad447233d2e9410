"""certkit's folder in the user's cache: ``$XDG_CACHE_HOME/certkit`` or ``~/.cache/certkit``.

It holds what can be rebuilt at any time (the rule index, pint's parsed unit definitions); losing it only costs time.
"""

from __future__ import annotations

import os
from pathlib import Path


def cache_folder() -> Path:
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "certkit"
