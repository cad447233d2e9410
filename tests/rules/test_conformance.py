"""Conformance suite run over every registered rule (as scikit-learn's check_estimator): metadata
complete, documentation present, cross-references well formed, findings name their conditions,
margins signed so that >= 0 complies, and nothing passes without a computed margin."""

import math

import pytest

from certkit.context import Context
from certkit.registry import RULE_ID, discover
from certkit.scheduler import evaluate_rule

RULES = discover()


@pytest.fixture(scope="module")
def shared_ctx(baseline):
    return Context(baseline)


@pytest.mark.parametrize("rule", RULES, ids=[r.id for r in RULES])
def test_metadata_and_documentation(rule):
    doc = rule.documentation()
    for heading in ("Requirement", "Criterion", "Conditions", "Margin"):
        assert heading in doc
    assert rule.requirement.strip() and rule.margin.strip() and rule.conditions.describe()
    for ref in rule.references:
        assert RULE_ID.match(ref)
    for name, c in rule.criteria.items():
        assert c.source and c.description, f"{rule.id} criterion {name} needs a source and a meaning"
    if rule.implementation == "partial":
        assert rule.unevaluated, f"{rule.id}: a partial rule lists the sub-paragraphs it does not evaluate"
        assert "Not evaluated" in doc


@pytest.mark.parametrize("rule", RULES, ids=[r.id for r in RULES])
def test_findings_on_the_baseline(rule, shared_ctx):
    result = evaluate_rule(rule, shared_ctx)
    assert result.findings, f"{rule.id} returned no finding"
    for f in result.findings:
        assert f.check
        if f.status == "not_evaluated":
            assert f.reason, f"{rule.id}: not_evaluated needs a reason"
            continue
        if f.margin is None:  # a computed 'does not apply' must say why
            assert f.status == "complies" and f.reason.startswith("not applicable"), f"{rule.id}: {f}"
            continue
        assert math.isfinite(f.margin) and f.unit is not None
        tol = 1e-9 * max(1.0, abs(f.limit))
        assert (f.margin >= -tol) == (f.status == "complies"), f"{rule.id}: margin sign and status disagree: {f}"
        if rule.conditions.loading is not None:
            assert f.condition.mass is not None and f.condition.x_cg is not None, f"{rule.id}: condition not named"
