"""The registered rules' metadata (id, symbol, title, implementation, documentation) without importing the rules.

``certkit rules`` and ``certkit explain`` print metadata only, but importing the rule modules loads the physics
(numba, scipy, pint: about 1 s). The metadata is therefore kept in a small JSON index in the user's cache folder
(``$XDG_CACHE_HOME/certkit`` or ``~/.cache/certkit``), keyed by the certkit version and the size and modification
time of every Python file of the ``certkit`` and ``certkit_rules`` packages: any change to a rule or to the engine
that formats its documentation makes a new key, and the rules are imported once to rebuild it. With plugins
installed or ``--rules`` folders, whose files are not in the key, the rules are always imported. A cache folder
that cannot be written only costs the time.
"""

from __future__ import annotations

import hashlib
import json
import os
from importlib.metadata import entry_points
from importlib.util import find_spec
from pathlib import Path

from certkit import __version__
from certkit.engine.registry import ENTRY_POINT_GROUP, DiscoveryOptions, discover
from certkit.user_cache import cache_folder

FIELDS = ("id", "symbol", "title", "implementation", "amendment")

#: one rule's entry: the :data:`FIELDS` and its ``documentation`` (strings)
RuleMetadata = dict[str, str]


def _package_folders() -> list[Path]:
    out = []
    for name in ("certkit", "certkit_rules"):
        spec = find_spec(name)
        if spec and spec.submodule_search_locations:
            out += [Path(p) for p in spec.submodule_search_locations]
    return out


def index_key() -> str:
    """A digest of the certkit version and every package file's path, size and modification time."""
    h = hashlib.sha256(__version__.encode())
    for folder in _package_folders():
        for root, dirs, files in os.walk(folder):
            dirs[:] = sorted(d for d in dirs if not d.startswith((".", "__pycache__")))
            for name in sorted(files):
                if name.endswith(".py"):
                    st = os.stat(os.path.join(root, name))
                    h.update(f"{root}/{name}:{st.st_size}:{st.st_mtime_ns}\n".encode())
    return h.hexdigest()[:32]


def _has_plugins() -> bool:
    return bool(list(entry_points(group=ENTRY_POINT_GROUP)))


def rule_metadata(rules_dirs: tuple[str, ...] = ()) -> list[RuleMetadata]:
    """Every registered rule's :data:`FIELDS` and ``documentation`` (its ``certkit explain`` text), in paragraph
    order, from the index when it is current (see the module docstring)."""
    if rules_dirs or _has_plugins():
        return _from_rules(rules_dirs)
    path = cache_folder() / f"rules-{index_key()}.json"
    try:
        cached: list[RuleMetadata] = json.loads(path.read_text(encoding="utf-8"))
        return cached
    except (OSError, ValueError):
        pass
    data = _from_rules(())
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        for old in path.parent.glob("rules-*.json"):
            old.unlink(missing_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(json.dumps(data), encoding="utf-8")
        os.replace(tmp, path)
    except OSError:
        pass
    return data


def _from_rules(rules_dirs: tuple[str, ...]) -> list[RuleMetadata]:
    return [
        {**{f: getattr(r, f) for f in FIELDS}, "documentation": r.documentation()}
        for r in discover(DiscoveryOptions(rules_dirs=tuple(rules_dirs)))
    ]


def find(metadata: list[RuleMetadata], query: str) -> list[RuleMetadata]:
    """The rules ``query`` names: an id (``25.337``, ``§25.337``, ``§ 25.331(c)(2)``), a symbol, or an id prefix."""
    q = query.strip().lstrip("§").strip()
    exact = [m for m in metadata if m["id"] == q or m["symbol"] == q]
    return exact or [m for m in metadata if m["id"].startswith(q)]
