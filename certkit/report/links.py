"""Where a paragraph's text is: the rule's own section in the report, else the official eCFR page."""

from __future__ import annotations

import re

ECFR_SECTION = "https://www.ecfr.gov/current/title-14/chapter-I/subchapter-C/part-25/section-{section}"
_PARAGRAPH = re.compile(r"^(\d+\.\d+[a-z]?)((?:\([a-z0-9]+\))*)$")


def ecfr_url(paragraph: str) -> str:
    """The eCFR page of ``paragraph`` (``25.121(b)`` → the page of §25.121 at its anchor ``p-25.121(b)``)."""
    m = _PARAGRAPH.match(paragraph)
    if not m:
        raise ValueError(f"not a paragraph id: {paragraph!r}")
    url = ECFR_SECTION.format(section=m[1])
    return f"{url}#p-{paragraph}" if m[2] else url


def slug(rule_id: str) -> str:
    """The HTML id of a rule's section (``25.331(c)(1)`` → ``r25-331-c-1``)."""
    return "r" + re.sub(r"[^0-9a-z]+", "-", rule_id.lower()).strip("-")


def resolve(paragraph: str, rule_ids) -> tuple[str, str | None]:
    """(href, rule id) for a reference: the rule itself when one is ``paragraph`` exactly; else the one rule that
    covers it (a rule of a parent paragraph: ``25.335(b)(1)`` → rule ``25.335(b)``; a paragraph whose only
    sub-paragraph rule is one: ``25.333`` → none unless exactly the section); else the eCFR page."""
    ids = set(rule_ids)
    if paragraph in ids:
        return "#" + slug(paragraph), paragraph
    parent = paragraph
    while "(" in parent:
        parent = parent[: parent.rindex("(")]
        if parent in ids:
            return "#" + slug(parent), parent
    return ecfr_url(paragraph), None
