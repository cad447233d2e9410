"""A rule's HTML section rendered where the rule was evaluated (a check's worker: ReportFinish) is the section the
report would render itself, and the page put together from such sections is the same page."""

import datetime as dt

from certkit.engine.registry import discover, select
from certkit.engine.scheduler import run
from certkit.report.html import ReportFinish, render_html

NOW = dt.datetime(2026, 1, 1, tzinfo=dt.timezone.utc)


def test_sections_rendered_by_the_workers_make_the_same_page(baseline):
    rules = select(discover(), ["25.335", "25.173"], [])
    assert len(rules) >= 4
    plain = run(baseline, rules, jobs=1, now=NOW)
    assert all(r.section is None for r in plain.rules)
    finished = run(baseline, rules, jobs=1, now=NOW, finish=ReportFinish(rules))
    assert all(r.section and r.section.startswith('<section class="rule"') for r in finished.rules)
    assert render_html(finished, rules) == render_html(plain, rules)


def test_a_section_links_only_to_rules_in_the_report(baseline):
    """§25.333's reference to §25.337 goes to §25.337's section when that rule is in the report, to eCFR otherwise
    (the worker renders with the report's selection of rules)."""
    both = select(discover(), ["25.333", "25.337"], [])
    alone = select(discover(), ["25.333"], [])
    [with_337] = [r.section for r in run(baseline, both, jobs=1, finish=ReportFinish(both)).rules if r.id == "25.333"]
    without = run(baseline, alone, jobs=1, finish=ReportFinish(alone)).rules[0].section
    assert 'href="#r25-337"' in with_337 and 'href="#r25-337"' not in without
    assert "section-25.337" in without
