"""The Jinja environment of certkit's HTML pages (the compliance report, the diff, the study report): the templates
in ``certkit/report/templates``, HTML autoescaped, block tags trimmed, their compiled code kept in certkit's cache
folder (compiling the report's templates is about 0.06 s of every check otherwise)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from jinja2 import Environment, FileSystemBytecodeCache, PackageLoader, select_autoescape
from jinja2.bccache import Bucket

from certkit.user_cache import cache_folder


class _TemplateCache(FileSystemBytecodeCache):
    """Jinja's file cache of compiled templates (keyed by the template's source checksum and Jinja's version; written
    to a temporary file and renamed), where a file that cannot be read is compiled afresh and a folder that cannot
    be written is left alone: the cache only saves time."""

    def load_bytecode(self, bucket: Bucket) -> None:
        try:
            super().load_bytecode(bucket)
        except Exception:  # noqa: BLE001 - any unreadable cache file (OSError, EOFError, UnpicklingError …)
            bucket.reset()

    def dump_bytecode(self, bucket: Bucket) -> None:
        try:
            super().dump_bytecode(bucket)
        except OSError:
            pass


def _bytecode_cache() -> _TemplateCache | None:
    folder = cache_folder() / "templates"
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return _TemplateCache(str(folder))


def page_environment(filters: dict[str, Callable[..., Any]]) -> Environment:
    """The environment with the page's own template ``filters``."""
    env = Environment(
        loader=PackageLoader("certkit.report", "templates"),
        autoescape=select_autoescape(["html"]),
        trim_blocks=True,
        lstrip_blocks=True,
        bytecode_cache=_bytecode_cache(),
    )
    env.filters.update(filters)
    return env
