"""The Jinja environment of certkit's HTML pages (the compliance report, the diff, the study report): the templates
in ``certkit/report/templates``, HTML autoescaped, block tags trimmed."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from jinja2 import Environment, PackageLoader, select_autoescape


def page_environment(filters: dict[str, Callable[..., Any]]) -> Environment:
    """The environment with the page's own template ``filters``."""
    env = Environment(
        loader=PackageLoader("certkit.report", "templates"),
        autoescape=select_autoescape(["html"]),
        trim_blocks=True,
        lstrip_blocks=True,
    )
    env.filters.update(filters)
    return env
