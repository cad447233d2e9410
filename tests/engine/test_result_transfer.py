"""A rule's result as a worker process sends it back (:meth:`RuleResult.__getstate__`): once encoded for
results.json its findings travel packed and are rebuilt only when asked for; what the terminal, the report's index
and the exit code read comes computed, the same as from the findings."""

from __future__ import annotations

import pickle

import pytest

from certkit.engine.registry import discover
from certkit.engine.results import SUMMARY, Condition, Finding, RuleResult
from certkit.engine.scheduler import evaluate_rule, run


def _result(findings):
    return RuleResult("25.0", "x", "x", findings)


def _sample_results():
    """Results of every status: fails (two failures, the worse second), complies, partial, not evaluated, empty."""
    c = Condition(loading="fwd", mass=1.0)
    ok = Finding.compare(c, "a ≥ 1", 2.0, 1.0, at_least=True, unit="g")
    bad = Finding.compare(c.with_(k=1), "b ≥ 1", 0.5, 1.0, at_least=True, unit="g")
    worse = Finding.compare(c.with_(k=2), "c ≥ 1", 0.2, 1.0, at_least=True, unit="g")
    na = Finding.not_evaluated(c, "d", "no data for d")
    scope = Finding.not_evaluated(Condition(), "(e)", "not evaluated by this rule", not_evaluated_by_rule="(e)")
    return [_result(f) for f in ([ok, bad, worse], [ok], [ok, scope], [na, scope], [scope], [])]


def test_an_encoded_result_travels_with_its_summary_and_its_findings_packed():
    for result in _sample_results():
        result.encoded = result.to_json()
        expected = {name: getattr(result, name) for name in SUMMARY}
        back = pickle.loads(pickle.dumps(result))
        assert "findings" not in back.__dict__
        assert {name: getattr(back, name) for name in SUMMARY} == expected
        assert "findings" not in back.__dict__  # the summary did not rebuild them
        assert back.findings == result.findings
        assert {name: getattr(back, name) for name in SUMMARY} == expected  # now from the findings
        assert "_summary" not in back.__dict__ and back == result


def test_the_summary_is_that_of_the_findings():
    """The worst failure is the failing finding of smallest normalised margin; a rule not evaluated gives its first
    own reason; each status as the module defines it."""
    fails, complies, partial, not_evaluated, scope_only, empty = _sample_results()
    assert fails.status == "fails" and fails.worst_failure.check == "c ≥ 1" and fails.critical.check == "c ≥ 1"
    assert complies.status == "complies" and complies.worst_failure is None
    assert partial.status == "complies_partial"
    assert not_evaluated.status == "not_evaluated" and not_evaluated.not_evaluated_reason == "no data for d"
    assert scope_only.status == "not_evaluated" and scope_only.critical is None
    assert empty.not_evaluated_reason == "no finding"


def test_a_result_not_encoded_travels_whole():
    result = _sample_results()[0]
    back = pickle.loads(pickle.dumps(result))
    assert "findings" in back.__dict__ and "_summary" not in back.__dict__ and back == result


def test_results_from_worker_processes_equal_those_of_one_process(baseline):
    """The findings of rules evaluated in worker processes (packed on the way) equal those evaluated here."""
    rules = [r for r in discover() if r.id in ("25.143(h)", "25.333", "25.335(a)")]
    two = run(baseline, rules, jobs=2)
    assert all("_packed_findings" in r.__dict__ for r in two.rules)
    from certkit.engine.context import Context

    ctx = Context(baseline)
    for r in two.rules:
        here = evaluate_rule(next(c for c in rules if c.id == r.id), ctx)
        assert r.status == here.status and r.critical == here.critical
        assert r.findings == here.findings


def test_a_result_whose_findings_do_not_travel_keeps_its_summary_and_says_where_they_are():
    for result in _sample_results():
        result.encoded = result.to_json()
        result.findings_travel = False
        expected = {name: getattr(result, name) for name in SUMMARY}
        back = pickle.loads(pickle.dumps(result))
        assert {name: getattr(back, name) for name in SUMMARY} == expected
        assert back.encoded == result.encoded
        with pytest.raises(AttributeError, match="stayed in the process that evaluated it"):
            back.findings  # noqa: B018
        assert not hasattr(back, "findings")


def test_run_without_findings_sends_summaries_and_text_only(baseline):
    rules = [r for r in discover() if r.id in ("25.143(h)", "25.333", "25.335(a)")]
    full, lean = run(baseline, rules, jobs=2), run(baseline, rules, jobs=2, findings=False)
    for a, b in zip(full.rules, lean.rules):
        assert "_packed_findings" in a.__dict__ and b.__dict__["_packed_findings"] is None
        assert (b.status, b.critical, b.worst_failure, b.encoded) == (a.status, a.critical, a.worst_failure, a.encoded)
    assert lean.to_json() == full.to_json().replace(full.created, lean.created)
