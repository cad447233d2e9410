"""Conformance suite run over every registered rule (as scikit-learn's check_estimator): metadata
complete, documentation present, cross-references well formed, findings name their conditions,
margins signed so that >= 0 complies, and nothing passes without a computed margin."""

import math
import re

import pytest

from certkit.engine.context import Context
from certkit.engine.registry import RULE_ID, discover
from certkit.engine.scheduler import evaluate_rule

RULES = discover()

#: the reasons for which a rule may find on the baseline that its paragraph does not apply (regular expressions on
#: the reason after "not applicable: "); anything else is a test failure, so a rule cannot pass a condition off as
#: not applicable without it being declared and checked here
FLAPS_ABOVE_20000 = r"^(takeoff|approach|landing) configuration above 20,000 ft \(flap altitude limit\)$"
BEYOND_VFE = r"^the (takeoff|landing) configuration's range ends at its VFE/VLE"
#: §25.121 at a weight–altitude–temperature corner where the design weight is above the WAT limit (§25.1533(a))
WAT_LIMITED = r"^[\d,]+ lb is above this corner's WAT limit weight"
NOT_APPLICABLE = {
    **{f"25.121({p})": [WAT_LIMITED] for p in "abcd"},
    "25.147(a)": [r"^\(b\) applies to airplanes with four or more engines \(2 here\)$"],
    "25.147(c)": [r"^\(e\) applies to airplanes with four or more engines \(2 here\)$"],
    "25.171": [FLAPS_ABOVE_20000],
    "25.173(a)": [FLAPS_ABOVE_20000, BEYOND_VFE],
    "25.177": [FLAPS_ABOVE_20000, BEYOND_VFE, r"^full rudder, full lateral control or the force bound is reached"],
    "25.181": [FLAPS_ABOVE_20000],
    "25.331(b)": [FLAPS_ABOVE_20000],
    "25.427(b)": [FLAPS_ABOVE_20000],  # the split of a §25.331(b) condition that does not apply
    "25.335(a)": [r"^VC is limited by MC at this altitude"],
    "25.345(a)(2)": [FLAPS_ABOVE_20000],
    "25.349(a)": [r"lies beyond the stall line of the V–n envelope"],
}


def _check_not_applicable(rule_id, f, ctx):
    """The reason is one declared for the rule, and what it states holds at the finding's condition."""
    why = f.reason.removeprefix("not applicable: ")
    matched = [p for p in NOT_APPLICABLE.get(rule_id, ()) if re.search(p, why)]
    assert matched, f"{rule_id}: undeclared 'not applicable' reason {why!r}"
    if matched[0] == WAT_LIMITED:  # an envelope corner, whose own limitation finding is in the rule's findings
        assert f.condition.get("airport") and "gradient_at_design_weight" in f.details
    if matched[0] == FLAPS_ABOVE_20000:
        assert f.condition.altitude > 20_000 * 0.3048 and f.condition.configuration in (
            "takeoff",
            "approach",
            "landing",
        )
    if "four or more engines" in why:
        assert len(ctx.aircraft.propulsion.engines) == 2
    if rule_id == "25.335(a)":  # VC 272 KEAS reaches MC 0.87 at 36,090 ft (ISA): above it, Mach-limited
        assert f.condition.altitude > 36_090 * 0.3048


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
        if f.margin is None:  # a computed 'does not apply': only the reasons listed below, each checked
            assert f.status == "complies" and f.reason.startswith("not applicable"), f"{rule.id}: {f}"
            _check_not_applicable(rule.id, f, shared_ctx)
            continue
        assert math.isfinite(f.margin) and f.unit is not None
        tol = 1e-9 * max(1.0, abs(f.limit))
        assert (f.margin >= -tol) == (f.status == "complies"), f"{rule.id}: margin sign and status disagree: {f}"
        if rule.conditions.loading is not None:
            assert f.condition.mass is not None and f.condition.x_cg is not None, f"{rule.id}: condition not named"
